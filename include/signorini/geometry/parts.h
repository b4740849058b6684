#ifndef signorini_geometry_parts_h
#define signorini_geometry_parts_h

#include <deal.II/grid/tria.h>

#include <vector>

/**
 * The bodies of a mesh as its connected parts. create_mesh() joins the
 * bodies of a scene without merging coincident vertices, so every body is
 * one connected part of the coarse mesh (a Gmsh file with two disjoint
 * volumes is two). Used where a quantity is per body: the rigid motions a
 * Jacobian must hold, the force balance of each body.
 */
namespace Signorini
{
  namespace Geometry
  {
    using namespace dealii;

    /** The part of each coarse cell (by its index), numbered in the order
     * of the first coarse cell of each part; @p n_parts their number. The
     * same on every rank (the coarse mesh is). */
    template <int dim>
    std::vector<unsigned int>
    coarse_parts(const Triangulation<dim> &tria, unsigned int &n_parts);

    /** The part of @p cell (any level): that of its coarse ancestor. */
    template <int dim>
    unsigned int
    part_of(const typename Triangulation<dim>::cell_iterator &cell,
            const std::vector<unsigned int>                  &parts);
  } // namespace Geometry
} // namespace Signorini

#endif
