#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <signorini/bulk/assembler.h>
#include <signorini/material/projected_volumetric_strain.h>

#include <algorithm>

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
    {
    }


    template <int dim>
    void
    Assembler<dim>::assemble(
      const DoFHandler<dim>               &dof_handler,
      const TrilinosWrappers::MPI::Vector &solution,
      const AffineConstraints<double>     &constraints,
      TrilinosWrappers::SparseMatrix      *matrix,
      TrilinosWrappers::MPI::Vector       &rhs,
      TrilinosWrappers::MPI::Vector       &internal_force,
      TrilinosWrappers::MPI::Vector       &external_force) const
    {
      const QGauss<dim>                quadrature(fe.degree + 1);
      const QGauss<dim - 1>            face_quadrature(fe.degree + 1);
      FEValues<dim>                    fe_values(mapping,
                              fe,
                              quadrature,
                              update_values | update_gradients |
                                update_quadrature_points | update_JxW_values);
      FEFaceValues<dim>                fe_face_values(mapping,
                                       fe,
                                       face_quadrature,
                                       update_values |
                                         update_quadrature_points |
                                         update_normal_vectors |
                                         update_JxW_values);
      const FEValuesExtractors::Vector displacement(0);
      const bool                       axisymmetric = parameters.axisymmetric;
      const bool projected = parameters.projected_volumetric_strain;
      Material::ProjectedVolumetricStrain<dim> projection(fe,
                                                          quadrature,
                                                          axisymmetric);

      const unsigned int n  = fe.n_dofs_per_cell();
      const unsigned int nq = quadrature.size();
      FullMatrix<double> cell_matrix(n, n);
      Vector<double>     cell_rhs(n), cell_fint(n), cell_fext(n), local_u(n),
        theta_bar;
      std::vector<types::global_dof_index> dofs(n);
      std::vector<SymmetricTensor<2, dim>> strains(nq);
      std::vector<Tensor<1, dim>>          u_values(nq);
      // The 3D strain of each shape function at each point (B operator),
      // its trace, and with B-bar d theta_bar / d u_i.
      std::vector<std::vector<SymmetricTensor<2, 3>>> B(
        nq, std::vector<SymmetricTensor<2, 3>>(n));
      std::vector<double>                theta_i(n), dtheta_bar;
      std::vector<double>                dV(nq);
      std::vector<SymmetricTensor<2, 3>> C_B(n);
      Vector<double>                     force_values(dim);

      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            cell_matrix          = 0;
            cell_fint            = 0;
            cell_fext            = 0;
            const auto &material = *materials.at(cell->material_id());
            fe_values[displacement].get_function_symmetric_gradients(solution,
                                                                     strains);
            if (axisymmetric)
              fe_values[displacement].get_function_values(solution, u_values);

            // B operator, body force, and the cell's projection (B-bar).
            if (projected)
              projection.start_cell();
            for (unsigned int q = 0; q < nq; ++q)
              {
                const Point<dim> &x = fe_values.quadrature_point(q);
                // Axisymmetric: the ring of radius r = x carries 2 pi r.
                dV[q] = fe_values.JxW(q) *
                        (axisymmetric ? 2 * numbers::PI * x[0] : 1.);
                body_force.vector_value(x, force_values);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    const unsigned int c =
                      fe.system_to_component_index(i).first;
                    const double hoop = axisymmetric && c == 0 ?
                                          fe_values.shape_value(i, q) / x[0] :
                                          0.;
                    B[q][i]           = Material::to_3d<dim>(
                      fe_values[displacement].symmetric_gradient(i, q), hoop);
                    theta_i[i] = trace(B[q][i]);
                    cell_fext(i) +=
                      force_values(c) * fe_values.shape_value(i, q) * dV[q];
                  }
                if (projected)
                  projection.add_point(q, dV[q], theta_i);
              }
            if (projected)
              {
                projection.finish_cell();
                cell->get_dof_values(solution, local_u);
                projection.coefficients(local_u, theta_bar);
              }

            // Stress and tangent of the cell's model at every point.
            for (unsigned int q = 0; q < nq; ++q)
              {
                const Point<dim> &x = fe_values.quadrature_point(q);
                const double hoop   = axisymmetric ? u_values[q][0] / x[0] : 0.;
                double       theta_q = 0;
                if (projected)
                  {
                    theta_q = projection.value_at(q, theta_bar);
                    projection.derivatives_at(q, dtheta_bar);
                    for (unsigned int i = 0; i < n; ++i)
                      B[q][i] += (dtheta_bar[i] - trace(B[q][i])) / 3. *
                                 unit_symmetric_tensor<3>();
                  }
                const SymmetricTensor<2, 3> strain =
                  point_strain<dim>(strains[q],
                                    hoop,
                                    projected ? &theta_q : nullptr);
                SymmetricTensor<2, 3> stress;
                SymmetricTensor<4, 3> C;
                material.evaluate(strain, stress, matrix ? &C : nullptr);
                for (unsigned int i = 0; i < n; ++i)
                  cell_fint(i) += (stress * B[q][i]) * dV[q];
                if (matrix)
                  {
                    for (unsigned int j = 0; j < n; ++j)
                      C_B[j] = C * B[q][j];
                    for (unsigned int i = 0; i < n; ++i)
                      for (unsigned int j = 0; j < n; ++j)
                        cell_matrix(i, j) += (B[q][i] * C_B[j]) * dV[q];
                  }
              }

            add_neumann(cell, fe_face_values, cell_fext);

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
    Assembler<dim>::add_neumann(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      FEFaceValues<dim>                                    &fe_face_values,
      Vector<double>                                       &cell_fext) const
    {
      const auto        &bc = parameters.boundary_conditions;
      const unsigned int n  = fe.n_dofs_per_cell();
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          for (unsigned int k = 0; k < bc.neumann.size(); ++k)
            if (std::count(bc.neumann[k].boundary_ids.begin(),
                           bc.neumann[k].boundary_ids.end(),
                           cell->face(f)->boundary_id()))
              {
                fe_face_values.reinit(cell, f);
                const auto &g = *neumann[k];
                for (unsigned int q = 0;
                     q < fe_face_values.get_quadrature().size();
                     ++q)
                  {
                    Tensor<1, dim> traction;
                    const auto    &x = fe_face_values.quadrature_point(q);
                    if (bc.neumann[k].type == NeumannType::traction)
                      for (unsigned int d = 0; d < dim; ++d)
                        traction[d] = g.value(x, d);
                    else
                      traction =
                        -g.value(x, 0) * fe_face_values.normal_vector(q);
                    const double ring =
                      parameters.axisymmetric ? 2 * numbers::PI * x[0] : 1.;
                    for (unsigned int i = 0; i < n; ++i)
                      cell_fext(i) +=
                        traction[fe.system_to_component_index(i).first] *
                        fe_face_values.shape_value(i, q) *
                        fe_face_values.JxW(q) * ring;
                  }
              }
    }


    template class Assembler<2>;
    template class Assembler<3>;
  } // namespace Bulk
} // namespace Signorini
