#ifndef signorini_postprocess_stress_postprocessor_h
#define signorini_postprocess_stress_postprocessor_h

#include <deal.II/numerics/data_postprocessor.h>

#include <signorini/material/elastic_material.h>

#include <map>

/**
 * Cauchy stress components [Pa] and the von Mises stress for DataOut, from
 * the displacement gradient and the material of each cell (by material id).
 * In 2D (plane strain) stress_zz is written too.
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
      /** @p axisymmetric: 2D meridian section, x = r (hoop strain u_r/r). */
      StressPostprocessor(
        const std::map<types::material_id, Material::ElasticMaterial<dim>>
          &        materials,
        const bool axisymmetric = false)
        : materials(materials)
        , axisymmetric(axisymmetric)
      {}

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names;
        const char *axis[] = {"x", "y", "z"};
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
        return axisymmetric ?
                 update_gradients | update_values | update_quadrature_points :
                 update_gradients;
      }

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<dim> &inputs,
        std::vector<Vector<double>> &computed) const override
      {
        const auto  cell = inputs.template get_cell<dim>();
        const auto &material = materials.at(cell->material_id());
        for (unsigned int q = 0; q < computed.size(); ++q)
          {
            SymmetricTensor<2, dim> strain;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = i; j < dim; ++j)
                strain[i][j] = 0.5 * (inputs.solution_gradients[q][i][j] +
                                      inputs.solution_gradients[q][j][i]);
            // Hoop strain u_r / r; on the axis its limit du_r/dr.
            const double r    = inputs.evaluation_points.empty() ?
                                  0. :
                                  inputs.evaluation_points[q][0];
            const double hoop = !axisymmetric ? 0. :
                                r > 0 ? inputs.solution_values[q][0] / r :
                                        inputs.solution_gradients[q][0][0];
            const SymmetricTensor<2, dim> stress =
              material.stress(strain, hoop);
            unsigned int                  k      = 0;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = i; j < dim; ++j)
                computed[q][k++] = stress[i][j];
            if (dim == 2)
              computed[q][k++] = material.stress_33(strain, hoop);
            computed[q][k] = material.von_mises(strain, hoop);
          }
      }

    private:
      const std::map<types::material_id, Material::ElasticMaterial<dim>>
        &        materials;
      const bool axisymmetric;
    };
  } // namespace Postprocess
} // namespace Signorini

#endif
