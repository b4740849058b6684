// Quasi-static load stepping with step cuts.
#include <signorini/base/format.h>
#include <signorini/solver/load_stepper.h>

namespace Signorini
{
  namespace Solver
  {
    LoadStepper::LoadStepper(const unsigned int        max_cuts,
                             const ConditionalOStream &out)
        : max_cuts(max_cuts)
        , out(out)
    {
    }


    bool
    LoadStepper::advance(QuasiStaticProblem &problem,
                         StepProgress       &progress,
                         const double        t_end) const
    {
      double t_target = t_end;
      while (progress.t_done < t_end)
        {
          unsigned int iterations = 0;
          const bool   converged =
            problem.solve_step(t_target, progress.t_done, iterations);
          // Failed attempts cost iterations too: they count.
          progress.iterations += iterations;
          if (converged)
            {
              problem.accept_step(t_target, progress.t_done);
              progress.t_sub_start = progress.t_done;
              progress.t_done      = t_target;
              t_target             = t_end;
              continue;
            }
          problem.reject_step();
          progress.t_failed = t_target;
          if (++progress.cuts > max_cuts)
            return false;
          const std::string why = problem.failure();
          t_target              = 0.5 * (progress.t_done + t_target);
          out << "  step not converged (" << why.substr(0, why.find("; "))
              << "): cut to t = " << Postprocess::format(t_target, 4)
              << std::endl;
        }
      return true;
    }
  } // namespace Solver
} // namespace Signorini
