// The postprocessor 'visualization': the VTU files of each written load
// step (one piece per rank, a PVTU record, and solution.pvd listing the
// steps) with the displacement, the stress, material and rank of each
// cell and, with contact, the contact fields at the slave nodes.
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/output_files.h>
#include <signorini/postprocess/stress_postprocessor.h>

#include <algorithm>
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
        directory = parameters.output.directory + "/";
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

      void
      write(const DataOut<dim> &data_out, const StepData<dim> &data);

      std::string                                 directory;
      std::vector<std::pair<double, std::string>> records; // (time, pvtu)
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
      write(data_out, data);
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


    // The names of DataOut::write_vtu_with_pvtu_record(), which writes in
    // place and leaves a truncated file behind a kill or a full disk: here
    // every file goes through a temporary name, each rank's piece first,
    // then (rank 0, once every piece is in place) the step's PVTU record,
    // then the PVD list, which so names complete steps only.
    template <int dim>
    void
    Visualization<dim>::write(const DataOut<dim>  &data_out,
                              const StepData<dim> &data)
    {
      const MPI_Comm     comm    = data.mpi_communicator;
      const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int digits =
        Utilities::needed_digits(std::max(0, static_cast<int>(n_ranks) - 1));
      const std::string stem =
        "solution_" + Utilities::int_to_string(data.step, 4);
      const auto piece = [&](const unsigned int r) {
        return stem + "." + Utilities::int_to_string(r, digits) + ".vtu";
      };
      check_written(write_atomically(directory + piece(rank),
                                     [&](std::ostream &out) {
                                       data_out.write_vtu(out);
                                     }),
                    data.parameters.output.directory,
                    comm);
      std::string failure;
      if (rank == 0)
        {
          std::vector<std::string> pieces;
          for (unsigned int r = 0; r < n_ranks; ++r)
            pieces.push_back(piece(r));
          failure = write_atomically(directory + stem + ".pvtu",
                                     [&](std::ostream &out) {
                                       data_out.write_pvtu_record(out, pieces);
                                     });
          if (failure.empty())
            {
              records.emplace_back(data.time, stem + ".pvtu");
              failure =
                write_atomically(directory + "solution.pvd",
                                 [&](std::ostream &out) {
                                   DataOutBase::write_pvd_record(out, records);
                                 });
            }
        }
      check_written(failure, data.parameters.output.directory, comm);
    }
  } // namespace Postprocess
} // namespace Signorini

SIGNORINI_REGISTER_POSTPROCESSOR(
  Signorini::Postprocess::Visualization,
  "visualization",
  "the VTU files of each written load step (solution_NNNN.pvtu, listed in "
  "solution.pvd): displacement, stress, material id, rank and, with "
  "contact, the contact fields at the slave nodes")
