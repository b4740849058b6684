// The simulation: mesh, DoFs, constraints, the system and its assembly
// (the run: simulation_run.cc; load step: simulation_newton.cc; Newton's
// problem: simulation_problem.cc; adaptivity: simulation_adaptivity.cc;
// results: simulation_output.cc).
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <signorini/core/input_checks.h>
#include <signorini/core/simulation.h>

#include <algorithm>
#include <signorini/geometry/mesh_checks.h>
#include <signorini/geometry/scene.h>
#include <signorini/postprocess/format.h>

#include <cmath>
#include <limits>
#include <set>

namespace Signorini
{
  using Postprocess::format;


  template <int dim>
  Simulation<dim>::Simulation(const Parameters &parameters,
                              ParameterHandler &prm,
                              const MPI_Comm    mpi_communicator)
      : parameters(parameters)
      , prm(prm)
      , mpi_communicator(mpi_communicator)
      , pcout(std::cout,
              Utilities::MPI::this_mpi_process(mpi_communicator) == 0 &&
                parameters.output.verbosity != Verbosity::quiet)
      , sout(std::cout, Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      , materials(Material::make_materials<dim>(parameters, prm))
      , obstacles(Obstacles::make_obstacles<dim>(parameters, prm))
      , timer(mpi_communicator,
              sout,
              TimerOutput::never,
              TimerOutput::wall_times)
      , triangulation(mpi_communicator,
                      Triangulation<dim>::limit_level_difference_at_vertices)
      , fe(FE_Q<dim>(parameters.fe_degree), dim)
      , mapping(parameters.fe_degree)
      , dof_handler(triangulation)
      , boundary_conditions(parameters.boundary_conditions)
      , linear_solver(
          std::make_unique<Solver::LinearSolver<dim>>(parameters.linear_solver))
      , postprocessors(Postprocess::make_postprocessors<dim>(parameters, prm))
      , report(parameters, pcout, sout, mpi_communicator)
  {
    for (const auto &[id, material] : materials)
      materials_linear &= material->is_linear();
    bulk =
      std::make_unique<Bulk::Assembler<dim>>(parameters,
                                             mapping,
                                             fe,
                                             materials,
                                             boundary_conditions.neumann(),
                                             boundary_conditions.body_force());
    contact = std::make_unique<Contact::ContactProblem<dim>>(
      parameters,
      mapping,
      fe,
      dof_handler,
      materials,
      std::move(obstacles),
      mpi_communicator);
  }


  template <int dim>
  std::vector<typename Contact::ContactProblem<dim>::PairSummary>
  Simulation<dim>::contact_summary() const
  {
    return contact->active() ? contact->summary() :
                               std::vector<typename Contact::ContactProblem<
                                 dim>::PairSummary>();
  }


  template <int dim>
  Simulation<dim>::~Simulation()
  {
    dof_handler.clear();
  }


  template <int dim>
  void
  Simulation<dim>::make_mesh()
  {
    TimerOutput::Scope t(timer, "mesh");
    Geometry::create_mesh(parameters, triangulation);
    // Size of the model for relative tolerances: the diagonal of the
    // bounding box of all cells (linear in the cells; GridTools::diameter
    // compares all vertex pairs and took a quarter of the run at 50k DoFs).
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
    check_input_against_mesh();
  }


  // Everything in the input that refers to the mesh is checked before any
  // work, so that a typo stops the run at once with a clear message.
  template <int dim>
  void
  Simulation<dim>::check_input_against_mesh() const
  {
    if (parameters.axisymmetric)
      {
        double x_min = 0;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              x_min = std::min(x_min, cell->vertex(v)[0]);
        x_min = Utilities::MPI::min(x_min, mpi_communicator);
        if (x_min < -1e-10 * model_size)
          throw InputError("parameter 'Axisymmetric': the mesh reaches x = " +
                           format(x_min, 4) +
                           " but x is the radius and must be >= 0. Move the "
                           "mesh (Geometry/Body k/Shift) or use a half "
                           "section (e.g. 'Segment = quarter').");
      }
    boundary_conditions.check_boundary_ids(
      Geometry::boundary_ids(triangulation));

    std::set<types::material_id> used;
    for (const auto &cell : triangulation.cell_iterators_on_level(0))
      used.insert(cell->material_id());
    for (const auto id : used)
      if (materials.count(id) == 0)
        throw InputError("subsection 'Materials': the mesh has cells with "
                         "material id " +
                         std::to_string(id) +
                         " but no 'Material k' subsection has 'Material id "
                         "= " +
                         std::to_string(id) +
                         "'. Add one (and raise 'Number of materials').");
  }


  template <int dim>
  void
  Simulation<dim>::setup_system()
  {
    TimerOutput::Scope t(timer, "setup");
    dof_handler.distribute_dofs(fe);
    DoFRenumbering::Cuthill_McKee(dof_handler);
    locally_owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant);

    solution.reinit(locally_owned, locally_relevant, mpi_communicator);
    internal_force.reinit(locally_owned, mpi_communicator);
    external_force.reinit(locally_owned, mpi_communicator);

    // The displacement constraints first: the contact set-up needs them to
    // exclude over-constrained slave nodes.
    owned_system    = locally_owned;
    relevant_system = locally_relevant;
    make_constraints(0.);
    if (contact->active())
      {
        contact->setup(constraints_update, locally_owned, pcout);
        const auto n_system = contact->contact_surfaces().n_system();
        owned_system        = IndexSet(n_system);
        owned_system.add_indices(locally_owned);
        owned_system.add_indices(
          contact->contact_surfaces().owned_multipliers());
        owned_system.compress();
        relevant_system = IndexSet(n_system);
        relevant_system.add_indices(locally_relevant);
        relevant_system.add_indices(
          contact->contact_surfaces().extra_relevant());
        relevant_system.add_indices(owned_system);
        relevant_system.compress();
        make_constraints(0.);
      }
    state.reinit(owned_system, relevant_system, mpi_communicator);
    state_step_start.reinit(owned_system, relevant_system, mpi_communicator);
    newton_rhs.reinit(owned_system, relevant_system, mpi_communicator, true);
    contact_force.reinit(locally_owned,
                         contact->active() ? relevant_system : locally_relevant,
                         mpi_communicator,
                         true);
    if (!contact->active())
      make_sparsity();
    linear_solver->set_null_space(mapping, dof_handler, locally_owned);
    rigid_modes.setup(mapping,
                      dof_handler,
                      constraints_update,
                      owned_system,
                      parameters.axisymmetric,
                      mpi_communicator);
    if (contact->active())
      linear_solver->set_multipliers(
        dof_handler.n_dofs(), contact->contact_surfaces().owned_multipliers());
  }


  // Bulk couplings, plus the contact couplings of the current pairing; the
  // pattern holds the Dirichlet couplings too (constraints are applied with
  // keep_constrained_dofs = false at assembly).
  template <int dim>
  void
  Simulation<dim>::make_sparsity()
  {
    TrilinosWrappers::SparsityPattern sp(owned_system,
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
    if (contact->active())
      contact->add_sparsity(sp, constraints_update);
    sp.compress();
    // The direct solver's analysis refers to the old matrix: dropped first.
    linear_solver->pattern_changed();
    system_matrix.reinit(sp);
  }


  template <int dim>
  void
  Simulation<dim>::make_constraints(const double time)
  {
    constraints_values.clear();
    constraints_values.reinit(relevant_system);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_values);
    constraints_update.clear();
    constraints_update.reinit(relevant_system);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_update);
    // Hanging nodes alone (weights summing to one, also where a master
    // carries a Dirichlet condition): support forces in compute_reactions.
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
    if (contact->active() && owned_system.size() > dof_handler.n_dofs())
      {
        contact->contact_surfaces().add_constraint_lines(constraints_values);
        contact->contact_surfaces().add_constraint_lines(constraints_update);
      }
    constraints_values.close();
    constraints_update.close();
  }


  // Assembles -R = F_ext - F_int on the free DoFs into newton_rhs and,
  // without constraints, F_int and F_ext for reactions and the force scale.
  template <int dim>
  void
  Simulation<dim>::assemble(const bool with_matrix, const bool trial)
  {
    timer.enter_subsection("bulk assembly");
    if (with_matrix)
      system_matrix = 0;
    newton_rhs     = 0;
    internal_force = 0;
    external_force = 0;

    bulk->assemble(dof_handler,
                   solution,
                   constraints_update,
                   with_matrix ? &system_matrix : nullptr,
                   newton_rhs,
                   internal_force,
                   external_force);
    timer.leave_subsection("bulk assembly");
    contact_force = 0;
    if (contact->active())
      {
        TimerOutput::Scope tc(timer, "contact assembly");
        contact_statistics =
          contact->assemble(state,
                            state_step_start,
                            constraints_update,
                            with_matrix ? &system_matrix : nullptr,
                            newton_rhs,
                            contact_force,
                            !with_matrix && !trial);
      }
    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    newton_rhs.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    external_force.compress(VectorOperation::add);
    contact_force.compress(VectorOperation::add);
  }


  template <int dim>
  void
  Simulation<dim>::update_solution()
  {
    TrilinosWrappers::MPI::Vector owned(locally_owned, mpi_communicator);
    for (const auto i : locally_owned)
      owned[i] = state[i];
    owned.compress(VectorOperation::insert);
    solution = owned;
  }


  unsigned int
  run_from_file(const std::string &filename, const MPI_Comm mpi_communicator)
  {
    ParameterHandler prm;
    const Parameters parameters = read_parameters(filename, prm);
    // Before any work: the results must have somewhere to go.
    check_output_directory(parameters.output.directory, mpi_communicator);
    // Errors leave the Simulation's scope only after it is destroyed, so
    // its TimerOutput does not complain about an exception in flight.
    std::exception_ptr failure;
    unsigned int       failed_checks = 0;
    const auto         run = [&](auto &&simulation) {
      try
        {
          simulation.run();
          failed_checks = simulation.failed_checks();
        }
      catch (...)
        {
          failure = std::current_exception();
        }
    };
    if (parameters.dimension == 2)
      run(Simulation<2>(parameters, prm, mpi_communicator));
    else
      run(Simulation<3>(parameters, prm, mpi_communicator));
    if (failure)
      std::rethrow_exception(failure);
    return failed_checks;
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
