// The postprocessor 'reference checks': every check of its subsection
// 'Output/Reference checks' (doc/verification.md lists which test asserts
// what), the bulk ones (SolutionErrors) and, with contact, the contact
// ones (ContactChecks).
#include <signorini/postprocess/contact_checks.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/solution_errors.h>

#include <memory>
#include <set>
#include <string>

namespace Signorini
{
  namespace Postprocess
  {
    template <int dim>
    class ReferenceChecks : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.enter_subsection("Reference checks");
        ReferenceParameters::declare_parameters(prm);
        prm.leave_subsection();
      }

      void
      parse_parameters(const Parameters &parameters,
                       ParameterHandler &prm) override
      {
        prm.enter_subsection("Reference checks");
        try
          {
            reference.parse_parameters(prm, parameters);
          }
        catch (...)
          {
            prm.leave_subsection();
            throw;
          }
        prm.leave_subsection();
        solution = std::make_unique<SolutionErrors<dim>>(parameters, reference);
        contact  = std::make_unique<ContactChecks<dim>>(parameters, reference);
      }

      // Every point of 'Point values' lies in a body, and 'History
      // quantity' names a quantity some material of the run has.
      void
      initialize(const StepData<dim> &data) override
      {
        const auto &points = reference.point_values;
        for (unsigned int k = 0; k < points.size(); ++k)
          {
            Point<dim> p;
            for (unsigned int d = 0; d < dim && d < points[k].point.size(); ++d)
              p[d] = points[k].point[d];
            try
              {
                data.displacement_at(p, 0);
              }
            catch (const InputError &e)
              {
                throw InputError("subsection 'Output/Reference checks', "
                                 "parameter 'Point values', entry " +
                                 std::to_string(k + 1) + ": " + e.what() +
                                 " Give a point of a body.");
              }
          }
        check_history_quantity(data);
      }

      std::vector<CheckResult>
      execute(const StepData<dim> &data) override
      {
        auto results = solution->evaluate(data);
        if (data.contact)
          for (auto &r : contact->evaluate(data))
            results.push_back(std::move(r));
        for (auto &r : contact->point_values(data.time, data.displacement_at))
          results.push_back(std::move(r));
        return results;
      }

    private:
      void
      check_history_quantity(const StepData<dim> &data) const
      {
        const std::string &name = reference.history_name;
        if (name.empty())
          return;
        std::set<std::string> names;
        for (const auto &[id, material] : data.materials)
          for (const auto &n : material->history_output_names())
            names.insert(n);
        if (names.count(name) != 0)
          return;
        std::string known;
        for (const auto &n : names)
          known += (known.empty() ? "" : ", ") + n;
        throw InputError("subsection 'Output/Reference checks', parameter "
                         "'History quantity': no material of the run has a "
                         "history quantity '" +
                         name + "'" +
                         (known.empty() ? std::string(" (none has any)") :
                                          " (they have: " + known + ")") +
                         ". Correct the name or remove the reference.");
      }

      ReferenceParameters                  reference;
      std::unique_ptr<SolutionErrors<dim>> solution;
      std::unique_ptr<ContactChecks<dim>>  contact;
    };
  } // namespace Postprocess
} // namespace Signorini

SIGNORINI_REGISTER_POSTPROCESSOR(
  Signorini::Postprocess::ReferenceChecks,
  "reference checks",
  "the checks of its subsection 'Reference checks' against exact solutions "
  "and closed forms")
