#ifndef signorini_driver_simulation_h
#define signorini_driver_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/assembler.h>
#include <signorini/bulk/boundary_conditions.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/driver/discrete_system.h>
#include <signorini/driver/equilibrium_problem.h>
#include <signorini/driver/load_step.h>
#include <signorini/driver/results.h>
#include <signorini/geometry/shapes/interface.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/run_report.h>
#include <signorini/solver/linear_solver.h>
#include <signorini/solver/load_stepper.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

/**
 * One Signorini run: mesh, finite element space, quasi-static load stepping
 * with a Newton loop per step, output. The residual convention is the one of
 * doc/theory.md section 4: R = F_int - F_ext, Newton solves K dU = -R, with
 * Dirichlet values imposed on the iterate and homogeneous constraints on the
 * update. A step that does not converge is halved and retried (Load
 * stepping/Maximum step cuts) before the run stops with a RunError.
 */
namespace Signorini
{
  using namespace dealii;

  /**
   * One run of a scene (the application's driver, as in step-44's Solid
   * run()): it creates the plug-ins the parameters select, owns the
   * DiscreteSystem (mesh, DoFs, vectors) and wires the pieces: the bulk
   * assembler and the contact problem, the EquilibriumProblem the Newton
   * solver iterates on, the LoadStep the load stepper advances, the
   * Results written after each step. Its members are defined in
   * source/driver/: simulation.cc (set-up), simulation_run.cc (the run over
   * the load steps: cuts, adaptive cycles, the end of the run) and
   * simulation_adaptivity.cc (refinement and the transfer of the state).
   */
  template <int dim>
  class Simulation
  {
  public:
    /** @p prm: the parameters read into @p parameters (the plug-ins read
     * their own from it). */
    Simulation(const Parameters &parameters,
               ParameterHandler &prm,
               const MPI_Comm    mpi_communicator);

    void
    run();

    /** The set-up of run() alone: the mesh, the unknowns and every check
     * of the input against them, printed as a run prints them; no load
     * step is solved and nothing is written ('signorini --check'). */
    void
    check_input();

    /** The checks of the postprocessors at the last written step. */
    const std::vector<Postprocess::CheckResult> &
    last_step_checks() const
    {
      return results.checks();
    }

    /** The error of the check @p what at the last written step (NaN: not
     * checked), e.g. "displacement L2 relative error". */
    double
    last_check_error(const std::string &what) const
    {
      for (const auto &check : results.checks())
        if (check.what == what)
          return check.error;
      return Postprocess::CheckResult::none;
    }

    /** Forces, counts and largest pressure per contact pair at the end
     * of the run (empty without contact). */
    std::vector<typename Contact::ContactProblem<dim>::PairSummary>
    contact_summary() const;

    /** Reference checks printed as FAIL over the run (0: all passed). */
    unsigned int
    failed_checks() const
    {
      return report.failed_checks();
    }

    types::global_dof_index
    n_dofs() const
    {
      return system.dof_handler.n_dofs();
    }

  private:
    // Set-up (simulation.cc).
    void
    make_mesh();
    void
    check_input_against_mesh() const;
    void
    setup_system();
    void
    print_setup();

    // The run (simulation_run.cc).
    void
    print_step_header(const unsigned int                           step,
                      const double                                 t_done,
                      const std::chrono::steady_clock::time_point &start,
                      const double last_step_seconds) const;
    /** Load step @p step from @p t_done: returns the time reached. */
    double
    run_load_step(const unsigned int         step,
                  const double               t_done,
                  const Solver::LoadStepper &stepper);
    /** Adaptive cycles within load step @p step (started at
     * @p t_step_start). */
    void
    adapt_in_step(const unsigned int         step,
                  const double               t_step_start,
                  Solver::StepProgress      &progress,
                  const Solver::LoadStepper &stepper);
    /** Advances to the end of load step @p step; when the step cuts are
     * used up, writes what converged and stops the run (RunError). */
    void
    advance_or_stop(const unsigned int         step,
                    const double               t_step_start,
                    Solver::StepProgress      &progress,
                    const Solver::LoadStepper &stepper);
    void
    write_step_results(const unsigned int step,
                       const double       time,
                       const unsigned int iterations);
    void
    finish_run();

    // Adaptivity (simulation_adaptivity.cc).
    /** One adaptive refinement cycle at time @p time (the step started at
     * @p step_start_time): marks, refines, transfers the state and the
     * state at the step start to the new mesh. False: no cell was
     * marked. */
    bool
    adapt_mesh(const double time, const double step_start_time);
    /** Sets the refinement and coarsening flags of adapt_mesh(); counts
     * this rank's marked cells into @p n_refine and @p n_coarsen. */
    void
    mark_cells(unsigned int &n_refine, unsigned int &n_coarsen);
    /** u and the multiplier field, now and at the step start, in the
     * displacement layout (with ghosts), for the solution transfer. */
    std::vector<TrilinosWrappers::MPI::Vector>
    fields_to_transfer() const;
    /** Stops the run (RunError) if the prepared refinement flags would
     * exceed 'Geometry/Maximum number of cells'. */
    void
    check_adapted_size() const;

    const Parameters  &parameters;
    MPI_Comm           mpi_communicator;
    ConditionalOStream pcout; // per-step output (off when quiet)
    ConditionalOStream sout;  // end-of-run summary (always, rank 0)
    // The plug-ins the parameters select, created (and their parameters
    // checked) before anything that reports at its destruction: the shape
    // of every body, the materials per material id and the rigid obstacle
    // of every pair (nullptr for a meshed master), handed to the contact
    // problem.
    std::vector<std::unique_ptr<Geometry::Shapes::Interface<dim>>> shapes;
    Bulk::Materials<dim>                                           materials;
    std::vector<std::unique_ptr<Obstacles::Interface<dim>>>        obstacles;
    TimerOutput                                                    timer;

    DiscreteSystem<dim> system;
    // Dirichlet values, loads and supports, functions of (x, t).
    Bulk::BoundaryConditions<dim> boundary_conditions;
    Bulk::Assembler<dim>          bulk;
    // After the system's matrix: destroyed before it (the direct solver's
    // factorisation refers to the matrix).
    Solver::LinearSolver<dim> linear_solver;
    // Contact: unknowns u | lambda | Lambda in one index space; inactive
    // without contact pairs.
    Contact::ContactProblem<dim> contact;
    // The step report, statistics.csv and the run summary, with the
    // counts of the load step under way.
    Postprocess::RunReport<dim> report;
    EquilibriumProblem<dim>     equilibrium;
    LoadStep<dim>               load_step;
    Postprocess::Results<dim>   results;

    unsigned int maximum_level = 0; // adaptivity: finest level (0: not set)
  };

  /** Reads @p filename, dispatches on Dimension and runs (@p check_only:
   * Simulation::check_input() instead); used by main(). Returns the
   * number of reference checks that failed. */
  unsigned int
  run_from_file(const std::string &filename,
                const MPI_Comm     mpi_communicator,
                const bool         check_only = false);
} // namespace Signorini

#endif
