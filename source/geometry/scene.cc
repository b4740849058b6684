#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/physics/transformations.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameter_helpers.h>
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
      using Shapes::Placement;

      // The subsection of body @p b, for messages.
      std::string
      body_name(const unsigned int b)
      {
        return "subsection 'Geometry/Body " + std::to_string(b + 1) + "'";
      }

      // The body's placement: 'Shift', then 'Rotation angle' about
      // 'Rotation axis' through 'Rotation centre'.
      template <int dim>
      Placement<dim>
      placement_of(const BodyParameters &body)
      {
        using internal::point_of;
        Tensor<2, dim> R;
        if constexpr (dim == 2)
          R = Physics::Transformations::Rotations::rotation_matrix_2d(
            body.rotation_angle);
        else
          {
            const Point<3> axis =
              point_of<3>(body.rotation_axis, "Rotation axis");
            if (axis.norm() == 0)
              throw InputError("parameter 'Rotation axis': give a nonzero "
                               "direction.");
            R = Physics::Transformations::Rotations::rotation_matrix_3d(
              Tensor<1, 3>(axis / axis.norm()), body.rotation_angle);
          }
        return Placement<dim>(point_of<dim>(body.shift, "Shift"),
                              R,
                              point_of<dim>(body.rotation_centre,
                                            "Rotation centre"));
      }


      // Gives the face groups of a generated shape the body's user-visible
      // ids: 'Boundary ids', or 10 (b + 1) + group.
      types::boundary_id
      user_id(const BodyParameters &body,
              const unsigned int    b,
              const unsigned int    group)
      {
        return body.boundary_ids.empty() ? 10 * (b + 1) + group :
                                           body.boundary_ids[group];
      }


      // Body @p b built by its shape: its faces' user ids, its curved
      // surface (returned), its placement and material ids.
      template <int dim>
      Shapes::CurvedSurface<dim>
      build_body(const BodyParameters         &body,
                 const unsigned int            b,
                 const Shapes::Interface<dim> &shape,
                 const Parameters             &parameters,
                 Triangulation<dim>           &tria)
      {
        const std::string where = Shapes::subsection_of(b, body.shape);
        std::string       entry;
        const double      cells = shape.n_cells(entry);
        check_body_cells(cells,
                         where + ", parameter '" + entry + "'",
                         entry,
                         parameters);
        const unsigned int n_groups = shape.n_face_groups();
        if (n_groups == 0 && !body.boundary_ids.empty())
          throw InputError(body_name(b) +
                           ", parameter 'Boundary ids': a mesh read from a "
                           "file keeps its own ids; rename them with 'Boundary "
                           "id map' in " +
                           where + " and remove this entry.");
        if (!body.boundary_ids.empty() && body.boundary_ids.size() < n_groups)
          throw InputError(body_name(b) +
                           ", parameter 'Boundary ids': this "
                           "shape has " +
                           std::to_string(n_groups) + " face groups, give " +
                           std::to_string(n_groups) +
                           " ids (or leave it empty).");
        Placement<dim> placement;
        try
          {
            placement = placement_of<dim>(body);
          }
        catch (const InputError &e)
          {
            throw InputError(body_name(b) + ", " + e.what());
          }
        Shapes::CurvedSurface<dim> curved;
        try
          {
            shape.build(tria);
            curved = shape.curved_surface(tria, placement);
          }
        catch (const InputError &e)
          {
            throw InputError(where + ", " + e.what());
          }
        if (n_groups > 0)
          {
            for (const auto &face : tria.active_face_iterators())
              if (face->at_boundary())
                face->set_boundary_id(user_id(body, b, face->boundary_id()));
            for (auto &id : curved.faces)
              id = user_id(body, b, id);
          }
        GridTools::transform([&](const Point<dim> &p) { return placement(p); },
                             tria);
        if (body.material_id >= 0 || n_groups > 0)
          for (const auto &cell : tria.active_cell_iterators())
            cell->set_material_id(body.material_id >= 0 ? body.material_id :
                                                          b + 1);
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
    create_mesh(
      const Parameters                                           &parameters,
      const std::vector<std::unique_ptr<Shapes::Interface<dim>>> &shapes,
      parallel::distributed::Triangulation<dim>                  &triangulation)
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
          Triangulation<dim>         body_tria;
          Shapes::CurvedSurface<dim> curved =
            build_body(bodies[b], b, *shapes[b], parameters, body_tria);
          add_mesh_parts(body_tria, b, parts);
          coarse.push_back(std::make_unique<Triangulation<dim>>());
          coarse.back()->copy_triangulation(body_tria);

          // Curved surfaces: their manifold on the curved faces; where the
          // shape asks for it (a generated segment's few coarse cells), also
          // transfinite interpolation in the volume (initialised on the
          // joined mesh), so that its interior nodes follow the surface.
          const types::manifold_id surface = 2 * b + 1, volume = 2 * b + 2;
          if (curved.manifold && curved.cells_follow)
            {
              body_tria.set_all_manifold_ids(volume);
              volume_manifolds.push_back(volume);
            }
          else
            body_tria.set_all_manifold_ids(numbers::flat_manifold_id);
          if (curved.manifold)
            {
              for (const auto id : curved.faces)
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
                   const std::vector<std::unique_ptr<Shapes::Interface<2>>> &,
                   parallel::distributed::Triangulation<2> &);
    template void
    create_mesh<3>(const Parameters &,
                   const std::vector<std::unique_ptr<Shapes::Interface<3>>> &,
                   parallel::distributed::Triangulation<3> &);
    template std::set<types::boundary_id>
    boundary_ids<2>(const Triangulation<2> &);
    template std::set<types::boundary_id>
    boundary_ids<3>(const Triangulation<3> &);
  } // namespace Geometry
} // namespace Signorini
