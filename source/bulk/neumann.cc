// The Neumann loads of the bulk assembly: tractions (dead loads per
// reference area) and pressures (following the deformed face at finite
// strain, with their load stiffness): Bulk::Assembler.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <signorini/bulk/assembler.h>

#include <algorithm>

namespace Signorini
{
  namespace Bulk
  {
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


#define SIGNORINI_INSTANTIATE(dim)                          \
  template void Assembler<dim>::add_neumann(                \
    const typename DoFHandler<dim>::active_cell_iterator &, \
    const TrilinosWrappers::MPI::Vector &,                  \
    FEFaceValues<dim> &,                                    \
    Vector<double> &,                                       \
    FullMatrix<double> *) const;                            \
  template void Assembler<dim>::add_follower_pressure(      \
    const FEFaceValues<dim> &,                              \
    const unsigned int,                                     \
    const double,                                           \
    const Tensor<2, 3> &,                                   \
    const double,                                           \
    Vector<double> &,                                       \
    FullMatrix<double> *) const;
    SIGNORINI_INSTANTIATE(2)
    SIGNORINI_INSTANTIATE(3)
#undef SIGNORINI_INSTANTIATE
  } // namespace Bulk
} // namespace Signorini
