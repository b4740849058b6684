#ifndef signorini_postprocess_field_slips_h
#define signorini_postprocess_field_slips_h

#include <deal.II/base/tensor.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/postprocess/interface.h>

#include <vector>

/**
 * The slip of the contact points as the bodies move, for the slip-law
 * check (ContactChecks): computed from the displacement field and the
 * obstacles' prescribed motion alone, so that the check does not read the
 * slip the law was given (Pairing::slip() and the assembly compute that
 * one from the face DoFs and the obstacle increment of the pairing).
 */
namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    /**
     * For every point of the contact pairing (in its order; zero where
     * unpaired): the tangential part of v = du(X_e) - du_m over the step,
     * with du = u - u_start the displacement field's increment at the
     * slave's material point X_e, evaluated by deal.II's remote point
     * evaluation on the cells of the slave's body; du_m that of the
     * master's material point (a meshed master: the field at the paired
     * point of its face, on the master body's cells; a rigid obstacle: its
     * prescribed rigid motion between the step start and now, at the
     * slave's current position). Collective.
     */
    template <int dim>
    std::vector<Tensor<1, dim>>
    field_slips(const Contact::ContactProblem<dim> &contact,
                const StepData<dim>                &data);
  } // namespace Postprocess
} // namespace Signorini

#endif
