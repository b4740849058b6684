#ifndef signorini_base_shared_libraries_h
#define signorini_base_shared_libraries_h

#include <string>
#include <vector>

/**
 * User plug-ins loaded at run time: 'Additional shared libraries' (top
 * level of the parameter file) names shared libraries that register
 * materials, obstacles or postprocessors (SIGNORINI_REGISTER_*). They are
 * loaded in the first pass over the file (parameters_input.cc), before
 * the parameters are declared, so that their names are known to the
 * selections and their own subsections are declared with the library's.
 */
namespace Signorini
{
  /** The entry's name and its documentation (for the declaration). */
  extern const char *const shared_libraries_entry;
  extern const char *const shared_libraries_documentation;

  /**
   * dlopen()s each of @p names (a relative path starts at @p directory,
   * the parameter file's), once per process; a name already loaded is
   * skipped. Throws InputError naming the parameter, the library and the
   * loader's reason (never the file's content) if one cannot be loaded.
   */
  void
  load_shared_libraries(const std::vector<std::string> &names,
                        const std::string              &directory);
} // namespace Signorini

#endif
