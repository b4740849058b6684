#ifndef signorini_postprocess_stress_postprocessor_h
#define signorini_postprocess_stress_postprocessor_h

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/numerics/data_postprocessor.h>

#include <signorini/bulk/assembler.h>
#include <signorini/material/projected_volumetric_strain.h>

#include <map>

/**
 * Cauchy stress components [Pa] and the von Mises stress for DataOut, from
 * the displacement gradient and the material of each cell (by material id;
 * Material::Interface::cauchy_stress(), at finite strain tau / J, plotted
 * at the reference position of the point).
 * In 2D the stress normal to the plane is written too (stress_zz, or
 * stress_hoop axisymmetric). The strain is that of the equilibrium
 * (with the projection its volumetric part is theta_bar: B-bar, F-bar).
 * A model with history evaluates with the committed history of the bulk
 * quadrature point nearest to the output point.
 */
namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    template <int dim>
    class StressPostprocessor : public DataPostprocessor<dim>
    {
    public:
      /** @p axisymmetric: 2D meridian section, x = r (hoop strain u_r/r).
       * @p projected (the displacement element, with the ghosted
       * @p solution that DataOut writes): the volumetric strain projected
       * per cell (B-bar). */
      StressPostprocessor(
        const Mapping<dim>                  &mapping,
        const Bulk::Materials<dim>          &materials,
        const Material::History<dim>        &history,
        const bool                           axisymmetric = false,
        const FiniteElement<dim>            *projected    = nullptr,
        const TrilinosWrappers::MPI::Vector *solution     = nullptr)
          : mapping(mapping)
          , materials(materials)
          , history(history)
          , axisymmetric(axisymmetric)
          , projected(projected)
          , solution(solution)
      {
        Assert(!projected || solution, ExcInternalError());
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names;
        const char              *axis[] = {"x", "y", "z"};
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            names.push_back(std::string("stress_") + axis[i] + axis[j]);
        if (dim == 2)
          names.push_back(axisymmetric ? "stress_hoop" : "stress_zz");
        names.push_back("von_mises");
        return names;
      }

      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override
      {
        return std::vector<
          DataComponentInterpretation::DataComponentInterpretation>(
          get_names().size(), DataComponentInterpretation::component_is_scalar);
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return axisymmetric || projected || history.active() ?
                 update_gradients | update_values | update_quadrature_points :
                 update_gradients;
      }

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<dim> &inputs,
        std::vector<Vector<double>>                &computed) const override
      {
        const auto          cell     = inputs.template get_cell<dim>();
        const auto         &material = *materials.at(cell->material_id());
        std::vector<double> volumetric(computed.size());
        if (projected)
          {
            const QGauss<dim> quadrature(projected->degree + 1);
            FEValues<dim>     fe_values(mapping,
                                    *projected,
                                    quadrature,
                                    update_values | update_gradients |
                                      update_quadrature_points |
                                      update_JxW_values);
            fe_values.reinit(cell);
            Material::ProjectedVolumetricStrain<dim> projection(*projected,
                                                                quadrature,
                                                                axisymmetric);
            Vector<double> local_u(projected->n_dofs_per_cell()), theta_bar;
            if (material.kinematics() == Material::Kinematics::finite_strain)
              Material::projected_log_J(
                projection, fe_values, *solution, axisymmetric, theta_bar);
            else
              {
                projection.reinit(fe_values);
                cell->get_dof_values(*solution, local_u);
                projection.coefficients(local_u, theta_bar);
              }
            for (unsigned int q = 0; q < computed.size(); ++q)
              volumetric[q] =
                projection.value(theta_bar,
                                 mapping.transform_real_to_unit_cell(
                                   cell, inputs.evaluation_points[q]));
          }
        for (unsigned int q = 0; q < computed.size(); ++q)
          {
            Tensor<2, dim> grad;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                grad[i][j] = inputs.solution_gradients[q][i][j];
            // Hoop strain u_r / r; on the axis its limit du_r/dr.
            const double                r = inputs.evaluation_points.empty() ?
                                              0. :
                                              inputs.evaluation_points[q][0];
            const double                hoop      = !axisymmetric ? 0. :
                                                    r > 0 ? inputs.solution_values[q][0] / r :
                                                            inputs.solution_gradients[q][0][0];
            const unsigned int          n_history = material.n_history_values();
            const SymmetricTensor<2, 3> stress    = material.cauchy_stress(
              Material::to_3d<dim>(grad, hoop),
              n_history == 0 ?
                   ArrayView<const double>() :
                   history.at(cell,
                           history.nearest_point(
                             mapping.transform_real_to_unit_cell(
                               cell, inputs.evaluation_points[q])),
                           n_history),
              projected ? &volumetric[q] : nullptr);
            unsigned int k = 0;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = i; j < dim; ++j)
                computed[q][k++] = stress[i][j];
            if (dim == 2)
              computed[q][k++] = stress[2][2];
            computed[q][k] = Material::von_mises(stress);
          }
      }

    private:
      const Mapping<dim>                  &mapping;
      const Bulk::Materials<dim>          &materials;
      const Material::History<dim>        &history;
      const bool                           axisymmetric;
      const FiniteElement<dim>            *projected;
      const TrilinosWrappers::MPI::Vector *solution;
    };
  } // namespace Postprocess
} // namespace Signorini

#endif
