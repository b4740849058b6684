// Results: reactions, postprocessors, the contact CSV and the Newton
// history (the step report and statistics.csv: postprocess/run_report.cc).
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
    const TrilinosWrappers::MPI::Vector support_force(r);
    supports = boundary_conditions.supports(support_force,
                                            solution,
                                            force_scale,
                                            mpi_communicator);
  }


  // Displacement component at a point: the first locally owned cell that
  // contains it (lowest rank wins).
  template <int dim>
  double
  Simulation<dim>::point_value(const Point<dim> &p,
                               const unsigned int component) const
  {
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


  // The step's report on screen (iterations, reactions, pairs, reference
  // checks) and its statistics.csv lines.
  template <int dim>
  std::string
  Simulation<dim>::report_step(const unsigned int step,
                               const double       time,
                               const unsigned int newton_iterations)
  {
    // Largest displacement magnitude at the nodes.
    double u_max = 0;
    for (const auto i : locally_owned)
      u_max = std::max(u_max, std::abs(solution[i]));
    u_max = Utilities::MPI::max(u_max, mpi_communicator);
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
    return report.report_step({step,
                               time,
                               newton_iterations,
                               u_max,
                               supports.reactions,
                               supports.displacement,
                               supports.components,
                               summary,
                               postprocessor_columns,
                               step_checks});
  }


  template <int dim>
  void
  Simulation<dim>::check_output(const std::string &failure) const
  {
    Postprocess::check_written(failure,
                               parameters.output.directory,
                               mpi_communicator);
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
        if (failure.empty())
          failure = report.open_newton_history();
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
    run_postprocessors(step, time);
    report.append_newton_history();
    const std::string statistics_lines = report_step(step, time, iterations);
    if (contact->active() && parameters.output.write_csv)
      {
        std::ostringstream name;
        name << parameters.output.directory << "/contact_" << std::setw(4)
             << std::setfill('0') << step << ".csv";
        check_output(contact->contact_output().write_csv(name.str()));
      }
    // The step's line in statistics.csv last: a step listed there has
    // all its files on disk.
    report.append_statistics(statistics_lines);
  }


  // The postprocessors of 'Output/Postprocessors', in the listed order:
  // their checks of the step go to step_checks.
  template <int dim>
  void
  Simulation<dim>::run_postprocessors(const unsigned int step,
                                      const double       time)
  {
    TimerOutput::Scope               t(timer, "output");
    const Postprocess::StepData<dim> data{step,
                                          time,
                                          mpi_communicator,
                                          parameters,
                                          mapping,
                                          dof_handler,
                                          solution,
                                          materials,
                                          contact->active() ? contact.get() :
                                                              nullptr,
                                          state,
                                          force_scale,
                                          [this](const Point<dim>  &p,
                                                 const unsigned int c) {
                                            return point_value(p, c);
                                          },
                                          postprocessor_columns};
    step_checks.clear();
    postprocessor_columns.clear();
    for (unsigned int i = 0; i < postprocessors.size(); ++i)
      {
        postprocessor_columns.set_owner(parameters.output.postprocessors[i]);
        for (auto &check : postprocessors[i]->execute(data))
          step_checks.push_back(std::move(check));
      }
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
