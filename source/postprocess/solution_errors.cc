#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <signorini/base/format.h>
#include <signorini/bulk/assembler.h>
#include <signorini/material/projected_volumetric_strain.h>
#include <signorini/postprocess/solution_errors.h>

#include "parsed_function.h"

#include <algorithm>
#include <cmath>

namespace Signorini
{
  namespace Postprocess
  {
    namespace
    {
      // "what = e (tolerance t): PASS|FAIL"
      CheckResult
      relative_error(const std::string &what,
                     const double       error,
                     const double       tolerance)
      {
        CheckResult r;
        r.what      = what;
        r.error     = error;
        r.tolerance = tolerance;
        r.pass      = error <= tolerance;
        r.text      = what + " = " + format(std::max(error, 1e-16), 1) +
                 " (tolerance " + format(tolerance, 1) +
                 "): " + (r.pass ? "PASS" : "FAIL");
        return r;
      }
    } // namespace


    template <int dim>
    SolutionErrors<dim>::SolutionErrors(const Parameters          &parameters,
                                        const ReferenceParameters &reference)
        : parameters(parameters)
        , reference(reference)
        , u_exact(parsed<dim>(reference.displacement,
                              parameters.boundary_conditions.constants))
        , s_exact(parsed<dim>(reference.stress,
                              parameters.boundary_conditions.constants))
        , h_exact(parsed<dim>(reference.history,
                              parameters.boundary_conditions.constants))
    {
    }


    template <int dim>
    std::vector<CheckResult>
    SolutionErrors<dim>::evaluate(const StepData<dim> &data) const
    {
      std::vector<CheckResult> results;
      if (h_exact)
        {
          h_exact->set_time(data.time);
          const MPI_Comm comm      = data.dof_handler.get_communicator();
          const auto [error, norm] = local_history_error(data);
          const double max_error   = Utilities::MPI::max(error, comm);
          const double max_norm    = Utilities::MPI::max(norm, comm);
          results.push_back(
            relative_error(reference.history_name + " max relative error",
                           max_norm > 0 ? max_error / max_norm : max_error,
                           reference.tolerance));
        }
      if (!u_exact && !s_exact)
        return results;
      if (u_exact)
        u_exact->set_time(data.time);
      if (s_exact)
        s_exact->set_time(data.time);
      Sums           s       = local_sums(data);
      const MPI_Comm comm    = data.dof_handler.get_communicator();
      s.u_error2             = Utilities::MPI::sum(s.u_error2, comm);
      s.u_norm2              = Utilities::MPI::sum(s.u_norm2, comm);
      s.s_error_max          = Utilities::MPI::max(s.s_error_max, comm);
      s.s_norm_max           = Utilities::MPI::max(s.s_norm_max, comm);
      const double tolerance = reference.tolerance;
      if (u_exact)
        results.push_back(relative_error("displacement L2 relative error",
                                         s.u_norm2 > 0 ?
                                           std::sqrt(s.u_error2 / s.u_norm2) :
                                           std::sqrt(s.u_error2),
                                         tolerance));
      if (s_exact)
        results.push_back(relative_error("stress max relative error",
                                         s.s_norm_max > 0 ?
                                           s.s_error_max / s.s_norm_max :
                                           s.s_error_max,
                                         tolerance));
      return results;
    }


    // This rank's cells: the squared L2 error and norm of the
    // displacement, the largest stress error and reference stress.
    template <int dim>
    typename SolutionErrors<dim>::Sums
    SolutionErrors<dim>::local_sums(const StepData<dim> &data) const
    {
      const auto       &fe           = data.dof_handler.get_fe();
      const bool        axisymmetric = parameters.axisymmetric;
      const bool        projected    = parameters.projected_volumetric_strain;
      const QGauss<dim> quadrature(fe.degree + 2);
      FEValues<dim>     fe_values(data.mapping,
                              fe,
                              quadrature,
                              update_values | update_gradients |
                                update_quadrature_points | update_JxW_values);
      const FEValuesExtractors::Vector displacement(0);
      std::vector<Tensor<1, dim>>      u_h(quadrature.size());
      std::vector<Tensor<2, dim>>      grad_h(quadrature.size());
      // Projected volumetric strain: the stress with theta_bar.
      Material::ProjectedVolumetricStrain<dim> projection(fe,
                                                          quadrature,
                                                          axisymmetric);
      Vector<double> local_u(fe.n_dofs_per_cell()), theta_bar;
      // Finite strain: ln J is projected on the bulk rule (as assembled).
      const QGauss<dim>                        bulk_rule(fe.degree + 1);
      FEValues<dim>                            bulk_values(data.mapping,
                                fe,
                                bulk_rule,
                                update_values | update_gradients |
                                  update_quadrature_points | update_JxW_values);
      Material::ProjectedVolumetricStrain<dim> bulk_projection(fe,
                                                               bulk_rule,
                                                               axisymmetric);
      Sums                                     s;
      for (const auto &cell : data.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values[displacement].get_function_values(data.displacement, u_h);
            fe_values[displacement].get_function_gradients(data.displacement,
                                                           grad_h);
            const auto &material = *data.materials.at(cell->material_id());
            if (s_exact && projected &&
                material.kinematics() == Material::Kinematics::finite_strain)
              {
                // ln J projected on the bulk rule, as in the assembly.
                bulk_values.reinit(cell);
                Material::projected_log_J(bulk_projection,
                                          bulk_values,
                                          data.displacement,
                                          axisymmetric,
                                          theta_bar);
              }
            else if (s_exact && projected)
              {
                projection.reinit(fe_values);
                cell->get_dof_values(data.displacement, local_u);
                projection.coefficients(local_u, theta_bar);
              }
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                const auto  &x   = fe_values.quadrature_point(q);
                const double JxW = fe_values.JxW(q);
                if (u_exact)
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      const double ue = u_exact->value(x, d);
                      s.u_error2 += std::pow(u_h[q][d] - ue, 2) * JxW;
                      s.u_norm2 += ue * ue * JxW;
                    }
                if (!s_exact)
                  continue;
                // Axisymmetric: the hoop strain u_r / r enters the trace.
                const double hoop = axisymmetric ? u_h[q][0] / x[0] : 0.;
                const double theta =
                  projected ? projection.value(theta_bar, quadrature.point(q)) :
                              0.;
                // A model with history: that of the nearest bulk point.
                const unsigned int n_history = material.n_history_values();
                const SymmetricTensor<2, 3> stress = material.cauchy_stress(
                  Material::to_3d<dim>(grad_h[q], hoop),
                  n_history == 0 ? ArrayView<const double>() :
                                   data.history.at(cell,
                                                   data.history.nearest_point(
                                                     quadrature.point(q)),
                                                   n_history),
                  projected ? &theta : nullptr);
                const auto sigma = Material::from_3d<dim>(stress);
                double     e2 = 0, n2 = 0;
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int j = 0; j < dim; ++j)
                    {
                      const double se = s_exact->value(x, i * dim + j);
                      e2 += std::pow(sigma[i][j] - se, 2);
                      n2 += se * se;
                    }
                s.s_error_max = std::max(s.s_error_max, std::sqrt(e2));
                s.s_norm_max  = std::max(s.s_norm_max, std::sqrt(n2));
              }
          }
      return s;
    }


    template <int dim>
    std::pair<double, double>
    SolutionErrors<dim>::local_history_error(const StepData<dim> &data) const
    {
      const Quadrature<dim> &points = data.history.quadrature();
      FEValues<dim>          fe_values(data.mapping,
                              data.dof_handler.get_fe(),
                              points,
                              update_quadrature_points);
      const std::string     &name  = reference.history_name;
      double                 error = 0, norm = 0;
      for (const auto &cell : data.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto &material = *data.materials.at(cell->material_id());
            const auto  names    = material.history_output_names();
            const auto  k        = std::find(names.begin(), names.end(), name);
            if (k == names.end())
              continue;
            fe_values.reinit(cell);
            const auto history =
              data.history.on_cell(cell, material.n_history_values());
            for (unsigned int q = 0; q < points.size(); ++q)
              {
                const double value =
                  material.history_output(history[q])[k - names.begin()];
                const double exact =
                  h_exact->value(fe_values.quadrature_point(q));
                error = std::max(error, std::abs(value - exact));
                norm  = std::max(norm, std::abs(exact));
              }
          }
      return {error, norm};
    }


    template class SolutionErrors<2>;
    template class SolutionErrors<3>;
  } // namespace Postprocess
} // namespace Signorini
