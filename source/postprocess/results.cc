// The results of a load step: reactions, postprocessors, the contact CSV,
// the step's report (on screen and in statistics.csv: run_report.cc) and
// the Newton history.
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>

#include <signorini/core/errors.h>
#include <signorini/postprocess/output_files.h>
#include <signorini/postprocess/results.h>

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
      // Every point of 'Point values' lies in a body: found now, before a
      // step is solved, not when the first step is written.
      const auto &points = parameters.reference.point_values;
      for (unsigned int k = 0; k < points.size(); ++k)
        {
          Point<dim> p;
          for (unsigned int d = 0; d < dim && d < points[k].point.size(); ++d)
            p[d] = points[k].point[d];
          point_value(p, 0, k + 1);
        }
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


    // Sum over the DoFs of R = F_int - F_ext + F_contact: the reactions
    // where supports hold the body, zero elsewhere at equilibrium; the
    // internal forces of a body sum to zero (its stress does no work in a
    // rigid translation). So sum_k reaction_k + sum F_ext - sum F_contact
    // = 0, where the reactions are charged to the constraint lines of the
    // conditions (BoundaryConditions::supports()) and F_ext, F_contact are
    // summed over every DoF: a support force counted twice or left out,
    // or a load missing at the constrained DoFs, breaks it.
    template <int dim>
    void
    Results<dim>::check_force_balance()
    {
      Tensor<1, dim>            loads, contact_forces, reactions;
      std::vector<unsigned int> component(system.dof_handler.n_dofs(), 0);
      {
        std::vector<types::global_dof_index> dofs(system.fe.n_dofs_per_cell());
        for (const auto &cell : system.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (system.fe.system_to_component_index(i).first < dim)
                  component[dofs[i]] =
                    system.fe.system_to_component_index(i).first;
            }
      }
      for (const auto i : system.locally_owned)
        {
          loads[component[i]] += system.external_force[i];
          contact_forces[component[i]] += system.contact_force[i];
        }
      loads = Utilities::MPI::sum(loads, system.mpi_communicator);
      contact_forces =
        Utilities::MPI::sum(contact_forces, system.mpi_communicator);
      for (const auto &r : supports.reactions)
        reactions += r;
      const double tolerance = 1e-6;
      double       worst     = 0;
      for (unsigned int d = parameters.axisymmetric ? 1 : 0; d < dim; ++d)
        worst = std::max(worst,
                         std::abs(reactions[d] + loads[d] - contact_forces[d]));
      // Below the force of a strain of 1e-12 on the model's size the
      // forces are round-off (a rigid motion: force level and reactions
      // both of order eps E h^(dim-1)).
      double stiffest = 0;
      for (const auto &m : parameters.materials)
        stiffest = std::max(stiffest, m.youngs_modulus);
      const double floor =
        1e-12 * stiffest * std::pow(system.model_size, dim - 1);
      if (worst <= tolerance * force_scale + floor)
        return;
      const double       error = force_scale > 0 ? worst / force_scale : worst;
      std::ostringstream text;
      text << std::scientific << std::setprecision(4)
           << "force balance of the bodies: reactions " << reactions
           << " + loads " << loads << " - contact forces of the "
           << "rigid obstacles " << contact_forces << " = "
           << reactions + loads - contact_forces << std::setprecision(1) << ", "
           << error << " of the force level (tolerance " << tolerance
           << "): FAIL";
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
                              const unsigned int component,
                              const unsigned int entry) const
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
          where << "subsection 'Reference solution', parameter 'Point "
                   "values': the point (";
          for (unsigned int d = 0; d < dim; ++d)
            where << (d ? ", " : "") << p[d];
          where << ")"
                << (entry > 0 ? " of entry " + std::to_string(entry) : "")
                << " lies in no cell of the mesh. Give a point of a body.";
          throw InputError(where.str());
        }
      return Utilities::MPI::sum(rank == owner ? value : 0.,
                                 system.mpi_communicator);
    }


    // The postprocessors of 'Output/Postprocessors', in the listed order:
    // their checks of the step go to step_checks.
    template <int dim>
    void
    Results<dim>::run_postprocessors(const unsigned int step, const double time)
    {
      TimerOutput::Scope  t(timer, "output");
      const StepData<dim> data{step,
                               time,
                               system.mpi_communicator,
                               parameters,
                               system.mapping,
                               system.dof_handler,
                               system.solution,
                               materials,
                               system.history,
                               contact.active() ? &contact : nullptr,
                               system.state,
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
