#ifndef signorini_postprocess_contact_checks_h
#define signorini_postprocess_contact_checks_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/reference_parameters.h>

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

/**
 * The contact checks of subsection 'Output/Reference checks'
 * (doc/verification.md lists which test asserts what): after each written load
 * step, each computed quantity against its reference with a tolerance, as a
 * structured result.
 *
 * Against references: the largest pressure p0, the contact half-width a,
 * the pressure profile (relative L2 error), the stick zone of
 * Cattaneo-Mindlin partial slip, the friction force ratio in steady
 * sliding, the total contact force, displacements at points.
 * Facts that hold for every converged state and that the residual does not
 * restate: action = reaction between the displacement rows and the
 * multipliers, the direction of friction against the slip, the gap of
 * closed points, smooth forces in steady sliding.
 */
namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    template <int dim>
    class ContactChecks
    {
    public:
      ContactChecks(const Parameters          &parameters,
                    const ReferenceParameters &reference);

      /**
       * The checks of the written step @p data (with its contact problem:
       * the converged system vector, the force level of the step, the
       * largest internal or external force norm, which is the scale of a
       * contact force that is zero up to round-off). Checks that keep
       * history (stick zone after a reversal, force variation) record the
       * step.
       */
      std::vector<CheckResult>
      evaluate(const StepData<dim> &data);

      /** The 'Point values' checks of the step ending at @p time (with or
       * without contact; from 'Point values from time' on). */
      std::vector<CheckResult>
      point_values(
        const double time,
        const std::function<double(const Point<dim> &, const unsigned int)>
          &displacement_at) const;

    private:
      using Records =
        std::vector<typename Contact::ContactProblem<dim>::PointRecord>;
      using PairSummary = typename Contact::ContactProblem<dim>::PairSummary;

      // One function per check (see the class documentation).
      CheckResult
      check_max_pressure(const Records &records, const double exact) const;
      CheckResult
      check_half_width(const Records &records, const double exact) const;
      CheckResult
      check_pressure_profile(const Records &records, const double time) const;
      CheckResult
      check_friction_ratio(const PairSummary &pair) const;
      CheckResult
      check_force_variation() const;
      CheckResult
      check_gaps(const Records &records, const double time) const;
      CheckResult
      check_contact_force(const PairSummary &pair, const double time) const;
      CheckResult
      check_point_value(
        const ReferenceParameters::PointValue &pv,
        const std::function<double(const Point<dim> &, const unsigned int)>
          &displacement_at) const;

      void
      check_stick_zone(const Records                      &records,
                       const Contact::ContactProblem<dim> &contact,
                       std::vector<CheckResult>           &results);

      void
      check_laws(const StepData<dim>      &data,
                 std::vector<CheckResult> &results) const;

      bool
      is_last_step(const double time) const;

      const Parameters                    &parameters;
      const ReferenceParameters           &reference;
      std::unique_ptr<FunctionParser<dim>> exact_pressure, exact_force;
      // p0 and a, expressions of t (nullptr: not checked).
      std::unique_ptr<FunctionParser<dim>> exact_p0, exact_a;
      // The components of 'Contact force' that are compared (not '*').
      std::array<bool, dim> force_compared;

      // Force variation check: the forces of pair 1 at the steady steps.
      std::vector<Tensor<1, dim>> steady_forces;

      // Stick zone check: the tangential direction, the last tangential
      // force, the force at the last reversal and the loading direction.
      Tensor<1, dim> mindlin_tangent;
      double         mindlin_q_last = 0, mindlin_q_turn = 0;
      int            mindlin_direction = 0;
      bool           mindlin_turned    = false;
    };
  } // namespace Postprocess
} // namespace Signorini

#endif
