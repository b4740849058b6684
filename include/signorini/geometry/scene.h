#ifndef signorini_geometry_scene_h
#define signorini_geometry_scene_h

#include <deal.II/distributed/tria.h>

#include <signorini/base/parameters.h>

#include <set>

/**
 * Builds the mesh of a scene: every body (generated block, ball or cylinder
 * segment, or a Gmsh/Abaqus file) is made on its own and the bodies are then
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

    template <int dim>
    void
    create_mesh(const Parameters                          &parameters,
                parallel::distributed::Triangulation<dim> &triangulation);

    /** All boundary ids of the coarse mesh (the same on every rank). */
    template <int dim>
    std::set<types::boundary_id>
    boundary_ids(const Triangulation<dim> &triangulation);
  } // namespace Geometry
} // namespace Signorini

#endif
