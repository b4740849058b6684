// The shapes of the bodies (shapes.cc) and the helpers the scene shares
// with them: names and points of a body's entries, its boundary ids.
// Private to source/geometry/.
#ifndef signorini_source_geometry_shapes_h
#define signorini_source_geometry_shapes_h

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <signorini/base/errors.h>
#include <signorini/base/parameters.h>

#include <string>
#include <vector>

namespace Signorini
{
  namespace Geometry
  {
    namespace internal
    {
      using namespace dealii;

      // The subsection of body @p b, for messages.
      inline std::string
      body_name(const unsigned int b)
      {
        return "subsection 'Geometry/Body " + std::to_string(b + 1) + "'";
      }

      // The first dim numbers of entry @p entry of body @p b.
      template <int dim>
      inline Point<dim>
      point_of(const std::vector<double> &v,
               const unsigned int         b,
               const std::string         &entry)
      {
        // Entries default to 3 numbers; use the first dim of them.
        if (v.size() < dim)
          throw InputError(body_name(b) + ", parameter '" + entry + "': give " +
                           std::to_string(dim) + " coordinates.");
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = v[d];
        return p;
      }

      // The user-visible id of face group @p local of body @p b: 10 (b + 1)
      // + local, or the body's 'Boundary ids' entry.
      inline types::boundary_id
      boundary_id_of(const BodyParameters &body,
                     const unsigned int    b,
                     const unsigned int    local)
      {
        return body.boundary_ids.empty() ? 10 * (b + 1) + local :
                                           body.boundary_ids[local];
      }

      // Number of face groups of a ball segment (see make_ball_segment).
      inline unsigned int
      n_segment_faces(const Segment segment, const unsigned int dim)
      {
        return segment == Segment::full ? 1 :
               segment == Segment::half ? 2 :
                                          (dim == 2 ? 3 : 4);
      }

      // The local face group of the inner curved face of a hollow segment:
      // after the flat faces of a ball segment, after the end caps of a 3D
      // cylinder segment; numbers::invalid_unsigned_int for a solid one.
      inline unsigned int
      inner_face_group(const BodyParameters &body, const unsigned int dim)
      {
        if (body.inner_radius == 0)
          return numbers::invalid_unsigned_int;
        return (dim == 3 && body.shape == BodyShape::cylinder_segment) ?
                 5 :
                 n_segment_faces(body.segment, dim);
      }

      /** A block ('Lower corner', 'Upper corner', 'Subdivisions'): faces
       * x-, x+, y-, y+(, z-, z+). */
      template <int dim>
      void
      build_block(const BodyParameters &body,
                  const unsigned int    b,
                  const Point<dim>     &shift,
                  Triangulation<dim>   &tria);

      /** A ball segment, or in 3D a cylinder segment (the disc segment
       * extruded along z over 'Length'), solid or hollow, about 'Centre'. */
      template <int dim>
      void
      build_segment(const BodyParameters &body,
                    const unsigned int    b,
                    const Point<dim>     &shift,
                    Triangulation<dim>   &tria);

      /** A Gmsh or Abaqus 'Mesh file' (relative to @p input_directory),
       * its cells checked, its ids renamed by 'Boundary id map'. */
      template <int dim>
      void
      build_from_file(const BodyParameters &body,
                      const unsigned int    b,
                      const std::string    &input_directory,
                      const Point<dim>     &shift,
                      Triangulation<dim>   &tria);
    } // namespace internal
  }   // namespace Geometry
} // namespace Signorini

#endif
