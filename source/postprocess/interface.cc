#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/reference_parameters.h>

#include <algorithm>

namespace Signorini
{
  namespace Postprocess
  {
    void
    declare_parameters(ParameterHandler &prm)
    {
      const auto &registry = Registry<2>::instance();
      prm.declare_entry("Postprocessors",
                        "visualization, contact surface, reference checks",
                        Patterns::MultipleSelection(registry.selection()),
                        "What runs after every written load step, in this "
                        "order (names separated by ','; empty: none): " +
                          registry.documentation() +
                          ". A postprocessor reads its own parameters from a "
                          "subsection of 'Output' named after it, "
                          "capitalised.");
      registry.declare_parameters(prm);
    }


    namespace
    {
      // The family's declaration, handed to the parameters (base/plugins.h).
      const Plugins::Declaration declaration(Plugins::Family::postprocessor,
                                             declare_parameters);
    } // namespace


    template <int dim>
    std::vector<std::unique_ptr<Interface<dim>>>
    make_postprocessors(const Parameters &parameters, ParameterHandler &prm)
    {
      const auto       &names = parameters.output.postprocessors;
      const std::string where =
        "subsection 'Output', parameter 'Postprocessors'";
      if (std::find(names.begin(), names.end(), "reference checks") ==
          names.end())
        {
          // References given to a postprocessor that does not run would be
          // a silent pass.
          ReferenceParameters references;
          prm.enter_subsection("Output");
          prm.enter_subsection("Reference checks");
          references.parse_parameters(prm, parameters);
          prm.leave_subsection();
          prm.leave_subsection();
          if (references.any())
            throw InputError(where +
                             ": subsection 'Output/Reference checks' gives "
                             "references but 'reference checks' is not "
                             "listed. Add it to the list, or delete the "
                             "references.");
        }
      for (auto it = names.begin(); it != names.end(); ++it)
        if (std::find(it + 1, names.end(), *it) != names.end())
          throw InputError(where + ": '" + *it +
                           "' is listed twice. List each postprocessor once.");
      std::vector<std::unique_ptr<Interface<dim>>> result;
      prm.enter_subsection("Output");
      for (const auto &name : names)
        {
          result.push_back(Registry<dim>::instance().create(name, where));
          try
            {
              result.back()->parse_parameters(parameters, prm);
            }
          catch (const InputError &e)
            {
              prm.leave_subsection();
              throw InputError("subsection 'Output', postprocessor '" + name +
                               "': " + e.what());
            }
        }
      prm.leave_subsection();
      return result;
    }


    template std::vector<std::unique_ptr<Interface<2>>>
    make_postprocessors<2>(const Parameters &, ParameterHandler &);
    template std::vector<std::unique_ptr<Interface<3>>>
    make_postprocessors<3>(const Parameters &, ParameterHandler &);
  } // namespace Postprocess
} // namespace Signorini
