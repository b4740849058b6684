// The shape 'block' (shapes/block.h).
#include <deal.II/grid/grid_generator.h>

#include <signorini/base/parameter_helpers.h>
#include <signorini/geometry/shapes/block.h>

namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      template <int dim>
      void
      Block<dim>::declare_parameters(ParameterHandler &prm)
      {
        prm.enter_subsection("Block");
        prm.declare_entry("Lower corner",
                          "0, 0, 0",
                          internal::point_pattern(),
                          "Lower corner [m]; the first Dimension numbers are "
                          "used.");
        prm.declare_entry("Upper corner",
                          "1, 1, 1",
                          internal::point_pattern(),
                          "Upper corner [m]; the first Dimension numbers are "
                          "used.");
        prm.declare_entry(
          "Subdivisions",
          "1, 1, 1",
          Patterns::List(Patterns::Integer(1, 10000), 1, 3, ","),
          "Number of cells per coordinate direction [-]; the "
          "first Dimension numbers are used.");
        prm.leave_subsection();
      }


      template <int dim>
      void
      Block<dim>::parse_parameters(ParameterHandler &prm, const std::string &)
      {
        prm.enter_subsection("Block");
        try
          {
            lower        = internal::parse_point<dim>(prm, "Lower corner");
            upper        = internal::parse_point<dim>(prm, "Upper corner");
            subdivisions = internal::to_unsigned(prm.get("Subdivisions"));
          }
        catch (...)
          {
            prm.leave_subsection();
            throw;
          }
        prm.leave_subsection();
        if (subdivisions.size() < dim)
          throw InputError("parameter 'Subdivisions': give " +
                           std::to_string(dim) + " numbers.");
        subdivisions.resize(dim);
        for (unsigned int d = 0; d < dim; ++d)
          if (!(upper[d] > lower[d]))
            throw InputError("parameter 'Upper corner': it must exceed "
                             "'Lower corner' in every coordinate.");
      }


      template <int dim>
      double
      Block<dim>::n_cells(std::string &entry) const
      {
        entry        = "Subdivisions";
        double cells = 1;
        for (const unsigned int n : subdivisions)
          cells *= n;
        return cells;
      }


      template <int dim>
      void
      Block<dim>::build(Triangulation<dim> &tria) const
      {
        // colorize: the faces x-, x+, y-, y+ (, z-, z+) get ids 0 .. 2 dim - 1.
        GridGenerator::subdivided_hyper_rectangle(
          tria, subdivisions, lower, upper, true);
      }


      template <int dim>
      unsigned int
      Block<dim>::n_face_groups() const
      {
        return 2 * dim;
      }

      template class Block<2>;
      template class Block<3>;
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini

SIGNORINI_REGISTER_SHAPE(
  Signorini::Geometry::Shapes::Block,
  "block",
  "rectangle (2D) or box (3D) between 'Lower corner' and 'Upper corner' "
  "with 'Subdivisions' cells per direction; face groups 0..3 (2D: x-, x+, "
  "y-, y+) or 0..5 (3D: x-, x+, y-, y+, z-, z+)")
