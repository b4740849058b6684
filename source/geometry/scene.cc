#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/physics/transformations.h>

#include <signorini/base/input_checks.h>
#include <signorini/geometry/mesh_checks.h>
#include <signorini/geometry/scene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>
#include <set>
#include <sstream>

namespace Signorini
{
  namespace Geometry
  {
    namespace
    {
      std::string
      body_name(const unsigned int b)
      {
        return "subsection 'Geometry/Body " + std::to_string(b + 1) + "'";
      }

      template <int dim>
      Point<dim>
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

      // The body's rotation ('Rotation angle' about 'Rotation axis' through
      // 'Rotation centre'): of points, and of directions.
      template <int dim>
      class BodyRotation
      {
      public:
        BodyRotation(const BodyParameters &body, const unsigned int b)
            : centre(point_of<dim>(body.rotation_centre, b, "Rotation centre"))
        {
          if constexpr (dim == 2)
            R = Physics::Transformations::Rotations::rotation_matrix_2d(
              body.rotation_angle);
          else
            {
              const Point<3> axis =
                point_of<3>(body.rotation_axis, b, "Rotation axis");
              if (axis.norm() == 0)
                throw InputError(body_name(b) +
                                 ", parameter 'Rotation axis': give a "
                                 "nonzero direction.");
              R = Physics::Transformations::Rotations::rotation_matrix_3d(
                Tensor<1, 3>(axis / axis.norm()), body.rotation_angle);
            }
        }

        Point<dim>
        operator()(const Point<dim> &p) const
        {
          return centre + R * (p - centre);
        }

        Tensor<1, dim>
        direction(const Tensor<1, dim> &v) const
        {
          return R * v;
        }

      private:
        Point<dim>     centre;
        Tensor<2, dim> R;
      };

      // Refuses a coarse cell whose (multi)linear map is not orientation
      // preserving at every vertex: inverted or tangled (e.g. a bow-tie
      // quadrilateral from a wrong node order). deal.II's readers repair
      // cells that are merely inverted as a whole; a tangled cell would run
      // and give a wrong solution without any sign.
      template <int dim>
      void
      check_cells(const Triangulation<dim> &tria,
                  const unsigned int        b,
                  const BodyParameters     &body)
      {
        for (const auto &cell : tria.active_cell_iterators())
          {
            const double h = cell->diameter();
            for (unsigned int corner = 0; corner < (1u << dim); ++corner)
              {
                // Edge vectors along the three reference directions at this
                // corner (deal.II's lexicographic vertex numbering).
                Tensor<2, dim> J;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const unsigned int   from = corner & ~(1u << d);
                    const unsigned int   to   = corner | (1u << d);
                    const Tensor<1, dim> e =
                      cell->vertex(to) - cell->vertex(from);
                    for (unsigned int r = 0; r < dim; ++r)
                      J[r][d] = e[r];
                  }
                if (determinant(J) <= 1e-12 * std::pow(h, dim))
                  {
                    std::ostringstream where;
                    where << cell->center();
                    std::ostringstream vertex;
                    vertex << cell->vertex(corner);
                    throw InputError(
                      body_name(b) +
                      (body.shape == BodyShape::file ?
                         ", parameter 'Mesh file' (" + body.mesh_file + ")" :
                         std::string()) +
                      ": the cell with centre (" + where.str() +
                      ") is inverted or tangled (its map from the reference "
                      "cell is not orientation preserving at vertex (" +
                      vertex.str() +
                      ")). Fix the node order or the node positions of that "
                      "element in the mesh.");
                  }
              }
          }
      }

      // The user-visible id of face group @p local of body @p b: 10 (b + 1)
      // + local, or the body's 'Boundary ids' entry.
      types::boundary_id
      boundary_id_of(const BodyParameters &body,
                     const unsigned int    b,
                     const unsigned int    local)
      {
        return body.boundary_ids.empty() ? 10 * (b + 1) + local :
                                           body.boundary_ids[local];
      }

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

      // Number of face groups of a ball segment (see make_ball_segment).
      unsigned int
      n_segment_faces(const Segment segment, const unsigned int dim)
      {
        return segment == Segment::full ? 1 :
               segment == Segment::half ? 2 :
                                          (dim == 2 ? 3 : 4);
      }

      // The local face group of the inner curved face of a hollow segment:
      // after the flat faces of a ball segment, after the end caps of a 3D
      // cylinder segment; numbers::invalid_unsigned_int for a solid one.
      unsigned int
      inner_face_group(const BodyParameters &body, const unsigned int dim)
      {
        if (body.inner_radius == 0)
          return numbers::invalid_unsigned_int;
        return (dim == 3 && body.shape == BodyShape::cylinder_segment) ?
                 5 :
                 n_segment_faces(body.segment, dim);
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
          GridTools::rotate(Tensor<1, 3>({0., 0., 1.}), -numbers::PI / 2, tria);
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

      struct CurvedBody
      {
        types::manifold_id surface_id, volume_id;
      };

      template <int dim>
      void
      build_body(const BodyParameters &body,
                 const unsigned int    b,
                 const std::string    &input_directory,
                 Triangulation<dim>   &tria)
      {
        const Point<dim> shift = point_of<dim>(body.shift, b, "Shift");
        switch (body.shape)
          {
            case BodyShape::block:
              {
                if (body.subdivisions.size() < dim)
                  throw InputError(body_name(b) +
                                   ", parameter 'Subdivisions': give " +
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
                break;
              }
            case BodyShape::ball_segment:
            case BodyShape::cylinder_segment:
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
                          else if (std::abs(z - body.length) <
                                   1e-12 * body.length)
                            face->set_boundary_id(4);
                        }
                    if constexpr (dim == 3)
                      {
                        tria.copy_triangulation(cylinder);
                        GridTools::shift(centre, tria);
                      }
                    assign_boundary_ids(tria,
                                        body,
                                        b,
                                        body.inner_radius > 0 ? 6 : 5);
                  }
                break;
              }
            case BodyShape::file:
              {
                std::string name = body.mesh_file;
                if (name[0] != '/')
                  name = input_directory + "/" + name;
                std::ifstream in(name);
                if (!in || std::filesystem::is_directory(name))
                  throw InputError(body_name(b) +
                                   ", parameter 'Mesh file': cannot open '" +
                                   name +
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
                const std::string where = body_name(b) +
                                          ", parameter 'Mesh file' (" +
                                          body.mesh_file + ")";
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
                        std::regex_replace(info.str(),
                                           quoted,
                                           "(a line of the file)");
                      const std::string more =
                        std::regex_replace(grid_in_diagnostics(
                                             diagnostics.text()),
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
                      const auto it =
                        body.boundary_id_map.find(face->boundary_id());
                      if (it != body.boundary_id_map.end())
                        face->set_boundary_id(it->second);
                    }
                GridTools::shift(shift, tria);
                break;
              }
          }
        if (body.rotation_angle != 0)
          GridTools::transform(BodyRotation<dim>(body, b), tria);
        if (body.material_id >= 0 || body.shape != BodyShape::file)
          for (const auto &cell : tria.active_cell_iterators())
            cell->set_material_id(body.material_id >= 0 ? body.material_id :
                                                          b + 1);
      }

      // The curved faces of a body and the exact surface they lie on.
      template <int dim>
      struct CurvedSurface
      {
        std::vector<types::boundary_id> boundary_ids;
        std::unique_ptr<Manifold<dim>>  manifold; // null: no curved faces
      };

      // Refuses a 'Manifold boundary ids' entry that names no face of the
      // built body, or a face whose vertices are not equidistant from the
      // manifold's centre (sphere) or axis (cylinder): a wrong 'Centre'
      // would otherwise bend the refined mesh out of shape.
      template <int dim>
      void
      check_curved_faces(const Triangulation<dim>              &tria,
                         const std::vector<types::boundary_id> &ids,
                         const Point<dim>                      &centre,
                         const Tensor<1, dim>                  &axis,
                         const unsigned int                     b)
      {
        const auto distance = [&](const Point<dim> &p) {
          const Tensor<1, dim> r = p - centre;
          return (r - (r * axis) * axis).norm();
        };
        const std::string where = body_name(b) + ", parameter 'Manifold ";
        std::set<types::boundary_id> found;
        for (const auto &face : tria.active_face_iterators())
          if (face->at_boundary() &&
              std::find(ids.begin(), ids.end(), face->boundary_id()) !=
                ids.end())
            {
              found.insert(face->boundary_id());
              double r_min = distance(face->vertex(0)), r_max = r_min;
              for (const auto v : face->vertex_indices())
                {
                  r_min = std::min(r_min, distance(face->vertex(v)));
                  r_max = std::max(r_max, distance(face->vertex(v)));
                }
              if (r_max - r_min > 1e-5 * r_max)
                {
                  std::ostringstream text;
                  text << where << "boundary ids': the face with centre ("
                       << face->center() << ") and boundary id "
                       << face->boundary_id() << " has vertices at distances "
                       << r_min << " to " << r_max << " from the manifold's "
                       << (axis.norm() > 0 ? "axis" : "centre")
                       << ", so it does not lie on one surface about it. "
                          "Check 'Centre' (in the file's coordinates)"
                       << (axis.norm() > 0 ? " and 'Manifold axis'" : "")
                       << ", or leave this id out.";
                  throw InputError(text.str());
                }
            }
        for (const auto id : ids)
          if (found.count(id) == 0)
            throw InputError(where +
                             "boundary ids': no boundary face of "
                             "this body has the id " +
                             std::to_string(id) +
                             " (ids after 'Boundary id map').");
      }

      // The curved faces of body @p b, built as @p tria (shifted and
      // rotated): the outer and inner curved faces of a generated segment, or
      // a file mesh's 'Manifold boundary ids'; their sphere or cylinder
      // about the placed 'Centre'.
      template <int dim>
      CurvedSurface<dim>
      curved_surface(const BodyParameters     &body,
                     const unsigned int        b,
                     const Triangulation<dim> &tria)
      {
        CurvedSurface<dim> curved;
        const bool         segment = body.shape == BodyShape::ball_segment ||
                             body.shape == BodyShape::cylinder_segment;
        if (body.manifold != CurvedShape::none && body.shape != BodyShape::file)
          throw InputError(body_name(b) +
                           ", parameter 'Manifold': it is for Shape = file; "
                           "a generated shape has its curved surface "
                           "already. Remove the entry.");
        if (body.manifold == CurvedShape::none &&
            !body.manifold_boundary_ids.empty())
          throw InputError(body_name(b) +
                           ", parameter 'Manifold boundary ids': it needs "
                           "'Manifold' (sphere or cylinder) for Shape = "
                           "file; remove it otherwise.");
        if (!segment && body.manifold == CurvedShape::none)
          return curved;
        bool           cylinder = false;
        Tensor<1, dim> axis; // along the cylinder's axis, 0 for a sphere
        if (segment)
          {
            curved.boundary_ids.push_back(boundary_id_of(body, b, 0));
            const unsigned int inner = inner_face_group(body, dim);
            if (inner != numbers::invalid_unsigned_int)
              curved.boundary_ids.push_back(boundary_id_of(body, b, inner));
            cylinder = dim == 3 && body.shape == BodyShape::cylinder_segment;
            axis[dim - 1] = cylinder ? 1. : 0.;
          }
        else
          {
            if (body.manifold_boundary_ids.empty())
              throw InputError(body_name(b) +
                               ", parameter 'Manifold boundary ids': list "
                               "the boundary ids of the faces on the "
                               "'Manifold' surface.");
            curved.boundary_ids.assign(body.manifold_boundary_ids.begin(),
                                       body.manifold_boundary_ids.end());
            cylinder = body.manifold == CurvedShape::cylinder;
            if (cylinder && dim == 2)
              throw InputError(body_name(b) +
                               ", parameter 'Manifold': cylinder is for 3D "
                               "meshes; a circle in 2D is 'sphere'.");
            if (cylinder)
              {
                const Point<dim> a =
                  point_of<dim>(body.manifold_axis, b, "Manifold axis");
                if (a.norm() == 0)
                  throw InputError(body_name(b) +
                                   ", parameter 'Manifold axis': give a "
                                   "nonzero direction.");
                axis = a / a.norm();
              }
          }
        const BodyRotation<dim> rotation(body, b);
        const Point<dim>        centre =
          rotation(point_of<dim>(body.centre, b, "Centre") +
                   point_of<dim>(body.shift, b, "Shift"));
        axis = rotation.direction(axis);
        if (!segment)
          check_curved_faces(tria, curved.boundary_ids, centre, axis, b);
        if (cylinder)
          curved.manifold =
            std::make_unique<CylindricalManifold<dim>>(axis, centre);
        else
          curved.manifold = std::make_unique<SphericalManifold<dim>>(centre);
        return curved;
      }
    } // namespace


    template <int dim>
    void
    create_mesh(const Parameters                          &parameters,
                parallel::distributed::Triangulation<dim> &triangulation)
    {
      std::vector<Point<dim>>    vertices;
      std::vector<CellData<dim>> cells;
      SubCellData                subcells;
      // Manifold objects to attach: id -> (surface manifold, curved body?)
      std::map<types::manifold_id, std::unique_ptr<Manifold<dim>>> manifolds;
      std::vector<types::manifold_id> volume_manifolds;

      const auto           &bodies = parameters.geometry.bodies;
      std::vector<MeshPart> parts; // the bodies, for the contact checks
      // Their coarse meshes, for the overlap check.
      std::vector<std::unique_ptr<Triangulation<dim>>> coarse;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          Triangulation<dim> body_tria;
          check_subdivisions(bodies[b], b, parameters);
          build_body(bodies[b], b, parameters.input_directory, body_tria);
          check_cells(body_tria, b, bodies[b]);
          add_mesh_parts(body_tria, b, parts);
          coarse.push_back(std::make_unique<Triangulation<dim>>());
          coarse.back()->copy_triangulation(body_tria);

          // Curved surfaces: their manifold on the curved faces. A generated
          // segment's few coarse cells also get transfinite interpolation in
          // the volume (initialised on the joined mesh), so that its interior
          // nodes follow the surface; a file mesh's cells stay flat (the
          // transfinite chart fails on irregular cells, e.g. hexahedra split
          // from tetrahedra, and a file mesh is fine enough without it).
          CurvedSurface<dim> curved = curved_surface(bodies[b], b, body_tria);
          const types::manifold_id surface = 2 * b + 1, volume = 2 * b + 2;
          if (curved.manifold && bodies[b].shape != BodyShape::file)
            {
              body_tria.set_all_manifold_ids(volume);
              volume_manifolds.push_back(volume);
            }
          else
            body_tria.set_all_manifold_ids(numbers::flat_manifold_id);
          if (curved.manifold)
            {
              for (const auto id : curved.boundary_ids)
                body_tria.set_all_manifold_ids_on_boundary(id, surface);
              manifolds[surface] = std::move(curved.manifold);
            }

          auto description = GridTools::get_coarse_mesh_description(body_tria);
          const unsigned int offset = vertices.size();
          for (const auto &v : std::get<0>(description))
            vertices.push_back(v);
          for (auto c : std::get<1>(description))
            {
              for (auto &v : c.vertices)
                v += offset;
              cells.push_back(c);
            }
          auto &sub = std::get<2>(description);
          for (auto l : sub.boundary_lines)
            {
              for (auto &v : l.vertices)
                v += offset;
              subcells.boundary_lines.push_back(l);
            }
          for (auto q : sub.boundary_quads)
            {
              for (auto &v : q.vertices)
                v += offset;
              subcells.boundary_quads.push_back(q);
            }
        }

      check_contact_surfaces(parameters.contact, parts);
      {
        std::vector<const Triangulation<dim> *> meshes;
        for (const auto &m : coarse)
          meshes.push_back(m.get());
        const std::string warning =
          overlap_warning(meshes, parts, parameters.contact);
        if (!warning.empty() && Utilities::MPI::this_mpi_process(
                                  triangulation.get_communicator()) == 0)
          std::cout << warning << std::endl;
      }
      check_global_refinements(cells.size(), parameters);
      triangulation.create_triangulation(vertices, cells, subcells);
      for (auto &[id, manifold] : manifolds)
        triangulation.set_manifold(id, *manifold);
      for (const auto id : volume_manifolds)
        {
          TransfiniteInterpolationManifold<dim> transfinite;
          transfinite.initialize(triangulation);
          triangulation.set_manifold(id, transfinite);
        }
      triangulation.refine_global(parameters.geometry.global_refinements);

      // Local refinement where the user's region function is positive.
      const auto &geometry = parameters.geometry;
      if (geometry.local_refinements > 0)
        {
          FunctionParser<dim> region(1);
          try
            {
              region.initialize(dim == 2 ? "x,y,cycle" : "x,y,z,cycle",
                                geometry.refinement_region,
                                parameters.boundary_conditions.constants,
                                true);
              region.value(Point<dim>());
            }
          catch (const ExceptionBase &e)
            {
              throw InputError(
                "subsection 'Geometry', parameter 'Refinement region': "
                "cannot parse '" +
                geometry.refinement_region + "'. Give an expression in x, y" +
                std::string(dim == 3 ? ", z" : "") +
                ", the cycle number 'cycle' (1, 2, ...) and 'Function "
                "constants', positive where cells are to be refined.");
            }
          for (unsigned int cycle = 0; cycle < geometry.local_refinements;
               ++cycle)
            {
              // The region of this cycle: one that shrinks with 'cycle'
              // grades the mesh.
              region.set_time(cycle + 1);
              // A cell touches the region if the expression is positive at
              // its centre or at one of its vertices, so that a region
              // smaller than the coarse cells still gets refined.
              for (const auto &cell : triangulation.active_cell_iterators())
                if (cell->is_locally_owned())
                  {
                    bool touches = region.value(cell->center()) > 0;
                    for (const unsigned int v : cell->vertex_indices())
                      touches = touches || region.value(cell->vertex(v)) > 0;
                    if (touches)
                      cell->set_refine_flag();
                  }
              // The closure (one hanging node per face) is flagged by
              // prepare_coarsening_and_refinement(), which the execution
              // would call anyway: the count after it is the new size.
              triangulation.prepare_coarsening_and_refinement();
              check_local_refinement(triangulation, cycle, parameters);
              triangulation.execute_coarsening_and_refinement();
            }
        }
    }


    template <int dim>
    std::set<types::boundary_id>
    boundary_ids(const Triangulation<dim> &triangulation)
    {
      // The coarse mesh is known on every rank of a distributed mesh.
      std::set<types::boundary_id> ids;
      for (const auto &cell : triangulation.cell_iterators_on_level(0))
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            ids.insert(face->boundary_id());
      return ids;
    }

    template void
    create_mesh<2>(const Parameters &,
                   parallel::distributed::Triangulation<2> &);
    template void
    create_mesh<3>(const Parameters &,
                   parallel::distributed::Triangulation<3> &);
    template std::set<types::boundary_id>
    boundary_ids<2>(const Triangulation<2> &);
    template std::set<types::boundary_id>
    boundary_ids<3>(const Triangulation<3> &);
  } // namespace Geometry
} // namespace Signorini
