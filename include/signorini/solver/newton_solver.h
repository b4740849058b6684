#ifndef signorini_solver_newton_solver_h
#define signorini_solver_newton_solver_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <signorini/solver/nonlinear_problem.h>

#include <string>
#include <vector>

/**
 * The generalised Newton method of theory.md F7 on a
 * NonlinearProblem: the statuses are decided again at every iterate, and a
 * solve has converged when every block of the residual is small and no
 * status changed since the previous iterate. The convergence rules (the
 * tolerances against the force level, the round-off floor, stagnation), the
 * line search on the residual norm and the reason of a failure live here;
 * what an iterate is, how its residual and Jacobian are assembled and
 * solved, and how a status is logged belong to the problem.
 */
namespace Signorini
{
  namespace Solver
  {
    /** Why a Newton solve (or a load step's geometric loop) failed. */
    enum class NewtonFailure
    {
      non_finite,      // NaN or inf in the residual
      statuses,        // contact statuses still changing
      stagnation,      // settled statuses, residual no longer decreasing
      iteration_limit, // still converging when the iterations ran out
      geometric,       // the pairing loop did not settle
      linear_solve     // the linearised system could not be solved
    };

    class NewtonSolver
    {
    public:
      struct Parameters
      {
        unsigned int max_iterations     = 20;
        double       relative_tolerance = 1e-10; // of the force level
        double       absolute_tolerance = 0;     // [N]
        /** Halvings of a full update that made the residual grow; 0: full
         * updates always. */
        unsigned int line_search_steps = 0;
        /** Only the round-off acceptances print (no line search rows). */
        bool quiet = false;
      };

      struct Result
      {
        bool         converged  = false;
        unsigned int iterations = 0;
        /** Converged at the round-off floor of an exact step (linear
         * equations at settled statuses, a direct solve, the full update),
         * with this residual and floor over the force level. */
        bool   exact_at_end    = false;
        double residual_at_end = 0;
        double floor_at_end    = 0;
        /** Not converged: why, and what kind of failure. */
        NewtonFailure failure = NewtonFailure::iteration_limit;
        std::string   why;
        /** Line searches that took less than the full update. */
        unsigned int line_searches = 0;

        /** The log line of a residual that ended at the floor of an exact
         * step (printed when a later solve is skipped for it). */
        std::string
        exact_floor_line() const;
      };

      NewtonSolver(const Parameters         &parameters,
                   const ConditionalOStream &out,
                   TimerOutput              &timer);

      /**
       * Newton iterations on @p problem from its current iterate.
       * @p tolerance > 0 replaces the relative tolerance once the statuses
       * have settled (a solve that hands over to a new pairing).
       * @p force_level is the force level of the load step so far (0 at its
       * start): the largest internal or external force norm of its
       * iterates, raised by this solve's.
       */
      Result
      solve(NonlinearProblem &problem,
            double           &force_level,
            const double      tolerance = 0.) const;

    private:
      /** What the rules say of an evaluated iterate. */
      struct Verdict
      {
        bool   converged      = false;
        bool   release        = false; // frozen statuses to release first
        bool   at_exact_floor = false;
        double floor          = 0; // round-off floor [N]
      };
      /** Applies the convergence rules to @p evaluation (residual
       * @p residual) with the history of the solve in @p settled_before,
       * @p residual_before and whether the iterate came from an exact
       * step. */
      Verdict
      judge(const Evaluation  &evaluation,
            const double       residual,
            const double       force_level,
            const double       tolerance,
            const unsigned int iteration,
            const bool         step_exact,
            bool              &settled_before,
            double            &residual_before) const;
      /** The last solve's base, update and residual, tried at the next
       * evaluation (a line search is pending if @p pending). */
      struct SearchTrial
      {
        bool                          pending = false;
        TrilinosWrappers::MPI::Vector base, update;
        double                        residual = 0;
      };
      /** Evaluates the iterate, which is the full update of a pending
       * @p trial: if its residual did not fall, the line search's iterate
       * instead (then @p step_exact is false unless the whole step was
       * taken). */
      Evaluation
      evaluate_trial(NonlinearProblem &problem,
                     SearchTrial      &trial,
                     bool             &step_exact,
                     Result           &result) const;
      /** Backtracking after a full update that made the residual grow from
       * @p residual_now to @p residual_full: the fraction of @p update
       * from @p base to take. */
      double
      line_search(NonlinearProblem                    &problem,
                  const TrilinosWrappers::MPI::Vector &base,
                  const TrilinosWrappers::MPI::Vector &update,
                  const double                         residual_now,
                  const double                         residual_full,
                  Result                              &result) const;

      const Parameters          parameters;
      const ConditionalOStream &out;
      TimerOutput              &timer;
    };
  } // namespace Solver
} // namespace Signorini

#endif
