// The postprocessor 'reference checks': every check of subsection
// 'Reference solution' (doc/verification.md lists which test asserts
// what), the bulk ones (SolutionErrors) and, with contact, the contact
// ones (ContactChecks).
#include <signorini/postprocess/contact_checks.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/solution_errors.h>

#include <memory>

namespace Signorini
{
  namespace Postprocess
  {
    template <int dim>
    class ReferenceChecks : public Interface<dim>
    {
    public:
      // Its parameters are subsection 'Reference solution' (base/parameters).
      static void
      declare_parameters(ParameterHandler &)
      {
      }

      void
      parse_parameters(const Parameters &parameters,
                       ParameterHandler &) override
      {
        solution = std::make_unique<SolutionErrors<dim>>(parameters);
        contact  = std::make_unique<ContactChecks<dim>>(parameters);
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
      std::unique_ptr<SolutionErrors<dim>> solution;
      std::unique_ptr<ContactChecks<dim>>  contact;
    };
  } // namespace Postprocess
} // namespace Signorini

SIGNORINI_REGISTER_POSTPROCESSOR(
  Signorini::Postprocess::ReferenceChecks,
  "reference checks",
  "the checks of subsection 'Reference solution' against its references")
