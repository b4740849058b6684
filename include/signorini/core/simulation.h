#ifndef signorini_core_simulation_h
#define signorini_core_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/core/parameters.h>
#include <signorini/material/elastic_material.h>
#include <signorini/solver/linear_solver.h>

#include <array>
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

  /** A run that must stop (not a user input problem): says where and why. */
  class RunError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  template <int dim>
  class Simulation
  {
  public:
    Simulation(const Parameters &      parameters,
               const ParameterHandler &prm,
               const MPI_Comm          mpi_communicator);
    ~Simulation();

    void
    run();

    /** Errors against the Reference solution subsection (negative: none). */
    struct ReferenceErrors
    {
      double displacement_l2_relative = -1;
      double stress_max_relative      = -1;
    };
    ReferenceErrors
    reference_errors() const
    {
      return errors;
    }

    /** Reference checks printed as FAIL over the run (0: all passed). */
    unsigned int
    failed_checks() const
    {
      return n_failed_checks;
    }

    types::global_dof_index
    n_dofs() const
    {
      return dof_handler.n_dofs();
    }

  private:
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
    /** One adaptive refinement cycle at time @p time (the step started at
     * @p step_start_time): marks, refines, transfers state and
     * state_step_start to the new mesh. False: no cell was marked. */
    bool
    adapt_mesh(const double time, const double step_start_time);
    /** Stops the run (RunError) if the prepared refinement flags would
     * exceed 'Geometry/Maximum number of cells'. */
    void
    check_adapted_size() const;
    /** Newton loop on the current pairing; @p tolerance > 0 replaces
     * 'Relative tolerance' once the statuses have settled (a solve that
     * hands over to a new pairing). */
    bool
    newton(unsigned int &n_iterations, const double tolerance = 0.);
    double
    line_search(const TrilinosWrappers::MPI::Vector &base,
                const TrilinosWrappers::MPI::Vector &update,
                const double                         residual_now,
                const double                         residual_full);
    void
    check_jacobian();
    void
    update_solution(); // u part of the system state -> solution
    double
    point_value(const Point<dim> &p, const unsigned int component) const;
    void
    check_contact_references(const double time);
    void
    check_stick_zone(
      const std::vector<typename Contact::ContactProblem<dim>::PointRecord>
        &records);
    void
    check_force_balance();
    void
    compute_reactions();
    void
    compute_reference_errors(const double time);
    void
    output_results(const unsigned int step, const double time);
    void
    write_statistics(const unsigned int step,
                     const double       time,
                     const unsigned int newton_iterations);

    const Parameters &      parameters;
    const ParameterHandler &prm;
    MPI_Comm                mpi_communicator;
    ConditionalOStream      pcout; // per-step output (off when quiet)
    ConditionalOStream      sout;  // end-of-run summary (always, rank 0)
    TimerOutput             timer;

    parallel::distributed::Triangulation<dim> triangulation;
    FESystem<dim>                             fe;
    DoFHandler<dim>                           dof_handler;
    IndexSet                                  locally_owned, locally_relevant;

    std::map<types::material_id, Material::ElasticMaterial<dim>> materials;

    // Expressions of the loads and Dirichlet data, functions of (x, t).
    std::vector<std::unique_ptr<FunctionParser<dim>>> dirichlet_functions;
    std::vector<std::unique_ptr<FunctionParser<dim>>> neumann_functions;
    std::unique_ptr<FunctionParser<dim>>              body_force;

    AffineConstraints<double> constraints_values; // hanging + Dirichlet(t)
    AffineConstraints<double> constraints_update; // hanging + zero Dirichlet
    AffineConstraints<double> constraints_hanging; // hanging nodes only
    // Locally owned (DoF, component) pairs each Dirichlet condition constrains.
    std::vector<std::vector<std::pair<types::global_dof_index, unsigned int>>>
      dirichlet_dofs;

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
    TrilinosWrappers::MPI::Vector contact_force;    // on u DoFs [N]
    // R = F_int - F_ext + F_contact after hanging-node condensation: the
    // support forces at the Dirichlet DoFs (compute_reactions).
    TrilinosWrappers::MPI::Vector support_force;
    Contact::ContactStatistics    contact_statistics;
    bool                          first_pairing = true;
    std::vector<std::string>      contact_checks; // printed after each step
    std::vector<std::string>      last_checks;    // all checks, last step
    bool                          contact_checks_pass = true;
    double                        jacobian_error_max  = 0; // Check Jacobian

    double                           force_scale = 0;
    // The last newton() call converged at the round-off floor of an exact
    // step (see newton()).
    bool   exact_at_end    = false;
    double residual_at_end = 0; // its residual over the force level
    double model_size = 0; // bounding-box diagonal of the mesh [m]
    unsigned int maximum_level = 0; // adaptivity: finest level (0: not set)
    std::vector<Tensor<1, dim>>      reactions; // per Dirichlet condition
    // Mean displacement of the DoFs each Dirichlet condition constrains,
    // per component, and which components it constrains (statistics.csv:
    // force-displacement curves).
    std::vector<Tensor<1, dim>>          dirichlet_displacement;
    std::vector<std::array<bool, dim>>   dirichlet_components;
    std::vector<std::string>             statistics_header;
    ReferenceErrors                  errors;
    std::vector<std::pair<double, std::string>> pvtu_records;
    std::vector<std::vector<std::string>>       statistics_rows;
    // Newton history for newton_history.csv: one row per iterate, and
    // where the iterate belongs (load step, target time, geometric
    // iteration).
    std::vector<std::string> newton_rows;
    // Anti-cycling and step-cut counts of the current load step, and the
    // Newton iterations of every step (run summary).
    unsigned int cycle_detections = 0, points_frozen = 0, points_released = 0,
                 step_cuts = 0;
    std::vector<unsigned int> step_iterations;
    std::vector<Tensor<1, dim>> steady_forces; // Force variation check
    // Stick zone check: tangent of the tangential force, its last value,
    // loading direction (+1/-1, 0 before loading) and last turning point.
    Tensor<1, dim> mindlin_tangent;
    double         mindlin_q_last = 0, mindlin_q_turn = 0;
    int            mindlin_direction = 0;
    bool           mindlin_turned    = false;
    unsigned int line_searches = 0, run_line_searches = 0;
    unsigned int krylov_iterations = 0, krylov_max = 0; // per load step
    unsigned int n_failed_checks = 0;
    unsigned int run_cuts = 0, run_cycles = 0, run_frozen = 0,
                 run_released = 0;
    // Points opened early by the release extrapolation (whole run).
    unsigned int early_releases = 0;
    unsigned int             history_step = 0, history_geometric = 0;
    double                   history_time = 0;
    // Pairing within the Newton solve (status-changing iterates): the step
    // start time and the state at the last pairing.
    double                        pairing_step_start_time = 0;
    TrilinosWrappers::MPI::Vector state_at_pairing;
  };

  /** Reads @p filename, dispatches on Dimension and runs; used by main().
   * Returns the number of reference checks that failed. */
  unsigned int
  run_from_file(const std::string &filename, const MPI_Comm mpi_communicator);
} // namespace Signorini

#endif
