#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <signorini/bulk/assembler.h>

#include <algorithm>
#include <limits>

namespace Signorini
{
  namespace Bulk
  {
    template <int dim>
    Assembler<dim>::Assembler(
      const Parameters                                        &parameters,
      const Mapping<dim>                                      &mapping,
      const FESystem<dim>                                     &fe,
      const Materials<dim>                                    &materials,
      const std::vector<std::unique_ptr<FunctionParser<dim>>> &neumann,
      const FunctionParser<dim>                               &body_force)
        : parameters(parameters)
        , mapping(mapping)
        , fe(fe)
        , materials(materials)
        , neumann(neumann)
        , body_force(body_force)
        , cell_quadrature(fe.degree + 1)
    {
    }


    template <int dim>
    Assembler<dim>::CellKinematics::CellKinematics(
      const Mapping<dim>    &mapping,
      const FESystem<dim>   &fe,
      const Quadrature<dim> &quadrature,
      const bool             axisymmetric)
        : fe_values(mapping,
                    fe,
                    quadrature,
                    update_values | update_gradients |
                      update_quadrature_points | update_JxW_values)
        , projection(fe, quadrature, axisymmetric)
        , B(quadrature.size(),
            std::vector<SymmetricTensor<2, 3>>(fe.n_dofs_per_cell()))
        , dV(quadrature.size())
        , strain(quadrature.size())
        , gradients(quadrature.size())
        , u_values(quadrature.size())
        , theta_i(fe.n_dofs_per_cell())
        , local_u(fe.n_dofs_per_cell())
        , full_gradients(quadrature.size())
        , H(quadrature.size())
        , grad_N(quadrature.size(),
                 std::vector<Tensor<2, 3>>(fe.n_dofs_per_cell()))
        , g(fe.n_dofs_per_cell())
        , g_tau(fe.n_dofs_per_cell())
        , d(fe.n_dofs_per_cell())
        , c_d(fe.n_dofs_per_cell())
        , F(quadrature.size())
        , F_bar(quadrature.size())
        , log_J(quadrature.size())
        , g_q(quadrature.size(),
              std::vector<Tensor<2, 3>>(fe.n_dofs_per_cell()))
        , g_bar(quadrature.size(),
                std::vector<Tensor<2, 3>>(fe.n_dofs_per_cell()))
        , tau_q(quadrature.size())
        , c_q(quadrature.size())
    {
    }


    template <int dim>
    void
    Assembler<dim>::cell_kinematics(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const TrilinosWrappers::MPI::Vector                  &solution,
      const Material::Kinematics                            kinematics,
      CellKinematics                                       &k) const
    {
      const FEValuesExtractors::Vector displacement(0);
      const bool                       axisymmetric = parameters.axisymmetric;
      const bool         projected = parameters.projected_volumetric_strain;
      const unsigned int n         = fe.n_dofs_per_cell();
      const unsigned int nq        = cell_quadrature.size();
      auto              &fe_values = k.fe_values;
      fe_values.reinit(cell);
      if (axisymmetric)
        fe_values[displacement].get_function_values(solution, k.u_values);
      if (kinematics == Material::Kinematics::finite_strain)
        {
          fe_values[displacement].get_function_gradients(solution,
                                                         k.full_gradients);
          finite_strain_kinematics(k);
          return;
        }
      fe_values[displacement].get_function_symmetric_gradients(solution,
                                                               k.gradients);

      // B operator and the cell's projection (B-bar).
      if (projected)
        k.projection.start_cell();
      for (unsigned int q = 0; q < nq; ++q)
        {
          const Point<dim> &x = fe_values.quadrature_point(q);
          // Axisymmetric: the ring of radius r = x carries 2 pi r.
          k.dV[q] =
            fe_values.JxW(q) * (axisymmetric ? 2 * numbers::PI * x[0] : 1.);
          for (unsigned int i = 0; i < n; ++i)
            {
              const unsigned int c    = fe.system_to_component_index(i).first;
              const double       hoop = axisymmetric && c == 0 ?
                                          fe_values.shape_value(i, q) / x[0] :
                                          0.;
              k.B[q][i]               = Material::to_3d<dim>(
                fe_values[displacement].symmetric_gradient(i, q), hoop);
              k.theta_i[i] = trace(k.B[q][i]);
            }
          if (projected)
            k.projection.add_point(q, k.dV[q], k.theta_i);
        }
      if (projected)
        {
          k.projection.finish_cell();
          cell->get_dof_values(solution, k.local_u);
          k.projection.coefficients(k.local_u, k.theta_bar);
        }

      // The strain of the solution (with B-bar its projected volumetric
      // part, and the matching operator).
      for (unsigned int q = 0; q < nq; ++q)
        {
          const double hoop =
            axisymmetric ? k.u_values[q][0] / fe_values.quadrature_point(q)[0] :
                           0.;
          double theta_q = 0;
          if (projected)
            {
              theta_q = k.projection.value_at(q, k.theta_bar);
              k.projection.derivatives_at(q, k.dtheta_bar);
              for (unsigned int i = 0; i < n; ++i)
                k.B[q][i] += (k.dtheta_bar[i] - trace(k.B[q][i])) / 3. *
                             unit_symmetric_tensor<3>();
            }
          k.strain[q] = point_strain<dim>(k.gradients[q],
                                          hoop,
                                          projected ? &theta_q : nullptr);
        }
    }


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
      k.inverted = false;
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
          k.F[q]     = unit_symmetric_tensor<3>() + k.H[q];
          k.log_J[q] = std::log(determinant(k.F[q])); // NaN if inverted
          k.inverted = k.inverted || !(determinant(k.F[q]) > 0);
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
          k.F_bar[q] = std::exp((theta_bar - k.log_J[q]) / 3.) * k.F[q];
        }
    }


    template <int dim>
    std::unique_ptr<FEFaceValues<dim>>
    Assembler<dim>::neumann_face_values() const
    {
      return std::make_unique<FEFaceValues<dim>>(mapping,
                                                 fe,
                                                 QGauss<dim - 1>(fe.degree + 1),
                                                 update_values |
                                                   update_gradients |
                                                   update_quadrature_points |
                                                   update_normal_vectors |
                                                   update_JxW_values);
    }


    template <int dim>
    void
    Assembler<dim>::add_body_force(const CellKinematics &k,
                                   Vector<double>       &cell_fext) const
    {
      Vector<double> force(dim);
      for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
        {
          body_force.vector_value(k.fe_values.quadrature_point(q), force);
          for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
            cell_fext(i) += force(fe.system_to_component_index(i).first) *
                            k.fe_values.shape_value(i, q) * k.dV[q];
        }
    }


    template <int dim>
    void
    Assembler<dim>::add_small_strain_point(
      const Material::Interface<dim> &material,
      const ArrayView<const double>  &history,
      const unsigned int              q,
      CellKinematics                 &k,
      Vector<double>                 &f_int,
      FullMatrix<double>             *matrix) const
    {
      const unsigned int    n = fe.n_dofs_per_cell();
      SymmetricTensor<2, 3> stress;
      SymmetricTensor<4, 3> C;
      material.evaluate(k.strain[q], history, stress, matrix ? &C : nullptr);
      const auto &B = k.B[q];
      for (unsigned int i = 0; i < n; ++i)
        f_int(i) += (stress * B[i]) * k.dV[q];
      if (!matrix)
        return;
      for (unsigned int j = 0; j < n; ++j)
        k.c_d[j] = C * B[j];
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          (*matrix)(i, j) += (B[i] * k.c_d[j]) * k.dV[q];
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
      const unsigned int n = fe.n_dofs_per_cell();
      const Tensor<2, 3> F = k.F[q];
      if (!(determinant(F) > 0))
        {
          // An inverted element: a NaN residual makes Newton fail this
          // iterate (and the load stepper cut the step).
          ++n_inverted;
          f_int(0) += std::numeric_limits<double>::quiet_NaN();
          return;
        }
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
    //                 + tr(tau_bar) / 3 (T_ij - P[T_ij]) dV,  T_ij = tr(g_i
    //                 g_j),
    // the last two terms from d g_i = -g_i g_j.
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
      if (k.inverted)
        {
          ++n_inverted;
          f_int(0) += std::numeric_limits<double>::quiet_NaN();
          return;
        }
      std::vector<double> tr_g(nq * n), w(nq, 0.);
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


    template <int dim>
    void
    Assembler<dim>::assemble(
      const DoFHandler<dim>               &dof_handler,
      const TrilinosWrappers::MPI::Vector &solution,
      const Material::History<dim>        &history,
      const AffineConstraints<double>     &constraints,
      TrilinosWrappers::SparseMatrix      *matrix,
      TrilinosWrappers::MPI::Vector       &rhs,
      TrilinosWrappers::MPI::Vector       &internal_force,
      TrilinosWrappers::MPI::Vector       &external_force) const
    {
      const auto     fe_face_values = neumann_face_values();
      CellKinematics k(mapping, fe, cell_quadrature, parameters.axisymmetric);

      const unsigned int n = fe.n_dofs_per_cell();
      FullMatrix<double> cell_matrix(n, n);
      Vector<double>     cell_rhs(n), cell_fint(n), cell_fext(n);
      std::vector<types::global_dof_index> dofs(n);
      n_inverted = 0;

      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell_matrix                  = 0;
            cell_fint                    = 0;
            cell_fext                    = 0;
            const auto        &material  = *materials.at(cell->material_id());
            const unsigned int n_history = material.n_history_values();
            const auto         cell_history = history.on_cell(cell, n_history);
            const auto         kinematics   = material.kinematics();
            cell_kinematics(cell, solution, kinematics, k);
            add_body_force(k, cell_fext);

            // Stress and tangent of the cell's model at every point.
            FullMatrix<double> *local_matrix = matrix ? &cell_matrix : nullptr;
            const bool          finite =
              kinematics == Material::Kinematics::finite_strain;
            if (finite && parameters.projected_volumetric_strain)
              add_projected_finite_strain_cell(
                material, cell_history, k, cell_fint, local_matrix);
            else
              for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
                if (finite)
                  add_finite_strain_point(
                    material, cell_history[q], q, k, cell_fint, local_matrix);
                else
                  add_small_strain_point(
                    material, cell_history[q], q, k, cell_fint, local_matrix);

            add_neumann(cell,
                        solution,
                        *fe_face_values,
                        cell_fext,
                        matrix ? &cell_matrix : nullptr);

            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < n; ++i)
              cell_rhs(i) = cell_fext(i) - cell_fint(i);
            if (matrix)
              constraints.distribute_local_to_global(
                cell_matrix, cell_rhs, dofs, *matrix, rhs);
            else
              constraints.distribute_local_to_global(cell_rhs, dofs, rhs);
            internal_force.add(dofs, cell_fint);
            external_force.add(dofs, cell_fext);
          }
    }


    template <int dim>
    void
    Assembler<dim>::assemble_external_force(
      const DoFHandler<dim>               &dof_handler,
      const TrilinosWrappers::MPI::Vector &solution,
      const bool                           with_body_force,
      TrilinosWrappers::MPI::Vector       &external_force) const
    {
      const auto     fe_face_values = neumann_face_values();
      CellKinematics k(mapping, fe, cell_quadrature, parameters.axisymmetric);
      Vector<double> cell_fext(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      external_force = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            if (!with_body_force && !cell->at_boundary())
              continue;
            cell_fext = 0;
            if (with_body_force)
              {
                cell_kinematics(cell,
                                solution,
                                materials.at(cell->material_id())->kinematics(),
                                k);
                add_body_force(k, cell_fext);
              }
            add_neumann(cell, solution, *fe_face_values, cell_fext, nullptr);
            cell->get_dof_indices(dofs);
            external_force.add(dofs, cell_fext);
          }
      external_force.compress(VectorOperation::add);
    }


    template <int dim>
    void
    Assembler<dim>::update_history(
      const DoFHandler<dim>               &dof_handler,
      const TrilinosWrappers::MPI::Vector &solution,
      Material::History<dim>              &history) const
    {
      if (!history.active())
        return;
      CellKinematics k(mapping, fe, cell_quadrature, parameters.axisymmetric);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto &material  = *materials.at(cell->material_id());
            const auto  n_history = material.n_history_values();
            if (n_history == 0)
              continue;
            const auto cell_history = history.on_cell(cell, n_history);
            const auto kinematics   = material.kinematics();
            cell_kinematics(cell, solution, kinematics, k);
            for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
              if (kinematics == Material::Kinematics::finite_strain)
                material.update_history_finite_strain(k.F_bar[q],
                                                      cell_history[q]);
              else
                material.update_history(k.strain[q], cell_history[q]);
          }
    }


    template <int dim>
    void
    Assembler<dim>::add_neumann(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const TrilinosWrappers::MPI::Vector                  &solution,
      FEFaceValues<dim>                                    &fe_face_values,
      Vector<double>                                       &cell_fext,
      FullMatrix<double>                                   *cell_matrix) const
    {
      const FEValuesExtractors::Vector displacement(0);
      const auto                      &bc = parameters.boundary_conditions;
      const unsigned int               n  = fe.n_dofs_per_cell();
      const unsigned int nq = fe_face_values.get_quadrature().size();
      const bool finite     = materials.at(cell->material_id())->kinematics() ==
                          Material::Kinematics::finite_strain;
      std::vector<Tensor<2, dim>> grad_u(nq);
      std::vector<Tensor<1, dim>> u(nq);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          for (unsigned int k = 0; k < bc.neumann.size(); ++k)
            if (std::count(bc.neumann[k].boundary_ids.begin(),
                           bc.neumann[k].boundary_ids.end(),
                           cell->face(f)->boundary_id()))
              {
                fe_face_values.reinit(cell, f);
                const auto &g = *neumann[k];
                const bool  follower =
                  finite && bc.neumann[k].type == NeumannType::pressure;
                if (follower)
                  {
                    fe_face_values[displacement].get_function_gradients(
                      solution, grad_u);
                    fe_face_values[displacement].get_function_values(solution,
                                                                     u);
                  }
                for (unsigned int q = 0; q < nq; ++q)
                  {
                    const auto  &x = fe_face_values.quadrature_point(q);
                    const double ring =
                      parameters.axisymmetric ? 2 * numbers::PI * x[0] : 1.;
                    if (follower)
                      {
                        const Tensor<2, 3> H =
                          Material::to_3d<dim>(grad_u[q],
                                               parameters.axisymmetric ?
                                                 u[q][0] / x[0] :
                                                 0.);
                        add_follower_pressure(fe_face_values,
                                              q,
                                              g.value(x, 0),
                                              H,
                                              ring,
                                              cell_fext,
                                              cell_matrix);
                        continue;
                      }
                    Tensor<1, dim> traction;
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
                        fe_face_values.JxW(q) * ring;
                  }
              }
    }


    // Nanson: n da = cof(F) N dA with cof(F) = J F^-T; its derivative in
    // the direction A = Grad N_j is J (tr(F^-1 A) F^-T - F^-T A^T F^-T).
    // Axisymmetric, F_33 = r / R makes cof(F) N 2 pi R dA = n da 2 pi r.
    template <int dim>
    void
    Assembler<dim>::add_follower_pressure(
      const FEFaceValues<dim> &fe_face_values,
      const unsigned int       q,
      const double             p,
      const Tensor<2, 3>      &H,
      const double             ring,
      Vector<double>          &cell_fext,
      FullMatrix<double>      *cell_matrix) const
    {
      const FEValuesExtractors::Vector displacement(0);
      const unsigned int               n      = fe.n_dofs_per_cell();
      const Tensor<2, 3>               F      = unit_symmetric_tensor<3>() + H;
      const double                     J      = determinant(F);
      const Tensor<2, 3>               F_invT = transpose(invert(F));
      Tensor<1, 3>                     N;
      for (unsigned int d = 0; d < dim; ++d)
        N[d] = fe_face_values.normal_vector(q)[d];
      const double       dA       = fe_face_values.JxW(q) * ring;
      const Tensor<1, 3> traction = -p * J * (F_invT * N);
      for (unsigned int i = 0; i < n; ++i)
        cell_fext(i) += traction[fe.system_to_component_index(i).first] *
                        fe_face_values.shape_value(i, q) * dA;
      if (!cell_matrix)
        return;
      const double R = fe_face_values.quadrature_point(q)[0];
      for (unsigned int j = 0; j < n; ++j)
        {
          const unsigned int cj = fe.system_to_component_index(j).first;
          const Tensor<2, 3> A =
            Material::to_3d<dim>(fe_face_values[displacement].gradient(j, q),
                                 parameters.axisymmetric && cj == 0 ?
                                   fe_face_values.shape_value(j, q) / R :
                                   0.);
          const Tensor<2, 3> d_cof =
            J * (trace(transpose(F_invT) * A) * F_invT -
                 F_invT * transpose(A) * F_invT);
          const Tensor<1, 3> d_traction = -p * (d_cof * N);
          for (unsigned int i = 0; i < n; ++i)
            (*cell_matrix)(i, j) -=
              d_traction[fe.system_to_component_index(i).first] *
              fe_face_values.shape_value(i, q) * dA;
        }
    }


    template class Assembler<2>;
    template class Assembler<3>;
  } // namespace Bulk
} // namespace Signorini
