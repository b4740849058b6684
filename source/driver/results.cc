// The results of a load step: reactions, postprocessors, the contact CSV,
// the step's report (on screen and in statistics.csv: run_report.cc) and
// the Newton history.
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>

#include <signorini/base/errors.h>
#include <signorini/base/output_files.h>
#include <signorini/driver/results.h>
#include <signorini/geometry/parts.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace Signorini
{
  namespace Postprocess
  {
    template <int dim>
    Results<dim>::Results(
      const Parameters                    &parameters,
      ParameterHandler                    &prm,
      const DiscreteSystem<dim>           &system,
      const Bulk::Materials<dim>          &materials,
      const Bulk::BoundaryConditions<dim> &boundary_conditions,
      const Contact::ContactProblem<dim>  &contact,
      RunReport<dim>                      &report,
      TimerOutput                         &timer,
      ConditionalOStream                  &sout)
        : parameters(parameters)
        , prm(prm)
        , system(system)
        , materials(materials)
        , boundary_conditions(boundary_conditions)
        , contact(contact)
        , report(report)
        , timer(timer)
        , sout(sout)
        , postprocessors(make_postprocessors<dim>(parameters, prm))
    {
    }


    // Results of an earlier run in the directory would be mixed with this
    // run's (more steps, other ranks): this program's own result files are
    // removed first, and said so. The echo never replaces the input file.
    template <int dim>
    void
    Results<dim>::prepare_output()
    {
      const std::string &directory = parameters.output.directory;
      std::string        failure;
      if (Utilities::MPI::this_mpi_process(system.mpi_communicator) == 0)
        {
          std::error_code error;
          std::filesystem::create_directories(directory, error);
          if (error)
            failure = "cannot create the output directory '" + directory +
                      "': " + error.message();
          const unsigned int n_removed =
            failure.empty() ? remove_earlier_results(directory, failure) : 0;
          if (n_removed > 0)
            sout << "Removed " << n_removed
                 << " result file(s) of an earlier run from '" << directory
                 << "'" << std::endl;
          const std::string echo =
            echo_filename(directory, parameters.input_file);
          if (echo != directory + "/parameters.prm")
            sout << "Note: '" << directory
                 << "/parameters.prm' is the input file: the parameters are "
                    "echoed to '"
                 << echo << "'" << std::endl;
          if (failure.empty())
            failure = write_atomically(echo, [&](std::ostream &out) {
              prm.print_parameters(out, ParameterHandler::ShortPRM);
            });
          if (failure.empty())
            failure = report.open_newton_history();
        }
      check_output(failure);
      // The postprocessors check their parameters against the scene now,
      // before a step is solved.
      const StepData<dim> data = step_data(0, 0., system.solution);
      for (auto &postprocessor : postprocessors)
        postprocessor->initialize(data);
    }


    template <int dim>
    void
    Results<dim>::write(const unsigned int step,
                        const double       time,
                        const unsigned int iterations,
                        const double       force_level)
    {
      force_scale = force_level;
      compute_reactions();
      run_postprocessors(step, time);
      check_force_balance();
      report.append_newton_history();
      const std::string statistics_lines = report_step(step, time, iterations);
      if (contact.active() && parameters.output.write_csv)
        {
          std::ostringstream name;
          name << parameters.output.directory << "/contact_" << std::setw(4)
               << std::setfill('0') << step << ".csv";
          check_output(
            contact.contact_output().write_csv(name.str(), system.solution));
        }
      // The step's line in statistics.csv last: a step listed there has
      // all its files on disk.
      report.append_statistics(statistics_lines);
    }


    // Reaction of the supports on the body: F_int - F_ext summed over the
    // DoFs each Dirichlet condition constrains, per component [N].
    template <int dim>
    void
    Results<dim>::compute_reactions()
    {
      // The residual R = F_int - F_ext + F_contact with the hanging-node
      // constraints applied (a hanging DoF passes its share to its masters,
      // some of which may carry a Dirichlet condition): at the Dirichlet DoFs
      // it is the force of the supports.
      TrilinosWrappers::MPI::Vector r;
      r.reinit(system.locally_owned,
               system.locally_relevant,
               system.mpi_communicator,
               true);
      for (const auto i : system.locally_owned)
        {
          const double raw = system.internal_force[i] -
                             system.external_force[i] + system.contact_force[i];
          const auto *entries =
            system.constraints_hanging.get_constraint_entries(i);
          if (entries && !entries->empty())
            for (const auto &[j, w] : *entries)
              r(j) += w * raw; // hanging: to the masters
          else
            r(i) += raw;
        }
      r.compress(VectorOperation::add);
      const TrilinosWrappers::MPI::Vector support_force(r);
      supports = boundary_conditions.supports(support_force,
                                              system.solution,
                                              force_scale,
                                              system.mpi_communicator);
    }


    // Sum over the DoFs of a body of R = F_int - F_ext + F_contact: the
    // reactions where supports hold it, zero elsewhere at equilibrium; the
    // internal forces of a body sum to zero (its stress does no work in a
    // rigid translation). So, per body and component, the sum of its
    // support forces + its loads - the contact forces on it = 0, where the
    // support forces are those charged to the conditions (BoundaryConditions
    // ::supports()) and the loads and contact forces are summed over the
    // body's DoFs: a support force counted twice, left out or charged to
    // the wrong body, a load missing at the constrained DoFs, or a contact
    // force on one body without its reaction on the other, breaks it.
    template <int dim>
    void
    Results<dim>::check_force_balance()
    {
      const auto  &tria    = system.dof_handler.get_triangulation();
      unsigned int n_parts = 0;
      const auto   parts   = Geometry::coarse_parts(tria, n_parts);
      // Per body: support forces, loads, contact forces.
      std::vector<std::array<Tensor<1, dim>, 3>> sums(n_parts);
      std::vector<Tensor<1, dim>>                centre(n_parts);
      std::vector<double>                        n_cells(n_parts, 0);
      // Body and component of each locally owned displacement DoF (by its
      // index within the owned set).
      constexpr unsigned int none = numbers::invalid_unsigned_int;
      std::vector<std::pair<unsigned int, unsigned int>> of_dof(
        system.locally_owned.n_elements(), {none, none});
      std::vector<types::global_dof_index> dofs(system.fe.n_dofs_per_cell());
      for (const auto &cell : system.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const unsigned int b = Geometry::part_of<dim>(cell, parts);
            centre[b] += cell->center();
            n_cells[b] += 1;
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
              {
                const unsigned int c =
                  system.fe.system_to_component_index(i).first;
                if (c < dim && system.locally_owned.is_element(dofs[i]))
                  of_dof[system.locally_owned.index_within_set(dofs[i])] = {b,
                                                                            c};
              }
          }
      unsigned int k = 0; // the owned set is iterated in index order
      for (const auto i : system.locally_owned)
        {
          const auto [b, c] = of_dof[k++];
          if (b == none)
            continue;
          sums[b][1][c] += system.external_force[i];
          sums[b][2][c] += system.contact_force[i];
        }
      for (const auto &[dof, f] : supports.node_forces)
        sums[of_dof[system.locally_owned.index_within_set(dof)].first][0] += f;
      for (unsigned int b = 0; b < n_parts; ++b)
        {
          for (auto &t : sums[b])
            t = Utilities::MPI::sum(t, system.mpi_communicator);
          centre[b]  = Utilities::MPI::sum(centre[b], system.mpi_communicator);
          n_cells[b] = Utilities::MPI::sum(n_cells[b], system.mpi_communicator);
        }

      const double tolerance = 1e-6;
      // Below the force of a strain of 1e-12 on the model's size the
      // forces are round-off (a rigid motion: force level and reactions
      // both of order eps E h^(dim-1)).
      double stiffest = 0;
      for (const auto &m : parameters.materials)
        stiffest = std::max(stiffest, m.youngs_modulus);
      const double floor =
        1e-12 * stiffest * std::pow(system.model_size, dim - 1);
      double       worst      = 0;
      unsigned int worst_body = 0;
      for (unsigned int b = 0; b < n_parts; ++b)
        for (unsigned int d = parameters.axisymmetric ? 1 : 0; d < dim; ++d)
          {
            const double e =
              std::abs(sums[b][0][d] + sums[b][1][d] - sums[b][2][d]);
            if (e > worst)
              {
                worst      = e;
                worst_body = b;
              }
          }
      if (worst <= tolerance * force_scale + floor)
        return;
      const auto        &s     = sums[worst_body];
      const double       error = force_scale > 0 ? worst / force_scale : worst;
      std::ostringstream text;
      text << std::scientific << std::setprecision(4)
           << "force balance of body " << worst_body + 1 << " of " << n_parts
           << " (around "
           << centre[worst_body] / std::max(1., n_cells[worst_body])
           << "): reactions " << s[0] << " + loads " << s[1]
           << " - contact forces on it " << s[2] << " = " << s[0] + s[1] - s[2]
           << std::setprecision(1) << ", " << error
           << " of the force level (tolerance " << tolerance << "): FAIL";
      CheckResult check;
      check.what      = "force balance";
      check.error     = error;
      check.tolerance = tolerance;
      check.pass      = false;
      check.text      = text.str();
      step_checks.push_back(check);
    }


    // Displacement component at a point: the first locally owned cell that
    // contains it (lowest rank wins).
    template <int dim>
    double
    Results<dim>::point_value(const Point<dim>  &p,
                              const unsigned int component) const
    {
      double value = 0;
      bool   found = false;
      for (const auto &cell : system.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && !found)
          {
            if (!cell->bounding_box().point_inside(p, 1e-10))
              continue;
            Point<dim> unit;
            try
              {
                unit = system.mapping.transform_real_to_unit_cell(cell, p);
              }
            catch (...)
              {
                continue;
              }
            if (!GeometryInfo<dim>::is_inside_unit_cell(unit, 1e-8))
              continue;
            const Quadrature<dim> q(
              GeometryInfo<dim>::project_to_unit_cell(unit));
            FEValues<dim> fv(system.mapping, system.fe, q, update_values);
            fv.reinit(cell);
            std::vector<Vector<double>> v(1, Vector<double>(dim));
            fv.get_function_values(system.solution, v);
            value = v[0][component];
            found = true;
          }
      const unsigned int rank =
        Utilities::MPI::this_mpi_process(system.mpi_communicator);
      const unsigned int owner =
        Utilities::MPI::min(found ? rank :
                                    std::numeric_limits<unsigned int>::max(),
                            system.mpi_communicator);
      if (owner == std::numeric_limits<unsigned int>::max())
        {
          std::ostringstream where;
          where << "the point (";
          for (unsigned int d = 0; d < dim; ++d)
            where << (d ? ", " : "") << p[d];
          where << ") lies in no cell of the mesh.";
          throw InputError(where.str());
        }
      return Utilities::MPI::sum(rank == owner ? value : 0.,
                                 system.mpi_communicator);
    }


    template <int dim>
    StepData<dim>
    Results<dim>::step_data(const unsigned int                   step,
                            const double                         time,
                            const TrilinosWrappers::MPI::Vector &start)
    {
      return StepData<dim>{step,
                           time,
                           system.mpi_communicator,
                           parameters,
                           system.mapping,
                           system.dof_handler,
                           system.solution,
                           start,
                           materials,
                           system.history,
                           contact.active() ? &contact : nullptr,
                           system.state,
                           force_scale,
                           [this](const Point<dim> &p, const unsigned int c) {
                             return point_value(p, c);
                           },
                           postprocessor_columns};
    }


    // The postprocessors of 'Output/Postprocessors', in the listed order:
    // their checks of the step go to step_checks.
    template <int dim>
    void
    Results<dim>::run_postprocessors(const unsigned int step, const double time)
    {
      TimerOutput::Scope            t(timer, "output");
      TrilinosWrappers::MPI::Vector owned(system.locally_owned,
                                          system.mpi_communicator);
      for (const auto i : system.locally_owned)
        owned[i] = system.state_step_start[i];
      owned.compress(VectorOperation::insert);
      TrilinosWrappers::MPI::Vector start(system.locally_owned,
                                          system.locally_relevant,
                                          system.mpi_communicator);
      start                    = owned;
      const StepData<dim> data = step_data(step, time, start);
      step_checks.clear();
      postprocessor_columns.clear();
      for (unsigned int i = 0; i < postprocessors.size(); ++i)
        {
          postprocessor_columns.set_owner(parameters.output.postprocessors[i]);
          for (auto &check : postprocessors[i]->execute(data))
            step_checks.push_back(std::move(check));
        }
    }


    // The step's report on screen (iterations, reactions, pairs, reference
    // checks) and its statistics.csv lines.
    template <int dim>
    std::string
    Results<dim>::report_step(const unsigned int step,
                              const double       time,
                              const unsigned int newton_iterations)
    {
      // Largest displacement magnitude at the nodes.
      double u_max = 0;
      for (const auto i : system.locally_owned)
        u_max = std::max(u_max, std::abs(system.solution[i]));
      u_max = Utilities::MPI::max(u_max, system.mpi_communicator);
      // Contact pair summaries, their forces with round-off (relative to the
      // force level) set to zero so that output does not depend on the ranks.
      auto summary =
        contact.active() ?
          contact.summary() :
          std::vector<typename Contact::ContactProblem<dim>::PairSummary>();
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
    Results<dim>::check_output(const std::string &failure) const
    {
      check_written(failure,
                    parameters.output.directory,
                    system.mpi_communicator);
    }


    template class Results<2>;
    template class Results<3>;
  } // namespace Postprocess
} // namespace Signorini
