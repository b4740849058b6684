// The run along the load path: set-up report, load steps with step cuts
// (Solver::LoadStepper, with the LoadStep as its problem), adaptive
// cycles within and between steps, the end of the run.
#include <deal.II/base/utilities.h>

#include <signorini/base/format.h>
#include <signorini/driver/simulation.h>

#include <chrono>
#include <iomanip>
#include <sstream>
#include <unistd.h>

namespace Signorini
{
  using Postprocess::format;


  template <int dim>
  void
  Simulation<dim>::run()
  {
    make_mesh();
    setup_system();
    print_setup();
    results.prepare_output();
    const auto &times = parameters.load_stepping.step_times;
    load_step.mark_converged(false);
    const Solver::LoadStepper stepper(parameters.load_stepping.max_cuts, pcout);
    double                    t_done = 0;
    const auto                start  = std::chrono::steady_clock::now();
    double                    last_step_seconds = 0;
    for (unsigned int step = 1; step <= times.size(); ++step)
      {
        print_step_header(step, t_done, start, last_step_seconds);
        const auto step_start = std::chrono::steady_clock::now();
        t_done                = run_load_step(step, t_done, stepper);
        last_step_seconds     = std::chrono::duration<double>(
                              std::chrono::steady_clock::now() - step_start)
                              .count();
      }
    report.print_run_summary(times.size(), 0);
    finish_run();
  }


  template <int dim>
  void
  Simulation<dim>::check_input()
  {
    make_mesh();
    setup_system();
    print_setup();
  }


  // "Load step k of n, t = ...", with the time of the last step, the
  // elapsed and the estimated remaining time (from the share of the load
  // path done) on a terminal only: log files and test outputs stay
  // reproducible. A quiet run prints this line (and nothing else per step)
  // on a terminal only. (Under OpenMPI the ranks' stdout is a
  // pseudo-terminal even when mpirun's output goes to a file; their stderr
  // is a pipe.)
  template <int dim>
  void
  Simulation<dim>::print_step_header(
    const unsigned int                           step,
    const double                                 t_done,
    const std::chrono::steady_clock::time_point &start,
    const double                                 last_step_seconds) const
  {
    const auto &times = parameters.load_stepping.step_times;
    const bool  terminal =
      isatty(STDOUT_FILENO) != 0 && isatty(STDERR_FILENO) != 0;
    const bool quiet = parameters.output.verbosity == Verbosity::quiet;
    if (quiet && !terminal)
      return;
    std::ostringstream line;
    line << "Load step " << step << " of " << times.size()
         << ", t = " << format(times[step - 1], 4);
    if (terminal && t_done > 0)
      {
        const double elapsed = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();
        const double left =
          elapsed / t_done * std::max(0., times.back() - t_done);
        line << std::fixed << std::setprecision(1) << "  (last step "
             << last_step_seconds << " s, elapsed " << elapsed << " s, about "
             << left << " s left)";
      }
    (quiet ? sout : pcout) << line.str() << std::endl;
  }


  // One load step from @p t_done: sub-steps with cuts, adaptive cycles
  // after it ('Steps = every' or 'last'), its results, adaptive cycles for
  // the next step ('between'). Returns the time reached.
  template <int dim>
  double
  Simulation<dim>::run_load_step(const unsigned int         step,
                                 const double               t_done,
                                 const Solver::LoadStepper &stepper)
  {
    const auto &times    = parameters.load_stepping.step_times;
    report.position.step = step;
    report.start_step();
    Solver::StepProgress progress;
    progress.t_done      = t_done;
    progress.t_sub_start = t_done;
    advance_or_stop(step, t_done, progress, stepper);
    const auto &adaptivity = parameters.adaptivity;
    using AdaptedSteps     = AdaptivityParameters::Steps;
    if (adaptivity.steps == AdaptedSteps::every ||
        (adaptivity.steps == AdaptedSteps::last && step == times.size()))
      adapt_in_step(step, t_done, progress, stepper);
    report.counts.step_cuts = progress.cuts;
    write_step_results(step, times[step - 1], progress.iterations);
    // 'Steps = between': the mesh follows the converged state; the next
    // step starts on it from the transferred state (its increment: the
    // extrapolated predictor's).
    if (adaptivity.steps == AdaptedSteps::between && step < times.size())
      for (unsigned int cycle = 1; cycle <= adaptivity.cycles; ++cycle)
        {
          pcout << "  adaptive cycle " << cycle << " of " << adaptivity.cycles
                << " for the next step" << std::endl;
          if (!adapt_mesh(progress.t_done, progress.t_sub_start))
            break;
          load_step.mark_converged(true);
        }
    return progress.t_done;
  }


  // Adaptive refinement within a step: refine, transfer, solve the last
  // sub-step again on the new mesh from the transferred converged state
  // (the history from its start) and commit it; if that fails, from its
  // transferred start, with step cuts.
  template <int dim>
  void
  Simulation<dim>::adapt_in_step(const unsigned int         step,
                                 const double               t_step_start,
                                 Solver::StepProgress      &progress,
                                 const Solver::LoadStepper &stepper)
  {
    const unsigned int cycles = parameters.adaptivity.cycles;
    for (unsigned int cycle = 1; cycle <= cycles; ++cycle)
      {
        pcout << "  adaptive cycle " << cycle << " of " << cycles << std::endl;
        if (!adapt_mesh(progress.t_done, progress.t_sub_start))
          break;
        // The sub-step is solved again from its start, history included.
        system.history.restore_start();
        unsigned int iterations = 0;
        const bool   ok         = load_step.solve(progress.t_done,
                                        progress.t_sub_start,
                                        iterations,
                                        true);
        progress.iterations += iterations;
        if (ok)
          load_step.accept_step(progress.t_done, progress.t_sub_start);
        else
          {
            pcout << "  not converged on the refined mesh: again from the "
                     "start of the step"
                  << std::endl;
            load_step.restart_from_step_start();
            progress.t_done = progress.t_sub_start;
            advance_or_stop(step, t_step_start, progress, stepper);
          }
      }
  }


  // The load stepper's advance to the end of the step; when the cuts are
  // used up, the last converged sub-step of this step, if any, is written
  // as the step's results (at its time), the run summary printed, and the
  // run stopped.
  template <int dim>
  void
  Simulation<dim>::advance_or_stop(const unsigned int         step,
                                   const double               t_step_start,
                                   Solver::StepProgress      &progress,
                                   const Solver::LoadStepper &stepper)
  {
    if (stepper.advance(load_step,
                        progress,
                        parameters.load_stepping.step_times[step - 1]))
      return;
    const bool partial = progress.t_done > t_step_start;
    if (partial)
      {
        report.counts.step_cuts = progress.cuts - 1;
        load_step.restore_last_converged(progress.t_done);
        pcout << "  results of the last converged sub-step (t = "
              << format(progress.t_done, 4) << ") written as step " << step
              << std::endl;
        write_step_results(step, progress.t_done, progress.iterations);
      }
    report.print_run_summary(step - (partial ? 0 : 1), step);
    throw RunError(
      "load step " + std::to_string(step) + " did not converge between t = " +
      format(progress.t_done, 4) + " and t = " + format(progress.t_failed, 4) +
      " after " + std::to_string(parameters.load_stepping.max_cuts) +
      " step cuts: " + load_step.failure() +
      ". The results of the completed steps" +
      (partial ? " and of the last converged sub-step" : "") + " are in '" +
      parameters.output.directory + "'. " + load_step.failure_advice());
  }


  template <int dim>
  void
  Simulation<dim>::write_step_results(const unsigned int step,
                                      const double       time,
                                      const unsigned int iterations)
  {
    results.write(step, time, iterations, load_step.force_level());
  }


  // After the last step: the Jacobian check's verdict, the count of
  // failed reference checks, the timing and memory summary.
  template <int dim>
  void
  Simulation<dim>::finish_run()
  {
    const bool jacobian_checked =
      parameters.newton.check_jacobian && contact.active();
    if (jacobian_checked)
      sout << "Jacobian check: largest relative error of the contact "
              "Jacobian over the run = "
           << std::scientific << std::setprecision(1)
           << equilibrium.jacobian_error() << " (tolerance 1.0e-06): "
           << (equilibrium.jacobian_error() < 1e-6 ? "PASS" : "FAIL")
           << std::defaultfloat << std::endl;
    if (jacobian_checked && !(equilibrium.jacobian_error() < 1e-6))
      report.count_failed_check();
    if (report.failed_checks() > 0)
      sout << "Reference checks: " << report.failed_checks()
           << " FAIL(s) over the run; exit code 4" << std::endl;
    if (parameters.output.timing_summary)
      {
        timer.print_wall_time_statistics(mpi_communicator);
        // Peak resident memory (VmHWM) of each rank.
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        const double mb = memory.VmHWM / 1024.;
        sout << "Peak memory: " << std::fixed << std::setprecision(1)
             << Utilities::MPI::max(mb, mpi_communicator)
             << " MB on the largest rank, "
             << Utilities::MPI::sum(mb, mpi_communicator) << " MB over "
             << Utilities::MPI::n_mpi_processes(mpi_communicator) << " rank(s)"
             << std::defaultfloat << std::setprecision(6) << std::endl;
      }
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
