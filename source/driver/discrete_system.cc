// The discrete system: DoFs, index sets, constraints, sparsity, vectors.
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <signorini/driver/discrete_system.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace Signorini
{
  template <int dim>
  DiscreteSystem<dim>::DiscreteSystem(const unsigned int degree,
                                      const MPI_Comm     mpi_communicator)
      : mpi_communicator(mpi_communicator)
      , triangulation(mpi_communicator,
                      Triangulation<dim>::limit_level_difference_at_vertices)
      , fe(FE_Q<dim>(degree), dim)
      , mapping(degree)
      , dof_handler(triangulation)
  {
  }


  template <int dim>
  DiscreteSystem<dim>::~DiscreteSystem()
  {
    dof_handler.clear();
  }


  // Linear in the cells: GridTools::diameter compares all vertex pairs and
  // took a quarter of the run at 50k DoFs.
  template <int dim>
  void
  DiscreteSystem<dim>::measure_mesh()
  {
    Point<dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] = std::numeric_limits<double>::max();
        hi[d] = -std::numeric_limits<double>::max();
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < dim; ++d)
            {
              lo[d] = std::min(lo[d], cell->vertex(v)[d]);
              hi[d] = std::max(hi[d], cell->vertex(v)[d]);
            }
    double size2 = 0;
    for (unsigned int d = 0; d < dim; ++d)
      size2 += std::pow(Utilities::MPI::max(hi[d], mpi_communicator) +
                          Utilities::MPI::max(-lo[d], mpi_communicator),
                        2);
    model_size = std::sqrt(size2);
  }


  template <int dim>
  void
  DiscreteSystem<dim>::setup(Bulk::BoundaryConditions<dim> &boundary_conditions,
                             Contact::ContactProblem<dim>  &contact,
                             Solver::LinearSolver<dim>     &linear_solver,
                             ConditionalOStream            &pcout)
  {
    mapping.initialize(MappingQ<dim>(fe.degree), triangulation);
    dof_handler.distribute_dofs(fe);
    DoFRenumbering::Cuthill_McKee(dof_handler);
    locally_owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant);

    solution.reinit(locally_owned, locally_relevant, mpi_communicator);
    internal_force.reinit(locally_owned, mpi_communicator);
    external_force.reinit(locally_owned, mpi_communicator);

    owned_system    = locally_owned;
    relevant_system = locally_relevant;
    make_constraints(0., boundary_conditions, contact);
    if (contact.active())
      {
        contact.setup(constraints_update,
                      locally_owned,
                      boundary_conditions.point_lines(),
                      pcout);
        const auto &surfaces = contact.contact_surfaces();
        owned_system         = IndexSet(surfaces.n_system());
        owned_system.add_indices(locally_owned);
        owned_system.add_indices(surfaces.owned_multipliers());
        owned_system.compress();
        relevant_system = IndexSet(surfaces.n_system());
        relevant_system.add_indices(locally_relevant);
        relevant_system.add_indices(surfaces.extra_relevant());
        relevant_system.add_indices(owned_system);
        relevant_system.compress();
        make_constraints(0., boundary_conditions, contact);
      }
    state.reinit(owned_system, relevant_system, mpi_communicator);
    state_step_start.reinit(owned_system, relevant_system, mpi_communicator);
    newton_rhs.reinit(owned_system, relevant_system, mpi_communicator, true);
    bulk_rhs.reinit(owned_system, relevant_system, mpi_communicator, true);
    contact_force.reinit(locally_owned,
                         contact.active() ? relevant_system : locally_relevant,
                         mpi_communicator,
                         true);
    if (!contact.active())
      make_sparsity(contact, linear_solver);
  }


  // The pattern holds the Dirichlet couplings too (constraints are applied
  // with keep_constrained_dofs = false at assembly).
  template <int dim>
  void
  DiscreteSystem<dim>::make_sparsity(
    const Contact::ContactProblem<dim> &contact,
    Solver::LinearSolver<dim>          &linear_solver)
  {
    TrilinosWrappers::SparsityPattern    sp(owned_system,
                                         owned_system,
                                         relevant_system,
                                         mpi_communicator);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          constraints_update.add_entries_local_to_global(dofs, sp, false);
        }
    if (contact.active())
      contact.add_sparsity(sp, constraints_update);
    make_pin_rows(contact, sp);
    sp.compress();
    // The direct solver's analysis refers to the old matrix: dropped first.
    linear_solver.pattern_changed();
    matrix.reinit(sp);
    ++layout_count;
  }


  // The layout of pin_rows (the bulk rows of the pinned DoFs, columns
  // condensed) and, in @p sp, the same columns in the friction rows of
  // their nodes, which take those rows while the node sticks (and in 3D
  // while it slides: its H depends on them).
  template <int dim>
  void
  DiscreteSystem<dim>::make_pin_rows(
    const Contact::ContactProblem<dim> &contact,
    TrilinosWrappers::SparsityPattern  &sp)
  {
    pin_dofs.clear();
    if (!contact.active() || contact.contact_surfaces().pins().empty())
      return;
    const auto &pins = contact.contact_surfaces().pins();
    for (const auto &pin : pins)
      pin_dofs.insert(pin.first);
    TrilinosWrappers::SparsityPattern    pin_sp(owned_system,
                                             owned_system,
                                             relevant_system,
                                             mpi_communicator);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          for (const auto d : dofs)
            if (pin_dofs.count(d) > 0)
              Bulk::rows_as_they_are().add_entries_local_to_global(
                {d}, constraints_update, dofs, pin_sp, false);
        }
    pin_sp.compress();
    for (const auto &[d, pin] : pins)
      if (locally_owned.is_element(d))
        for (auto it = pin_sp.begin(d); it != pin_sp.end(d); ++it)
          for (unsigned int k = 0; k < dim - 1; ++k)
            sp.add(pin.friction + k, it->column());
    pin_rows.reinit(pin_sp);
    pin_shift.reinit(locally_owned, locally_relevant, mpi_communicator, true);
  }


  template <int dim>
  void
  DiscreteSystem<dim>::make_constraints(
    const double                        time,
    Bulk::BoundaryConditions<dim>      &boundary_conditions,
    const Contact::ContactProblem<dim> &contact)
  {
    ++layout_count;
    constraints_values.clear();
    constraints_values.reinit(relevant_system);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_values);
    constraints_update.clear();
    constraints_update.reinit(relevant_system);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_update);
    // Hanging nodes alone (weights summing to one, also where a master
    // carries a Dirichlet condition): the support forces of the results.
    constraints_hanging.clear();
    constraints_hanging.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_hanging);
    constraints_hanging.close();
    boundary_conditions.add_dirichlet_constraints(time,
                                                  mapping,
                                                  dof_handler,
                                                  1e-8 * model_size,
                                                  constraints_values,
                                                  constraints_update);
    if (contact.active() && owned_system.size() > dof_handler.n_dofs())
      {
        contact.contact_surfaces().add_constraint_lines(constraints_values);
        contact.contact_surfaces().add_constraint_lines(constraints_update);
      }
    constraints_values.close();
    constraints_update.close();
  }


  template <int dim>
  bool
  DiscreteSystem<dim>::make_first_update_constraints(
    const Contact::ContactProblem<dim>  &contact,
    const TrilinosWrappers::MPI::Vector &state_before)
  {
    constraints_first.clear();
    constraints_first.reinit(relevant_system);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_first);
    double offset = 0, increment = 0;
    for (const auto i : locally_relevant)
      if (constraints_values.is_constrained(i) &&
          !constraints_hanging.is_constrained(i))
        {
          // u_i = sum_j w_j u_j + g (a Cartesian value: no entries): the
          // update takes the state onto the line.
          double value = constraints_values.get_inhomogeneity(i);
          constraints_first.add_line(i);
          for (const auto &[j, w] :
               *constraints_values.get_constraint_entries(i))
            {
              constraints_first.add_entry(i, j, w);
              value += w * state[j];
            }
          constraints_first.set_inhomogeneity(i, value - state[i]);
          if (locally_owned.is_element(i))
            {
              offset = std::max(offset, std::abs(value - state[i]));
              increment =
                std::max(increment, std::abs(value - state_before[i]));
            }
        }
    if (contact.active() && owned_system.size() > dof_handler.n_dofs())
      contact.contact_surfaces().add_constraint_lines(constraints_first);
    constraints_first.close();
    offset    = Utilities::MPI::max(offset, mpi_communicator);
    increment = Utilities::MPI::max(increment, mpi_communicator);
    return offset > 1e-10 * increment;
  }


  template <int dim>
  void
  DiscreteSystem<dim>::update_solution()
  {
    TrilinosWrappers::MPI::Vector owned(locally_owned, mpi_communicator);
    for (const auto i : locally_owned)
      owned[i] = state[i];
    owned.compress(VectorOperation::insert);
    solution = owned;
  }


  template struct DiscreteSystem<2>;
  template struct DiscreteSystem<3>;
} // namespace Signorini
