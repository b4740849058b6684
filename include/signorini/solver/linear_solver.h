#ifndef signorini_solver_linear_solver_h
#define signorini_solver_linear_solver_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/core/parameters.h>

#include <memory>

class Epetra_MultiVector;

/**
 * The linear solve of one Newton iteration. Default: sparse LU by MUMPS
 * through Trilinos Amesos (TrilinosWrappers::SolverDirect with
 * "Amesos_Mumps"), which also handles the unsymmetric saddle-point systems of
 * contact. Option: CG or GMRES preconditioned by Trilinos ML AMG whose
 * near-null space is the set of rigid-body modes (dim translations and
 * dim(dim-1)/2 rotations) computed from the displacement support points,
 * since deal.II 9.4's AMG interface only knows translations.
 */
namespace Signorini
{
  namespace Solver
  {
    using namespace dealii;

    template <int dim>
    class LinearSolver
    {
    public:
      explicit LinearSolver(const LinearSolverParameters &parameters);
      ~LinearSolver();

      /**
       * Rigid-body modes of the displacement field of @p dof_handler (first
       * dim components of its FE); call after every change of the DoFs.
       */
      void
      set_null_space(const DoFHandler<dim> &dof_handler,
                     const IndexSet &       locally_owned_dofs);

      /** Solves A x = b; returns the Krylov iterations (0 for direct). */
      unsigned int
      solve(const TrilinosWrappers::SparseMatrix &A,
            TrilinosWrappers::MPI::Vector &       x,
            const TrilinosWrappers::MPI::Vector & b);

    private:
      const LinearSolverParameters        parameters;
      std::vector<std::vector<double>>    modes; // locally owned entries
      IndexSet                            owned;
      std::unique_ptr<Epetra_MultiVector> null_space;
    };
  } // namespace Solver
} // namespace Signorini

#endif
