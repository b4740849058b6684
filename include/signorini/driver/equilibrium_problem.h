#ifndef signorini_driver_equilibrium_problem_h
#define signorini_driver_equilibrium_problem_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/assembler.h>
#include <signorini/bulk/boundary_conditions.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/driver/discrete_system.h>
#include <signorini/postprocess/run_report.h>
#include <signorini/solver/linear_solver.h>
#include <signorini/solver/nonlinear_problem.h>
#include <signorini/solver/rigid_modes.h>

#include <array>
#include <memory>
#include <string>

namespace Signorini
{
  using namespace dealii;

  /**
   * The equilibrium of the bodies at one load and one pairing, as the
   * problem the Newton solver iterates on (Solver::NonlinearProblem): the
   * residual of the bulk (Bulk::Assembler) and of contact
   * (Contact::ContactProblem) at the iterate of the DiscreteSystem, its
   * block norms and round-off scales, the log rows, the Jacobian and the
   * linearised solve (with the rigid motions nothing holds), and the
   * saved and restored state of the contact points for trial iterates.
   */
  template <int dim>
  class EquilibriumProblem : public Solver::NonlinearProblem
  {
  public:
    EquilibriumProblem(const Parameters                    &parameters,
                       DiscreteSystem<dim>                 &system,
                       const Bulk::Materials<dim>          &materials,
                       const Bulk::BoundaryConditions<dim> &boundary_conditions,
                       Bulk::Assembler<dim>                &bulk,
                       Contact::ContactProblem<dim>        &contact,
                       Solver::LinearSolver<dim>           &linear_solver,
                       Postprocess::RunReport<dim>         &report,
                       TimerOutput                         &timer,
                       ConditionalOStream                  &pcout);

    /** After each set-up of the system: its rigid motions. */
    void
    setup();

    /** Status counts of the last evaluation. */
    const Contact::ContactStatistics &
    statistics() const
    {
      return contact_statistics;
    }

    /** The next linearised solve moves the iterate to the prescribed
     * values of @p constraints (its inhomogeneities are the remaining
     * differences); nullptr: none pending. */
    void
    impose_in_first_update(const AffineConstraints<double> *constraints)
    {
      first_update        = constraints;
      bulk_jacobian_ready = false;
    }

    /** Every material is linear without history (Newton's step at fixed
     * contact statuses is then exact). */
    bool
    linear_bulk() const
    {
      return materials_linear;
    }

    /** The largest relative error of the Jacobian checks so far ('Newton/
     * Check Jacobian'). */
    double
    jacobian_error() const
    {
      return jacobian_error_max;
    }

    // Solver::NonlinearProblem.
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

  private:
    struct IterateSnapshot;

    /** For non_finite_cause(): the inverted finite-strain cells of the
     * last bulk assembly, with the smallest det F and its cell ("" if
     * none). */
    std::string
    inversion_cause() const;

    /** The bulk residual into newton_rhs (with F_int, F_ext); with
     * @p with_jacobian in the same pass the bulk Jacobian into the matrix
     * and its right-hand side into bulk_rhs, through the constraints of
     * the next solve (a pending first update). */
    void
    assemble_bulk(const bool with_jacobian);
    /** F_int - F_ext at the pinned DoFs to the contact's statuses
     * (collective; nothing without pins). */
    void
    share_pin_loads();

    /** The bulk's part of the rows of the sticking pinned nodes this rank
     * owns (theory.md F8, pins), with their Jacobian if @p with_matrix. */
    void
    add_pin_rows(const bool with_matrix);

    /** The contact terms at the iterate into newton_rhs (and the matrix
     * if @p with_matrix), through @p constraints. @p new_iterate: the
     * statuses are updated for the status history (not for a line-search
     * trial nor for the Jacobian of a solve). */
    void
    assemble_contact(const bool                       with_matrix,
                     const AffineConstraints<double> &constraints,
                     const bool                       new_iterate);

    /** Norms of the u, lambda and Lambda blocks of newton_rhs. */
    std::array<double, 3>
    block_residuals() const;
    /** Before a solve: the rigid motions the assembled Jacobian does not
     * hold. With closed frictional points (friction that has no threshold
     * yet, or slips everywhere) they are held by springs for this solve;
     * otherwise the system is singular and the run stops (RunError).
     * Returns the motions held ("" if none). */
    std::string
    hold_free_motions(const unsigned int iteration);
    void
    check_jacobian();

    const Parameters                    &parameters;
    DiscreteSystem<dim>                 &system;
    const Bulk::Materials<dim>          &materials;
    const Bulk::BoundaryConditions<dim> &boundary_conditions;
    Bulk::Assembler<dim>                &bulk;
    Contact::ContactProblem<dim>        &contact;
    Solver::LinearSolver<dim>           &linear_solver;
    Postprocess::RunReport<dim>         &report;
    TimerOutput                         &timer;
    ConditionalOStream                  &pcout;

    // True if every material is linear without history (Newton's exact
    // step at fixed contact statuses).
    bool materials_linear = true;
    // The constraints of a pending first update (impose_in_first_update).
    const AffineConstraints<double> *first_update = nullptr;
    // The matrix holds the bulk Jacobian of the current iterate (and
    // bulk_rhs its right-hand side): assembled by the iterate's evaluation,
    // used by its linear solve.
    bool bulk_jacobian_ready = false;
    // A linear bulk's Jacobian (materials_linear) does not change from one
    // iterate to the next: the first one assembled at a layout count of
    // the system is kept here and copied into the matrix while the count
    // stays, and the later evaluations assemble the residual only.
    TrilinosWrappers::SparseMatrix linear_bulk_matrix;
    unsigned int            linear_bulk_layout = numbers::invalid_unsigned_int;
    Solver::RigidModes<dim> rigid_modes;
    Contact::ContactStatistics contact_statistics;
    // || |K| |x| || of the last Jacobian K at the state x it was assembled
    // at: the round-off scale of the internal force (evaluate()).
    double matrix_roundoff = 0;
    // Finite strain: per displacement DoF, the diameter of the largest cell
    // around it (zero at the multipliers; ghosted like the state), set by
    // setup(). The stress of F = I + grad u carries a round-off of eps
    // itself, not eps |grad u|, as if every position were off by eps h:
    // the floor takes || |K| (|x| + h) || (doc/robustness.md). Empty at
    // small strain.
    bool                          finite_strain = false;
    TrilinosWrappers::MPI::Vector position_scale;
    double                        jacobian_error_max = 0;
  };
} // namespace Signorini

#endif
