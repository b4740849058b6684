// The simulation's set-up: the plug-ins, the mesh and its checks against
// the input, the discrete system (the run: simulation_run.cc; adaptivity:
// simulation_adaptivity.cc).
#include <deal.II/base/utilities.h>

#include <signorini/base/format.h>
#include <signorini/base/input_checks.h>
#include <signorini/driver/simulation.h>
#include <signorini/geometry/scene.h>

#include <algorithm>
#include <set>

namespace Signorini
{
  using Postprocess::format;


  template <int dim>
  Simulation<dim>::Simulation(const Parameters &parameters,
                              ParameterHandler &prm,
                              const MPI_Comm    mpi_communicator)
      : parameters(parameters)
      , mpi_communicator(mpi_communicator)
      , pcout(std::cout,
              Utilities::MPI::this_mpi_process(mpi_communicator) == 0 &&
                parameters.output.verbosity != Verbosity::quiet)
      , sout(std::cout, Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      , shapes(Geometry::Shapes::make_shapes<dim>(parameters, prm))
      , materials(Material::make_materials<dim>(parameters, prm))
      , obstacles(Obstacles::make_obstacles<dim>(parameters, prm))
      , timer(mpi_communicator,
              sout,
              TimerOutput::never,
              TimerOutput::wall_times)
      , system(parameters.fe_degree, mpi_communicator)
      , boundary_conditions(parameters.boundary_conditions,
                            parameters.materials)
      , bulk(parameters,
             system.mapping,
             system.fe,
             materials,
             boundary_conditions.neumann(),
             boundary_conditions.body_forces())
      , linear_solver(parameters.linear_solver)
      , contact(parameters,
                system.mapping,
                system.fe,
                system.dof_handler,
                materials,
                std::move(obstacles),
                mpi_communicator)
      , report(parameters, pcout, sout, mpi_communicator)
      , equilibrium(parameters,
                    system,
                    materials,
                    boundary_conditions,
                    bulk,
                    contact,
                    linear_solver,
                    report,
                    timer,
                    pcout)
      , load_step(parameters,
                  system,
                  bulk,
                  boundary_conditions,
                  contact,
                  linear_solver,
                  equilibrium,
                  report,
                  timer,
                  pcout)
      , results(parameters,
                prm,
                system,
                materials,
                boundary_conditions,
                contact,
                report,
                timer,
                sout)
  {
  }


  template <int dim>
  std::vector<typename Contact::ContactProblem<dim>::PairSummary>
  Simulation<dim>::contact_summary() const
  {
    return contact.active() ?
             contact.summary() :
             std::vector<typename Contact::ContactProblem<dim>::PairSummary>();
  }


  template <int dim>
  void
  Simulation<dim>::make_mesh()
  {
    TimerOutput::Scope t(timer, "mesh");
    Geometry::create_mesh(parameters, shapes, system.triangulation);
    system.measure_mesh();
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
        for (const auto &cell : system.triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              x_min = std::min(x_min, cell->vertex(v)[0]);
        x_min = Utilities::MPI::min(x_min, mpi_communicator);
        if (x_min < -1e-10 * system.model_size)
          throw InputError("parameter 'Axisymmetric': the mesh reaches x = " +
                           format(x_min, 4) +
                           " but x is the radius and must be >= 0. Move the "
                           "mesh (Geometry/Body k/Shift) or use a half "
                           "section (e.g. 'Segment = quarter').");
      }
    boundary_conditions.check_boundary_ids(
      Geometry::boundary_ids(system.triangulation));

    std::set<types::material_id> used;
    for (const auto &cell : system.triangulation.cell_iterators_on_level(0))
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
    for (unsigned int k = 0; k < parameters.materials.size(); ++k)
      if (parameters.adaptivity.cycles > 0 &&
          parameters.adaptivity.coarsening_fraction > 0 &&
          materials.at(parameters.materials[k].material_id)
              ->n_history_values() > 0)
        throw InputError(
          "subsection 'Adaptive refinement', parameter 'Coarsening "
          "fraction': material " +
          std::to_string(k + 1) + " ('" + parameters.materials[k].model +
          "') keeps a history at its quadrature points, which is carried "
          "to refined cells but cannot be merged into a coarsened one. Set "
          "'Coarsening fraction = 0'.");
  }



  template <int dim>
  void
  Simulation<dim>::setup_system()
  {
    TimerOutput::Scope t(timer, "setup");
    system.setup(boundary_conditions, contact, linear_solver, pcout);
    linear_solver.set_null_space(system.mapping,
                                 system.dof_handler,
                                 system.locally_owned);
    equilibrium.setup();
    unsigned int n_history = 0;
    for (const auto &[id, material] : materials)
      n_history = std::max(n_history, material->n_history_values());
    system.history.initialize(system.triangulation,
                              bulk.quadrature(),
                              n_history);
    if (contact.active())
      linear_solver.set_multipliers(
        system.dof_handler.n_dofs(),
        contact.contact_surfaces().owned_multipliers());
  }


  template <int dim>
  void
  Simulation<dim>::print_setup()
  {
    pcout << "Signorini: " << dim << "D, Q" << system.fe.degree << ", "
          << system.triangulation.n_global_active_cells() << " cells, "
          << system.dof_handler.n_dofs() << " displacement DoFs, "
          << parameters.geometry.bodies.size() << " body(ies)" << std::endl;
    if (parameters.projected_volumetric_strain)
      pcout << "Volumetric strain projected onto Q" << system.fe.degree - 1
            << " in each cell (B-bar)" << std::endl;
    else
      for (const auto &m : parameters.materials)
        if (m.poissons_ratio >= 0.45)
          pcout << "Note: material " << m.material_id << " has Poisson's ratio "
                << m.poissons_ratio
                << ": pure-displacement elements lock as nu -> 0.5 (contact "
                   "pressures too high); "
                << "set 'Finite element/Volumetric strain = projected'"
                << std::endl;
    if (contact.active())
      pcout << "DoFs per block: u " << system.dof_handler.n_dofs()
            << ", lambda " << contact.contact_surfaces().n_lambda()
            << ", Lambda " << contact.contact_surfaces().n_friction()
            << " (total " << contact.contact_surfaces().n_system() << ")"
            << std::endl;
  }


  unsigned int
  run_from_file(const std::string &filename,
                const MPI_Comm     mpi_communicator,
                const bool         check_only)
  {
    ParameterHandler prm;
    const Parameters parameters = read_parameters(filename, prm);
    // Before any work: the results must have somewhere to go.
    check_output_directory(parameters.output.directory, mpi_communicator);
    // Errors leave the Simulation's scope only after it is destroyed, so
    // its TimerOutput does not complain about an exception in flight.
    std::exception_ptr failure;
    unsigned int       failed_checks = 0;
    const auto         run           = [&](auto &&simulation) {
      try
        {
          if (check_only)
            simulation.check_input();
          else
            {
              simulation.run();
              failed_checks = simulation.failed_checks();
            }
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
