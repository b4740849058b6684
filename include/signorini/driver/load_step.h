#ifndef signorini_driver_load_step_h
#define signorini_driver_load_step_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/vector.h>

#include <signorini/driver/equilibrium_problem.h>
#include <signorini/solver/load_stepper.h>
#include <signorini/solver/newton_solver.h>

#include <array>
#include <string>
#include <utility>

namespace Signorini
{
  using namespace dealii;

  using Solver::NewtonFailure;

  /**
   * One load step (theory.md F7), as the problem of the load stepper
   * (Solver::QuasiStaticProblem): the loads and Dirichlet values of the
   * new time, the extrapolated predictor, then the geometric loop of
   * pairings with a Newton solve (Solver::NewtonSolver on the
   * EquilibriumProblem) each, or one Newton solve without contact. It
   * keeps what the next step needs: the last converged state and
   * increment, and why the last solve failed.
   */
  template <int dim>
  class LoadStep : public Solver::QuasiStaticProblem
  {
  public:
    LoadStep(const Parameters              &parameters,
             DiscreteSystem<dim>           &system,
             const Bulk::Assembler<dim>    &bulk,
             Bulk::BoundaryConditions<dim> &boundary_conditions,
             Contact::ContactProblem<dim>  &contact,
             Solver::LinearSolver<dim>     &linear_solver,
             EquilibriumProblem<dim>       &equilibrium,
             Postprocess::RunReport<dim>   &report,
             TimerOutput                   &timer,
             ConditionalOStream            &pcout);

    /** Solves the step from @p step_start_time to @p time; with @p resume
     * from the current state and the kept state_step_start (after mesh
     * adaptation), else from the step start with the predictor. */
    bool
    solve(const double  time,
          const double  step_start_time,
          unsigned int &iterations,
          const bool    resume = false);

    /** The current state is converged (the start of the run, or a state
     * transferred to a new mesh): failed sub-steps go back to it, and with
     * @p with_increment its increment since the step start is the next
     * predictor's. */
    void
    mark_converged(const bool with_increment);

    /** Back to the last converged (sub)step, at its time @p time, with its
     * forces evaluated again (a failed attempt leaves its own in the
     * system): for writing it as the step's results when the run stops. */
    void
    restore_last_converged(const double time);

    /** Back to the state at the start of the step (a solve on a refined
     * mesh failed). */
    void
    restart_from_step_start();

    /** Force level of the load step: the largest internal or external
     * force norm of its iterates. */
    double
    force_level() const
    {
      return force_scale;
    }

    /** What to change after the last failure, naming the parameters the
     * user set (Number of steps or Step times). */
    std::string
    failure_advice() const;

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

  private:
    /** Loads, Dirichlet values and the first iterate of a load step. */
    void
    start(const double time, const double step_start_time, const bool resume);
    /** The scale of the last converged increment in the extrapolated
     * predictor of the step from @p step_start_time to @p time. */
    double
    predictor_factor(const double time, const double step_start_time);
    /** With the external force increments f_new of this step and f_old
     * of the last: this rank's parts of f_new . f_old and f_old . f_old. */
    std::array<double, 2>
    load_increment_products(const double time,
                            const double start,
                            const double previous);
    /** A pairing of the geometric loop and its sparsity pattern. */
    void
    pair(const double time, const double step_start_time);
    /** The geometric loop's measure: the largest displacement change since
     * @p state_at_pairing over the largest increment of the step. */
    double
    pairing_change(const TrilinosWrappers::MPI::Vector &state_at_pairing) const;
    /** The geometric loop has converged: the last solve at the final
     * tolerance if it was handed over at @p handover > 0. */
    bool
    finish_geometric_loop(const double handover, unsigned int &iterations);
    /** The step's first Newton update moves the Dirichlet DoFs from the
     * current state to their values (a nonlinear bulk; see start()). */
    void
    arm_first_update();
    /** Newton solve on the current pairing; @p tolerance > 0 replaces
     * 'Relative tolerance' once the statuses have settled (a solve that
     * hands over to a new pairing). */
    bool
    newton(unsigned int &iterations, const double tolerance = 0.);
    void
    record_increment();
    /** Counts and prints @p n points frozen by the geometric loop's
     * anti-cycling; @p what ends the line. */
    void
    count_geometric_freezes(const unsigned int n, const char *what);

    const Parameters              &parameters;
    DiscreteSystem<dim>           &system;
    const Bulk::Assembler<dim>    &bulk;
    Bulk::BoundaryConditions<dim> &boundary_conditions;
    Contact::ContactProblem<dim>  &contact;
    Solver::LinearSolver<dim>     &linear_solver;
    EquilibriumProblem<dim>       &equilibrium;
    Postprocess::RunReport<dim>   &report;
    TimerOutput                   &timer;
    ConditionalOStream            &pcout;

    // Increment of the last converged (sub)step and its size in t, for the
    // extrapolated predictor; size 0: none yet.
    TrilinosWrappers::MPI::Vector last_increment; // owned
    double                        last_step_size = 0;
    // The last converged state (a failed sub-step goes back to it), and
    // whether any sub-step has converged yet.
    TrilinosWrappers::MPI::Vector last_converged;
    bool                          none_converged = true;
    bool                          first_pairing  = true;
    // The Dirichlet values of the step are still to be reached by the
    // first Newton update (a nonlinear bulk): set by start(), consumed by
    // arm_first_update() before the step's first Newton solve.
    bool   values_pending = false;
    double force_scale    = 0;
    // The result of the last newton() call, and why the last newton() or
    // solve() call failed.
    Solver::NewtonSolver::Result last_newton;
    std::string                  newton_failure;
    NewtonFailure newton_failure_kind = NewtonFailure::iteration_limit;
  };
} // namespace Signorini

#endif
