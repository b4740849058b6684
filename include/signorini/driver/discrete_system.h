#ifndef signorini_driver_discrete_system_h
#define signorini_driver_discrete_system_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/fe/mapping_q_cache.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/bulk/boundary_conditions.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/material/history.h>
#include <signorini/solver/linear_solver.h>

/**
 * The discrete system of a run (the "DoFs" step of the data path): the
 * mesh, the finite element space, its DoFs and index sets, the constraints,
 * the Jacobian and the state vectors. The unknowns are u | lambda | Lambda
 * in one index space (Contact::ContactProblem), u alone without contact.
 */
namespace Signorini
{
  using namespace dealii;

  /**
   * A plain aggregate, shared by reference: it holds data and no policy.
   * The residual convention is the one of doc/theory.md section 4:
   * R = F_int - F_ext, Newton solves K dU = -R, with the Dirichlet values
   * on the iterate (constraints_values) and homogeneous constraints on the
   * update (constraints_update).
   *
   * Who writes what (one writer per rule; everyone else reads):
   * - mesh, fe, dof_handler, index sets, model_size: setup() and
   *   measure_mesh(), called by Simulation (start, adaptivity);
   * - constraints_*: make_constraints() and
   *   make_first_update_constraints(), called by LoadStep (the time of a
   *   step, its first update) and Simulation (setup);
   * - matrix, layout_count, pin_dofs, pin_rows' layout: make_sparsity()
   *   (called at each pairing by LoadStep, by Simulation without contact);
   *   the entries of matrix, pin_rows and pin_shift: EquilibriumProblem
   *   (assembly);
   * - state between Newton iterates: LoadStep alone (the predictor in
   *   start(), the initial multipliers at the first pairing, the values of
   *   a first update already met in arm_first_update(), a retry or a
   *   restart from the last converged state); within a Newton solve:
   *   EquilibriumProblem::set_iterate(), called by Solver::NewtonSolver
   *   (updates and line-search trials) only; on a new mesh: Simulation
   *   (reinit, then the transfer of adaptivity). The rule "the first
   *   update of a step carries the Dirichlet increment" is LoadStep's
   *   (arm_first_update() hands the constraints to EquilibriumProblem,
   *   which applies them in the next linear solve only);
   * - state_step_start: LoadStep::start() (and a restore or restart),
   *   Simulation's transfer on a new mesh;
   * - solution: update_solution(), by whoever wrote state;
   * - newton_rhs, bulk_rhs, internal_force, external_force,
   *   contact_force: EquilibriumProblem (evaluation);
   * - history: Bulk::Assembler::update_history() at a converged
   *   (sub)step (LoadStep::accept_step()); Simulation on a new mesh (and
   *   back to the sub-step's start to solve it again there). Contact
   *   statuses are not here: Contact::ContactProblem owns them.
   */
  template <int dim>
  struct DiscreteSystem
  {
    DiscreteSystem(const unsigned int degree, const MPI_Comm mpi_communicator);
    ~DiscreteSystem();

    /** The bounding-box diagonal of the mesh, model_size: the length
     * scale of relative tolerances. */
    void
    measure_mesh();

    /** DoFs, index sets, constraints at t = 0 and vectors on the current
     * mesh; with contact also its surfaces and multipliers
     * (ContactProblem::setup()), which need the displacement constraints
     * to exclude over-constrained slave nodes. Without contact also the
     * sparsity pattern (with contact: at each pairing). */
    void
    setup(Bulk::BoundaryConditions<dim> &boundary_conditions,
          Contact::ContactProblem<dim>  &contact,
          Solver::LinearSolver<dim>     &linear_solver,
          ConditionalOStream            &pcout);

    /**
     * The constraints of a first Newton update that takes the current
     * state to the Dirichlet values of make_constraints() (its
     * inhomogeneities are their differences), with the hanging-node and
     * contact lines. False if the state has those values already, to
     * 1e-10 of the step's largest prescribed increment from
     * @p state_before.
     */
    bool
    make_first_update_constraints(
      const Contact::ContactProblem<dim>  &contact,
      const TrilinosWrappers::MPI::Vector &state_before);

    /** Hanging nodes, Dirichlet values at @p time and the contact
     * constraint lines. */
    void
    make_constraints(const double                        time,
                     Bulk::BoundaryConditions<dim>      &boundary_conditions,
                     const Contact::ContactProblem<dim> &contact);

    /** Bulk couplings plus the contact couplings of the current pairing;
     * the matrix is sized to it (the linear solver's analysis of the old
     * pattern is dropped first). */
    void
    make_sparsity(const Contact::ContactProblem<dim> &contact,
                  Solver::LinearSolver<dim>          &linear_solver);

    /** pin_dofs, the layout of pin_rows and the held-tangent rows of
     * the pinned nodes in @p sp (make_sparsity()). */
    void
    make_pin_rows(const Contact::ContactProblem<dim> &contact,
                  TrilinosWrappers::SparsityPattern  &sp);

    /** The u part of state -> solution. */
    void
    update_solution();

    MPI_Comm                                  mpi_communicator;
    parallel::distributed::Triangulation<dim> triangulation;
    FESystem<dim>                             fe;
    // The geometry of the cells: polynomials of the element's degree
    // through its support points (isoparametric), so that the nodes of a
    // Q2 element follow a curved boundary (its manifold).
    // The isoparametric mapping of the reference mesh. Its support points
    // are computed through the manifolds once per mesh (setup()); a plain
    // MappingQ(2) computed them at every FEValues::reinit().
    MappingQCache<dim> mapping;
    DoFHandler<dim>    dof_handler;
    // Displacement DoFs, and the system's (with the multipliers).
    IndexSet locally_owned, locally_relevant;
    IndexSet owned_system, relevant_system;

    AffineConstraints<double> constraints_values;  // hanging + Dirichlet(t)
    AffineConstraints<double> constraints_update;  // hanging + zero Dirichlet
    AffineConstraints<double> constraints_hanging; // hanging nodes only
    // hanging + Dirichlet(t) - state: the first update of a load step that
    // moves to the prescribed values (make_first_update_constraints).
    AffineConstraints<double> constraints_first;

    TrilinosWrappers::SparseMatrix matrix;
    // The pinned DoFs of sticking-capable slave nodes (theory.md F8,
    // pins; Contact::Surfaces::pins()) and the bulk Jacobian rows of those
    // a rank owns, kept unconstrained (columns condensed); pin_shift:
    // sum_c K_dc g_c of a first update's prescribed increments.
    std::set<types::global_dof_index> pin_dofs;
    TrilinosWrappers::SparseMatrix    pin_rows;
    TrilinosWrappers::MPI::Vector     pin_shift;
    // Counts the changes of the matrix layout and of the constraints
    // (make_sparsity(), make_constraints()): a bulk matrix assembled at
    // one count is the bulk matrix of a linear bulk while the count stays.
    unsigned int                  layout_count = 0;
    TrilinosWrappers::MPI::Vector solution;         // ghosted u of the iterate
    TrilinosWrappers::MPI::Vector state;            // ghosted system iterate
    TrilinosWrappers::MPI::Vector state_step_start; // ghosted, step start
    TrilinosWrappers::MPI::Vector newton_rhs;       // -R on free DoFs
    // The bulk part of the right-hand side of the next linear solve (-R,
    // with -K_fd delta in a first update), assembled with the residual.
    TrilinosWrappers::MPI::Vector bulk_rhs;
    // Without constraints, on u DoFs [N].
    TrilinosWrappers::MPI::Vector internal_force, external_force;
    TrilinosWrappers::MPI::Vector contact_force;
    // The materials' history at the bulk quadrature points, committed at
    // the last converged (sub)step (Bulk::Assembler::update_history).
    Material::History<dim> history;

    double model_size = 0; // bounding-box diagonal of the mesh [m]
  };
} // namespace Signorini

#endif
