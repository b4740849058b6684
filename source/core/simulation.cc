#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/base/bounding_box.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include <signorini/core/input_checks.h>
#include <signorini/core/simulation.h>

#include <algorithm>
#include <signorini/geometry/mesh_checks.h>
#include <signorini/geometry/scene.h>
#include <signorini/material/projected_volumetric_strain.h>
#include <signorini/postprocess/contact_checks.h>
#include <signorini/postprocess/format.h>
#include <signorini/postprocess/stress_postprocessor.h>
#include <signorini/solver/roundoff.h>

#include <cmath>
#include <chrono>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <iomanip>
#include <functional>
#include <limits>
#include <set>
#include <sstream>

namespace Signorini
{
  using Postprocess::format;

  namespace
  {
    // FunctionParser with x, y(, z), t and the user's constants.
    template <int dim>
    std::unique_ptr<FunctionParser<dim>>
    make_function(const std::vector<std::string> &expressions,
                  const std::map<std::string, double> &constants,
                  const std::string &                  where)
    {
      auto f = std::make_unique<FunctionParser<dim>>(expressions.size());
      const std::string variables = dim == 2 ? "x,y,t" : "x,y,z,t";
      try
        {
          f->initialize(variables, expressions, constants, true);
          // muparser reports some errors only on evaluation.
          f->value(Point<dim>(), 0);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream info;
          e.print_info(info);
          std::string text = info.str();
          for (auto &c : text)
            if (c == '\n')
              c = ' ';
          throw InputError(where + ": cannot parse the expression(s) '" +
                           Utilities::trim(
                             [&] {
                               std::string s;
                               for (const auto &e : expressions)
                                 s += (s.empty() ? "" : "; ") + e;
                               return s;
                             }()) +
                           "' (variables: " + variables +
                           ", plus 'Function constants'). " +
                           Utilities::trim(text));
        }
      return f;
    }

    // The log line of a residual accepted at the round-off floor (Newton
    // loop): @p relative over the force level, @p why the rule.
    std::string
    floor_line(const double relative, const double floor, const char *why)
    {
      std::ostringstream s;
      s << "    residual " << std::scientific << std::setprecision(2)
        << relative << " " << why << " (round-off floor "
        << std::setprecision(1) << floor << "): accepted";
      return s.str();
    }
    constexpr const char *stagnated_why = "no longer decreases";
    constexpr const char *exact_why =
      "after an exact step of linear equations";

    // The residual norm from its three block norms (u, lambda, Lambda).
    double
    norm_of(const std::array<double, 3> &block)
    {
      return std::sqrt(block[0] * block[0] + block[1] * block[1] +
                       block[2] * block[2]);
    }

    // Why a Newton solve used up its iterations, from its residuals over
    // the force level, the status changes of the last iterate and the
    // rigid motions nothing held at the last solve.
    std::pair<NewtonFailure, std::string>
    newton_failure_reason(const std::vector<double> &r,
                          const unsigned int         n_changed,
                          const std::string &        free_motions,
                          const unsigned int         max_iterations)
    {
      std::ostringstream s;
      s << std::scientific << std::setprecision(2);
      const double last = r.empty() ? 0. : r.back();
      // Stagnation: the last residual is not below half the smallest of
      // the few iterates before it.
      const std::size_t n = r.size(), k = std::max<std::size_t>(3, n / 4);
      const bool        stalled =
        n > k && last > 0.5 * *std::min_element(r.end() - k - 1, r.end() - 1);
      NewtonFailure kind = NewtonFailure::iteration_limit;
      if (n_changed > 0)
        {
          kind = NewtonFailure::statuses;
          s << "the contact statuses still change at the last Newton "
               "iterate ("
            << n_changed << " changed, |R|/|F| = " << last << ")";
        }
      else if (stalled)
        {
          kind = NewtonFailure::stagnation;
          s << "the residual stagnates at |R|/|F| = " << last
            << " with settled contact statuses";
        }
      else
        s << "'Newton/Maximum iterations' (" << max_iterations
          << ") was reached while the residual still decreased (|R|/|F| = "
          << last << ")";
      if (!free_motions.empty())
        s << "; at the last iterate nothing held " << free_motions
          << " (no Dirichlet condition along it and no closed point "
             "sticking: under force control a tangential load above mu "
             "times the normal force has no equilibrium)";
      return {kind, s.str()};
    }
  } // namespace


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
    , sout(std::cout,
           Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
    , materials(Material::make_materials<dim>(parameters, prm))
    , obstacles(Obstacles::make_obstacles<dim>(parameters, prm))
    , timer(mpi_communicator,
            sout,
            TimerOutput::never,
            TimerOutput::wall_times)
    , triangulation(mpi_communicator,
                    Triangulation<dim>::limit_level_difference_at_vertices)
    , fe(FE_Q<dim>(parameters.fe_degree), dim)
    , dof_handler(triangulation)
    , linear_solver(
        std::make_unique<Solver::LinearSolver<dim>>(parameters.linear_solver))
    , contact_reference_checks(parameters)
  {
    const auto &bc = parameters.boundary_conditions;
    for (unsigned int k = 0; k < bc.dirichlet.size(); ++k)
      dirichlet_functions.push_back(make_function<dim>(
        bc.dirichlet[k].values,
        bc.constants,
        "subsection 'Boundary conditions/Dirichlet " + std::to_string(k + 1) +
          "', parameter 'Values'"));
    for (unsigned int k = 0; k < bc.neumann.size(); ++k)
      neumann_functions.push_back(make_function<dim>(
        bc.neumann[k].values,
        bc.constants,
        "subsection 'Boundary conditions/Neumann " + std::to_string(k + 1) +
          "', parameter 'Values'"));
    body_force = make_function<dim>(
      std::vector<std::string>(bc.body_force.begin(),
                               bc.body_force.begin() + dim),
      bc.constants,
      "subsection 'Boundary conditions', parameter 'Body force'");
    for (const auto &[id, material] : materials)
      materials_linear &= material->is_linear();
    bulk = std::make_unique<Bulk::Assembler<dim>>(
      parameters, fe, materials, neumann_functions, *body_force);
    contact = std::make_unique<Contact::ContactProblem<dim>>(
      parameters,
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
    const auto  ids = Geometry::boundary_ids(triangulation);
    std::string available;
    for (const auto id : ids)
      available += (available.empty() ? "" : ", ") + std::to_string(id);
    const auto check = [&](const unsigned int id, const std::string &where) {
      if (ids.count(id) == 0)
        throw InputError(where + ", parameter 'Boundary id': the mesh has no "
                                 "boundary with id " +
                         std::to_string(id) + " (it has: " + available +
                         "). Set 'Boundary id' to one of these.");
    };
    const auto &bc = parameters.boundary_conditions;
    for (unsigned int k = 0; k < bc.dirichlet.size(); ++k)
      for (const auto id : bc.dirichlet[k].boundary_ids)
        check(id,
              "subsection 'Boundary conditions/Dirichlet " +
                std::to_string(k + 1) + "'");
    for (unsigned int k = 0; k < bc.neumann.size(); ++k)
      for (const auto id : bc.neumann[k].boundary_ids)
        check(id,
              "subsection 'Boundary conditions/Neumann " +
                std::to_string(k + 1) + "'");

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
        const auto n_system = contact->n_system();
        owned_system        = IndexSet(n_system);
        owned_system.add_indices(locally_owned);
        owned_system.add_indices(contact->locally_owned_multipliers());
        owned_system.compress();
        relevant_system = IndexSet(n_system);
        relevant_system.add_indices(locally_relevant);
        relevant_system.add_indices(contact->extra_relevant());
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
    linear_solver->set_null_space(dof_handler, locally_owned);
    rigid_modes.setup(dof_handler,
                      constraints_update,
                      owned_system,
                      parameters.axisymmetric,
                      mpi_communicator);
    if (contact->active())
      linear_solver->set_multipliers(dof_handler.n_dofs(),
                                     contact->locally_owned_multipliers());
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
    const auto &bc = parameters.boundary_conditions;
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
    dirichlet_dofs.assign(bc.dirichlet.size(), {});

    for (unsigned int k = 0; k < bc.dirichlet.size(); ++k)
      {
        const auto &d = bc.dirichlet[k];
        auto &      f = *dirichlet_functions[k];
        f.set_time(time);
        const bool   at_point = !d.at_point.empty();
        Point<dim>   point;
        if (at_point)
          point = to_point<dim>(d.at_point, "Dirichlet/At point");
        const double tolerance =
          1e-8 * model_size;
        unsigned int found = 0;
        // Nodes of this boundary (vertices only for 'At point'); every
        // support point gets the value of its component's expression.
        std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
        const auto &unit_face_points = fe.get_unit_face_support_points();
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial())
            for (const unsigned int fi : cell->face_indices())
              if (cell->face(fi)->at_boundary() &&
                  std::count(d.boundary_ids.begin(),
                             d.boundary_ids.end(),
                             cell->face(fi)->boundary_id()))
                {
                  const auto face = cell->face(fi);
                  face->get_dof_indices(face_dofs);
                  for (unsigned int i = 0; i < face_dofs.size(); ++i)
                    {
                      const unsigned int comp =
                        fe.face_system_to_component_index(i).first;
                      const auto pos =
                        std::find(d.components.begin(),
                                  d.components.end(),
                                  comp);
                      if (pos == d.components.end())
                        continue;
                      // Support point in real space (bilinear map of the
                      // face: exact for the straight faces of generated
                      // meshes, nodes of curved faces lie on the manifold
                      // after refinement only at vertices).
                      Point<dim> x;
                      const auto &up = unit_face_points[i];
                      for (const unsigned int v : face->vertex_indices())
                        {
                          double shape = 1.;
                          for (unsigned int c = 0; c < dim - 1; ++c)
                            shape *= ((v >> c) & 1) ? up[c] : 1 - up[c];
                          x += shape * face->vertex(v);
                        }
                      if (at_point && x.distance(point) > tolerance)
                        continue;
                      const types::global_dof_index dof = face_dofs[i];
                      const double value =
                        f.value(x, pos - d.components.begin());
                      if (!constraints_values.is_constrained(dof))
                        {
                          constraints_values.add_line(dof);
                          constraints_values.set_inhomogeneity(dof, value);
                          constraints_update.add_line(dof);
                        }
                      if (locally_owned.is_element(dof))
                        dirichlet_dofs[k].emplace_back(dof, comp);
                      ++found;
                    }
                }
        if (at_point &&
            Utilities::MPI::sum(found, mpi_communicator) == 0)
          throw InputError(
            "subsection 'Boundary conditions/Dirichlet " +
            std::to_string(k + 1) +
            "', parameter 'At point': no mesh node of the listed boundary "
            "id(s) lies at this point. Give the coordinates of a vertex of that "
            "boundary.");
        std::sort(dirichlet_dofs[k].begin(), dirichlet_dofs[k].end());
        dirichlet_dofs[k].erase(std::unique(dirichlet_dofs[k].begin(),
                                            dirichlet_dofs[k].end()),
                                dirichlet_dofs[k].end());
      }
    if (contact->active() && owned_system.size() > dof_handler.n_dofs())
      {
        contact->add_constraint_lines(constraints_values);
        contact->add_constraint_lines(constraints_update);
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


  // One load step (formulation.md 7): Dirichlet values of the new time on
  // the iterate, then the geometric loop (pairing, Newton) with contact, or
  // Newton alone without.
  template <int dim>
  bool
  Simulation<dim>::solve_load_step(const double  time,
                                   const double  step_start_time,
                                   unsigned int &iterations,
                                   const bool    resume)
  {
    history_time      = time;
    history_geometric = 0;
    pairing_step_start_time = step_start_time;
    force_scale       = 0;
    make_constraints(time);
    for (auto &f : neumann_functions)
      f->set_time(time);
    body_force->set_time(time);
    // resume (after mesh adaptation): state_step_start is kept and the
    // first iterate is the state as it is, with this step's Dirichlet
    // values.
    if (!resume)
      state_step_start = state;
    {
      // Extrapolated predictor: the last converged increment, scaled to
      // this step's size; Dirichlet values then override their entries.
      // One insert per entry: an add after an insert would leave the ranks
      // with and without DoFs in different compress modes (a deadlock).
      const double factor =
        !resume && parameters.load_stepping.extrapolate && last_step_size > 0 ?
          (time - step_start_time) / last_step_size :
          0.;
      TrilinosWrappers::MPI::Vector owned(owned_system, mpi_communicator);
      for (const auto i : owned_system)
        owned[i] = factor != 0 ? state[i] + factor * last_increment[i] :
                                 static_cast<double>(state[i]);
      owned.compress(VectorOperation::insert);
      constraints_values.distribute(owned);
      state = owned;
    }
    update_solution();
    iterations = 0;
    if (!contact->active())
      return newton(iterations);

    const auto &c       = parameters.contact;
    const bool  verbose = parameters.output.verbosity != Verbosity::quiet;
    contact->start_geometric_loop();
    for (unsigned int g = 1; g <= c.max_geometric_iterations; ++g)
      {
        history_geometric = g;
        {
          TimerOutput::Scope t(timer, "pairing");
          contact->pair(state, time, step_start_time);
          if (const unsigned int n = contact->deep_points(); n > 0)
            pcout << "    pairing: " << n
                  << " slave point(s) deep inside the master body, paired "
                     "from the penetrated side"
                  << std::endl;
          if (const unsigned int n = contact->newly_pinned(); n > 0)
            {
              cycle_detections += n;
              points_frozen += n;
              pcout << "    geometric loop: " << n
                    << " point(s) back on their master face of two pairings"
                       " before: pinned to it for the rest of the step"
                    << std::endl;
            }
          if (first_pairing)
            {
              TrilinosWrappers::MPI::Vector owned(owned_system,
                                                  mpi_communicator);
              owned = state;
              contact->set_initial_multipliers(state, owned);
              // Hanging and excluded multipliers follow their constraint
              // lines from the start: Newton updates are distributed with
              // homogeneous lines, so a start off the lines would stay off.
              constraints_values.distribute(owned);
              state         = owned;
              first_pairing = false;
            }
        }
        {
          TimerOutput::Scope t(timer, "sparsity");
          make_sparsity();
        }
        state_at_pairing = state;
        unsigned int its = 0;
        // A pairing that will change is not worth the last quadratic
        // iterations: hand over at 'Tolerance between pairings' (not in
        // the last allowed geometric iteration, nor when a new pairing
        // cannot change the equations).
        const double handover =
          g < c.max_geometric_iterations && !contact->pairing_is_exact() ?
            parameters.newton.tolerance_between_pairings :
            0.;
        const bool ok = newton(its, handover);
        iterations += its;
        if (!ok)
          return false;
        // Rigid obstacles projected at every iterate: nothing to re-pair.
        if (contact->pairing_is_exact())
          return true;
        // Largest displacement change since the pairing against the step's
        // increment (code_aster's criterion, formulation.md 7.3).
        double change = 0, increment = 0;
        for (const auto i : locally_owned)
          {
            change =
              std::max(change, std::abs(state[i] - state_at_pairing[i]));
            increment = std::max(increment,
                                 std::abs(state[i] - state_step_start[i]));
          }
        change    = Utilities::MPI::max(change, mpi_communicator);
        increment = Utilities::MPI::max(increment, mpi_communicator);
        const double ratio = increment > 0 ? change / increment : 0.;
        if (verbose)
          pcout << "    geometric iteration " << g
                << ": change/increment = " << std::scientific
                << std::setprecision(2) << ratio << std::defaultfloat
                << std::endl;
        if (ratio <= c.geometric_tolerance)
          {
            // The pairing stays: finish the solve at 'Relative tolerance',
            // unless its last step was exact (linear equations at settled
            // statuses, direct solve) and left a residual above it: a
            // further solve would only stir the round-off.
            const bool at_floor =
              handover > 0 && exact_at_end &&
              residual_at_end > parameters.newton.relative_tolerance;
            if (at_floor)
              pcout << floor_line(residual_at_end, floor_at_end, exact_why)
                    << std::endl;
            if (handover > 0 && !at_floor)
              {
                unsigned int more = 0;
                const bool   done = newton(more);
                iterations += more;
                if (!done)
                  return false;
              }
            if (contact_statistics.n_geometric_frozen > 0)
              pcout << "    geometric loop converged with "
                    << contact_statistics.n_geometric_frozen
                    << " point(s) frozen by the geometric loop, "
                    << contact_statistics.n_geometric_violated
                    << " of them against the plain contact law" << std::endl;
            return true;
          }
        // Anti-cycling across pairings: points back at their status of two
        // pairings before keep one status for the rest of the step.
        if (const unsigned int n = contact->end_geometric_iteration(g); n > 0)
          {
            cycle_detections += n;
            points_frozen += n;
            pcout << "    geometric loop: " << n
                  << " point(s) back at their status of two pairings before:"
                     " status frozen for the rest of the step"
                  << std::endl;
          }
      }
    newton_failure_kind = NewtonFailure::geometric;
    newton_failure      = "the geometric loop did not converge in " +
                     std::to_string(c.max_geometric_iterations) +
                     " pairings ('Contact/Maximum geometric iterations')";
    return false;
  }


  // Adaptive refinement: the Kelly indicator of the displacement, weighted
  // to the energy norm of each cell's material, marks a fixed fraction of
  // the cells; the active contact zone is always refined. The converged
  // state and the state at the start of the step (displacements, and the
  // multipliers as a nodal field on the slave surface) are interpolated to
  // the new mesh.
  template <int dim>
  bool
  Simulation<dim>::adapt_mesh(const double time, const double step_start_time)
  {
    const auto &a = parameters.adaptivity;
    if (maximum_level == 0)
      maximum_level = a.maximum_level > 0 ?
                        a.maximum_level :
                        triangulation.n_global_levels() - 1 + a.cycles;
    update_solution();
    // Vectors in the displacement layout: u and the multiplier field, now
    // and at the step start.
    std::vector<TrilinosWrappers::MPI::Vector> old_vectors;
    unsigned int n_refine = 0, n_coarsen = 0;
    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector>
      transfer(dof_handler);
    {
      TimerOutput::Scope t(timer, "adaptation");
      Vector<float>      indicator(triangulation.n_active_cells());
      KellyErrorEstimator<dim>::estimate(dof_handler,
                                         QGauss<dim - 1>(fe.degree + 1),
                                         {},
                                         solution,
                                         indicator);
      // Energy norm: sqrt(E) of the cell's material (bodies of different
      // stiffness), and sqrt(r) in axisymmetry (the 2 pi r weight).
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            double w =
              materials.at(cell->material_id())->representative_modulus();
            if (parameters.axisymmetric)
              w *= std::max(cell->center()[0], cell->diameter());
            indicator[cell->active_cell_index()] *= std::sqrt(w);
          }
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
        triangulation, indicator, a.refinement_fraction, a.coarsening_fraction);
      if (a.refine_contact_zone && contact->active())
        for (const auto &cell : contact->contact_zone_cells())
          {
            cell->clear_coarsen_flag();
            cell->set_refine_flag();
          }
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            if (cell->refine_flag_set() &&
                static_cast<unsigned int>(cell->level()) >= maximum_level)
              cell->clear_refine_flag();
            n_refine += cell->refine_flag_set() ? 1 : 0;
            n_coarsen += cell->coarsen_flag_set() ? 1 : 0;
          }
      n_refine  = Utilities::MPI::sum(n_refine, mpi_communicator);
      n_coarsen = Utilities::MPI::sum(n_coarsen, mpi_communicator);
      if (n_refine + n_coarsen == 0)
        {
          pcout << "  adaptive refinement: no cell marked (all at 'Maximum "
                   "level'?)"
                << std::endl;
          return false;
        }

      for (const auto *source : {&state, &state_step_start})
        {
          TrilinosWrappers::MPI::Vector u(locally_owned, mpi_communicator);
          TrilinosWrappers::MPI::Vector m(locally_owned, mpi_communicator);
          for (const auto i : locally_owned)
            u[i] = (*source)[i];
          u.compress(VectorOperation::insert);
          if (contact->active())
            contact->multipliers_to_field(*source, m);
          for (const auto *v : {&u, &m})
            {
              old_vectors.emplace_back(locally_owned,
                                       locally_relevant,
                                       mpi_communicator);
              old_vectors.back() = *v;
            }
        }
      std::vector<const TrilinosWrappers::MPI::Vector *> pointers;
      for (const auto &v : old_vectors)
        pointers.push_back(&v);
      triangulation.prepare_coarsening_and_refinement();
      check_adapted_size();
      transfer.prepare_for_coarsening_and_refinement(pointers);
      triangulation.execute_coarsening_and_refinement();
    }
    setup_system();
    TimerOutput::Scope t(timer, "adaptation");
    std::vector<TrilinosWrappers::MPI::Vector> new_vectors(
      old_vectors.size(),
      TrilinosWrappers::MPI::Vector(locally_owned, mpi_communicator));
    std::vector<TrilinosWrappers::MPI::Vector *> pointers;
    for (auto &v : new_vectors)
      pointers.push_back(&v);
    transfer.interpolate(pointers);
    for (auto &v : new_vectors)
      constraints_hanging.distribute(v);

    // Back into the system layout, with the constraint values of each time.
    for (unsigned int k = 0; k < 2; ++k)
      {
        TrilinosWrappers::MPI::Vector s(owned_system, mpi_communicator);
        for (const auto i : locally_owned)
          s[i] = new_vectors[2 * k][i];
        s.compress(VectorOperation::insert);
        if (contact->active())
          {
            TrilinosWrappers::MPI::Vector m(locally_owned,
                                            locally_relevant,
                                            mpi_communicator);
            m = new_vectors[2 * k + 1];
            contact->multipliers_from_field(m, s);
          }
        make_constraints(k == 0 ? time : step_start_time);
        constraints_values.distribute(s);
        (k == 0 ? state : state_step_start) = s;
      }
    update_solution();
    pcout << "  adaptive refinement: " << n_refine << " cells refined, "
          << n_coarsen << " coarsened -> "
          << triangulation.n_global_active_cells() << " cells, "
          << dof_handler.n_dofs() << " displacement DoFs";
    if (contact->active())
      pcout << ", " << contact->n_lambda_dofs() << " lambda, "
            << contact->n_friction_dofs() << " Lambda";
    pcout << std::endl;
    return true;
  }


  // The refinement flagged by adapt_mesh() (prepared) must stay within
  // 'Geometry/Maximum number of cells'; found during the run, so a RunError.
  template <int dim>
  void
  Simulation<dim>::check_adapted_size() const
  {
    const double n_cells = Geometry::cells_after_refinement(triangulation);
    if (n_cells > parameters.geometry.maximum_cells)
      throw RunError(
        "adaptive refinement: the next cycle would make " +
        Geometry::cell_estimate_text(n_cells, parameters) +
        ". The results of the completed steps are in '" +
        parameters.output.directory +
        "'. Lower 'Adaptive refinement/Cycles' or 'Refinement fraction', "
        "set its 'Maximum level', or raise 'Geometry/Maximum number of "
        "cells' if the machine has the memory.");
  }


  // Generalised Newton (formulation.md 7.2): statuses are recomputed at
  // every iterate; converged when every block residual is small AND no
  // status changed since the previous iterate.
  template <int dim>
  bool
  Simulation<dim>::newton(unsigned int &iterations, const double tolerance)
  {
    const bool verbose = parameters.output.verbosity == Verbosity::verbose;
    const bool show_contact =
      contact->active() && parameters.output.verbosity != Verbosity::quiet;
    double residual_before = 0;
    bool   settled_before = false;
    // The iterate is the result of an exact Newton step: a direct solve,
    // the full update, with the statuses of its evaluation (no early
    // release, no frozen point released without a solve).
    bool step_exact = false;
    // Line search: the last solve's base, update and residual, tried at
    // the next evaluation.
    bool                          line_search_pending = false;
    TrilinosWrappers::MPI::Vector search_base, search_update;
    double                        search_residual = 0;
    exact_at_end    = false;
    std::vector<double> residuals; // relative, per iterate (failure reason)
    for (iterations = 0; iterations <= parameters.newton.max_iterations;
         ++iterations)
      {
        // Residual first; the matrix only if a solve follows, so the
        // converged check does not pay for a matrix assembly.
        // rho_t follows the pressure level once per Newton solve: changing
        // it between iterates would change the equations being solved and
        // spoil the quadratic convergence.
        if (contact->active() && iterations == 0)
          {
            contact->update_coefficients(state);
            contact->start_newton_solve();
          }
        // A status change at this iterate means another solve: with
        // 'Pairing at status changes', pair at this iterate first and
        // evaluate it again, so that the pairing follows the active-set
        // search (the first evaluation is undone: the statuses of the
        // last solve stay the reference of the status history).
        const bool pair_here = contact->active() && iterations >= 1 &&
                               contact->pairing_within_newton();
        // Line search (Newton/Line search steps): the full update of the
        // last solve is this iterate. Its evaluation is the trial of the
        // full step, so an accepted full step costs no extra assembly;
        // when it made the residual grow, the evaluation is undone and
        // the fractions are tried (line_search()).
        const bool search = line_search_pending;
        line_search_pending = false;
        const auto saved_points =
          pair_here || search ? contact->save_points() : nullptr;
        assemble(false);
        if (search)
          {
            const double r_full = norm_of(block_residuals());
            if (r_full > (1 - 1e-4) * search_residual)
              {
                contact->restore_points(*saved_points);
                const double alpha = line_search(search_base,
                                                 search_update,
                                                 search_residual,
                                                 r_full);
                if (alpha < 1)
                  step_exact = false;
                TrilinosWrappers::MPI::Vector owned = search_base;
                owned.add(alpha, search_update);
                state = owned;
                update_solution();
                assemble(false);
              }
          }
        bool paired_here = false;
        if (pair_here && contact_statistics.n_changed > 0)
          {
            {
              TimerOutput::Scope t(timer, "pairing");
              contact->restore_points(*saved_points);
              contact->pair(state,
                            history_time,
                            pairing_step_start_time,
                            true);
              make_sparsity();
            }
            assemble(false);
            state_at_pairing = state;
            paired_here      = true;
          }
        const auto   block = block_residuals();
        const double residual = norm_of(block);
        // The force level of the load step so far: the largest internal
        // and external force of its iterates. Not the residual: its
        // multiplier rows (scaled by rho_n) hold rho_n times the initial
        // gaps at a 'closed' start, and its displacement rows rho_n times
        // the gap of a point that just closed, so a level taken from it
        // (and every relative tolerance) depended on the Normal
        // coefficient (c_n = 1e6: a level 1e6 times the load). The
        // maximum over the step: in a later geometric iteration of a
        // stress-free step (open contact, rigid motion) the forces are
        // round-off and must not become the scale.
        force_scale = std::max({force_scale,
                                internal_force.l2_norm(),
                                external_force.l2_norm()});
        const double relative_tolerance =
          tolerance > 0 ? std::max(tolerance,
                                   parameters.newton.relative_tolerance) :
                          parameters.newton.relative_tolerance;
        const auto small = [&](const double r) {
          return r <= parameters.newton.absolute_tolerance ||
                 r <= relative_tolerance * force_scale;
        };
        // Round-off floor (doc/robustness.md, "Round-off floor computed"):
        // the residual cannot go below the round-off of its terms: eps
        // || |K| |x| || for the internal force and the linear contact
        // terms (large where the terms cancel: a rigid motion, a stiffness
        // contrast; Solver::absolute_product_norm() with the last Jacobian
        // and the state it was assembled at: the scale changes little from
        // one iterate to the next, and at the first iterate of a pairing
        // the matrix is not assembled yet), and eps rho_n |x| for the
        // gaps, which are differences of positions (large for large
        // coefficients c_n; ContactProblem::roundoff_scale()). An iterate
        // at or below 10 eps times that scale is accepted once the
        // statuses have settled
        // and Newton can do no more: its last step no longer halved the
        // residual (stagnation), or it was an exact step of equations
        // linear at fixed statuses (a direct solve, the full update;
        // contact->linear_at_fixed_statuses(), and every material says
        // is_linear()),
        // after which what is left is round-off. A Newton that still
        // contracts, or one that stalls above round-off (a Jacobian that is
        // not the derivative of the residual), is never accepted here.
        constexpr double floor_factor =
          10 * std::numeric_limits<double>::epsilon();
        const double bulk_floor = floor_factor * matrix_roundoff;
        const double contact_floor =
          contact->active() ? floor_factor * contact->roundoff_scale() : 0.;
        const double roundoff_floor = std::hypot(bulk_floor, contact_floor);
        const bool statuses_settled =
          !contact->active() || contact_statistics.n_changed == 0;
        const bool stagnated = iterations >= 1 && statuses_settled &&
                               settled_before &&
                               residual > 0.5 * residual_before;
        settled_before  = statuses_settled;
        residual_before = residual;
        const bool exact_step =
          step_exact && statuses_settled && materials_linear &&
          (!contact->active() || contact->linear_at_fixed_statuses());
        const bool at_floor =
          residual <= roundoff_floor && (stagnated || exact_step);
        const bool at_exact_floor = at_floor && exact_step;
        // A force level near zero (a body moving rigidly without touching
        // anything): the displacement rows at the round-off of the
        // internal force are as small as they get, at any iterate (the
        // rigid motion of a predictor), and relative to a force level that
        // is itself round-off they stay near 1e-2.
        const bool below_tolerance =
          (small(block[0]) || block[0] <= bulk_floor) && small(block[1]) &&
          small(block[2]);
        const bool residual_small = below_tolerance || at_floor;
        if (below_tolerance && !small(block[0]) &&
            parameters.output.verbosity != Verbosity::quiet)
          pcout << "    residual at the round-off of the displacement (the "
                   "force level is near zero: a rigid motion): accepted"
                << std::endl;
        if (at_floor && !below_tolerance)
          pcout << floor_line(residual / force_scale,
                              roundoff_floor / force_scale,
                              exact_step ? exact_why : stagnated_why)
                << std::endl;
        // A frozen point (anti-cycling) that the plain law contradicts at
        // the converged iterate is released; Newton goes on from there.
        const bool release = residual_small && statuses_settled &&
                             contact->active() &&
                             contact_statistics.n_violated > 0;
        const bool converged = residual_small && statuses_settled && !release;
        cycle_detections += contact->active() ? contact_statistics.n_cycling : 0;
        points_frozen += contact->active() ? contact_statistics.n_newly_frozen : 0;
        const auto relative = [&](const double r) {
          return force_scale > 0 ? r / force_scale : 0.;
        };
        // Printed: above 1e6 the force level is the round-off of a
        // stress-free state (a body moving freely before contact), and the
        // digits of the ratio are round-off too.
        const auto shown = [&](const double r) {
          std::ostringstream text;
          if (!std::isfinite(r) || !std::isfinite(force_scale))
            text << (std::isnan(r) || std::isnan(force_scale) ? "NaN" :
                                                                 "inf");
          else if (relative(r) > 1e6)
            text << ">1.0e+06";
          else
            text << std::scientific << std::setprecision(2) << relative(r);
          return text.str();
        };
        if (show_contact)
          {
            const auto &st = contact_statistics;
            pcout << "    Newton " << std::setw(2) << iterations
                  << ": |R_u| " << shown(block[0]) << " |R_lambda| "
                  << shown(block[1]);
            if (contact->n_friction_dofs() > 0)
              pcout << " |R_Lambda| " << shown(block[2]);
            pcout << std::defaultfloat << "  contact " << st.n_contact;
            if (contact->n_friction_dofs() > 0)
              pcout << " (stick " << st.n_stick << ", slip " << st.n_slip
                    << ")";
            pcout << " free " << st.n_points - st.n_contact << " changed "
                  << st.n_changed;
            if (st.n_reversed > 0)
              pcout << " (slip reversed " << st.n_reversed << ")";
            if (st.n_cycling > 0)
              pcout << " cycling " << st.n_cycling;
            if (st.n_frozen + st.n_newly_frozen > 0)
              pcout << " frozen " << st.n_frozen + st.n_newly_frozen;
            pcout << (paired_here ? "  (paired again)" : "")
                  << (converged ? "  converged" : "") << std::endl;
          }
        else if (verbose)
          pcout << "    Newton " << std::setw(2) << iterations
                << ": |R|/|F| = " << std::scientific << std::setprecision(2)
                << relative(residual) << std::defaultfloat
                << (converged ? "  converged" : "") << std::endl;
        {
          const auto &       st = contact_statistics;
          std::ostringstream row;
          row << history_step << "," << format(history_time) << ","
              << history_geometric << "," << iterations << ","
              << format(relative(block[0]), 3) << ","
              << format(relative(block[1]), 3) << ","
              << format(relative(block[2]), 3);
          if (contact->active())
            row << "," << st.n_contact << "," << st.n_stick << ","
                << st.n_slip << "," << st.n_changed << "," << st.n_reversed
                << "," << st.n_cycling << "," << st.n_frozen + st.n_newly_frozen;
          else
            row << ",0,0,0,0,0,0,0";
          row << "," << (converged ? 1 : 0);
          newton_rows.push_back(row.str());
        }
        if (!std::isfinite(residual))
          {
            newton_failure_kind = NewtonFailure::non_finite;
            newton_failure =
              "the residual is not finite (" + format(residual, 2) +
              ") at Newton iterate " + std::to_string(iterations) +
              non_finite_loads(history_time);
            return false;
          }
        residuals.push_back(relative(residual));
        if (parameters.newton.check_jacobian && contact->active())
          check_jacobian();
        if (converged)
          {
            exact_at_end      = at_exact_floor;
            residual_at_end   = relative(residual);
            floor_at_end      = relative(roundoff_floor);
            return true;
          }
        if (iterations == parameters.newton.max_iterations)
          break;
        step_exact = false;
        if (release)
          {
            unsigned int       refrozen = 0;
            const unsigned int n        = contact->release_frozen(refrozen);
            points_released += n;
            points_frozen += refrozen;
            if (show_contact)
              {
                pcout << "    frozen point(s) that the contact law "
                         "contradicts: "
                      << n << " released";
                if (refrozen > 0)
                  pcout << ", " << refrozen
                        << " frozen again in the friction status the law "
                           "asks for";
                pcout << std::endl;
              }
            continue; // re-evaluate the same iterate
          }

        // Release extrapolation (a shrinking contact zone): the points
        // released early stay open for this solve only.
        unsigned int n_early = 0;
        if (contact->active() && iterations >= 1)
          if (const unsigned int n = contact->extrapolate_releases(); n > 0)
            {
              n_early = n;
              early_releases += n;
              if (show_contact)
                pcout << "    release extrapolation: " << n
                      << " point(s) opened for this solve" << std::endl;
            }
        assemble(true);
        if (contact->active())
          contact->clear_releases();
        matrix_roundoff =
          Solver::absolute_product_norm(system_matrix, state, mpi_communicator);
        hold_free_motions(iterations);
        TimerOutput::Scope t(timer, "linear solve");
        TrilinosWrappers::MPI::Vector update(owned_system, mpi_communicator);
        const unsigned int krylov =
          linear_solver->solve(system_matrix, update, newton_rhs);
        krylov_iterations += krylov;
        krylov_max = std::max(krylov_max, krylov);
        constraints_update.distribute(update);
        TrilinosWrappers::MPI::Vector owned(owned_system, mpi_communicator);
        owned = state;
        if (parameters.newton.line_search_steps > 0 && contact->active())
          {
            line_search_pending = true;
            search_base         = owned;
            search_update       = update;
            search_residual     = residual;
          }
        owned.add(1., update);
        state = owned;
        update_solution();
        step_exact = krylov == 0 && n_early == 0;
      }
    std::tie(newton_failure_kind, newton_failure) =
      newton_failure_reason(residuals,
                            contact->active() ? contact_statistics.n_changed :
                                                0,
                            free_motions,
                            parameters.newton.max_iterations);
    return false;
  }


  template <int dim>
  void
  Simulation<dim>::hold_free_motions(const unsigned int iteration)
  {
    free_motions.clear();
    const auto free = rigid_modes.find(system_matrix, dof_handler.n_dofs());
    if (free.empty())
      return;
    std::string list;
    for (const auto &m : free)
      list += (list.empty() ? "" : "; ") + rigid_modes.describe(m);
    // Friction can hold the motion once its points have a threshold: at
    // the first iterate after they close it is zero (formulation.md 3.3),
    // and while every point slips there is no tangential stiffness. The
    // motion's share of the update is then set to zero for this solve.
    const bool friction_may_hold = contact->active() &&
                                   contact->n_friction_dofs() > 0 &&
                                   contact_statistics.n_contact > 0;
    if (!friction_may_hold)
      throw RunError(
        "load step " + std::to_string(history_step) + ", Newton iterate " +
        std::to_string(iteration) + ": nothing holds " + list +
        " (no Dirichlet condition constrains it and no closed contact point "
        "resists it), so the linear system is singular. Support the body "
        "along that motion (a Dirichlet condition on that component, on one "
        "node if the body must stay free otherwise: 'Boundary "
        "conditions/Dirichlet k/Node'), drive it by a prescribed "
        "displacement, or let it start in contact ('Contact/Initial status "
        "= closed').");
    rigid_modes.hold(system_matrix, dof_handler.n_dofs(), free);
    free_motions = list;
    if (parameters.output.verbosity != Verbosity::quiet)
      pcout << "    held for this solve (friction without threshold or "
               "slipping everywhere): "
            << list << std::endl;
  }


  template <int dim>
  std::string
  Simulation<dim>::failure_advice() const
  {
    const std::string smaller =
      parameters.load_stepping.explicit_times ?
        "more times in 'Load stepping/Step times'" :
        "more steps ('Load stepping/Number of steps')";
    switch (newton_failure_kind)
      {
        case NewtonFailure::non_finite:
          return newton_failure.find("is not finite at") != std::string::npos ?
                   "Give a load expression that is finite over the load "
                   "path." :
                   "The loads are finite: the iterate diverged; try " +
                     smaller + ".";
        case NewtonFailure::stagnation:
          return "Either the load has no equilibrium (check it against what "
                 "the supports and friction can carry) or the iteration is "
                 "stuck; " +
                 smaller + " helps only in the second case.";
        case NewtonFailure::geometric:
          return "Raise 'Contact/Maximum geometric iterations' or use " +
                 smaller + ".";
        default:
          return "Raise 'Newton/Maximum iterations' or use " + smaller + ".";
      }
  }


  template <int dim>
  std::string
  Simulation<dim>::non_finite_loads(const double t) const
  {
    const auto &bc = parameters.boundary_conditions;
    std::vector<std::pair<std::string, const FunctionParser<dim> *>> loads;
    for (unsigned int k = 0; k < dirichlet_functions.size(); ++k)
      loads.emplace_back("Dirichlet " + std::to_string(k + 1),
                         dirichlet_functions[k].get());
    for (unsigned int k = 0; k < neumann_functions.size(); ++k)
      loads.emplace_back("Neumann " + std::to_string(k + 1),
                         neumann_functions[k].get());
    (void)bc;
    std::string text;
    for (const auto &[name, function] : loads)
      {
        // The first vertex of an owned cell where a component is not
        // finite, reduced to the smallest rank that has one.
        FunctionParser<dim> &f = const_cast<FunctionParser<dim> &>(*function);
        const double         t_before = f.get_time();
        f.set_time(t);
        std::vector<double> where(dim + 1, std::numeric_limits<double>::max());
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() && where[0] == std::numeric_limits<double>::max())
            for (const unsigned int v : cell->vertex_indices())
              {
                bool finite = true;
                for (unsigned int c = 0; c < f.n_components; ++c)
                  finite = finite && std::isfinite(f.value(cell->vertex(v), c));
                if (!finite)
                  {
                    where[0] = Utilities::MPI::this_mpi_process(mpi_communicator);
                    for (unsigned int d = 0; d < dim; ++d)
                      where[d + 1] = cell->vertex(v)[d];
                    break;
                  }
              }
        f.set_time(t_before);
        const auto all = Utilities::MPI::all_gather(mpi_communicator, where);
        for (const auto &w : all)
          if (w[0] != std::numeric_limits<double>::max())
            {
              text += "; subsection 'Boundary conditions/" + name +
                      "', parameter 'Values' is not finite at t = " +
                      format(t, 4) + ", x = (";
              for (unsigned int d = 0; d < dim; ++d)
                text += (d ? ", " : "") + format(w[d + 1], 4);
              text += ")";
              break;
            }
      }
    return text;
  }


  template <int dim>
  std::array<double, 3>
  Simulation<dim>::block_residuals() const
  {
    const types::global_dof_index n_u = dof_handler.n_dofs();
    const types::global_dof_index n_l =
      contact->active() ? contact->n_lambda_dofs() : 0;
    std::array<double, 3> block = {{0, 0, 0}};
    for (const auto i : owned_system)
      block[i < n_u ? 0 : (i < n_u + n_l ? 1 : 2)] +=
        newton_rhs[i] * newton_rhs[i];
    for (auto &b : block)
      b = std::sqrt(Utilities::MPI::sum(b, mpi_communicator));
    return block;
  }


  // Backtracking on the residual norm (Newton/Line search steps): the
  // full update made the residual grow from @p residual_now to
  // @p residual_full; try 1/2, 1/4, ... of it and return the first fraction
  // that decreases the residual, else the one with the smallest residual
  // (1 if no fraction beats the full update). Each trial is a residual
  // evaluation with its own statuses, outside the status history; the
  // contact points are left as they were on entry.
  template <int dim>
  double
  Simulation<dim>::line_search(const TrilinosWrappers::MPI::Vector &base,
                               const TrilinosWrappers::MPI::Vector &update,
                               const double residual_now,
                               const double residual_full)
  {
    TimerOutput::Scope t(timer, "line search");
    const auto   saved            = contact->save_points();
    const auto   saved_statistics = contact_statistics;
    double       best = residual_full, best_alpha = 1, alpha = 1;
    for (unsigned int k = 1; k <= parameters.newton.line_search_steps; ++k)
      {
        alpha *= 0.5;
        TrilinosWrappers::MPI::Vector trial = base;
        trial.add(alpha, update);
        state = trial;
        update_solution();
        assemble(false, true);
        const double r = norm_of(block_residuals());
        if (r < best)
          {
            best       = r;
            best_alpha = alpha;
          }
        if (r <= (1 - 1e-4 * alpha) * residual_now)
          break;
      }
    contact->restore_points(*saved);
    contact_statistics = saved_statistics;
    if (best_alpha < 1)
      {
        ++line_searches;
        if (parameters.output.verbosity != Verbosity::quiet)
          pcout << "    line search: " << best_alpha
                << " of the update (residual " << std::scientific
                << std::setprecision(2) << residual_full / residual_now
                << " -> " << best / residual_now << " of the current)"
                << std::defaultfloat << std::endl;
      }
    return best_alpha;
  }


  // Development check (Newton/Check Jacobian): every column j of the
  // assembled contact matrix K_c against the central difference
  // -(r(x + h e_j) - r(x - h e_j)) / 2h of the contact part r = -R_c of the
  // right-hand side, with the pairing fixed as in Newton. Columns whose
  // perturbation flips a status straddle a kink and are skipped (counted).
  template <int dim>
  void
  Simulation<dim>::check_jacobian()
  {
    const types::global_dof_index n_u = dof_handler.n_dofs();
    const types::global_dof_index n_l = contact->n_lambda_dofs();
    TrilinosWrappers::SparseMatrix K;
    K.reinit(system_matrix);
    K = 0;
    // Right-hand sides with the writable off-rank entries of newton_rhs.
    TrilinosWrappers::MPI::Vector r0 = newton_rhs, r_plus = newton_rhs,
                                  r_minus = newton_rhs;
    r0 = 0;
    TrilinosWrappers::MPI::Vector column(owned_system, mpi_communicator),
      unit(column);
    TrilinosWrappers::MPI::Vector force = contact_force;
    const auto saved_statistics = contact_statistics;
    contact->assemble(state, state_step_start, constraints_update, &K, r0,
                      force);
    K.compress(VectorOperation::add);

    // Step sizes: 1e-6 of the block's largest magnitude
    double scale[3] = {0, 0, 0};
    for (const auto i : owned_system)
      {
        double &s = scale[i < n_u ? 0 : (i < n_u + n_l ? 1 : 2)];
        s         = std::max(s, std::abs(state[i]));
      }
    // and never below a floor (1e-6 of the mesh diameter, 1e-3 of the
    // largest Young's modulus, a contact pressure level, and 1), so that a
    // block that is zero up to round-off is not perturbed by round-off
    // (with a floor of 1e-6 E, lambda = 0 after an open solve gave steps
    // of 1e-12 E and central differences of round-off noise, 6e-5).
    double E_max = 0;
    for (const auto &[id, material] : materials)
      E_max = std::max(E_max, material->representative_modulus());
    const double floor[3] = {1e-6 * model_size,
                             1e-3 * E_max,
                             1.};
    for (unsigned int b = 0; b < 3; ++b)
      scale[b] = 1e-6 * std::max(Utilities::MPI::max(scale[b], mpi_communicator),
                                 floor[b]);

    // The base state with the owned layout, copied entry by entry: an
    // assignment between vectors of different layouts may take a
    // collective code path on some ranks only.
    TrilinosWrappers::MPI::Vector base(owned_system, mpi_communicator);
    for (const auto i : owned_system)
      base[i] = state[i];
    base.compress(VectorOperation::insert);
    double       worst = 0;
    unsigned int n_checked = 0, n_kinked = 0;
    double       block_size[3] = {0, 0, 0};
    std::vector<std::pair<unsigned int, double>> differences;
    const auto   evaluate  = [&](const types::global_dof_index j,
                              const double                  delta,
                              TrilinosWrappers::MPI::Vector &r) {
      TrilinosWrappers::MPI::Vector owned = base;
      if (owned_system.is_element(j))
        owned[j] += delta;
      owned.compress(VectorOperation::insert);
      state = owned;
      r     = 0;
      const auto st = contact->assemble(
        state, state_step_start, constraints_update, nullptr, r, force);
      r.compress(VectorOperation::add);
      return st.n_changed;
    };
    for (const auto j : contact->coupled_dofs())
      {
        // Each rank knows the constraint lines of its relevant DoFs only;
        // all ranks must take the same branch (collective calls follow).
        if (Utilities::MPI::max(constraints_update.is_constrained(j) ? 1 : 0,
                                mpi_communicator) > 0)
          continue;
        const unsigned int b = j < n_u ? 0 : (j < n_u + n_l ? 1 : 2);
        unit = 0;
        if (owned_system.is_element(j))
          unit[j] = 1;
        unit.compress(VectorOperation::insert);
        K.vmult(column, unit);
        // The block's size from every column, also those at a kink: when
        // the few smooth columns of a block are zero up to round-off,
        // their noise is not an error.
        block_size[b] = std::max(block_size[b], column.linfty_norm());
        const double h = scale[b];
        const unsigned int flips =
          evaluate(j, h, r_plus) + evaluate(j, -h, r_minus);
        if (flips > 0)
          {
            ++n_kinked;
            evaluate(j, 0, r_plus); // statuses back to the base state
            continue;
          }
        r_plus -= r_minus;
        r_plus *= -1. / (2 * h); // the finite-difference column
        column -= r_plus;
        differences.emplace_back(b, column.linfty_norm());
      }
    // Relative to the largest column of the same block (u, lambda,
    // Lambda): a column that is zero up to round-off has a finite-
    // difference column of pure noise, eps |r| / h, which must not count.
    for (const auto &[b, d] : differences)
      if (block_size[b] > 0)
        {
          worst = std::max(worst, d / block_size[b]);
          ++n_checked;
        }
    // The displacement part 'solution' was never touched; restore the
    // state and the statuses and statistics of the base state.
    state = base;
    r0 = 0;
    contact->assemble(state, state_step_start, constraints_update, nullptr, r0,
                      force);
    contact_statistics = saved_statistics;
    jacobian_error_max = std::max(jacobian_error_max, worst);
    pcout << "      Jacobian check: " << n_checked << " columns, "
          << n_kinked << " at a kink, max relative error " << std::scientific
          << std::setprecision(1) << worst << std::defaultfloat << std::endl;
  }


  // Reaction of the supports on the body: F_int - F_ext summed over the
  // DoFs each Dirichlet condition constrains, per component [N].
  template <int dim>
  void
  Simulation<dim>::compute_reactions()
  {
    // The residual R = F_int - F_ext + F_contact with the hanging-node
    // constraints applied (a hanging DoF passes its share to its masters,
    // some of which may carry a Dirichlet condition): at the Dirichlet DoFs
    // it is the force of the supports.
    {
      TrilinosWrappers::MPI::Vector r;
      r.reinit(locally_owned, locally_relevant, mpi_communicator, true);
      for (const auto i : locally_owned)
        {
          const double raw =
            internal_force[i] - external_force[i] + contact_force[i];
          const auto *entries = constraints_hanging.get_constraint_entries(i);
          if (entries && !entries->empty())
            for (const auto &[j, w] : *entries)
              r(j) += w * raw; // hanging: to the masters
          else
            r(i) += raw;
        }
      r.compress(VectorOperation::add);
      support_force.reinit(locally_owned, mpi_communicator);
      support_force = r;
    }
    reactions.assign(dirichlet_dofs.size(), Tensor<1, dim>());
    dirichlet_displacement.assign(dirichlet_dofs.size(), Tensor<1, dim>());
    dirichlet_components.assign(dirichlet_dofs.size(), {});
    for (unsigned int k = 0; k < dirichlet_dofs.size(); ++k)
      {
        Tensor<1, dim> count;
        for (const auto &[dof, component] : dirichlet_dofs[k])
          {
            reactions[k][component] += support_force[dof];
            dirichlet_displacement[k][component] += solution[dof];
            count[component] += 1;
          }
        count = Utilities::MPI::sum(count, mpi_communicator);
        dirichlet_displacement[k] =
          Utilities::MPI::sum(dirichlet_displacement[k], mpi_communicator);
        for (unsigned int d = 0; d < dim; ++d)
          {
            dirichlet_components[k][d] = count[d] > 0;
            if (count[d] > 0)
              dirichlet_displacement[k][d] /= count[d];
          }
        // Round-off (relative to the force level) is printed as zero so the
        // output does not depend on the number of MPI ranks.
        for (unsigned int d = 0; d < dim; ++d)
          {
            reactions[k][d] =
              Utilities::MPI::sum(reactions[k][d], mpi_communicator);
            if (std::abs(reactions[k][d]) < 1e-12 * force_scale)
              reactions[k][d] = 0;
          }
      }
  }


  template <int dim>
  void
  Simulation<dim>::compute_reference_errors(const double time)
  {
    const auto &ref = parameters.reference;
    if (ref.displacement.empty() && ref.stress.empty())
      return;
    const QGauss<dim> quadrature(fe.degree + 2);
    FEValues<dim>     fe_values(fe,
                            quadrature,
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<1, dim>>          u_h(quadrature.size());
    std::vector<SymmetricTensor<2, dim>> eps_h(quadrature.size());
    std::unique_ptr<FunctionParser<dim>> u_exact, s_exact;
    const auto &constants = parameters.boundary_conditions.constants;
    if (!ref.displacement.empty())
      u_exact = make_function<dim>(ref.displacement,
                                   constants,
                                   "subsection 'Reference solution', "
                                   "parameter 'Displacement'");
    if (!ref.stress.empty())
      s_exact = make_function<dim>(ref.stress,
                                   constants,
                                   "subsection 'Reference solution', "
                                   "parameter 'Stress'");
    if (u_exact)
      u_exact->set_time(time);
    if (s_exact)
      s_exact->set_time(time);

    // Projected volumetric strain: the stress with theta_bar.
    Material::ProjectedVolumetricStrain<dim> projection(
      fe, quadrature, parameters.axisymmetric);
    Vector<double> local_u(fe.n_dofs_per_cell()), theta_bar;

    double u_err2 = 0, u_norm2 = 0, s_err_max = 0, s_norm_max = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_values(solution, u_h);
          fe_values[displacement].get_function_symmetric_gradients(solution,
                                                                   eps_h);
          if (s_exact && parameters.projected_volumetric_strain)
            {
              projection.reinit(fe_values);
              cell->get_dof_values(solution, local_u);
              projection.coefficients(local_u, theta_bar);
            }
          const auto &material = *materials.at(cell->material_id());
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const auto &x = fe_values.quadrature_point(q);
              if (u_exact)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const double ue = u_exact->value(x, d);
                    u_err2 += std::pow(u_h[q][d] - ue, 2) * fe_values.JxW(q);
                    u_norm2 += ue * ue * fe_values.JxW(q);
                  }
              if (s_exact)
                {
                  // Axisymmetric: the hoop strain u_r / r enters the trace.
                  const double hoop =
                    parameters.axisymmetric ? u_h[q][0] / x[0] : 0.;
                  const double theta =
                    parameters.projected_volumetric_strain ?
                      projection.value(theta_bar, quadrature.point(q)) :
                      0.;
                  SymmetricTensor<2, 3> stress;
                  material.evaluate(
                    Bulk::point_strain<dim>(
                      eps_h[q],
                      hoop,
                      parameters.projected_volumetric_strain ? &theta :
                                                               nullptr),
                    stress,
                    nullptr);
                  const auto s = Material::from_3d<dim>(stress);
                  double     e2 = 0, n2 = 0;
                  for (unsigned int i = 0; i < dim; ++i)
                    for (unsigned int j = 0; j < dim; ++j)
                      {
                        const double se = s_exact->value(x, i * dim + j);
                        e2 += std::pow(s[i][j] - se, 2);
                        n2 += se * se;
                      }
                  s_err_max  = std::max(s_err_max, std::sqrt(e2));
                  s_norm_max = std::max(s_norm_max, std::sqrt(n2));
                }
            }
        }
    u_err2     = Utilities::MPI::sum(u_err2, mpi_communicator);
    u_norm2    = Utilities::MPI::sum(u_norm2, mpi_communicator);
    s_err_max  = Utilities::MPI::max(s_err_max, mpi_communicator);
    s_norm_max = Utilities::MPI::max(s_norm_max, mpi_communicator);
    if (u_exact)
      errors.displacement_l2_relative =
        u_norm2 > 0 ? std::sqrt(u_err2 / u_norm2) : std::sqrt(u_err2);
    if (s_exact)
      errors.stress_max_relative =
        s_norm_max > 0 ? s_err_max / s_norm_max : s_err_max;
  }


  // Displacement component at a point: the first locally owned cell that
  // contains it (lowest rank wins).
  template <int dim>
  double
  Simulation<dim>::point_value(const Point<dim> &p,
                               const unsigned int component) const
  {
    const MappingQ1<dim> mapping;
    double               value = 0;
    bool                 found = false;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && !found)
        {
          if (!cell->bounding_box().point_inside(p, 1e-10))
            continue;
          Point<dim> unit;
          try
            {
              unit = mapping.transform_real_to_unit_cell(cell, p);
            }
          catch (...)
            {
              continue;
            }
          if (!GeometryInfo<dim>::is_inside_unit_cell(unit, 1e-8))
            continue;
          const Quadrature<dim> q(GeometryInfo<dim>::project_to_unit_cell(unit));
          FEValues<dim>     fv(mapping, fe, q, update_values);
          fv.reinit(cell);
          std::vector<Vector<double>> v(1, Vector<double>(dim));
          fv.get_function_values(solution, v);
          value = v[0][component];
          found = true;
        }
    const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int owner = Utilities::MPI::min(
      found ? rank : std::numeric_limits<unsigned int>::max(),
      mpi_communicator);
    if (owner == std::numeric_limits<unsigned int>::max())
      throw InputError("subsection 'Reference solution', parameter 'Point "
                       "values': the point lies in no cell of the mesh. Give "
                       "a point of a body.");
    return Utilities::MPI::sum(rank == owner ? value : 0., mpi_communicator);
  }


  template <int dim>
  void
  Simulation<dim>::output_results(const unsigned int step, const double time)
  {
    if (!parameters.output.write_vtu)
      return;
    TimerOutput::Scope t(timer, "output");
    DoFHandler<dim>    scalar_dofs(triangulation); // contact fields
    DataOut<dim>       data_out;
    data_out.attach_dof_handler(dof_handler);
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(dim,
                     DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(solution,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             interpretation);
    Postprocess::StressPostprocessor<dim> stress(
      materials,
      parameters.axisymmetric,
      parameters.projected_volumetric_strain ? &fe : nullptr,
      &solution);
    data_out.add_data_vector(solution, stress);
    Vector<float> material_id(triangulation.n_active_cells());
    Vector<float> subdomain(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          material_id(cell->active_cell_index()) = cell->material_id();
          subdomain(cell->active_cell_index()) = cell->subdomain_id();
        }
    data_out.add_data_vector(material_id, "material_id");
    data_out.add_data_vector(subdomain, "subdomain");
    // Contact fields at the slave nodes (zero elsewhere).
    std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector>> fields;
    if (contact->active())
      {
        scalar_dofs.distribute_dofs(fe.base_element(0));
        fields = contact->nodal_fields(scalar_dofs);
        for (const auto &[name, vector] : fields)
          data_out.add_data_vector(scalar_dofs, vector, name);
      }
    data_out.build_patches(fe.degree);
    write_solution_files(data_out, step, time);
  }


  // The names of DataOut::write_vtu_with_pvtu_record(), which writes in
  // place and leaves a truncated file behind a kill or a full disk: here
  // every file goes through a temporary name, each rank's piece first,
  // then (rank 0, once every piece is in place) the step's PVTU record,
  // then the PVD list, which so names complete steps only.
  template <int dim>
  void
  Simulation<dim>::write_solution_files(const DataOut<dim> &data_out,
                                        const unsigned int  step,
                                        const double        time)
  {
    const unsigned int rank =
      Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int n_ranks =
      Utilities::MPI::n_mpi_processes(mpi_communicator);
    const unsigned int digits =
      Utilities::needed_digits(std::max(0, static_cast<int>(n_ranks) - 1));
    const std::string stem = "solution_" + Utilities::int_to_string(step, 4);
    const auto        piece = [&](const unsigned int r) {
      return stem + "." + Utilities::int_to_string(r, digits) + ".vtu";
    };
    const std::string directory = parameters.output.directory + "/";
    check_output(Postprocess::write_atomically(
      directory + piece(rank),
      [&](std::ostream &out) { data_out.write_vtu(out); }));
    std::string failure;
    if (rank == 0)
      {
        std::vector<std::string> pieces;
        for (unsigned int r = 0; r < n_ranks; ++r)
          pieces.push_back(piece(r));
        failure = Postprocess::write_atomically(
          directory + stem + ".pvtu",
          [&](std::ostream &out) { data_out.write_pvtu_record(out, pieces); });
        if (failure.empty())
          {
            pvtu_records.emplace_back(time, stem + ".pvtu");
            failure = Postprocess::write_atomically(
              directory + "solution.pvd", [&](std::ostream &out) {
                DataOutBase::write_pvd_record(out, pvtu_records);
              });
          }
      }
    check_output(failure);
  }


  template <int dim>
  std::string
  Simulation<dim>::write_statistics(const unsigned int step,
                                    const double       time,
                                    const unsigned int newton_iterations)
  {
    // Largest displacement magnitude at the nodes.
    double u_max = 0;
    for (const auto i : locally_owned)
      u_max = std::max(u_max, std::abs(solution[i]));
    u_max = Utilities::MPI::max(u_max, mpi_communicator);

    std::vector<std::string> row = {std::to_string(step),
                                    format(time),
                                    std::to_string(newton_iterations),
                                    std::to_string(step_cuts),
                                    std::to_string(cycle_detections),
                                    std::to_string(points_frozen),
                                    format(u_max)};
    step_iterations.push_back(newton_iterations);
    run_cuts += step_cuts;
    run_cycles += cycle_detections;
    run_frozen += points_frozen;
    run_released += points_released;
    run_line_searches += line_searches;
    const char *axis[] = {"x", "y", "z"};
    // Contact pair summaries, their forces with round-off (relative to the
    // force level) set to zero so that output does not depend on the ranks.
    auto summary = contact->active() ?
                     contact->summary() :
                     std::vector<typename Contact::ContactProblem<
                       dim>::PairSummary>();
    for (auto &s : summary)
      for (unsigned int d = 0; d < dim; ++d)
        if (std::abs(s.force[d]) < 1e-10 * force_scale)
          s.force[d] = 0;
    const bool header = statistics_header.empty();
    if (header)
      statistics_header = {"step",
                           "time",
                           "newton_iterations",
                           "step_cuts",
                           "cycle_detections",
                           "points_frozen",
                           "max_abs_u"};
    const auto add_text = [&](const std::string &name, std::string value) {
      if (header)
        statistics_header.push_back(name);
      row.push_back(std::move(value));
    };
    const auto add = [&](const std::string &name, const double value) {
      add_text(name, format(value));
    };
    // Force-displacement data: each Dirichlet condition's reaction and the
    // mean displacement it prescribes (constrained components only), each
    // contact pair's force on the slave, closed points and, for a rigid
    // obstacle, its prescribed motion.
    for (unsigned int k = 0; k < reactions.size(); ++k)
      {
        const std::string name = "_" + std::to_string(k + 1) + "_";
        for (unsigned int d = 0; d < dim; ++d)
          add("reaction" + name + axis[d], reactions[k][d]);
        for (unsigned int d = 0; d < dim; ++d)
          if (dirichlet_components[k][d])
            add("displacement" + name + axis[d], dirichlet_displacement[k][d]);
      }
    for (unsigned int p = 0; p < summary.size(); ++p)
      {
        const std::string name = "_" + std::to_string(p + 1) + "_";
        for (unsigned int d = 0; d < dim; ++d)
          add("contact_force" + name + axis[d], summary[p].force[d]);
        add_text("contact_points" + name + "closed",
                 std::to_string(summary[p].n_contact));
        if (parameters.contact.pairs[p].friction > 0)
          {
            add_text("contact_points" + name + "stick",
                     std::to_string(summary[p].n_stick));
            add_text("contact_points" + name + "slip",
                     std::to_string(summary[p].n_slip));
          }
        if (summary[p].rigid)
          for (unsigned int d = 0; d < dim; ++d)
            add("obstacle_displacement" + name + axis[d],
                summary[p].obstacle_displacement[d]);
      }
    pcout << "  Newton iterations: " << newton_iterations << "\n";
    if (parameters.linear_solver.type != LinearSolverType::direct)
      {
        pcout << "  Krylov iterations: " << krylov_iterations
              << " in this step, at most " << krylov_max << " per solve\n";
        krylov_iterations = krylov_max = 0;
      }
    if (cycle_detections + points_frozen + points_released > 0)
      pcout << "  anti-cycling: " << cycle_detections
            << " status cycle(s) detected, " << points_frozen
            << " point(s) frozen, " << points_released << " released\n";
    pcout << "  max |u_i| = " << format(u_max) << "\n";
    // Components below 1e-10 of the largest reaction are round-off (sums of
    // nodal forces that cancel; with nu -> 0.5 lambda amplifies the
    // round-off of the displacement) and are printed as 0 (the CSV keeps
    // them).
    double largest_reaction = 0;
    for (const auto &r : reactions)
      largest_reaction = std::max(largest_reaction, r.norm());
    for (unsigned int k = 0; k < reactions.size(); ++k)
      {
        pcout << "  reaction Dirichlet " << k + 1 << " = (";
        for (unsigned int d = 0; d < dim; ++d)
          pcout << (d ? ", " : "")
                << format(std::abs(reactions[k][d]) <
                              1e-10 * largest_reaction ?
                            0. :
                            reactions[k][d],
                          4);
        pcout << ")\n";
      }
    const auto &ref = parameters.reference;
    // The step's reference checks, also kept for the end of a quiet run.
    last_checks.clear();
    const auto check_line = [&](const std::string &text, const bool pass) {
      last_checks.push_back(text);
      n_failed_checks += !pass;
      pcout << "  reference check: " << text << "\n";
    };
    const auto report = [&](const char *what, const double e) {
      if (e < 0)
        return;
      check_line(std::string(what) + " = " + format(std::max(e, 1e-16), 1) +
                   " (tolerance " + format(ref.tolerance, 1) +
                   "): " + (e <= ref.tolerance ? "PASS" : "FAIL"),
                 e <= ref.tolerance);
    };
    report("displacement L2 relative error", errors.displacement_l2_relative);
    report("stress max relative error", errors.stress_max_relative);
    if (contact->active())
      {
        for (unsigned int p = 0; p < summary.size(); ++p)
          {
            const auto &s = summary[p];
            pcout << "  contact pair " << p + 1 << ": " << s.n_contact
                  << " of " << s.n_points << " points closed";
            if (parameters.contact.pairs[p].friction > 0)
              pcout << " (stick " << s.n_stick << ", slip " << s.n_slip
                    << ")";
            pcout << ", force on master = (";
            for (unsigned int d = 0; d < dim; ++d)
              pcout << (d ? ", " : "") << format(s.force[d], 4);
            pcout << "), max p = " << format(s.p_max, 4) << "\n";
            // An open pair near contact, or one whose points find no
            // master face at all, is worth a word: bodies loaded towards
            // each other that close no point pass through each other
            // between the contact points (a coarse curved surface), or
            // do not face each other (ids swapped, normals away).
            if (s.n_contact == 0 && s.n_paired == 0)
              pcout << "  note: pair " << p + 1
                    << ": no slave point finds the master within 'Contact/"
                       "Projection tolerance': the surfaces do not face each "
                       "other here (check the slave and master ids and the "
                       "geometry)\n";
            else if (s.n_contact == 0 && -s.max_gap < 0.5 * s.face_size)
              {
                pcout << "  note: pair " << p + 1
                      << " closes no contact point; the nearest is "
                      << format(-s.max_gap, 2) << " m from the master ("
                      << format(-s.max_gap / s.face_size, 2)
                      << " slave faces): if the bodies should touch here, "
                         "the slave points may straddle the contact (refine "
                         "the slave surface, or make the finer surface the "
                         "slave)\n";
              }
          }
        for (const auto &check : contact_checks)
          check_line(check.text, check.pass);
      }
    pcout << std::flush;

    // statistics.csv starts with the header at the first completed step
    // (its columns follow the scene's conditions and pairs).
    const auto line = [](const std::vector<std::string> &fields) {
      std::string text;
      for (unsigned int c = 0; c < fields.size(); ++c)
        text += (c ? "," : "") + fields[c];
      return text + "\n";
    };
    return (header ? line(statistics_header) : std::string()) + line(row);
  }


  template <int dim>
  void
  Simulation<dim>::append_newton_history()
  {
    // Every Newton iterate, including failed attempts before a step cut
    // (their time is the cut step's target), residuals relative to the
    // force scale as on screen.
    std::string failure;
    if (history_file.is_open())
      {
        std::string lines;
        for (const auto &r : newton_rows)
          lines += r + "\n";
        failure = history_file.append(lines);
      }
    newton_rows.clear();
    check_output(failure);
  }


  template <int dim>
  void
  Simulation<dim>::append_statistics(const std::string &lines)
  {
    std::string failure;
    if (parameters.output.write_csv &&
        Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      failure = statistics_file.is_open() ?
                  statistics_file.append(lines) :
                  statistics_file.open(parameters.output.directory +
                                         "/statistics.csv",
                                       lines);
    check_output(failure);
  }


  template <int dim>
  void
  Simulation<dim>::check_output(const std::string &failure) const
  {
    const std::string first =
      Postprocess::first_failure(failure, mpi_communicator);
    if (!first.empty())
      throw RunError(first + ". The result files on disk are complete (up "
                     "to the last step written); make room in '" +
                     parameters.output.directory +
                     "' or choose another 'Output/Directory'.");
  }


  // Results of an earlier run in the directory would be mixed with this
  // run's (more steps, other ranks): this program's own result files are
  // removed first, and said so. The echo never replaces the input file.
  template <int dim>
  void
  Simulation<dim>::prepare_output()
  {
    const std::string &directory = parameters.output.directory;
    std::string        failure;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::error_code error;
        std::filesystem::create_directories(directory, error);
        if (error)
          failure = "cannot create the output directory '" + directory +
                    "': " + error.message();
        const unsigned int n_removed =
          failure.empty() ?
            Postprocess::remove_earlier_results(directory, failure) :
            0;
        if (n_removed > 0)
          sout << "Removed " << n_removed
               << " result file(s) of an earlier run from '" << directory
               << "'" << std::endl;
        const std::string echo =
          Postprocess::echo_filename(directory, parameters.input_file);
        if (echo != directory + "/parameters.prm")
          sout << "Note: '" << directory
               << "/parameters.prm' is the input file: the parameters are "
                  "echoed to '"
               << echo << "'" << std::endl;
        if (failure.empty())
          failure = Postprocess::write_atomically(echo, [&](std::ostream &out) {
            prm.print_parameters(out, ParameterHandler::ShortPRM);
          });
        if (failure.empty() && parameters.output.write_csv)
          failure = history_file.open(
            directory + "/newton_history.csv",
            "step,time,geometric_iteration,newton_iteration,r_u,r_lambda,"
            "r_Lambda,n_contact,n_stick,n_slip,n_changed,n_reversed,"
            "n_cycling,n_frozen,converged\n");
      }
    check_output(failure);
  }


  template <int dim>
  void
  Simulation<dim>::write_step_results(const unsigned int step,
                                      const double       time,
                                      const unsigned int iterations)
  {
    compute_reactions();
    compute_reference_errors(time);
    if (contact->active())
      contact_checks = contact_reference_checks.evaluate(
        time,
        *contact,
        state,
        force_scale,
        [this](const Point<dim> &p, const unsigned int c) {
          return point_value(p, c);
        });
    append_newton_history();
    const std::string statistics_lines =
      write_statistics(step, time, iterations);
    output_results(step, time);
    if (contact->active() && parameters.output.write_csv)
      {
        std::ostringstream name;
        name << parameters.output.directory << "/contact_" << std::setw(4)
             << std::setfill('0') << step << ".csv";
        check_output(contact->write_csv(name.str()));
      }
    // The step's line in statistics.csv last: a step listed there has
    // all its files on disk.
    append_statistics(statistics_lines);
    last_written_time = time;
  }


  template <int dim>
  void
  Simulation<dim>::print_run_summary(const unsigned int n_written,
                                     const unsigned int stopped_in)
  {
    const unsigned int n_steps = parameters.load_stepping.step_times.size();
    // What even a quiet run prints (sout): the last step's reference
    // checks, the run summary, the Jacobian check, timing and memory.
    if (parameters.output.verbosity == Verbosity::quiet && n_written > 0)
      {
        sout << (stopped_in > 0 ? "Last written step, t = " :
                                  "Final step, t = ")
             << format(last_written_time, 4) << "\n";
        for (const auto &line : last_checks)
          sout << "  reference check: " << line << "\n";
      }
    if ((n_steps > 1 || stopped_in > 0) && !step_iterations.empty())
      {
        // Newton iterations per load step (all geometric iterations and
        // cut attempts of the step that converged): median and maximum.
        // (Median of an even count: the mean of the two middle values.)
        std::vector<unsigned int> sorted = step_iterations;
        std::sort(sorted.begin(), sorted.end());
        const std::size_t  m   = sorted.size();
        const unsigned int sum = sorted[(m - 1) / 2] + sorted[m / 2];
        sout << "Run summary";
        if (stopped_in > 0)
          sout << " (stopped in load step " << stopped_in << " of " << n_steps
               << "): " << n_written << " load step(s) written";
        else
          sout << ": " << n_steps << " load steps";
        sout << ", Newton iterations per step median " << sum / 2
             << (sum % 2 ? ".5" : "") << ", max " << sorted.back()
             << ", step cuts " << run_cuts;
        if (contact->active())
          sout << ", status cycles detected " << run_cycles
               << ", points frozen " << run_frozen << ", released "
               << run_released;
        if (early_releases > 0)
          sout << ", opened early (release extrapolation) "
               << early_releases;
        if (run_line_searches > 0)
          sout << ", line searches " << run_line_searches;
        sout << std::endl;
      }
    else if (stopped_in > 0)
      sout << "Run summary (stopped in load step " << stopped_in << " of "
           << n_steps << "): no load step written" << std::endl;
  }


  template <int dim>
  void
  Simulation<dim>::run()
  {
    make_mesh();
    setup_system();
    pcout << "Signorini: " << dim << "D, Q" << fe.degree << ", "
          << triangulation.n_global_active_cells() << " cells, "
          << dof_handler.n_dofs() << " displacement DoFs, "
          << parameters.geometry.bodies.size() << " body(ies)" << std::endl;
    if (parameters.projected_volumetric_strain)
      pcout << "Volumetric strain projected onto Q" << fe.degree - 1
            << " in each cell (B-bar)" << std::endl;
    else
      for (const auto &m : parameters.materials)
        if (m.poissons_ratio >= 0.45)
          pcout << "Note: material " << m.material_id
                << " has Poisson's ratio " << m.poissons_ratio
                << ": pure-displacement elements lock as nu -> 0.5 (contact "
                   "pressures too high); set 'Finite element/Volumetric "
                   "strain = projected'"
                << std::endl;
    if (contact->active())
      pcout << "DoFs per block: u " << dof_handler.n_dofs() << ", lambda "
            << contact->n_lambda_dofs() << ", Lambda "
            << contact->n_friction_dofs() << " (total "
            << contact->n_system() << ")" << std::endl;

    prepare_output();

    const auto &times = parameters.load_stepping.step_times;
    double      t_done = 0;
    TrilinosWrappers::MPI::Vector last_converged = state;
    bool                          none_converged = true;
    // Progress with elapsed and estimated remaining time (from the share of
    // the load path done), on a terminal only: log files and test outputs
    // stay reproducible.
    // (Under OpenMPI the ranks' stdout is a pseudo-terminal even when
    // mpirun's output goes to a file; their stderr is a pipe.)
    const bool show_eta =
      isatty(STDOUT_FILENO) != 0 && isatty(STDERR_FILENO) != 0;
    const auto start    = std::chrono::steady_clock::now();
    for (unsigned int step = 1; step <= times.size(); ++step)
      {
        history_step = step;
        pcout << "Load step " << step << " of " << times.size()
              << ", t = " << format(times[step - 1], 4);
        if (show_eta && t_done > 0)
          {
            const double elapsed =
              std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                            start)
                .count();
            const double left =
              elapsed / t_done * std::max(0., times.back() - t_done);
            pcout << std::fixed << std::setprecision(1) << "  (elapsed "
                  << elapsed << " s, about " << left << " s left)"
                  << std::defaultfloat << std::setprecision(6);
          }
        pcout << std::endl;
        // Sub-steps: the whole step first, halved after each failure.
        unsigned int cuts = 0, total_iterations = 0;
        cycle_detections = points_frozen = points_released = line_searches = 0;
        double       t_sub_start  = t_done; // start of the last converged sub-step
        const double t_step_start = t_done;
        // The converged increment of the last (sub)step: the extrapolated
        // predictor of the next one.
        const auto record_increment = [&]() {
          last_increment.reinit(owned_system, mpi_communicator);
          for (const auto i : owned_system)
            last_increment[i] = state[i] - state_step_start[i];
          last_increment.compress(VectorOperation::insert);
        };
        const auto advance = [&]() {
          double t_target = times[step - 1];
          while (t_done < times[step - 1])
            {
              unsigned int iterations = 0;
              if (solve_load_step(t_target, t_done, iterations))
                {
                  t_sub_start = t_done;
                  record_increment();
                  last_step_size = t_target - t_done;
                  total_iterations += iterations;
                  last_converged = state;
                  none_converged = false;
                  // The quadrature-point history of the materials follows
                  // the converged (sub)steps only.
                  for (auto &[id, material] : materials)
                    material->commit();
                  t_done         = t_target;
                  t_target       = times[step - 1];
                }
              else
                {
                  // Failed attempts cost iterations too: they count.
                  total_iterations += iterations;
                  // Their iterates go to newton_history.csv now: the
                  // retry may be killed, or the run stop below.
                  append_newton_history();
                  state = last_converged;
                  update_solution();
                  for (auto &[id, material] : materials)
                    material->roll_back();
                  // Back to the initial state: the retry needs the initial
                  // multipliers again ('Initial status').
                  if (none_converged)
                    first_pairing = true;
                  if (++cuts > parameters.load_stepping.max_cuts)
                    {
                      // The last converged sub-step of this step, if any,
                      // is written as the step's results (at its time),
                      // and the run summary is printed before the stop.
                      const bool partial = t_done > t_step_start;
                      if (partial)
                        {
                          step_cuts = cuts - 1;
                          pcout << "  results of the last converged "
                                   "sub-step (t = "
                                << format(t_done, 4) << ") written as step "
                                << step << std::endl;
                          write_step_results(step, t_done, total_iterations);
                        }
                      print_run_summary(step - (partial ? 0 : 1), step);
                      throw RunError(
                        "load step " + std::to_string(step) +
                        " did not converge between t = " + format(t_done, 4) +
                        " and t = " + format(t_target, 4) + " after " +
                        std::to_string(parameters.load_stepping.max_cuts) +
                        " step cuts: " + newton_failure +
                        ". The results of the completed steps" +
                        (partial ? " and of the last converged sub-step" :
                                   "") +
                        " are in '" + parameters.output.directory + "'. " +
                        failure_advice());
                    }
                  pcout << "  step not converged ("
                        << newton_failure.substr(0, newton_failure.find("; "))
                        << "): cut to t = "
                        << format(0.5 * (t_done + t_target), 4) << std::endl;
                  t_target = 0.5 * (t_done + t_target);
                }
            }
        };
        advance();
        // Adaptive refinement: refine, transfer, solve the last sub-step
        // again on the new mesh from the transferred converged state; if
        // that fails, from its transferred start, with step cuts.
        const auto &adaptivity = parameters.adaptivity;
        using AdaptedSteps = AdaptivityParameters::Steps;
        if (adaptivity.steps == AdaptedSteps::every ||
            (adaptivity.steps == AdaptedSteps::last && step == times.size()))
          for (unsigned int cycle = 1; cycle <= adaptivity.cycles; ++cycle)
            {
              pcout << "  adaptive cycle " << cycle << " of "
                    << adaptivity.cycles << std::endl;
              if (!adapt_mesh(t_done, t_sub_start))
                break;
              unsigned int iterations = 0;
              const bool   ok =
                solve_load_step(t_done, t_sub_start, iterations, true);
              total_iterations += iterations;
              if (!ok)
                {
                  pcout << "  not converged on the refined mesh: again from "
                           "the start of the step"
                        << std::endl;
                  state = state_step_start;
                  update_solution();
                  t_done         = t_sub_start;
                  last_converged = state;
                  advance();
                }
              record_increment();
              last_converged = state;
            }
        step_cuts = cuts;
        write_step_results(step, times[step - 1], total_iterations);
        // 'Steps = between': the mesh follows the converged state; the
        // next step starts on it from the transferred state (its
        // increment: the extrapolated predictor's).
        if (adaptivity.steps == AdaptedSteps::between && step < times.size())
          for (unsigned int cycle = 1; cycle <= adaptivity.cycles; ++cycle)
            {
              pcout << "  adaptive cycle " << cycle << " of "
                    << adaptivity.cycles << " for the next step" << std::endl;
              if (!adapt_mesh(t_done, t_sub_start))
                break;
              record_increment();
              last_converged = state;
            }
      }
    print_run_summary(times.size());
    if (parameters.newton.check_jacobian && contact->active())
      sout << "Jacobian check: largest relative error of the contact "
               "Jacobian over the run = "
            << std::scientific << std::setprecision(1) << jacobian_error_max
            << " (tolerance 1.0e-06): "
            << (jacobian_error_max < 1e-6 ? "PASS" : "FAIL")
            << std::defaultfloat << std::endl;
    if (parameters.newton.check_jacobian && contact->active() &&
        !(jacobian_error_max < 1e-6))
      ++n_failed_checks;
    if (n_failed_checks > 0)
      sout << "Reference checks: " << n_failed_checks
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
              << Utilities::MPI::n_mpi_processes(mpi_communicator)
              << " rank(s)" << std::defaultfloat << std::setprecision(6)
              << std::endl;
      }
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
