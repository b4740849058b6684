#ifndef signorini_core_simulation_h
#define signorini_core_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/data_out.h>

#include <signorini/bulk/assembler.h>
#include <signorini/bulk/boundary_conditions.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/core/parameters.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/output_files.h>
#include <signorini/postprocess/run_report.h>
#include <signorini/solver/linear_solver.h>
#include <signorini/solver/load_stepper.h>
#include <signorini/solver/newton_solver.h>
#include <signorini/solver/nonlinear_problem.h>
#include <signorini/solver/rigid_modes.h>

#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <stdexcept>

/**
 * One Signorini run: mesh, finite element space, quasi-static load stepping
 * with a Newton loop per step, output. The residual convention is the one of
 * formulation.md section 4: R = F_int - F_ext, Newton solves K dU = -R, with
 * Dirichlet values imposed on the iterate and homogeneous constraints on the
 * update. A step that does not converge is halved and retried (Load
 * stepping/Maximum step cuts) before the run stops with a RunError.
 */
namespace Signorini
{
  using namespace dealii;

  using Solver::NewtonFailure;

  /**
   * One run of a scene: owns mesh, DoFs and vectors and wires the bulk
   * assembler, the contact problem and the linear solver. Its members are
   * defined by concern in source/core/: simulation.cc (mesh, DoFs,
   * constraints, assembly), simulation_run.cc (the run over the load
   * steps: cuts, adaptive cycles), simulation_newton.cc (load
   * step and its geometric loop, Jacobian check), simulation_problem.cc
   * (the problem the Newton solver iterates on: residual, log rows,
   * linearised solve),
   * simulation_adaptivity.cc (refinement between steps) and
   * simulation_output.cc (reactions, postprocessors, files, summary).
   */
  template <int dim>
  class Simulation : private Solver::NonlinearProblem,
                     private Solver::QuasiStaticProblem
  {
  public:
    /** @p prm: the parameters read into @p parameters (the models of
     * the materials read their own from it). */
    Simulation(const Parameters &parameters,
               ParameterHandler &prm,
               const MPI_Comm    mpi_communicator);
    ~Simulation() override;

    void
    run();

    /** The checks of the postprocessors at the last written step. */
    const std::vector<Postprocess::CheckResult> &
    last_step_checks() const
    {
      return step_checks;
    }

    /** The error of the check @p what at the last written step (NaN: not
     * checked), e.g. "displacement L2 relative error". */
    double
    last_check_error(const std::string &what) const
    {
      for (const auto &check : step_checks)
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
      return dof_handler.n_dofs();
    }

  private:
    // The run (simulation_run.cc).
    void
    print_setup();
    void
    print_step_header(const unsigned int                           step,
                      const double                                 t_done,
                      const std::chrono::steady_clock::time_point &start) const;
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
                  Solver::StepProgress &     progress,
                  const Solver::LoadStepper &stepper);
    /** Advances to the end of load step @p step; when the step cuts are
     * used up, writes what converged and stops the run (RunError). */
    void
    advance_or_stop(const unsigned int         step,
                    const double               t_step_start,
                    Solver::StepProgress &     progress,
                    const Solver::LoadStepper &stepper);
    void
    record_increment();
    void
    finish_run();
    // Solver::QuasiStaticProblem.
    bool
    solve_step(const double  time,
               const double  start_time,
               unsigned int &iterations) override;
    void
    accept_step(const double time, const double start_time) override;
    void
    reject_step() override;
    std::string
    failure() const override;

    void
    make_mesh();
    void
    check_input_against_mesh() const;
    void
    setup_system();
    void
    make_constraints(const double time);
    /** Residual (and with @p with_matrix the Jacobian) at the iterate.
     * A residual-only evaluation is a new Newton iterate for the status
     * history unless @p trial (line search). */
    void
    assemble(const bool with_matrix, const bool trial = false);
    /** Norms of the u, lambda and Lambda blocks of newton_rhs. */
    std::array<double, 3>
    block_residuals() const;
    void
    make_sparsity();
    /** Solves the step from @p step_start_time to @p time; with @p resume
     * from the current state and the kept state_step_start (after mesh
     * adaptation), else from the step start with the predictor. */
    bool
    solve_load_step(const double   time,
                    const double   step_start_time,
                    unsigned int & n_iterations,
                    const bool     resume = false);
    /** Loads, Dirichlet values and the first iterate of a load step. */
    void
    start_load_step(const double time,
                    const double step_start_time,
                    const bool   resume);
    /** A pairing of the geometric loop and its sparsity pattern. */
    void
    pair_for_step(const double time, const double step_start_time);
    /** The geometric loop's measure: the largest displacement change since
     * @p state_at_pairing over the largest increment of the step. */
    double
    pairing_change(const TrilinosWrappers::MPI::Vector &state_at_pairing) const;
    /** The geometric loop has converged: the last solve at the final
     * tolerance if it was handed over at @p handover > 0. */
    bool
    finish_geometric_loop(const double handover, unsigned int &iterations);
    /** One adaptive refinement cycle at time @p time (the step started at
     * @p step_start_time): marks, refines, transfers state and
     * state_step_start to the new mesh. False: no cell was marked. */
    bool
    adapt_mesh(const double time, const double step_start_time);
    /** Stops the run (RunError) if the prepared refinement flags would
     * exceed 'Geometry/Maximum number of cells'. */
    void
    check_adapted_size() const;
    /** Newton solve (Solver::NewtonSolver) on the current pairing;
     * @p tolerance > 0 replaces 'Relative tolerance' once the statuses
     * have settled (a solve that hands over to a new pairing). */
    bool
    newton(unsigned int &n_iterations, const double tolerance = 0.);
    void
    check_jacobian();

    // Solver::NonlinearProblem (simulation_problem.cc).
    struct IterateSnapshot;
    void
    start_solve() override;
    Solver::Evaluation
    evaluate(const bool trial) override;
    void
    record_iterate(const unsigned int        iteration,
                   const Solver::Evaluation &evaluation,
                   const double              force_level,
                   const bool                converged) override;
    void
    check_iterate() override;
    std::string
    non_finite_cause() const override;
    void
    release_contradicted() override;
    Solver::LinearisedStep
    solve_linearised(const unsigned int iteration) override;
    TrilinosWrappers::MPI::Vector
    iterate() const override;
    void
    set_iterate(const TrilinosWrappers::MPI::Vector &owned) override;
    std::unique_ptr<Solver::NonlinearProblem::Snapshot>
    save() const override;
    void
    restore(const Solver::NonlinearProblem::Snapshot &snapshot) override;

    /** Reactions, reference checks, statistics row, VTU and contact CSV of
     * load step @p step at time @p time (the statistics row last). */
    void
    write_step_results(const unsigned int step,
                       const double       time,
                       const unsigned int iterations);
    /** Before a solve: the rigid motions the assembled Jacobian does not
     * hold. With closed frictional points (friction that has no threshold
     * yet, or slips everywhere) they are held by springs for this solve;
     * otherwise the system is singular and the run stops (RunError).
     * Returns the motions held ("" if none). */
    std::string
    hold_free_motions(const unsigned int iteration);
    /** What to change after a failure of kind newton_failure_kind, naming
     * the parameters the user set (Number of steps or Step times). */
    std::string
    failure_advice() const;
    void
    update_solution(); // u part of the system state -> solution
    double
    point_value(const Point<dim> &p, const unsigned int component) const;
    void
    compute_reactions();
    void
    run_postprocessors(const unsigned int step, const double time);
    /** Output directory of the run: earlier results removed, parameters
     * echoed, newton_history.csv started. */
    void
    prepare_output();
    /** The step's report on screen; returns its statistics.csv lines. */
    std::string
    report_step(const unsigned int step,
                const double       time,
                const unsigned int newton_iterations);
    /** Collective: a failed write on any rank (@p failure, "" if none
     * here) stops every rank with a RunError naming the file. */
    void
    check_output(const std::string &failure) const;

    const Parameters &      parameters;
    const ParameterHandler &prm;
    MPI_Comm                mpi_communicator;
    ConditionalOStream      pcout; // per-step output (off when quiet)
    ConditionalOStream      sout;  // end-of-run summary (always, rank 0)
    // The plug-ins the parameters select, created (and their parameters
    // checked) before anything that reports at its destruction: the
    // materials per material id and the rigid obstacle of every pair
    // (nullptr for a meshed master), handed to the contact problem.
    Bulk::Materials<dim>                                    materials;
    std::vector<std::unique_ptr<Obstacles::Interface<dim>>> obstacles;
    TimerOutput                                             timer;

    parallel::distributed::Triangulation<dim> triangulation;
    FESystem<dim>                             fe;
    // The geometry of the cells: polynomials of the element's degree
    // through its support points (isoparametric), so that the nodes of a
    // Q2 element follow a curved boundary (its manifold).
    const MappingQ<dim> mapping;
    DoFHandler<dim>                           dof_handler;
    IndexSet                                  locally_owned, locally_relevant;

    // True if every material is linear without history (Newton's exact
    // step at fixed contact statuses).
    bool materials_linear = true;

    // Dirichlet values, loads and supports, functions of (x, t).
    Bulk::BoundaryConditions<dim>         boundary_conditions;
    std::unique_ptr<Bulk::Assembler<dim>> bulk;

    AffineConstraints<double> constraints_values; // hanging + Dirichlet(t)
    AffineConstraints<double> constraints_update; // hanging + zero Dirichlet
    AffineConstraints<double> constraints_hanging; // hanging nodes only

    TrilinosWrappers::SparseMatrix system_matrix;
    TrilinosWrappers::MPI::Vector  solution;     // ghosted, current iterate
    TrilinosWrappers::MPI::Vector  newton_rhs;   // -R on free DoFs
    TrilinosWrappers::MPI::Vector  internal_force, external_force; // no constraints

    // After system_matrix: destroyed before it (the direct solver's
    // factorisation refers to the matrix).
    std::unique_ptr<Solver::LinearSolver<dim>> linear_solver;

    // Contact: unknowns u | lambda | Lambda in one index space (see
    // Contact::ContactProblem); without contact the system is u only.
    std::unique_ptr<Contact::ContactProblem<dim>> contact;
    IndexSet                      owned_system, relevant_system;
    TrilinosWrappers::MPI::Vector state;            // ghosted system iterate
    TrilinosWrappers::MPI::Vector state_step_start; // ghosted, step start
    // Increment of the last converged (sub)step and its size in t, for the
    // extrapolated predictor; size 0: none yet.
    TrilinosWrappers::MPI::Vector last_increment; // owned
    double                        last_step_size = 0;
    // The last converged state (a failed sub-step goes back to it), and
    // whether any sub-step has converged yet.
    TrilinosWrappers::MPI::Vector last_converged;
    bool                          none_converged = true;
    TrilinosWrappers::MPI::Vector contact_force; // on u DoFs [N]
    Contact::ContactStatistics    contact_statistics;
    bool                          first_pairing = true;
    // The postprocessors of 'Output/Postprocessors' (some keep history
    // across steps) and their checks of the step, printed after it.
    std::vector<std::unique_ptr<Postprocess::Interface<dim>>> postprocessors;
    std::vector<Postprocess::CheckResult>                     step_checks;
    Postprocess::StatisticsColumns postprocessor_columns;   // of the step
    double                        jacobian_error_max  = 0; // Check Jacobian

    // Force level of the load step: the largest internal or external
    // force norm of its iterates (Solver::NewtonSolver::solve()).
    double                           force_scale = 0;
    // The result of the last newton() call.
    Solver::NewtonSolver::Result last_newton;
    // Rigid motions of the bodies (see hold_free_motions()).
    Solver::RigidModes<dim> rigid_modes;
    // Why the last newton() or solve_load_step() call failed (for the
    // message when the step cuts are used up).
    double        last_written_time = 0; // of the last step written
    // || |K| |x| || of the last Jacobian K at the state x it was assembled
    // at: the round-off scale of the internal force (evaluate()).
    double        matrix_roundoff = 0;
    std::string   newton_failure;
    NewtonFailure newton_failure_kind = NewtonFailure::iteration_limit;
    double model_size = 0; // bounding-box diagonal of the mesh [m]
    unsigned int maximum_level = 0; // adaptivity: finest level (0: not set)
    // Reactions and displacements of the supports at the last written
    // step.
    Bulk::Supports<dim> supports;
    // The step report, statistics.csv and the run summary, with the
    // counts of the load step under way.
    Postprocess::RunReport<dim> report;
  };

  /** Reads @p filename, dispatches on Dimension and runs; used by main().
   * Returns the number of reference checks that failed. */
  unsigned int
  run_from_file(const std::string &filename, const MPI_Comm mpi_communicator);
} // namespace Signorini

#endif
