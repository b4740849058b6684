// The finite-strain part of the bulk assembly (total Lagrangian, and F-bar
// with the projection): Bulk::Assembler, class documentation.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <signorini/bulk/assembler.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace Signorini
{
  namespace Bulk
  {
    // H and Grad N_i (axisymmetric with the hoop terms u_r / R and N_i / R
    // of the radial shape functions), F, and with the projection theta_bar
    // = P[ln J] and F_bar = exp((theta_bar - ln J) / 3) F.
    template <int dim>
    void
    Assembler<dim>::finite_strain_kinematics(CellKinematics &k) const
    {
      const FEValuesExtractors::Vector displacement(0);
      const bool                       axisymmetric = parameters.axisymmetric;
      const bool         projected = parameters.projected_volumetric_strain;
      const unsigned int n         = fe.n_dofs_per_cell();
      const unsigned int nq        = cell_quadrature.size();
      const auto        &fe_values = k.fe_values;
      if (projected)
        k.projection.start_cell();
      k.inverted   = false;
      k.smallest_J = std::numeric_limits<double>::max();
      for (unsigned int q = 0; q < nq; ++q)
        {
          const double R = fe_values.quadrature_point(q)[0];
          k.dV[q] =
            fe_values.JxW(q) * (axisymmetric ? 2 * numbers::PI * R : 1.);
          k.H[q] =
            Material::to_3d<dim>(k.full_gradients[q],
                                 axisymmetric ? k.u_values[q][0] / R : 0.);
          for (unsigned int i = 0; i < n; ++i)
            {
              const unsigned int c = fe.system_to_component_index(i).first;
              k.grad_N[q][i] =
                Material::to_3d<dim>(fe_values[displacement].gradient(i, q),
                                     axisymmetric && c == 0 ?
                                       fe_values.shape_value(i, q) / R :
                                       0.);
              k.theta_i[i] = trace(k.grad_N[q][i]);
            }
          k.F[q]         = unit_symmetric_tensor<3>() + k.H[q];
          const double J = determinant(k.F[q]);
          k.log_J[q]     = std::log(J); // NaN if inverted
          k.inverted     = k.inverted || !(J > 0);
          k.smallest_J   = std::min(k.smallest_J, J);
          if (projected)
            k.projection.add_point(q, k.dV[q], k.theta_i);
        }
      k.F_bar = k.F;
      if (!projected || k.inverted)
        return;
      k.projection.finish_cell();
      k.projection.projection_matrix(k.Pi);
      for (unsigned int q = 0; q < nq; ++q)
        {
          double theta_bar = 0;
          for (unsigned int p = 0; p < nq; ++p)
            theta_bar += k.Pi(q, p) * k.log_J[p];
          k.F_bar[q] = Material::with_volumetric(k.F[q], theta_bar, k.log_J[q]);
        }
    }

    // det F at the output points too: on the axis (R = 0) the hoop
    // stretch u_r / R takes its limit d u_r / d R.
    template <int dim>
    bool
    Assembler<dim>::deformation_valid(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const TrilinosWrappers::MPI::Vector                  &solution,
      CellKinematics                                       &k) const
    {
      const FEValuesExtractors::Vector displacement(0);
      auto                            &points = k.output_points;
      points.reinit(cell);
      points[displacement].get_function_gradients(solution, k.output_gradients);
      if (parameters.axisymmetric)
        points[displacement].get_function_values(solution, k.output_u);
      double       J_min = k.smallest_J;
      const double R_min = 1e-12 * cell->diameter();
      for (unsigned int q = 0; q < points.n_quadrature_points; ++q)
        {
          const double       R    = points.quadrature_point(q)[0];
          const double       hoop = !parameters.axisymmetric ? 0. :
                                    R > R_min ? k.output_u[q][0] / R :
                                                k.output_gradients[q][0][0];
          const Tensor<2, 3> F =
            unit_symmetric_tensor<3>() +
            Material::to_3d<dim>(k.output_gradients[q], hoop);
          J_min = std::min(J_min, determinant(F));
        }
      if (J_min > 0)
        return true;
      const bool first = inverted.n_cells++ == 0;
      if (first || inverted.named_instead_by(J_min, cell->center()))
        {
          inverted.smallest_J = J_min;
          inverted.where      = cell->center();
        }
      return false;
    }


    template <int dim>
    void
    Assembler<dim>::add_finite_strain_point(
      const Material::Interface<dim> &material,
      const ArrayView<const double>  &history,
      const unsigned int              q,
      CellKinematics                 &k,
      Vector<double>                 &f_int,
      FullMatrix<double>             *matrix) const
    {
      const unsigned int    n     = fe.n_dofs_per_cell();
      const Tensor<2, 3>    F     = k.F[q];
      const Tensor<2, 3>    F_inv = invert(F);
      SymmetricTensor<2, 3> tau;
      SymmetricTensor<4, 3> c;
      material.evaluate_finite_strain(F, history, tau, matrix ? &c : nullptr);
      for (unsigned int i = 0; i < n; ++i)
        {
          k.g[i] = k.grad_N[q][i] * F_inv;
          k.d[i] = symmetrize(k.g[i]);
          f_int(i) += (tau * k.d[i]) * k.dV[q];
        }
      if (!matrix)
        return;
      for (unsigned int j = 0; j < n; ++j)
        {
          k.c_d[j]   = c * k.d[j];
          k.g_tau[j] = k.g[j] * tau;
        }
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          (*matrix)(i, j) +=
            (k.d[i] * k.c_d[j] + scalar_product(k.g[i], k.g_tau[j])) * k.dV[q];
    }


    // F-bar with theta_bar = P[ln J] (class documentation of
    // Material::ProjectedVolumetricStrain). With g_i = Grad N_i F^-1 and
    // g_bar_i = g_i + (P[tr g_i] - tr g_i) / 3 I = dF_bar F_bar^-1 in the
    // direction of u_i:
    //   F_int,i = int tau_bar : g_bar_i dV,
    //   K_ij    = int g_bar_i : c_bar : g_bar_j
    //                 + g_bar_i : (g_bar_j tau_bar + tau_bar g_bar_j^T)
    //                 - tau_bar : (g_i g_j)
    //                 + tr(tau_bar) / 3 (T_ij - P[T_ij]) dV,
    // with T_ij = tr(g_i g_j); the last two terms come from d g_i = -g_i g_j.
    template <int dim>
    void
    Assembler<dim>::add_projected_finite_strain_cell(
      const Material::Interface<dim>             &material,
      const std::vector<ArrayView<const double>> &history,
      CellKinematics                             &k,
      Vector<double>                             &f_int,
      FullMatrix<double>                         *matrix) const
    {
      const unsigned int          n  = fe.n_dofs_per_cell();
      const unsigned int          nq = cell_quadrature.size();
      const SymmetricTensor<2, 3> I  = unit_symmetric_tensor<3>();
      std::vector<double>         tr_g(nq * n), w(nq, 0.);
      for (unsigned int q = 0; q < nq; ++q)
        {
          const Tensor<2, 3> F_inv = invert(k.F[q]);
          for (unsigned int i = 0; i < n; ++i)
            {
              k.g_q[q][i]     = k.grad_N[q][i] * F_inv;
              tr_g[q * n + i] = trace(k.g_q[q][i]);
            }
          material.evaluate_finite_strain(k.F_bar[q],
                                          history[q],
                                          k.tau_q[q],
                                          matrix ? &k.c_q[q] : nullptr);
        }
      for (unsigned int q = 0; q < nq; ++q)
        for (unsigned int i = 0; i < n; ++i)
          {
            double p_tr = 0;
            for (unsigned int p = 0; p < nq; ++p)
              p_tr += k.Pi(q, p) * tr_g[p * n + i];
            k.g_bar[q][i] = k.g_q[q][i] + (p_tr - tr_g[q * n + i]) / 3. * I;
            f_int(i) += scalar_product(k.tau_q[q], k.g_bar[q][i]) * k.dV[q];
          }
      if (!matrix)
        return;
      // w(p) = sum_q dV_q tr(tau_bar_q) Pi(q, p): the P[T_ij] term.
      for (unsigned int q = 0; q < nq; ++q)
        for (unsigned int p = 0; p < nq; ++p)
          w[p] += k.dV[q] * trace(k.tau_q[q]) * k.Pi(q, p);
      for (unsigned int q = 0; q < nq; ++q)
        {
          const auto  &tau = k.tau_q[q];
          const double s   = (k.dV[q] * trace(tau) - w[q]) / 3.;
          for (unsigned int j = 0; j < n; ++j)
            {
              k.c_d[j]   = k.c_q[q] * symmetrize(k.g_bar[q][j]);
              k.g_tau[j] = k.g_bar[q][j] * tau + tau * transpose(k.g_bar[q][j]);
            }
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              {
                const Tensor<2, 3> gg = k.g_q[q][i] * k.g_q[q][j];
                (*matrix)(i, j) += (scalar_product(k.g_bar[q][i], k.c_d[j]) +
                                    scalar_product(k.g_bar[q][i], k.g_tau[j]) -
                                    scalar_product(tau, gg)) *
                                     k.dV[q] +
                                   s * trace(gg);
              }
        }
    }


#define SIGNORINI_INSTANTIATE(dim)                                \
  template void Assembler<dim>::finite_strain_kinematics(         \
    Assembler<dim>::CellKinematics &) const;                      \
  template bool Assembler<dim>::deformation_valid(                \
    const typename DoFHandler<dim>::active_cell_iterator &,       \
    const TrilinosWrappers::MPI::Vector &,                        \
    Assembler<dim>::CellKinematics &) const;                      \
  template void Assembler<dim>::add_finite_strain_point(          \
    const Material::Interface<dim> &,                             \
    const ArrayView<const double> &,                              \
    const unsigned int,                                           \
    Assembler<dim>::CellKinematics &,                             \
    Vector<double> &,                                             \
    FullMatrix<double> *) const;                                  \
  template void Assembler<dim>::add_projected_finite_strain_cell( \
    const Material::Interface<dim> &,                             \
    const std::vector<ArrayView<const double>> &,                 \
    Assembler<dim>::CellKinematics &,                             \
    Vector<double> &,                                             \
    FullMatrix<double> *) const;
    SIGNORINI_INSTANTIATE(2)
    SIGNORINI_INSTANTIATE(3)
#undef SIGNORINI_INSTANTIATE
  } // namespace Bulk
} // namespace Signorini
