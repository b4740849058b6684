#ifndef signorini_geometry_scene_h
#define signorini_geometry_scene_h

#include <deal.II/distributed/tria.h>

#include <signorini/base/parameters.h>
#include <signorini/geometry/shapes/interface.h>

#include <memory>
#include <vector>

#include <set>

/**
 * Builds the mesh of a scene: every body is made on its own by its shape
 * (geometry/shapes/: a generated block, ball or cylinder segment, a
 * Gmsh/Abaqus file, or a user's shape), placed, and the bodies are then
 * joined into one coarse mesh WITHOUT merging coincident vertices, so bodies
 * touching at an interface stay separate components (a contact interface is
 * two boundaries, never shared nodes). Curved boundaries keep their manifolds
 * (spherical/cylindrical on the surface, transfinite interpolation inside), so
 * refinement follows the true geometry.
 */
namespace Signorini
{
  namespace Geometry
  {
    using namespace dealii;

    /** The joined mesh of the bodies of @p parameters, body k made by
     * @p shapes[k] (Shapes::make_shapes()). */
    template <int dim>
    void
    create_mesh(
      const Parameters                                           &parameters,
      const std::vector<std::unique_ptr<Shapes::Interface<dim>>> &shapes,
      parallel::distributed::Triangulation<dim> &triangulation);

    /** All boundary ids of the coarse mesh (the same on every rank). */
    template <int dim>
    std::set<types::boundary_id>
    boundary_ids(const Triangulation<dim> &triangulation);
  } // namespace Geometry
} // namespace Signorini

#endif
