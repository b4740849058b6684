// User plug-in libraries loaded at run time (shared_libraries.h).
#include <signorini/base/errors.h>
#include <signorini/base/shared_libraries.h>

#include <dlfcn.h>

#include <filesystem>
#include <set>

namespace Signorini
{
  const char *const shared_libraries_entry = "Additional shared libraries";
  const char *const shared_libraries_documentation =
    "Shared libraries of your own plug-ins (materials, obstacles, "
    "postprocessors registered with SIGNORINI_REGISTER_*), loaded before "
    "the rest of this file is read: their names can then be selected and "
    "their subsections set here. A comma-separated list of paths; a "
    "relative path starts at the directory of this file. Build a plug-in "
    "as a module against the installed library (doc/extending.md); it "
    "needs no main().";


  void
  load_shared_libraries(const std::vector<std::string> &names,
                        const std::string              &directory)
  {
    // The paths loaded by this process: a second parameter file naming the
    // same library (--check of several files) does not load it again.
    static std::set<std::string> loaded;
    for (const auto &name : names)
      {
        std::filesystem::path path(name);
        if (path.is_relative())
          path = std::filesystem::path(directory) / path;
        const std::string where = std::string("parameter '") +
                                  shared_libraries_entry + "', library '" +
                                  name + "'";
        std::error_code error;
        if (!std::filesystem::is_regular_file(path, error))
          throw InputError(where + ": no such file ('" + path.string() +
                           "'). Give the path of a shared library (.so); a "
                           "relative path starts at the directory of the "
                           "parameter file.");
        const std::string key =
          std::filesystem::weakly_canonical(path, error).string();
        if (loaded.count(key) > 0)
          continue;
        // RTLD_NOW: a symbol the library lacks is reported here, not when
        // the run first calls it; RTLD_GLOBAL: its registrations and
        // symbols are visible to libraries loaded after it.
        if (dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL) == nullptr)
          {
            const char *reason = dlerror();
            throw InputError(
              where +
              " cannot be loaded: " + (reason ? reason : "unknown reason") +
              ". Give a shared library built against this Signorini "
              "(doc/extending.md).");
          }
        loaded.insert(key);
      }
  }
} // namespace Signorini
