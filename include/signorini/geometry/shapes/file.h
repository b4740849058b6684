#ifndef signorini_geometry_shapes_file_h
#define signorini_geometry_shapes_file_h

#include <signorini/geometry/shapes/interface.h>

#include <map>

namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      /**
       * A Gmsh (.msh) or Abaqus (.inp) 'Mesh file' read by deal.II's
       * GridIn: its cells are checked (first-order quadrilaterals or
       * hexahedra, none inverted or tangled), its boundary ids renamed by
       * 'Boundary id map', its material ids kept. Faces on a sphere or
       * cylinder can be given their exact surface ('Manifold').
       * Parameters: subsection 'File'.
       */
      template <int dim>
      class MeshFile : public Interface<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm);

        void
        parse_parameters(ParameterHandler  &prm,
                         const std::string &input_directory) override;

        void
        build(Triangulation<dim> &tria) const override;

        unsigned int
        n_face_groups() const override;

        CurvedSurface<dim>
        curved_surface(const Triangulation<dim> &tria,
                       const Placement<dim>     &placement) const override;

      private:
        /** Reads the file into @p tria (GridIn), its cell types checked on
         * the text first. */
        void
        read(Triangulation<dim> &tria) const;

        std::string                          name; // as given
        std::string                          path; // to open
        std::map<unsigned int, unsigned int> id_map;
        std::string                          manifold; // none|sphere|cylinder
        std::vector<types::boundary_id>      manifold_ids;
        Point<dim>                           manifold_centre;
        Tensor<1, dim>                       manifold_axis;
      };
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini

#endif
