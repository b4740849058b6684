#ifndef signorini_solver_nonlinear_problem_h
#define signorini_solver_nonlinear_problem_h

#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <memory>
#include <string>

/**
 * What the Newton solver (newton_solver.h) asks of the problem it solves:
 * the residual at the current iterate with what the convergence rules need
 * to judge it, the linearised solve, and a copy of the iterate's state for
 * trial evaluations. The problem owns the iterate, the statuses and their
 * history; the solver owns the iteration: when to evaluate, solve, search
 * along the update or stop.
 */
namespace Signorini
{
  namespace Solver
  {
    using namespace dealii;

    /** The residual of one evaluation and what the convergence rules need. */
    struct Evaluation
    {
      /** Norms of the residual rows of u, lambda and Lambda. */
      std::array<double, 3> block = {{0, 0, 0}};
      /** The larger of the internal and external force norms at the
       * iterate; their maximum over the iterates of a load step is the
       * force level the relative tolerances refer to. */
      double force = 0;
      /** Round-off scales of the residual [N]: of the bulk terms (|K||x|
       * of the last Jacobian) and of the contact terms (0 without). */
      double bulk_roundoff    = 0;
      double contact_roundoff = 0;
      /** Statuses that changed since the previous iterate. */
      unsigned int n_changed = 0;
      /** A frozen status (anti-cycling) that the plain law contradicts. */
      bool frozen_contradicted = false;
      /** The equations are linear once the statuses are fixed (a full
       * direct step then leaves only round-off). */
      bool linear_at_fixed_statuses = false;
      /** Prescribed values the iterate has not reached yet (the first
       * update of the solve takes it there): never converged. */
      bool values_pending = false;
    };

    /** The result of the linearised solve at an iterate. */
    struct LinearisedStep
    {
      TrilinosWrappers::MPI::Vector update; // owned
      /** The update moves prescribed values (the pending ones of the
       * evaluation): it is taken whole, never searched along. */
      bool prescribes_values = false;
      /** A direct solve of the Jacobian at the iterate's own statuses (no
       * status opened for this solve only). */
      bool exact = false;
      /** Rigid motions nothing held at this solve ("" if none). */
      std::string held_motions;
    };

    class NonlinearProblem
    {
    public:
      /** The problem's state at an iterate, for trial evaluations. */
      class Snapshot
      {
      public:
        virtual ~Snapshot() = default;
      };

      virtual ~NonlinearProblem() = default;

      /** Before the first evaluation of a solve. */
      virtual void
      start_solve() = 0;
      /** The residual at the current iterate. A trial evaluation (line
       * search) is not an iterate of the status history, and only its
       * block norms are filled in. */
      virtual Evaluation
      evaluate(const bool trial) = 0;
      /** Called once per iterate, after its evaluation and judgement:
       * the log row (residuals over @p force_level, statuses,
       * @p converged). */
      virtual void
      record_iterate(const unsigned int iteration,
                     const Evaluation  &evaluation,
                     const double       force_level,
                     const bool         converged) = 0;
      /** Development checks of an iterate with a finite residual (the
       * Jacobian against finite differences). */
      virtual void
      check_iterate() = 0;
      /** Why the residual is not finite (the loads), for the message. */
      virtual std::string
      non_finite_cause() const = 0;
      /** Releases the frozen statuses the law contradicts; the iterate is
       * evaluated again. */
      virtual void
      release_contradicted() = 0;
      /** Jacobian at the current iterate and its solve. */
      virtual LinearisedStep
      solve_linearised(const unsigned int iteration) = 0;

      /** The iterate (owned layout) and its replacement. */
      virtual TrilinosWrappers::MPI::Vector
      iterate() const = 0;
      virtual void
      set_iterate(const TrilinosWrappers::MPI::Vector &owned) = 0;
      virtual std::unique_ptr<Snapshot>
      save() const = 0;
      virtual void
      restore(const Snapshot &snapshot) = 0;
    };
  } // namespace Solver
} // namespace Signorini

#endif
