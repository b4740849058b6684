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
    namespace
    {
      // Every entry of @p v and @p m is finite (deal.II's norms assert it
      // in a Debug build instead of answering).
      bool
      all_finite(const Vector<double> &v, const FullMatrix<double> &m)
      {
        for (const double x : v)
          if (!std::isfinite(x))
            return false;
        for (unsigned int i = 0; i < m.m(); ++i)
          for (unsigned int j = 0; j < m.n(); ++j)
            if (!std::isfinite(m(i, j)))
              return false;
        return true;
      }
    } // namespace

    template <int dim>
    Assembler<dim>::Assembler(
      const Parameters                                        &parameters,
      const Mapping<dim>                                      &mapping,
      const FESystem<dim>                                     &fe,
      const Materials<dim>                                    &materials,
      const std::vector<std::unique_ptr<FunctionParser<dim>>> &neumann,
      const BodyForces<dim>                                   &body_forces)
        : parameters(parameters)
        , mapping(mapping)
        , fe(fe)
        , materials(materials)
        , neumann(neumann)
        , body_forces(body_forces)
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
        , output_points(mapping,
                        fe,
                        QIterated<dim>(QTrapezoid<1>(), fe.degree),
                        update_values | update_gradients |
                          update_quadrature_points)
        , output_gradients(output_points.n_quadrature_points)
        , output_u(output_points.n_quadrature_points)
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
    Assembler<dim>::add_body_force(const types::material_id material_id,
                                   const CellKinematics    &k,
                                   Vector<double>          &cell_fext) const
    {
      const auto    &body_force = *body_forces.at(material_id);
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
      material.evaluate_completed(k.strain[q],
                                  history,
                                  stress,
                                  matrix ? &C : nullptr);
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
    Assembler<dim>::assemble(const DoFHandler<dim>               &dof_handler,
                             const TrilinosWrappers::MPI::Vector &solution,
                             const Material::History<dim>        &history,
                             const AffineConstraints<double>     &constraints,
                             TrilinosWrappers::SparseMatrix      *matrix,
                             TrilinosWrappers::MPI::Vector       &rhs,
                             TrilinosWrappers::MPI::Vector &internal_force,
                             TrilinosWrappers::MPI::Vector &external_force,
                             const LinearSystemRhs         *linear_system,
                             const PinRows                 *pin_rows) const
    {
      const auto     fe_face_values = neumann_face_values();
      CellKinematics k(mapping, fe, cell_quadrature, parameters.axisymmetric);

      const unsigned int n = fe.n_dofs_per_cell();
      FullMatrix<double> cell_matrix(n, n);
      Vector<double>     cell_rhs(n), cell_fint(n), cell_fext(n);
      std::vector<types::global_dof_index> dofs(n);
      inverted = Inversion();

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
            add_body_force(cell->material_id(), k, cell_fext);

            // Stress and tangent of the cell's model at every point.
            FullMatrix<double> *local_matrix = matrix ? &cell_matrix : nullptr;
            const bool          finite =
              kinematics == Material::Kinematics::finite_strain;
            if (finite && !deformation_valid(cell, solution, k))
              cell_fint(0) = std::numeric_limits<double>::quiet_NaN();
            else if (finite && parameters.projected_volumetric_strain)
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
            // A cell with a non-finite value (a NaN load, an inverted
            // element) makes the residual non-finite, and Newton stops at
            // it: its Jacobian is left out (deal.II's Debug build stops at
            // a non-finite matrix entry).
            const bool with_matrix =
              matrix != nullptr && all_finite(cell_rhs, cell_matrix);
            if (with_matrix && linear_system)
              linear_system->constraints.distribute_local_to_global(
                cell_matrix, cell_rhs, dofs, *matrix, linear_system->rhs);
            if (with_matrix && !linear_system)
              constraints.distribute_local_to_global(
                cell_matrix, cell_rhs, dofs, *matrix, rhs);
            else
              constraints.distribute_local_to_global(cell_rhs, dofs, rhs);
            if (with_matrix && pin_rows)
              add_pin_rows(cell_matrix,
                           dofs,
                           constraints,
                           linear_system ? &linear_system->constraints :
                                           nullptr,
                           *pin_rows);
            internal_force.add(dofs, cell_fint);
            external_force.add(dofs, cell_fext);
          }
    }


    const AffineConstraints<double> &
    rows_as_they_are()
    {
      static const AffineConstraints<double> none = [] {
        AffineConstraints<double> constraints;
        constraints.close();
        return constraints;
      }();
      return none;
    }


    template <int dim>
    void
    Assembler<dim>::add_pin_rows(
      const FullMatrix<double>                   &cell_matrix,
      const std::vector<types::global_dof_index> &dofs,
      const AffineConstraints<double>            &constraints,
      const AffineConstraints<double>            *first_update,
      const PinRows                              &pin_rows) const
    {
      // Rows kept as they are, columns condensed.
      const unsigned int n = dofs.size();
      FullMatrix<double> row(1, n);
      for (unsigned int i = 0; i < n; ++i)
        if (pin_rows.dofs.count(dofs[i]) > 0)
          {
            for (unsigned int j = 0; j < n; ++j)
              row(0, j) = cell_matrix(i, j);
            rows_as_they_are().distribute_local_to_global(
              row, {dofs[i]}, constraints, dofs, pin_rows.matrix);
            if (first_update)
              {
                double shift = 0;
                for (unsigned int j = 0; j < n; ++j)
                  if (first_update->is_inhomogeneously_constrained(dofs[j]))
                    shift += cell_matrix(i, j) *
                             first_update->get_inhomogeneity(dofs[j]);
                const TrilinosWrappers::MPI::Vector::size_type index = dofs[i];
                pin_rows.shift.add(1, &index, &shift);
              }
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
                add_body_force(cell->material_id(), k, cell_fext);
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
                material.update_history(
                  material.completed_strain(k.strain[q], cell_history[q]),
                  cell_history[q]);
          }
    }


    template class Assembler<2>;
    template class Assembler<3>;
  } // namespace Bulk
} // namespace Signorini
