#ifndef signorini_geometry_shapes_block_h
#define signorini_geometry_shapes_block_h

#include <signorini/geometry/shapes/interface.h>

namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      /**
       * A rectangle (2D) or box (3D) between 'Lower corner' and 'Upper
       * corner' with 'Subdivisions' cells per direction. Face groups: 0 x-,
       * 1 x+, 2 y-, 3 y+ (3D: 4 z-, 5 z+). Parameters: subsection 'Block'.
       */
      template <int dim>
      class Block : public Interface<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm);

        void
        parse_parameters(ParameterHandler  &prm,
                         const std::string &input_directory) override;

        double
        n_cells(std::string &entry) const override;

        void
        build(Triangulation<dim> &tria) const override;

        unsigned int
        n_face_groups() const override;

      private:
        Point<dim>                lower, upper;
        std::vector<unsigned int> subdivisions;
      };
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini

#endif
