#ifndef signorini_solver_roundoff_h
#define signorini_solver_roundoff_h

#include <deal.II/base/mpi.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

namespace Signorini
{
  namespace Solver
  {
    using namespace dealii;

    /**
     * || |K| |x| ||_2, the l2 norm over the rows of K of sum_j |K_ij x_j|
     * (all ranks): the size of the terms whose sum is K x, so eps times it
     * is the round-off of K x. Newton's round-off floor uses it for the
     * internal force, where a rigid motion or a stiffness contrast makes the
     * terms cancel (doc/robustness.md, "Round-off floor"). @p x is a ghosted
     * vector; columns it does not hold count as zero. The rows of the DoFs
     * @p constraints constrains are left out: they are no equations (their
     * residual is zero by construction), and their placeholder diagonal
     * times a constrained multiplier (an axis node's lambda, 1e8 Pa) made
     * the floor 1e-5 of the force level. A nonempty @p s (ghosted, the
     * layout of @p x) adds sum_j |K_ij| s_j: an absolute round-off s_j of
     * unknown j besides eps |x_j| (the positions of a finite-strain body).
     */
    double
    absolute_product_norm(
      const TrilinosWrappers::SparseMatrix &K,
      const TrilinosWrappers::MPI::Vector  &x,
      const AffineConstraints<double>      &constraints,
      const MPI_Comm                        comm,
      const TrilinosWrappers::MPI::Vector &s = TrilinosWrappers::MPI::Vector());
  } // namespace Solver
} // namespace Signorini

#endif
