#ifndef signorini_solver_load_stepper_h
#define signorini_solver_load_stepper_h

#include <deal.II/base/conditional_ostream.h>

#include <string>

/**
 * Quasi-static load stepping: the load path is a list of times; each load
 * step is solved as a whole first and, after a failure, in sub-steps of
 * half the remaining size (at most 'Load stepping/Maximum step cuts'
 * halvings per load step). What a sub-step is (the predictor, the
 * geometric loop, the Newton solves) belongs to the problem.
 */
namespace Signorini
{
  namespace Solver
  {
    using namespace dealii;

    /** What the load stepper asks of the problem it drives. */
    class QuasiStaticProblem
    {
    public:
      virtual ~QuasiStaticProblem() = default;

      /** Solves the sub-step from the converged state at @p start_time to
       * @p time; adds the Newton iterations spent to @p iterations. */
      virtual bool
      solve_step(const double  time,
                 const double  start_time,
                 unsigned int &iterations) = 0;
      /** The sub-step from @p start_time to @p time converged: its state
       * is the start of the next (history committed, predictor updated). */
      virtual void
      accept_step(const double time, const double start_time) = 0;
      /** The sub-step failed: back to the last converged state. */
      virtual void
      reject_step() = 0;
      /** Why the last solve_step() failed. */
      virtual std::string
      failure() const = 0;
    };

    /** Where a load step stands. */
    struct StepProgress
    {
      double       t_done      = 0; // end of the last converged sub-step
      double       t_sub_start = 0; // start of the last converged sub-step
      double       t_failed    = 0; // target of the last failed sub-step
      unsigned int cuts        = 0; // halvings so far in this load step
      unsigned int iterations  = 0; // Newton iterations, failures included
    };

    class LoadStepper
    {
    public:
      LoadStepper(const unsigned int max_cuts, const ConditionalOStream &out);

      /** Advances @p problem from progress.t_done to @p t_end, halving the
       * sub-step after each failure. False when the cuts are used up
       * (progress.t_failed: the target that failed last). */
      bool
      advance(QuasiStaticProblem &problem,
              StepProgress       &progress,
              const double        t_end) const;

    private:
      const unsigned int        max_cuts;
      const ConditionalOStream &out;
    };
  } // namespace Solver
} // namespace Signorini

#endif
