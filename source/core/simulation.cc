#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <signorini/core/simulation.h>
#include <signorini/geometry/scene.h>
#include <signorini/postprocess/stress_postprocessor.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace Signorini
{
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

    std::string
    format(const double value, const int digits = 6)
    {
      std::ostringstream s;
      // Values at round-off level are printed as 0 so that compared output
      // does not depend on the number of MPI ranks.
      s << std::scientific << std::setprecision(digits)
        << (std::abs(value) < 1e-300 ? 0. : value);
      return s.str();
    }
  } // namespace


  template <int dim>
  Simulation<dim>::Simulation(const Parameters &      parameters,
                              const ParameterHandler &prm,
                              const MPI_Comm          mpi_communicator)
    : parameters(parameters)
    , prm(prm)
    , mpi_communicator(mpi_communicator)
    , pcout(std::cout,
            Utilities::MPI::this_mpi_process(mpi_communicator) == 0 &&
              parameters.output.verbosity != Verbosity::quiet)
    , timer(mpi_communicator,
            pcout,
            TimerOutput::never,
            TimerOutput::wall_times)
    , triangulation(mpi_communicator,
                    Triangulation<dim>::limit_level_difference_at_vertices)
    , fe(FE_Q<dim>(parameters.fe_degree), dim)
    , dof_handler(triangulation)
    , materials(Material::make_materials<dim>(parameters))
    , linear_solver(
        std::make_unique<Solver::LinearSolver<dim>>(parameters.linear_solver))
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
    check_input_against_mesh();
  }


  // Everything in the input that refers to the mesh is checked before any
  // work, so that a typo stops the run at once with a clear message.
  template <int dim>
  void
  Simulation<dim>::check_input_against_mesh() const
  {
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
    newton_rhs.reinit(locally_owned, mpi_communicator);
    internal_force.reinit(locally_owned, mpi_communicator);
    external_force.reinit(locally_owned, mpi_communicator);

    // The sparsity pattern holds the Dirichlet couplings too (constraints
    // are applied with keep_constrained_dofs = false at assembly).
    make_constraints(0.);
    TrilinosWrappers::SparsityPattern sp(locally_owned,
                                         locally_owned,
                                         locally_relevant,
                                         mpi_communicator);
    DoFTools::make_sparsity_pattern(dof_handler,
                                    sp,
                                    constraints_update,
                                    false,
                                    Utilities::MPI::this_mpi_process(
                                      mpi_communicator));
    sp.compress();
    system_matrix.reinit(sp);
    linear_solver->set_null_space(dof_handler, locally_owned);
  }


  template <int dim>
  void
  Simulation<dim>::make_constraints(const double time)
  {
    const auto &bc = parameters.boundary_conditions;
    constraints_values.clear();
    constraints_values.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_values);
    constraints_update.clear();
    constraints_update.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_update);
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
          1e-8 * GridTools::diameter(triangulation);
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
    constraints_values.close();
    constraints_update.close();
  }


  // Assembles -R = F_ext - F_int on the free DoFs into newton_rhs and,
  // without constraints, F_int and F_ext for reactions and the force scale.
  template <int dim>
  void
  Simulation<dim>::assemble(const bool with_matrix)
  {
    TimerOutput::Scope t(timer, "bulk assembly");
    if (with_matrix)
      system_matrix = 0;
    newton_rhs     = 0;
    internal_force = 0;
    external_force = 0;

    const QGauss<dim>     quadrature(fe.degree + 1);
    const QGauss<dim - 1> face_quadrature(fe.degree + 1);
    FEValues<dim>         fe_values(fe,
                            quadrature,
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
    FEFaceValues<dim>     fe_face_values(fe,
                                     face_quadrature,
                                     update_values | update_quadrature_points |
                                       update_normal_vectors |
                                       update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);

    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> cell_matrix(n, n);
    Vector<double>     cell_rhs(n), cell_fint(n), cell_fext(n);
    std::vector<types::global_dof_index> dofs(n);
    std::vector<SymmetricTensor<2, dim>> strains(quadrature.size());
    std::vector<SymmetricTensor<2, dim>> sym_grad(n);
    Vector<double>                       force_values(dim);

    const auto &bc = parameters.boundary_conditions;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          cell_fint   = 0;
          cell_fext   = 0;
          const auto &material = materials.at(cell->material_id());
          const auto &C        = material.stiffness();
          fe_values[displacement].get_function_symmetric_gradients(solution,
                                                                   strains);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double JxW = fe_values.JxW(q);
              for (unsigned int i = 0; i < n; ++i)
                sym_grad[i] =
                  fe_values[displacement].symmetric_gradient(i, q);
              const SymmetricTensor<2, dim> stress = C * strains[q];
              body_force->vector_value(fe_values.quadrature_point(q),
                                       force_values);
              for (unsigned int i = 0; i < n; ++i)
                {
                  const unsigned int comp =
                    fe.system_to_component_index(i).first;
                  cell_fint(i) += (stress * sym_grad[i]) * JxW;
                  cell_fext(i) += force_values(comp) *
                                  fe_values.shape_value(i, q) * JxW;
                  if (with_matrix)
                    {
                      const SymmetricTensor<2, dim> Ci = C * sym_grad[i];
                      for (unsigned int j = 0; j < n; ++j)
                        cell_matrix(i, j) += (Ci * sym_grad[j]) * JxW;
                    }
                }
            }

          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              for (unsigned int k = 0; k < bc.neumann.size(); ++k)
                if (std::count(bc.neumann[k].boundary_ids.begin(),
                               bc.neumann[k].boundary_ids.end(),
                               cell->face(f)->boundary_id()))
                  {
                    fe_face_values.reinit(cell, f);
                    auto &g = *neumann_functions[k];
                    for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                      {
                        Tensor<1, dim> traction;
                        const auto &   x = fe_face_values.quadrature_point(q);
                        if (bc.neumann[k].type == NeumannType::traction)
                          for (unsigned int d = 0; d < dim; ++d)
                            traction[d] = g.value(x, d);
                        else
                          traction =
                            -g.value(x, 0) * fe_face_values.normal_vector(q);
                        for (unsigned int i = 0; i < n; ++i)
                          cell_fext(i) +=
                            traction[fe.system_to_component_index(i).first] *
                            fe_face_values.shape_value(i, q) *
                            fe_face_values.JxW(q);
                      }
                  }

          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < n; ++i)
            cell_rhs(i) = cell_fext(i) - cell_fint(i);
          if (with_matrix)
            constraints_update.distribute_local_to_global(
              cell_matrix, cell_rhs, dofs, system_matrix, newton_rhs);
          else
            constraints_update.distribute_local_to_global(cell_rhs,
                                                          dofs,
                                                          newton_rhs);
          internal_force.add(dofs, cell_fint);
          external_force.add(dofs, cell_fext);
        }
    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    newton_rhs.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    external_force.compress(VectorOperation::add);
  }


  template <int dim>
  bool
  Simulation<dim>::solve_load_step(const double time, unsigned int &iterations)
  {
    make_constraints(time);
    for (auto &f : neumann_functions)
      f->set_time(time);
    body_force->set_time(time);

    // Impose the Dirichlet values of this time on the iterate.
    {
      TrilinosWrappers::MPI::Vector owned(locally_owned, mpi_communicator);
      owned = solution;
      constraints_values.distribute(owned);
      solution = owned;
    }

    const bool verbose = parameters.output.verbosity == Verbosity::verbose;
    double     residual_0 = 0;
    for (iterations = 0; iterations <= parameters.newton.max_iterations;
         ++iterations)
      {
        // Residual first; the matrix only if a solve follows, so the
        // converged check does not pay for a matrix assembly.
        assemble(false);
        const double residual = newton_rhs.l2_norm();
        if (iterations == 0)
          {
            residual_0  = residual;
            force_scale = std::max({internal_force.l2_norm(),
                                    external_force.l2_norm(),
                                    residual_0});
          }
        const bool converged =
          residual <= parameters.newton.absolute_tolerance ||
          residual <= parameters.newton.relative_tolerance * force_scale;
        if (verbose)
          pcout << "    Newton " << std::setw(2) << iterations
                << ": |R|/|F| = " << std::scientific << std::setprecision(2)
                << (force_scale > 0 ? residual / force_scale : 0.)
                << std::defaultfloat << (converged ? "  converged" : "")
                << std::endl;
        if (!std::isfinite(residual))
          return false;
        if (converged)
          return true;
        if (iterations == parameters.newton.max_iterations)
          break;

        assemble(true);
        TimerOutput::Scope t(timer, "linear solve");
        TrilinosWrappers::MPI::Vector update(locally_owned, mpi_communicator);
        linear_solver->solve(system_matrix, update, newton_rhs);
        constraints_update.distribute(update);
        TrilinosWrappers::MPI::Vector owned(locally_owned, mpi_communicator);
        owned = solution;
        owned += update;
        solution = owned;
      }
    return false;
  }


  // Reaction of the supports on the body: F_int - F_ext summed over the
  // DoFs each Dirichlet condition constrains, per component [N].
  template <int dim>
  void
  Simulation<dim>::compute_reactions()
  {
    reactions.assign(dirichlet_dofs.size(), Tensor<1, dim>());
    for (unsigned int k = 0; k < dirichlet_dofs.size(); ++k)
      {
        for (const auto &[dof, component] : dirichlet_dofs[k])
          reactions[k][component] +=
            internal_force[dof] - external_force[dof];
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

    double u_err2 = 0, u_norm2 = 0, s_err_max = 0, s_norm_max = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_values(solution, u_h);
          fe_values[displacement].get_function_symmetric_gradients(solution,
                                                                   eps_h);
          const auto &material = materials.at(cell->material_id());
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
                  const SymmetricTensor<2, dim> s = material.stress(eps_h[q]);
                  double                        e2 = 0, n2 = 0;
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


  template <int dim>
  void
  Simulation<dim>::output_results(const unsigned int step, const double time)
  {
    if (!parameters.output.write_vtu)
      return;
    TimerOutput::Scope t(timer, "output");
    DataOut<dim>       data_out;
    data_out.attach_dof_handler(dof_handler);
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(dim,
                     DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(solution,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             interpretation);
    Postprocess::StressPostprocessor<dim> stress(materials);
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
    data_out.build_patches(fe.degree);
    const std::string name = data_out.write_vtu_with_pvtu_record(
      parameters.output.directory + "/", "solution", step, mpi_communicator, 4);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        pvtu_records.emplace_back(time, name);
        std::ofstream pvd(parameters.output.directory + "/solution.pvd");
        DataOutBase::write_pvd_record(pvd, pvtu_records);
      }
  }


  template <int dim>
  void
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
                                    format(u_max)};
    for (const auto &r : reactions)
      for (unsigned int d = 0; d < dim; ++d)
        row.push_back(format(r[d]));
    statistics_rows.push_back(row);

    const char *axis[] = {"x", "y", "z"};
    pcout << "  Newton iterations: " << newton_iterations << "\n"
          << "  max |u_i| = " << format(u_max) << "\n";
    for (unsigned int k = 0; k < reactions.size(); ++k)
      {
        pcout << "  reaction Dirichlet " << k + 1 << " = (";
        for (unsigned int d = 0; d < dim; ++d)
          pcout << (d ? ", " : "") << format(reactions[k][d], 4);
        pcout << ")\n";
      }
    const auto &ref = parameters.reference;
    const auto  report = [&](const char *what, const double e) {
      if (e < 0)
        return;
      pcout << "  reference check: " << what << " = "
            << format(std::max(e, 1e-16), 1) << " (tolerance "
            << format(ref.tolerance, 1)
            << "): " << (e <= ref.tolerance ? "PASS" : "FAIL") << "\n";
    };
    report("displacement L2 relative error", errors.displacement_l2_relative);
    report("stress max relative error", errors.stress_max_relative);
    pcout << std::flush;

    if (parameters.output.write_csv &&
        Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ofstream csv(parameters.output.directory + "/statistics.csv");
        csv << "step,time,newton_iterations,max_abs_u";
        for (unsigned int k = 0; k < reactions.size(); ++k)
          for (unsigned int d = 0; d < dim; ++d)
            csv << ",reaction_" << k + 1 << "_" << axis[d];
        csv << "\n";
        for (const auto &r : statistics_rows)
          {
            for (unsigned int c = 0; c < r.size(); ++c)
              csv << (c ? "," : "") << r[c];
            csv << "\n";
          }
      }
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

    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::filesystem::create_directories(parameters.output.directory);
        std::ofstream echo(parameters.output.directory + "/parameters.prm");
        prm.print_parameters(echo, ParameterHandler::ShortPRM);
      }
    MPI_Barrier(mpi_communicator);

    const auto &times = parameters.load_stepping.step_times;
    double      t_done = 0;
    TrilinosWrappers::MPI::Vector last_converged = solution;
    for (unsigned int step = 1; step <= times.size(); ++step)
      {
        pcout << "Load step " << step << " of " << times.size()
              << ", t = " << format(times[step - 1], 4) << std::endl;
        // Sub-steps: the whole step first, halved after each failure.
        unsigned int cuts = 0, total_iterations = 0;
        double       t_target = times[step - 1];
        while (t_done < times[step - 1])
          {
            unsigned int iterations = 0;
            if (solve_load_step(t_target, iterations))
              {
                total_iterations += iterations;
                last_converged = solution;
                t_done         = t_target;
                t_target       = times[step - 1];
              }
            else
              {
                solution = last_converged;
                if (++cuts > parameters.load_stepping.max_cuts)
                  throw RunError(
                    "load step " + std::to_string(step) + " did not converge "
                    "between t = " + format(t_done, 4) + " and t = " +
                    format(t_target, 4) + " after " +
                    std::to_string(parameters.load_stepping.max_cuts) +
                    " step cuts. The results of the completed steps are in '" +
                    parameters.output.directory +
                    "'. Raise 'Newton/Maximum iterations' or 'Load "
                    "stepping/Number of steps'.");
                pcout << "  step not converged: cut to t = "
                      << format(0.5 * (t_done + t_target), 4) << std::endl;
                t_target = 0.5 * (t_done + t_target);
              }
          }
        compute_reactions();
        compute_reference_errors(times[step - 1]);
        write_statistics(step, times[step - 1], total_iterations);
        output_results(step, times[step - 1]);
      }
    if (parameters.output.timing_summary)
      timer.print_wall_time_statistics(mpi_communicator);
  }


  void
  run_from_file(const std::string &filename, const MPI_Comm mpi_communicator)
  {
    ParameterHandler prm;
    const Parameters parameters = read_parameters(filename, prm);
    // Errors leave the Simulation's scope only after it is destroyed, so
    // its TimerOutput does not complain about an exception in flight.
    std::exception_ptr failure;
    const auto         run = [&](auto &&simulation) {
      try
        {
          simulation.run();
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
  }

  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
