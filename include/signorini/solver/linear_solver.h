#ifndef signorini_solver_linear_solver_h
#define signorini_solver_linear_solver_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>

#include <memory>

class Amesos_BaseSolver;
class Epetra_LinearProblem;
class Epetra_MultiVector;

/**
 * The linear solve of one Newton iteration. Default: sparse LU by MUMPS
 * through Trilinos Amesos ("Amesos_Mumps"), which also handles the
 * unsymmetric saddle-point systems of contact; its analysis (ordering,
 * symbolic factorisation) is kept while the sparsity pattern stays the same,
 * so that a Newton iteration pays the numeric factorisation only. Option:
 * CG or GMRES preconditioned by Trilinos ML AMG whose near-null space is
 * the set of rigid-body modes (dim translations and dim(dim-1)/2
 * rotations) computed from the displacement support points,
 * since deal.II 9.4's AMG interface only knows translations. Contact
 * systems: GMRES with a block preconditioner (set_multipliers()).
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
      set_null_space(const Mapping<dim>    &mapping,
                     const DoFHandler<dim> &dof_handler,
                     const IndexSet        &locally_owned_dofs);

      /**
       * Contact systems: the system index space is u in [0, n_u) followed
       * by the multipliers; @p owned_multipliers are this rank's (system
       * numbering). With n_u < size, GMRES runs on the whole system with
       * the block lower-triangular preconditioner
       *   P = [A 0; C S],  S = D - C diag(A)^-1 B^T,
       * of the blocks [A B^T; C D] (u rows first): one ML AMG V-cycle with
       * rigid-body modes for A, and S (multipliers only: a surface-sized
       * matrix) factorised by MUMPS.
       */
      void
      set_multipliers(const types::global_dof_index n_u,
                      const IndexSet               &owned_multipliers);

      /**
       * The sparsity pattern of the system matrix was rebuilt (new DoFs, a
       * new pairing): the next direct solve analyses the matrix again
       * (ordering, symbolic factorisation). Until then, a direct solve only
       * refactorises the new values of the same pattern. The AMG hierarchy
       * of the displacement block is rebuilt too, unless the bulk is
       * linear (set_bulk_linear()) and the DoFs stayed.
       */
      void
      pattern_changed();

      /**
       * @p linear: the bulk stiffness does not depend on the iterate (every
       * material linear, small strain). A new pattern on the same DoFs then
       * changes only the contact terms of the displacement block, and the
       * AMG hierarchy built on its first matrix is kept until the DoFs
       * change (set_null_space()), as it is kept across the Newton
       * iterations of one pattern.
       */
      void
      set_bulk_linear(const bool linear);

      /** Solves A x = b; returns the Krylov iterations (0 for direct).
       * Throws LinearSolveError where the factorisation or the Krylov solve
       * fails. */
      unsigned int
      solve(const TrilinosWrappers::SparseMatrix &A,
            TrilinosWrappers::MPI::Vector        &x,
            const TrilinosWrappers::MPI::Vector  &b);

    private:
      const LinearSolverParameters        parameters;
      std::vector<std::vector<double>>    modes; // locally owned entries
      IndexSet                            owned;
      std::unique_ptr<Epetra_MultiVector> null_space;
      types::global_dof_index             n_u = 0;
      IndexSet                            owned_m; // multipliers, from 0

      // Direct solver kept across solves with the same pattern: the
      // analysis (ordering, symbolic factorisation) is done once per
      // pattern, the numeric factorisation at every solve.
      std::unique_ptr<Epetra_LinearProblem> direct_problem;
      std::unique_ptr<Amesos_BaseSolver>    direct_solver;
      const void                           *analysed_matrix = nullptr;
      // Contact systems with GMRES: the u block of the first matrix of the
      // pattern (of the DoFs if the bulk is linear) and its AMG hierarchy
      // (destroyed before it).
      bool                                               bulk_linear = false;
      std::unique_ptr<TrilinosWrappers::SparseMatrix>    kept_A;
      std::unique_ptr<TrilinosWrappers::PreconditionAMG> kept_amg;

      void
      solve_direct(const TrilinosWrappers::SparseMatrix &A,
                   TrilinosWrappers::MPI::Vector        &x,
                   const TrilinosWrappers::MPI::Vector  &b);

      /** The Krylov solves (throw SolverControl::NoConvergence). */
      unsigned int
      solve_iterative(const TrilinosWrappers::SparseMatrix &A,
                      TrilinosWrappers::MPI::Vector        &x,
                      const TrilinosWrappers::MPI::Vector  &b);

      unsigned int
      solve_blocks(const TrilinosWrappers::SparseMatrix &A,
                   TrilinosWrappers::MPI::Vector        &x,
                   const TrilinosWrappers::MPI::Vector  &b);
      void
      initialize_amg(TrilinosWrappers::PreconditionAMG    &amg,
                     const TrilinosWrappers::SparseMatrix &A);
    };
  } // namespace Solver
} // namespace Signorini

#endif
