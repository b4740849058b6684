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

#include "shapes.h"

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
      using namespace internal;

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

      template <int dim>
      void
      build_body(const BodyParameters &body,
                 const unsigned int    b,
                 const std::string    &input_directory,
                 Triangulation<dim>   &tria)
      {
        const Point<dim> shift = point_of<dim>(body.shift, b, "Shift");
        if (body.shape == BodyShape::block)
          build_block(body, b, shift, tria);
        else if (body.shape == BodyShape::file)
          build_from_file(body, b, input_directory, shift, tria);
        else
          build_segment(body, b, shift, tria);
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
      // Appends the coarse cells of a body to the joined mesh's lists.
      template <int dim>
      void
      append_coarse_mesh(const Triangulation<dim>   &body_tria,
                         std::vector<Point<dim>>    &vertices,
                         std::vector<CellData<dim>> &cells,
                         SubCellData                &subcells)
      {
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


      // 'Local refinements' cycles where 'Refinement region' is positive.
      template <int dim>
      void
      refine_region(const Parameters                          &parameters,
                    parallel::distributed::Triangulation<dim> &triangulation)
      {
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

          append_coarse_mesh(body_tria, vertices, cells, subcells);
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

      refine_region(parameters, triangulation);
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
