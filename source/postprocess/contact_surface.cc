// The postprocessor 'contact surface': the contact fields on the slave
// surfaces themselves (deal.II's DataOutFaces restricted to the slave
// faces), one VTU series, so that a viewer shows the contact patch of a 3D
// scene as a surface: pressure, tangential traction, gap, slip and status
// at the slave nodes, the displacement (to draw the deformed surface) and
// the pair of each face.
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out_faces.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/vtu_series.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace Signorini
{
  namespace Postprocess
  {
    namespace
    {
      /** DataOutFaces over a given list of faces (this rank's slave faces). */
      template <int dim>
      class FaceListOutput : public DataOutFaces<dim>
      {
      public:
        using FaceDescriptor = typename DataOutFaces<dim>::FaceDescriptor;

        explicit FaceListOutput(std::vector<FaceDescriptor> faces)
            : DataOutFaces<dim>(false)
            , faces(std::move(faces))
        {
        }

        FaceDescriptor
        first_face() override
        {
          next = 0;
          return advance();
        }

        FaceDescriptor
        next_face(const FaceDescriptor &) override
        {
          return advance();
        }

      private:
        // The faces in list order; past the end, the end iterator.
        FaceDescriptor
        advance()
        {
          if (next < faces.size())
            return faces[next++];
          return FaceDescriptor(this->triangulation->end(), 0);
        }

        std::vector<FaceDescriptor> faces;
        std::size_t                 next = 0;
      };
    } // namespace


    template <int dim>
    class ContactSurface : public Interface<dim>
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
        series = std::make_unique<VtuSeries>(parameters.output.directory,
                                             "contact_surface");
      }

      std::vector<CheckResult>
      execute(const StepData<dim> &data) override;

    private:
      std::unique_ptr<VtuSeries> series;
    };


    template <int dim>
    std::vector<CheckResult>
    ContactSurface<dim>::execute(const StepData<dim> &data)
    {
      if (data.contact == nullptr)
        return {};
      const auto &triangulation = data.dof_handler.get_triangulation();
      const auto &faces = data.contact->contact_surfaces().slave_faces();
      std::vector<typename FaceListOutput<dim>::FaceDescriptor> list;
      // The pair of each face as cell data (of its cell: a cell with faces
      // of two pairs shows the later one).
      Vector<float> pair(triangulation.n_active_cells());
      for (const auto &face : faces)
        {
          list.emplace_back(face.cell, face.face);
          pair(face.cell->active_cell_index()) = face.pair + 1;
        }
      FaceListOutput<dim> data_out(std::move(list));
      data_out.attach_dof_handler(data.dof_handler);
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
        vector(dim, DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(data.displacement,
                               std::vector<std::string>(dim, "displacement"),
                               DataOutFaces<dim>::type_dof_data,
                               vector);
      const auto     &fe = data.dof_handler.get_fe();
      DoFHandler<dim> scalar_dofs(triangulation);
      scalar_dofs.distribute_dofs(fe.base_element(0));
      const auto fields =
        data.contact->contact_output().nodal_fields(scalar_dofs);
      for (const auto &[name, field] : fields)
        data_out.add_data_vector(scalar_dofs, field, name);
      data_out.add_data_vector(pair, "pair", DataOutFaces<dim>::type_cell_data);
      data_out.build_patches(data.mapping, fe.degree);
      series->write(data_out, data.step, data.time, data.mpi_communicator);
      return {};
    }
  } // namespace Postprocess
} // namespace Signorini

SIGNORINI_REGISTER_POSTPROCESSOR(
  Signorini::Postprocess::ContactSurface,
  "contact surface",
  "with contact, the VTU files of the slave surfaces of each written load "
  "step (contact_surface_NNNN.pvtu, listed in contact_surface.pvd): "
  "contact_pressure, tangential_traction_k, gap, slip_k and status (0 "
  "open, 1 stick, 2 slip or closed without friction; averaged where faces "
  "of different status meet) at the slave nodes, the displacement and the "
  "pair of each face, on the reference surface")
