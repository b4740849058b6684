#ifndef signorini_base_plugins_h
#define signorini_base_plugins_h

#include <deal.II/base/parameter_handler.h>

#include <signorini/base/parameters.h>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

/**
 * Plug-in families (after ASPECT's plugin lists): a family is an abstract
 * class `Interface` (for example Material::Interface<dim>); each model is a
 * class derived from it, registered under a name with a description, a
 * function that declares its own parameters and a factory. A parameter file
 * selects a model by that name; the names form the Patterns::Selection of
 * the family's selection entry, so that an unknown name is an input error
 * naming the known ones (never a silent default).
 *
 * A model registers itself from its own source file with the family's
 * registration macro (for example SIGNORINI_REGISTER_MATERIAL), also in a
 * program outside the library that links it: the static object the macro
 * defines registers the model before main() runs. The registry is a
 * function-local static, so registration does not depend on the order in
 * which static objects of different files are built.
 */
namespace Signorini
{
  namespace Plugins
  {
    using namespace dealii;

    template <typename Interface>
    class Registry
    {
    public:
      using Factory = std::function<std::unique_ptr<Interface>()>;
      using Declare = std::function<void(ParameterHandler &)>;

      struct Entry
      {
        std::string name, description;
        Declare     declare_parameters;
        Factory     create;
      };

      /** The one registry of the family. */
      static Registry &
      instance()
      {
        static Registry registry;
        return registry;
      }

      /** Adds a model; a second model of the same name is a programming
       * error (two plug-ins cannot share a name in a parameter file). */
      void
      add(const std::string &name,
          const std::string &description,
          const Declare     &declare_parameters,
          const Factory     &create)
      {
        AssertThrow(entries.count(name) == 0,
                    ExcMessage("Two plug-ins are registered under the name '" +
                               name + "'."));
        entries[name] = {name, description, declare_parameters, create};
      }

      /** "a|b|c", sorted: the Patterns::Selection of the family. */
      std::string
      selection() const
      {
        std::string text;
        for (const auto &[name, entry] : entries)
          text += (text.empty() ? "" : "|") + name;
        return text;
      }

      /** "'a' (what a is), 'b' (...)": for the documentation string. */
      std::string
      documentation() const
      {
        std::string text;
        for (const auto &[name, entry] : entries)
          text += (text.empty() ? "" : "; ") + ("'" + name + "': ") +
                  entry.description;
        return text;
      }

      /** Lets every model declare its parameters (in the current
       * subsection of @p prm; a model declares its own subsection). */
      void
      declare_parameters(ParameterHandler &prm) const
      {
        for (const auto &[name, entry] : entries)
          if (entry.declare_parameters)
            entry.declare_parameters(prm);
      }

      /** A new object of the model @p name; @p where names the parameter
       * for the message of an unknown name. */
      std::unique_ptr<Interface>
      create(const std::string &name, const std::string &where) const
      {
        const auto it = entries.find(name);
        if (it == entries.end())
          throw InputError(where + ": there is no model '" + name +
                           "'. Known: " + selection() + ".");
        return it->second.create();
      }

      bool
      has(const std::string &name) const
      {
        return entries.count(name) > 0;
      }

    private:
      Registry() = default;
      std::map<std::string, Entry> entries;
    };

    /** Registers @p Model (derived from @p Interface) on construction: the
     * registration macros of the families define a static object of it. */
    template <typename Interface, typename Model>
    struct Registration
    {
      Registration(const std::string &name, const std::string &description)
      {
        Registry<Interface>::instance().add(
          name,
          description,
          [](ParameterHandler &prm) { Model::declare_parameters(prm); },
          []() -> std::unique_ptr<Interface> {
            return std::make_unique<Model>();
          });
      }
    };

    /**
     * The plug-in families whose selection entry and models' subsections
     * the parameters declare: 'Materials/Material k/Model', 'Contact/Pair
     * k/Master' (rigid obstacles), 'Output/Postprocessors', 'Geometry/Body
     * k/Shape'.
     */
    enum class Family
    {
      material,
      obstacle,
      postprocessor,
      shape
    };

    /**
     * Each family declares its own parameters (ASPECT's idiom): it hands
     * its declaration to the parameters through a static Declaration
     * object of its own source file, so that the parameters (base/) need
     * not know the families, which are above them. declare() calls it in
     * the current subsection of @p prm; a family that registered nothing
     * declares nothing.
     */
    using Declare = std::function<void(ParameterHandler &)>;
    void
    declare(const Family family, ParameterHandler &prm);

    /** Registers @p declare as the declaration of @p family on
     * construction. */
    struct Declaration
    {
      Declaration(const Family family, const Declare &declare);
    };
  } // namespace Plugins
} // namespace Signorini

/** A name for the static registration object of a plug-in, unique in its
 * source file (the line of the registration). */
#define SIGNORINI_PLUGIN_NAME_CONCAT(a, b) a##b
#define SIGNORINI_PLUGIN_NAME_LINE(a, b) SIGNORINI_PLUGIN_NAME_CONCAT(a, b)
#define SIGNORINI_PLUGIN_NAME(prefix) \
  SIGNORINI_PLUGIN_NAME_LINE(prefix, __LINE__)

#endif
