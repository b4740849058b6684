// Results: reactions, postprocessors, VTU and CSV files, statistics, the
// run summary.
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

#include "simulation_helpers.h"

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
  using internal::make_function;


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
  // checks) and its statistics.csv line.
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
    step_iterations.push_back(newton_iterations);
    run_cuts += step_cuts;
    run_cycles += cycle_detections;
    run_frozen += points_frozen;
    run_released += points_released;
    run_line_searches += line_searches;
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
    print_step_report(newton_iterations, u_max);
    if (contact->active())
      print_pair_report(summary);
    // The step's checks, also kept for the end of a quiet run.
    last_checks.clear();
    for (const auto &check : step_checks)
      record_check(check.text, check.pass);
    pcout << std::flush;
    return statistics_lines(step, time, newton_iterations, u_max, summary);
  }


  template <int dim>
  void
  Simulation<dim>::record_check(const std::string &text, const bool pass)
  {
    last_checks.push_back(text);
    n_failed_checks += !pass;
    pcout << "  reference check: " << text << "\n";
  }


  // Newton and Krylov iterations, anti-cycling counts, the largest
  // displacement and the reactions of the step.
  template <int dim>
  void
  Simulation<dim>::print_step_report(const unsigned int newton_iterations,
                                     const double       u_max)
  {
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
  }


  // Per contact pair: closed points, force, largest pressure, and a note
  // for a pair that closes nothing.
  template <int dim>
  void
  Simulation<dim>::print_pair_report(
    const std::vector<typename Contact::ContactProblem<dim>::PairSummary>
      &summary)
  {
    for (unsigned int p = 0; p < summary.size(); ++p)
      {
        const auto &s = summary[p];
        pcout << "  contact pair " << p + 1 << ": " << s.n_contact << " of "
              << s.n_points << " points closed";
        if (parameters.contact.pairs[p].friction > 0)
          pcout << " (stick " << s.n_stick << ", slip " << s.n_slip << ")";
        pcout << ", force on master = (";
        for (unsigned int d = 0; d < dim; ++d)
          pcout << (d ? ", " : "") << format(s.force[d], 4);
        pcout << "), max p = " << format(s.p_max, 4) << "\n";
        // An open pair near contact, or one whose points find no master
        // face at all, is worth a word: bodies loaded towards each other
        // that close no point pass through each other between the contact
        // points (a coarse curved surface), or do not face each other (ids
        // swapped, normals away).
        if (s.n_contact == 0 && s.n_paired == 0)
          pcout << "  note: pair " << p + 1
                << ": no slave point finds the master within 'Contact/"
                   "Projection tolerance': the surfaces do not face each "
                   "other here (check the slave and master ids and the "
                   "geometry)\n";
        else if (s.n_contact == 0 && -s.max_gap < 0.5 * s.face_size)
          pcout << "  note: pair " << p + 1
                << " closes no contact point; the nearest is "
                << format(-s.max_gap, 2) << " m from the master ("
                << format(-s.max_gap / s.face_size, 2)
                << " slave faces): if the bodies should touch here, the "
                   "slave points may straddle the contact (refine the slave "
                   "surface, or make the finer surface the slave)\n";
      }
  }


  // The step's statistics.csv line, with the header at the first step (its
  // columns follow the scene's conditions and pairs): force-displacement
  // data of each Dirichlet condition (its reaction and the mean
  // displacement it prescribes, constrained components only), each contact
  // pair's force on the master, closed points and, for a rigid obstacle,
  // its prescribed motion.
  template <int dim>
  std::string
  Simulation<dim>::statistics_lines(
    const unsigned int step,
    const double       time,
    const unsigned int newton_iterations,
    const double       u_max,
    const std::vector<typename Contact::ContactProblem<dim>::PairSummary>
      &summary)
  {
    std::vector<std::string> row = {std::to_string(step),
                                    format(time),
                                    std::to_string(newton_iterations),
                                    std::to_string(step_cuts),
                                    std::to_string(cycle_detections),
                                    std::to_string(points_frozen),
                                    format(u_max)};
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
    const char *axis[] = {"x", "y", "z"};
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
    add_postprocessor_columns(header, row);
    const auto line = [](const std::vector<std::string> &fields) {
      std::string text;
      for (unsigned int c = 0; c < fields.size(); ++c)
        text += (c ? "," : "") + fields[c];
      return text + "\n";
    };
    return (header ? line(statistics_header) : std::string()) + line(row);
  }


  // The postprocessors' columns after the run's own: at the first step
  // they extend the header, later the names must be the header's.
  template <int dim>
  void
  Simulation<dim>::add_postprocessor_columns(const bool                header,
                                             std::vector<std::string> &row)
  {
    for (const auto &column : postprocessor_columns.columns())
      {
        if (header)
          statistics_header.push_back(column.name);
        else if (row.size() >= statistics_header.size() ||
                 statistics_header[row.size()] != column.name)
          throw RunError("postprocessor '" + column.owner +
                         "': the statistics column '" + column.name +
                         "' stands where the first step's statistics.csv "
                         "header has another; a postprocessor must add the "
                         "same columns at every step.");
        row.push_back(format(column.value));
      }
    if (row.size() != statistics_header.size())
      throw RunError("statistics.csv: the postprocessors added fewer "
                     "columns than at the first step; a postprocessor must "
                     "add the same columns at every step.");
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
    run_postprocessors(step, time);
    append_newton_history();
    const std::string statistics_lines =
      write_statistics(step, time, iterations);
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


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
