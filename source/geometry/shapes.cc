// The shapes a body can have ('Geometry/Body k/Shape'): each builds its
// coarse mesh with the faces' user-visible boundary ids, shifted by
// 'Shift' (the scene rotates it and sets its material afterwards).
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <signorini/base/input_checks.h>
#include <signorini/geometry/mesh_checks.h>

#include "shapes.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace Signorini
{
  namespace Geometry
  {
    namespace internal
    {
      namespace
      {
        // Gives the faces of a generated shape their user-visible ids.
        template <int dim>
        void
        assign_boundary_ids(Triangulation<dim>   &tria,
                            const BodyParameters &body,
                            const unsigned int    b,
                            const unsigned int    n_faces)
        {
          if (!body.boundary_ids.empty() && body.boundary_ids.size() < n_faces)
            throw InputError(body_name(b) +
                             ", parameter 'Boundary ids': this "
                             "shape has " +
                             std::to_string(n_faces) + " face groups, give " +
                             std::to_string(n_faces) +
                             " ids (or leave it empty).");
          for (const auto &face : tria.active_face_iterators())
            if (face->at_boundary())
              {
                face->set_boundary_id(
                  boundary_id_of(body, b, face->boundary_id()));
              }
        }


        // deal.II's disc/ball or shell segment: halves cut at x = 0 (kept
        // x > 0), quarters in the positive quadrant/octant, centred at 0.
        template <int dim>
        void
        make_deal_ii_segment(Triangulation<dim> &tria,
                             const Segment       segment,
                             const double        radius,
                             const double        inner_radius)
        {
          const Point<dim> o;
          if (inner_radius == 0)
            {
              if (segment == Segment::full)
                GridGenerator::hyper_ball(tria, o, radius);
              else if (segment == Segment::half)
                GridGenerator::half_hyper_ball(tria, o, radius);
              else
                GridGenerator::quarter_hyper_ball(tria, o, radius);
            }
          else if (segment == Segment::full)
            GridGenerator::hyper_shell(tria, o, inner_radius, radius);
          else if (segment == Segment::half)
            GridGenerator::half_hyper_shell(tria, o, inner_radius, radius);
          else
            GridGenerator::quarter_hyper_shell(tria, o, inner_radius, radius);
        }

        // Disc (2D) or ball (3D) segment, solid or hollow, with the curved
        // side below the centre: deal.II's segment turned by -90 degrees about
        // z (+x becomes -y). Face groups: 0 the outer curved face, 1 the top
        // (y = centre), 2 the symmetry plane x = centre, 3 the symmetry plane
        // z = centre, then @p inner_id the inner curved face of a shell.
        template <int dim>
        void
        make_ball_segment(Triangulation<dim>   &tria,
                          const BodyParameters &body,
                          const unsigned int    inner_id)
        {
          make_deal_ii_segment(tria,
                               body.segment,
                               body.radius,
                               body.inner_radius);
          if constexpr (dim == 2)
            GridTools::rotate(-numbers::PI / 2, tria);
          else
            GridTools::rotate(Tensor<1, 3>({0., 0., 1.}),
                              -numbers::PI / 2,
                              tria);
          const double tol = 1e-10 * body.radius;
          // On the sphere of radius r: every vertex of the face is.
          const auto on_sphere = [tol](const auto &face, const double r) {
            for (const auto v : face->vertex_indices())
              if (std::abs(face->vertex(v).norm() - r) > tol)
                return false;
            return true;
          };
          for (const auto &face : tria.active_face_iterators())
            if (face->at_boundary())
              {
                const Point<dim> c = face->center();
                if (on_sphere(face, body.radius))
                  face->set_boundary_id(0);
                else if (body.inner_radius > 0 &&
                         on_sphere(face, body.inner_radius))
                  face->set_boundary_id(inner_id);
                else if (std::abs(c[1]) < tol)
                  face->set_boundary_id(1);
                else if (std::abs(c[0]) < tol)
                  face->set_boundary_id(2);
                else if (dim == 3 && std::abs(c[dim - 1]) < tol)
                  face->set_boundary_id(3);
              }
        }
      } // namespace


      template <int dim>
      void
      build_block(const BodyParameters &body,
                  const unsigned int    b,
                  const Point<dim>     &shift,
                  Triangulation<dim>   &tria)
      {
        if (body.subdivisions.size() < dim)
          throw InputError(body_name(b) + ", parameter 'Subdivisions': give " +
                           std::to_string(dim) + " numbers.");
        const Point<dim> p1 =
          point_of<dim>(body.lower_corner, b, "Lower corner");
        const Point<dim> p2 =
          point_of<dim>(body.upper_corner, b, "Upper corner");
        for (unsigned int d = 0; d < dim; ++d)
          if (!(p2[d] > p1[d]))
            throw InputError(body_name(b) +
                             ": 'Upper corner' must exceed 'Lower "
                             "corner' in every coordinate.");
        std::vector<unsigned int> reps(body.subdivisions.begin(),
                                       body.subdivisions.begin() + dim);
        GridGenerator::subdivided_hyper_rectangle(
          tria, reps, p1 + shift, p2 + shift, true);
        assign_boundary_ids(tria, body, b, 2 * dim);
      }


      template <int dim>
      void
      build_segment(const BodyParameters &body,
                    const unsigned int    b,
                    const Point<dim>     &shift,
                    Triangulation<dim>   &tria)
      {
        if (body.inner_radius >= body.radius)
          throw InputError(body_name(b) +
                           ", parameter 'Inner radius': it must be "
                           "below 'Radius' (0 for a solid body).");
        const Point<dim> centre =
          point_of<dim>(body.centre, b, "Centre") + shift;
        if (dim == 2 || body.shape == BodyShape::ball_segment)
          {
            make_ball_segment(tria, body, inner_face_group(body, dim));
            GridTools::shift(centre, tria);
            assign_boundary_ids(tria,
                                body,
                                b,
                                n_segment_faces(body.segment, dim) +
                                  (body.inner_radius > 0));
          }
        else
          {
            Triangulation<2> disc;
            make_ball_segment(disc, body, inner_face_group(body, 3));
            // Side walls keep 0/1/2 (and 5 inside a tube); put the
            // end caps on 3 and 4.
            const unsigned int n_layers =
              body.subdivisions.empty() ? 1 : body.subdivisions[0];
            Triangulation<3> cylinder;
            GridGenerator::extrude_triangulation(disc,
                                                 n_layers + 1,
                                                 body.length,
                                                 cylinder);
            for (const auto &face : cylinder.active_face_iterators())
              if (face->at_boundary())
                {
                  const double z = face->center()[2];
                  if (std::abs(z) < 1e-12 * body.length)
                    face->set_boundary_id(3);
                  else if (std::abs(z - body.length) < 1e-12 * body.length)
                    face->set_boundary_id(4);
                }
            if constexpr (dim == 3)
              {
                tria.copy_triangulation(cylinder);
                GridTools::shift(centre, tria);
              }
            assign_boundary_ids(tria, body, b, body.inner_radius > 0 ? 6 : 5);
          }
      }


      template <int dim>
      void
      build_from_file(const BodyParameters &body,
                      const unsigned int    b,
                      const std::string    &input_directory,
                      const Point<dim>     &shift,
                      Triangulation<dim>   &tria)
      {
        std::string name = body.mesh_file;
        if (name[0] != '/')
          name = input_directory + "/" + name;
        std::ifstream in(name);
        if (!in || std::filesystem::is_directory(name))
          throw InputError(body_name(b) +
                           ", parameter 'Mesh file': cannot open '" + name +
                           "'. Give an existing .msh or .inp file "
                           "(relative paths start at the parameter "
                           "file's directory).");
        const std::string ext = name.substr(name.find_last_of('.') + 1);
        if (ext != "msh" && ext != "inp")
          throw InputError(body_name(b) +
                           ", parameter 'Mesh file': unknown "
                           "extension '." +
                           ext + "'; use .msh or .inp.");
        // Cell types are checked on the text first: GridIn reads
        // triangles and tetrahedra into cells the element loops
        // cannot use, and refuses others with a list that does not
        // say what to do.
        std::stringstream buffer;
        buffer << in.rdbuf();
        const std::string where =
          body_name(b) + ", parameter 'Mesh file' (" + body.mesh_file + ")";
        check_mesh_file_cells(buffer.str(), ext, dim, where);
        std::istringstream text(buffer.str());
        GridIn<dim>        grid_in;
        grid_in.attach_triangulation(tria);
        {
          // The Abaqus reader prints its inner exception (with a
          // stack trace) before it throws: kept for the message.
          CerrCapture diagnostics;
          try
            {
              if (ext == "msh")
                grid_in.read_msh(text);
              else
                grid_in.read_abaqus(text);
            }
          catch (const ExceptionBase &e)
            {
              std::ostringstream info;
              e.print_info(info);
              // What GridIn quotes of the file is left out: a
              // 'Mesh file' may be a link to any file.
              const std::regex  quoted("<[^<>\n]*>");
              const std::string text =
                std::regex_replace(info.str(), quoted, "(a line of the file)");
              const std::string more =
                std::regex_replace(grid_in_diagnostics(diagnostics.text()),
                                   quoted,
                                   "(a line of the file)");
              throw InputError(body_name(b) +
                               ", parameter 'Mesh file': GridIn could "
                               "not read '" +
                               name + "': " + text +
                               (more.empty() ? "" : " (" + more + ")"));
            }
        }
        check_reference_cells(tria, where);
        for (const auto &face : tria.active_face_iterators())
          if (face->at_boundary())
            {
              const auto it = body.boundary_id_map.find(face->boundary_id());
              if (it != body.boundary_id_map.end())
                face->set_boundary_id(it->second);
            }
        GridTools::shift(shift, tria);
      }


      template void
      build_block<2>(const BodyParameters &,
                     const unsigned int,
                     const Point<2> &,
                     Triangulation<2> &);
      template void
      build_block<3>(const BodyParameters &,
                     const unsigned int,
                     const Point<3> &,
                     Triangulation<3> &);
      template void
      build_segment<2>(const BodyParameters &,
                       const unsigned int,
                       const Point<2> &,
                       Triangulation<2> &);
      template void
      build_segment<3>(const BodyParameters &,
                       const unsigned int,
                       const Point<3> &,
                       Triangulation<3> &);
      template void
      build_from_file<2>(const BodyParameters &,
                         const unsigned int,
                         const std::string &,
                         const Point<2> &,
                         Triangulation<2> &);
      template void
      build_from_file<3>(const BodyParameters &,
                         const unsigned int,
                         const std::string &,
                         const Point<3> &,
                         Triangulation<3> &);
    } // namespace internal
  }   // namespace Geometry
} // namespace Signorini
