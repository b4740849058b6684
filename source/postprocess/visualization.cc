// The postprocessor 'visualization': the VTU files of each written load
// step (one piece per rank, a PVTU record, and solution.pvd listing the
// steps) with the displacement, the stress, material and rank of each
// cell and, with contact, the contact fields at the slave nodes (on the
// volume mesh; the postprocessor 'contact surface' writes them on the
// slave surface itself).
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/stress_postprocessor.h>
#include <signorini/postprocess/vtu_series.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace Signorini
{
  namespace Postprocess
  {
    template <int dim>
    class Visualization : public Interface<dim>
    {
    public:
      // The directory is 'Output/Directory'; nothing of its own.
      static void
      declare_parameters(ParameterHandler &)
      {
      }

      void
      parse_parameters(const Parameters &parameters,
                       ParameterHandler &) override
      {
        series =
          std::make_unique<VtuSeries>(parameters.output.directory, "solution");
      }

      std::vector<CheckResult>
      execute(const StepData<dim> &data) override;

    private:
      void
      add_cell_data(const StepData<dim> &data,
                    DataOut<dim>        &data_out,
                    Vector<float>       &material_id,
                    Vector<float>       &subdomain) const;

      void
      add_history_data(const StepData<dim>        &data,
                       DataOut<dim>               &data_out,
                       std::vector<Vector<float>> &fields) const;

      std::unique_ptr<VtuSeries> series;
    };


    template <int dim>
    std::vector<CheckResult>
    Visualization<dim>::execute(const StepData<dim> &data)
    {
      const auto  &fe = data.dof_handler.get_fe();
      DataOut<dim> data_out;
      data_out.attach_dof_handler(data.dof_handler);
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
        vector(dim, DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(data.displacement,
                               std::vector<std::string>(dim, "displacement"),
                               DataOut<dim>::type_dof_data,
                               vector);
      const StressPostprocessor<dim> stress(
        data.mapping,
        data.materials,
        data.history,
        data.parameters.axisymmetric,
        data.parameters.projected_volumetric_strain ? &fe : nullptr,
        &data.displacement);
      data_out.add_data_vector(data.displacement, stress);
      const auto   &triangulation = data.dof_handler.get_triangulation();
      Vector<float> material_id(triangulation.n_active_cells());
      Vector<float> subdomain(triangulation.n_active_cells());
      add_cell_data(data, data_out, material_id, subdomain);
      std::vector<Vector<float>> history_fields;
      add_history_data(data, data_out, history_fields);
      // Contact fields at the slave nodes (zero elsewhere), on a scalar
      // DoFHandler of the displacement's base element.
      DoFHandler<dim> scalar_dofs(triangulation);
      std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector>> fields;
      if (data.contact)
        {
          scalar_dofs.distribute_dofs(fe.base_element(0));
          fields = data.contact->contact_output().nodal_fields(scalar_dofs);
          for (const auto &[name, field] : fields)
            data_out.add_data_vector(scalar_dofs, field, name);
        }
      data_out.build_patches(data.mapping, fe.degree);
      series->write(data_out, data.step, data.time, data.mpi_communicator);
      return {};
    }


    template <int dim>
    void
    Visualization<dim>::add_cell_data(const StepData<dim> &data,
                                      DataOut<dim>        &data_out,
                                      Vector<float>       &material_id,
                                      Vector<float>       &subdomain) const
    {
      for (const auto &cell : data.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            material_id(cell->active_cell_index()) = cell->material_id();
            subdomain(cell->active_cell_index())   = cell->subdomain_id();
          }
      data_out.add_data_vector(material_id, "material_id");
      data_out.add_data_vector(subdomain, "subdomain");
    }


    // The materials' history quantities (history_output_names()) as cell
    // data: each the mean over the cell's bulk quadrature points (with the
    // rule's weights), 0 in cells whose material lacks it. @p fields keeps
    // the vectors until the patches are built.
    template <int dim>
    void
    Visualization<dim>::add_history_data(
      const StepData<dim>        &data,
      DataOut<dim>               &data_out,
      std::vector<Vector<float>> &fields) const
    {
      std::vector<std::string> names;
      for (const auto &[id, material] : data.materials)
        for (const auto &name : material->history_output_names())
          if (std::find(names.begin(), names.end(), name) == names.end())
            names.push_back(name);
      const auto &rule = data.history.quadrature();
      fields.assign(names.size(),
                    Vector<float>(
                      data.dof_handler.get_triangulation().n_active_cells()));
      for (const auto &cell : data.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto &material = *data.materials.at(cell->material_id());
            const auto  own      = material.history_output_names();
            if (own.empty())
              continue;
            const auto history =
              data.history.on_cell(cell, material.n_history_values());
            for (unsigned int q = 0; q < rule.size(); ++q)
              {
                const auto values = material.history_output(history[q]);
                for (unsigned int k = 0; k < own.size(); ++k)
                  {
                    const auto f =
                      std::find(names.begin(), names.end(), own[k]) -
                      names.begin();
                    fields[f](cell->active_cell_index()) +=
                      values[k] * rule.weight(q);
                  }
              }
          }
      for (unsigned int f = 0; f < names.size(); ++f)
        data_out.add_data_vector(fields[f], names[f]);
    }


  } // namespace Postprocess
} // namespace Signorini

SIGNORINI_REGISTER_POSTPROCESSOR(
  Signorini::Postprocess::Visualization,
  "visualization",
  "the VTU files of each written load step (solution_NNNN.pvtu, listed in "
  "solution.pvd): displacement, stress, material id, rank and, with "
  "contact, the contact fields at the slave nodes")
