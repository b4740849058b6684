#ifndef signorini_postprocess_solution_errors_h
#define signorini_postprocess_solution_errors_h

#include <deal.II/base/function_parser.h>

#include <signorini/base/parameters.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/reference_parameters.h>

#include <memory>
#include <vector>

namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    /**
     * The bulk checks of subsection 'Output/Reference checks': the displacement
     * against 'Displacement' (relative L2 error over the bodies) and the
     * stress against 'Stress' (largest pointwise error over the largest
     * reference stress, at the Gauss points of degree + 2), each against
     * 'Tolerance'. The stress is the materials' at the computed strain
     * (with the projected volumetric strain where the run uses it). A
     * history quantity against 'History quantity': the largest error over
     * the largest reference value, at the bulk quadrature points (where the
     * history lives) of the cells whose material has the quantity.
     */
    template <int dim>
    class SolutionErrors
    {
    public:
      SolutionErrors(const Parameters          &parameters,
                     const ReferenceParameters &reference);

      /** The checks of the step (none without references). */
      std::vector<CheckResult>
      evaluate(const StepData<dim> &data) const;

    private:
      struct Sums
      {
        double u_error2 = 0, u_norm2 = 0, s_error_max = 0, s_norm_max = 0;
      };
      Sums
      local_sums(const StepData<dim> &data) const;

      /** This rank's largest history error and reference value. */
      std::pair<double, double>
      local_history_error(const StepData<dim> &data) const;

      const Parameters                    &parameters;
      const ReferenceParameters           &reference;
      std::unique_ptr<FunctionParser<dim>> u_exact, s_exact, h_exact;
    };
  } // namespace Postprocess
} // namespace Signorini

#endif
