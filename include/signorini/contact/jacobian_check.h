#ifndef signorini_contact_jacobian_check_h
#define signorini_contact_jacobian_check_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/contact/contact_problem.h>

#include <array>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    /** What check_jacobian() measured at one iterate. */
    struct JacobianCheckResult
    {
      unsigned int n_checked = 0; // columns compared
      unsigned int n_kinked  = 0; // skipped: a status flips across them
      double       worst     = 0; // largest relative column error
    };

    /**
     * Development check ('Newton/Check Jacobian'): every column j of the
     * assembled contact matrix K_c (the columns a contact term touches)
     * against the central difference -(r(x + h e_j) - r(x - h e_j)) / 2h
     * of the contact part r = -R_c of the right-hand side, with the pairing
     * fixed as in Newton. Columns whose perturbation flips a status
     * straddle a kink and are skipped (counted). Errors are relative to the
     * largest column of the same block (u, lambda, Lambda).
     *
     * @p state is the ghosted system vector (u | lambda | Lambda) of the
     * iterate; it is perturbed and given back unchanged, and the contact
     * problem's statuses are those of @p state again on return.
     * @p matrix_layout and @p rhs_layout give the sparsity and the
     * (writable ghosted) vector layout of the system; @p n_u and @p n_l the
     * sizes of the u and lambda blocks. The step of block b is 1e-6 of its
     * largest magnitude, never below 1e-6 @p floor[b]. Collective.
     */
    template <int dim>
    JacobianCheckResult
    check_jacobian(ContactProblem<dim>                  &contact,
                   TrilinosWrappers::MPI::Vector        &state,
                   const TrilinosWrappers::MPI::Vector  &step_start,
                   const AffineConstraints<double>      &constraints,
                   const TrilinosWrappers::SparseMatrix &matrix_layout,
                   const TrilinosWrappers::MPI::Vector  &rhs_layout,
                   const TrilinosWrappers::MPI::Vector  &force_layout,
                   const types::global_dof_index         n_u,
                   const std::array<double, 3>          &floor);
  } // namespace Contact
} // namespace Signorini

#endif
