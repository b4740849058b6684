#ifndef signorini_geometry_mesh_checks_h
#define signorini_geometry_mesh_checks_h

#include <deal.II/distributed/tria.h>
#include <deal.II/grid/tria.h>

#include <signorini/base/parameters.h>

#include <set>
#include <string>
#include <vector>

/**
 * Checks of the mesh that stop a run with one InputError before any
 * expensive work: cell types the code cannot use (simplices, wedges,
 * pyramids, second-order or mixed meshes; the element loops assume
 * 2^dim-vertex cells and would read past a triangle's vertices), a
 * refinement beyond 'Geometry/Maximum number of cells', and contact
 * surfaces that do not match the bodies of the mesh.
 */
namespace Signorini
{
  namespace Geometry
  {
    using namespace dealii;

    /**
     * Refuses a mesh file text (Gmsh .msh or Abaqus .inp, by @p extension)
     * with cells other than first-order quadrilaterals (@p dim = 2) or
     * hexahedra (@p dim = 3), before GridIn reads it. @p where names the
     * body and the file.
     */
    void
    check_mesh_file_cells(const std::string &text,
                          const std::string &extension,
                          const unsigned int dim,
                          const std::string &where);

    /** The same for a mesh read by GridIn: every cell a hypercube. */
    template <int dim>
    void
    check_reference_cells(const Triangulation<dim> &tria,
                          const std::string        &where);

    /** GridIn's own diagnostics (printed to std::cerr) in one line. */
    std::string
    grid_in_diagnostics(const std::string &captured);

    /** InputError if a body's shape would have @p cells cells, more than
     * 'Geometry/Maximum number of cells', before it is built; @p where
     * names the entry @p entry that sets the count. */
    void
    check_body_cells(const double       cells,
                     const std::string &where,
                     const std::string &entry,
                     const Parameters  &parameters);

    /**
     * Refuses 'Global refinements' that would refine @p n_coarse_cells
     * beyond 'Maximum number of cells'.
     */
    void
    check_global_refinements(const std::size_t n_coarse_cells,
                             const Parameters &parameters);

    /**
     * Refuses local refinement cycle @p cycle (0-based) if the refinement
     * flagged and prepared on @p triangulation would exceed 'Maximum number
     * of cells'.
     */
    template <int dim>
    void
    check_local_refinement(
      const parallel::distributed::Triangulation<dim> &triangulation,
      const unsigned int                               cycle,
      const Parameters                                &parameters);

    /**
     * The number of active cells once the refinement flagged now (after
     * prepare_coarsening_and_refinement()) is executed, the same on every
     * rank: every flagged cell becomes 2^dim children; coarsening is not
     * subtracted (an upper bound).
     */
    template <int dim>
    double
    cells_after_refinement(
      const parallel::distributed::Triangulation<dim> &triangulation);

    /** "about N cells (about M displacement DoFs), more than ... = L" */
    std::string
    cell_estimate_text(const double cells, const Parameters &parameters);

    /** One connected component of one body's mesh and its boundary ids. */
    struct MeshPart
    {
      unsigned int                 body;    // 0-based body number
      unsigned int                 part;    // 0-based, within the body
      unsigned int                 n_parts; // components of the body's mesh
      std::set<types::boundary_id> boundary_ids;
    };

    /** Appends the connected components (cells sharing vertices) of @p tria. */
    template <int dim>
    void
    add_mesh_parts(const Triangulation<dim> &tria,
                   const unsigned int        body,
                   std::vector<MeshPart>    &parts);

    /**
     * Refuses a contact pair whose slave ids lie on more than one part, or
     * whose master ids (Master = body) lie on the slave's part. Ids no part
     * has are left to the contact set-up, which names them.
     */
    void
    check_contact_surfaces(const ContactParameters     &contact,
                           const std::vector<MeshPart> &parts);

    /**
     * A warning for the log if two bodies' coarse meshes overlap (a vertex
     * of one strictly inside a cell of the other) while no contact pair
     * joins them (they would pass through each other: a file cut before
     * its contact section runs without one); empty otherwise. @p bodies:
     * the coarse mesh of each body, in body order.
     */
    template <int dim>
    std::string
    overlap_warning(const std::vector<const Triangulation<dim> *> &bodies,
                    const std::vector<MeshPart>                   &parts,
                    const ContactParameters                       &contact);
  } // namespace Geometry
} // namespace Signorini

#endif
