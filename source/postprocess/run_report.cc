// The report of a run: the Newton log (screen and newton_history.csv), the
// step report on screen, statistics.csv, the run summary.
#include <signorini/base/format.h>
#include <signorini/postprocess/run_report.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace Signorini
{
  namespace Postprocess
  {
    template <int dim>
    RunReport<dim>::RunReport(const Parameters   &parameters,
                              ConditionalOStream &pcout,
                              ConditionalOStream &sout,
                              const MPI_Comm      comm)
        : parameters(parameters)
        , pcout(pcout)
        , sout(sout)
        , comm(comm)
    {
    }


    template <int dim>
    void
    RunReport<dim>::start_step()
    {
      counts.cycle_detections = counts.points_frozen = counts.points_released =
        counts.line_searches                         = 0;
    }


    template <int dim>
    std::string
    RunReport<dim>::report_step(const StepResults<dim> &results)
    {
      step_iterations.push_back(results.newton_iterations);
      run_cuts += counts.step_cuts;
      run_cycles += counts.cycle_detections;
      run_frozen += counts.points_frozen;
      run_released += counts.points_released;
      run_line_searches += counts.line_searches;
      last_written_time = results.time;
      print_step_counts(results);
      print_pair_report(results);
      // The step's checks, also kept for the end of a quiet run.
      last_checks.clear();
      for (const auto &check : results.checks)
        {
          last_checks.push_back(check.text);
          n_failed_checks += !check.pass;
          pcout << "  reference check: " << check.text << "\n";
        }
      pcout << std::flush;

      const bool header = statistics_header.empty();
      const auto row    = statistics_row(results);
      const auto line   = [](const std::vector<std::string> &fields) {
        std::string text;
        for (unsigned int c = 0; c < fields.size(); ++c)
          text += (c ? "," : "") + fields[c];
        return text + "\n";
      };
      return (header ? line(statistics_header) : std::string()) + line(row);
    }


    // Newton and Krylov iterations, anti-cycling counts, the largest
    // displacement and the reactions of the step.
    template <int dim>
    void
    RunReport<dim>::print_step_counts(const StepResults<dim> &results)
    {
      pcout << "  Newton iterations: " << results.newton_iterations << "\n";
      if (parameters.linear_solver.type != LinearSolverType::direct)
        {
          pcout << "  Krylov iterations: " << counts.krylov_iterations
                << " in this step, at most " << counts.krylov_max
                << " per solve\n";
          counts.krylov_iterations = counts.krylov_max = 0;
        }
      if (counts.cycle_detections + counts.points_frozen +
            counts.points_released >
          0)
        pcout << "  anti-cycling: " << counts.cycle_detections
              << " status cycle(s) detected, " << counts.points_frozen
              << " point(s) frozen, " << counts.points_released
              << " released\n";
      pcout << "  max |u_i| = " << format(results.u_max) << "\n";
      // Components below 1e-10 of the largest reaction are round-off (sums
      // of nodal forces that cancel; with nu -> 0.5 lambda amplifies the
      // round-off of the displacement) and are printed as 0 (the CSV keeps
      // them).
      const auto &reactions        = results.reactions;
      double      largest_reaction = 0;
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
    RunReport<dim>::print_pair_report(const StepResults<dim> &results) const
    {
      for (unsigned int p = 0; p < results.pairs.size(); ++p)
        {
          const auto &s = results.pairs[p];
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
          // that close no point pass through each other between the
          // contact points (a coarse curved surface), or do not face each
          // other (ids swapped, normals away).
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
                     "slave points may straddle the contact (refine the "
                     "slave surface, or make the finer surface the slave)\n";
        }
    }


    // The step's statistics.csv row; the header at the first step (its
    // columns follow the scene's conditions and pairs): force-displacement
    // data of each Dirichlet condition (its reaction and the mean
    // displacement it prescribes, constrained components only), each
    // contact pair's force on the master, closed points and, for a rigid
    // obstacle, its prescribed motion; then the postprocessors' columns.
    template <int dim>
    std::vector<std::string>
    RunReport<dim>::statistics_row(const StepResults<dim> &results)
    {
      std::vector<std::string> row    = {std::to_string(results.step),
                                         format(results.time),
                                         std::to_string(results.newton_iterations),
                                         std::to_string(counts.step_cuts),
                                         std::to_string(counts.cycle_detections),
                                         std::to_string(counts.points_frozen),
                                         format(results.u_max)};
      const bool               header = statistics_header.empty();
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
      for (unsigned int k = 0; k < results.reactions.size(); ++k)
        {
          const std::string name = "_" + std::to_string(k + 1) + "_";
          for (unsigned int d = 0; d < dim; ++d)
            add("reaction" + name + axis[d], results.reactions[k][d]);
          for (unsigned int d = 0; d < dim; ++d)
            if (results.dirichlet_components[k][d])
              add("displacement" + name + axis[d],
                  results.dirichlet_displacement[k][d]);
        }
      for (unsigned int p = 0; p < results.pairs.size(); ++p)
        {
          const auto       &s    = results.pairs[p];
          const std::string name = "_" + std::to_string(p + 1) + "_";
          for (unsigned int d = 0; d < dim; ++d)
            add("contact_force" + name + axis[d], s.force[d]);
          add_text("contact_points" + name + "closed",
                   std::to_string(s.n_contact));
          // What a forming or a Hertz study plots per pair: the largest
          // pressure, the closed area (plane strain: length), the normal
          // and tangential force in the contact frames.
          add("contact_pressure" + name + "max", s.p_max);
          add((dim == 2 && !parameters.axisymmetric ? "contact_length" :
                                                      "contact_area") +
                name.substr(0, name.size() - 1),
              s.area);
          add("contact_force" + name + "normal", s.normal_force_local);
          add("contact_force" + name + "tangential", s.tangential_force_local);
          if (parameters.contact.pairs[p].friction > 0)
            {
              add_text("contact_points" + name + "stick",
                       std::to_string(s.n_stick));
              add_text("contact_points" + name + "slip",
                       std::to_string(s.n_slip));
            }
          if (s.rigid)
            for (unsigned int d = 0; d < dim; ++d)
              add("obstacle_displacement" + name + axis[d],
                  s.obstacle_displacement[d]);
        }
      add_postprocessor_columns(results.columns, header, row);
      return row;
    }


    // The postprocessors' columns after the run's own: at the first step
    // they extend the header, later the names must be the header's.
    template <int dim>
    void
    RunReport<dim>::add_postprocessor_columns(const StatisticsColumns  &columns,
                                              const bool                header,
                                              std::vector<std::string> &row)
    {
      for (const auto &column : columns.columns())
        {
          if (header)
            statistics_header.push_back(column.name);
          else if (row.size() >= statistics_header.size() ||
                   statistics_header[row.size()] != column.name)
            throw RunError("postprocessor '" + column.owner +
                           "': the statistics column '" + column.name +
                           "' stands where the first step's statistics.csv "
                           "header has another; a postprocessor must add "
                           "the same columns at every step.");
          row.push_back(format(column.value));
        }
      if (row.size() != statistics_header.size())
        throw RunError("statistics.csv: the postprocessors added fewer "
                       "columns than at the first step; a postprocessor "
                       "must add the same columns at every step.");
    }


    template <int dim>
    void
    RunReport<dim>::append_statistics(const std::string &lines)
    {
      std::string failure;
      if (parameters.output.write_csv &&
          Utilities::MPI::this_mpi_process(comm) == 0)
        failure = statistics_file.is_open() ?
                    statistics_file.append(lines) :
                    statistics_file.open(parameters.output.directory +
                                           "/statistics.csv",
                                         lines);
      check_written(failure, parameters.output.directory, comm);
    }


    template <int dim>
    void
    RunReport<dim>::print_run_summary(const unsigned int n_written,
                                      const unsigned int stopped_in)
    {
      const unsigned int n_steps = parameters.load_stepping.step_times.size();
      // What even a quiet run prints (sout): the last step's reference
      // checks and the run summary.
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
          if (!parameters.contact.pairs.empty())
            sout << ", status cycles detected " << run_cycles
                 << ", points frozen " << run_frozen << ", released "
                 << run_released;
          if (early_releases > 0)
            sout << ", opened early (release extrapolation) " << early_releases;
          if (run_line_searches > 0)
            sout << ", line searches " << run_line_searches;
          sout << std::endl;
        }
      else if (stopped_in > 0)
        sout << "Run summary (stopped in load step " << stopped_in << " of "
             << n_steps << "): no load step written" << std::endl;
    }


    template <int dim>
    std::string
    RunReport<dim>::open_newton_history()
    {
      if (!parameters.output.write_csv ||
          Utilities::MPI::this_mpi_process(comm) != 0)
        return "";
      return history_file.open(
        parameters.output.directory + "/newton_history.csv",
        "step,time,geometric_iteration,newton_iteration,r_u,r_lambda,"
        "r_Lambda,n_contact,n_stick,n_slip,n_changed,n_reversed,"
        "n_cycling,n_frozen,converged\n");
    }


    template <int dim>
    void
    RunReport<dim>::log_iterate(const unsigned int                iteration,
                                const std::array<double, 3>      &block,
                                const double                      force_level,
                                const Contact::ContactStatistics *contact,
                                const bool                        friction,
                                const bool                        converged)
    {
      if (contact)
        {
          counts.cycle_detections += contact->n_cycling;
          counts.points_frozen += contact->n_newly_frozen;
        }
      const auto relative = [&](const double r) {
        return force_level > 0 ? r / force_level : 0.;
      };
      // Printed: above 1e6 the force level is the round-off of a
      // stress-free state (a body moving freely before contact), and the
      // digits of the ratio are round-off too.
      const auto shown = [&](const double r) {
        std::ostringstream text;
        if (!std::isfinite(r) || !std::isfinite(force_level))
          text << (std::isnan(r) || std::isnan(force_level) ? "NaN" : "inf");
        else if (relative(r) > 1e6)
          text << ">1.0e+06";
        else
          text << std::scientific << std::setprecision(2) << relative(r);
        return text.str();
      };
      const auto verbosity = parameters.output.verbosity;
      if (contact && verbosity != Verbosity::quiet)
        {
          const auto &st = *contact;
          pcout << "    Newton " << std::setw(2) << iteration << ": |R_u| "
                << shown(block[0]) << " |R_lambda| " << shown(block[1]);
          if (friction)
            pcout << " |R_Lambda| " << shown(block[2]);
          pcout << std::defaultfloat << "  contact " << st.n_contact;
          if (friction)
            pcout << " (stick " << st.n_stick << ", slip " << st.n_slip << ")";
          pcout << " free " << st.n_points - st.n_contact << " changed "
                << st.n_changed;
          if (st.n_reversed > 0)
            pcout << " (slip reversed " << st.n_reversed << ")";
          if (st.n_cycling > 0)
            pcout << " cycling " << st.n_cycling;
          if (st.n_frozen + st.n_newly_frozen > 0)
            pcout << " frozen " << st.n_frozen + st.n_newly_frozen;
          pcout << (converged ? "  converged" : "") << std::endl;
        }
      else if (verbosity == Verbosity::verbose)
        pcout << "    Newton " << std::setw(2) << iteration
              << ": |R|/|F| = " << std::scientific << std::setprecision(2)
              << relative(std::sqrt(block[0] * block[0] + block[1] * block[1] +
                                    block[2] * block[2]))
              << std::defaultfloat << (converged ? "  converged" : "")
              << std::endl;
      std::ostringstream row;
      row << position.step << "," << format(position.time) << ","
          << position.geometric << "," << iteration << ","
          << format(relative(block[0]), 3) << ","
          << format(relative(block[1]), 3) << ","
          << format(relative(block[2]), 3);
      if (contact)
        row << "," << contact->n_contact << "," << contact->n_stick << ","
            << contact->n_slip << "," << contact->n_changed << ","
            << contact->n_reversed << "," << contact->n_cycling << ","
            << contact->n_frozen + contact->n_newly_frozen;
      else
        row << ",0,0,0,0,0,0,0";
      row << "," << (converged ? 1 : 0);
      newton_rows.push_back(row.str());
    }


    template <int dim>
    void
    RunReport<dim>::append_newton_history()
    {
      std::string failure;
      if (history_file.is_open())
        {
          std::string lines;
          for (const auto &r : newton_rows)
            lines += r + "\n";
          failure = history_file.append(lines);
        }
      newton_rows.clear();
      check_written(failure, parameters.output.directory, comm);
    }


    template class RunReport<2>;
    template class RunReport<3>;
  } // namespace Postprocess
} // namespace Signorini
