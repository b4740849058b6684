// The parameters of the subsection Geometry (with Body k): the bodies'
// shapes, meshes, ids and placement, and the refinement of the joined mesh.
#include <deal.II/base/utilities.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameters.h>
#include <signorini/base/plugins.h>

#include <signorini/base/parameter_helpers.h>

namespace Signorini
{
  using internal::point_pattern;
  using internal::to_doubles;
  using internal::to_unsigned;

  // ------------------------------------------------------------------ Body
  void
  BodyParameters::declare_parameters(ParameterHandler &prm)
  {
    // 'Shape' and every shape's subsection: the family declares them.
    Plugins::declare(Plugins::Family::shape, prm);
    prm.declare_entry(
      "Boundary ids",
      "",
      Patterns::List(Patterns::Integer(0, 255), 0, 6, ","),
      "Boundary ids given to the face groups of a generated shape, in the "
      "order of the shape's own group numbers (see Shape). Empty: 10*k + "
      "group number for Body k, so that bodies never share a boundary id. A "
      "mesh file keeps its own ids (see 'File/Boundary id map').");
    prm.declare_entry("Material id",
                      "-1",
                      Patterns::Integer(-1, 255),
                      "Material id of every cell of this body; -1: the body "
                      "number k for generated shapes, the file's ids for "
                      "meshes read from a file.");
    prm.declare_entry("Shift",
                      "0, 0, 0",
                      point_pattern(),
                      "Translation applied to this body after it is built "
                      "[m]; the first Dimension numbers are used.");
    prm.declare_entry("Rotation angle",
                      "0",
                      Patterns::Double(),
                      "Rotation of this body after the shift [degrees], "
                      "counter-clockwise about 'Rotation axis' (2D: about "
                      "z) through 'Rotation centre'. Its faces keep their "
                      "ids and a curved surface keeps its exact shape: e.g. "
                      "180 turns a ball segment's curved side up.");
    prm.declare_entry("Rotation axis",
                      "0, 0, 1",
                      point_pattern(),
                      "Axis of the rotation in 3D (any length but 0); "
                      "ignored in 2D.");
    prm.declare_entry("Rotation centre",
                      "0, 0, 0",
                      point_pattern(),
                      "Point the rotation turns about [m] (e.g. a segment's "
                      "'Centre' to turn it in place); the first Dimension "
                      "numbers are used.");
  }


  void
  BodyParameters::parse_parameters(ParameterHandler &prm)
  {
    shape           = prm.get("Shape");
    boundary_ids    = to_unsigned(prm.get("Boundary ids"));
    material_id     = prm.get_integer("Material id");
    shift           = to_doubles(prm.get("Shift"));
    rotation_angle  = prm.get_double("Rotation angle") * numbers::PI / 180.;
    rotation_axis   = to_doubles(prm.get("Rotation axis"));
    rotation_centre = to_doubles(prm.get("Rotation centre"));
  }


  void
  GeometryParameters::declare_parameters(ParameterHandler &prm,
                                         const Counts     &counts)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Number of bodies",
                      "1",
                      Patterns::Integer(1, 16),
                      "Number of bodies; each has a subsection 'Body k', k = "
                      "1..N. Bodies never share vertices, even where they "
                      "touch.");
    prm.declare_entry("Global refinements",
                      "0",
                      Patterns::Integer(0, 12),
                      "Number of uniform refinements of the assembled mesh "
                      "[-].");
    prm.declare_entry("Local refinements",
                      "0",
                      Patterns::Integer(0, 20),
                      "Number of refinement cycles, after the global ones, of "
                      "the cells that touch 'Refinement region' "
                      "(typically the contact zone). Neighbours are refined "
                      "as needed to keep one hanging node per face.");
    prm.declare_entry("Refinement region",
                      "0",
                      Patterns::Anything(),
                      "Expression in x, y(, z), the local cycle 'cycle' (1, "
                      "2, ...) and 'Function constants': a cell is refined "
                      "in a local cycle iff it is > 0 at the cell centre or "
                      "at one of its vertices, e.g. '0.02 - sqrt(x^2 + y^2)' "
                      "(a disc refined in every cycle). A region that "
                      "shrinks with the cycle grades the mesh, e.g. '0.006 "
                      "+ 0.04 / 2^cycle - sqrt(x^2 + y^2)': about as many "
                      "cells of each size around a 6 mm disc of the finest "
                      "ones.");
    prm.declare_entry(
      "Maximum number of cells",
      "1000000",
      Patterns::Integer(1),
      "Largest number of active cells the mesh may reach. The cell count is "
      "estimated before every refinement (a global refinement multiplies it "
      "by 2^Dimension; a local or adaptive one adds 2^Dimension - 1 per "
      "marked cell) and a refinement beyond this limit is refused, with the "
      "estimate, instead of allocating until the machine runs out of "
      "memory. The default suits a machine of about 32 GB: measured peaks "
      "are about 7 kB per cell in 2D (Q1, direct solver) and 30 kB per cell "
      "in 3D (Q1, 200k cells: 6.2 GB, doc/performance.md), more with Q2. "
      "Raise it on a larger machine.");
    for (unsigned int b = 1; b <= counts.n_bodies; ++b)
      {
        prm.enter_subsection("Body " + std::to_string(b));
        BodyParameters::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  void
  GeometryParameters::parse_parameters(ParameterHandler &prm,
                                       const Counts     &counts)
  {
    prm.enter_subsection("Geometry");
    global_refinements = prm.get_integer("Global refinements");
    local_refinements  = prm.get_integer("Local refinements");
    maximum_cells      = prm.get_integer("Maximum number of cells");
    refinement_region  = prm.get("Refinement region");
    bodies.resize(counts.n_bodies);
    for (unsigned int b = 0; b < counts.n_bodies; ++b)
      {
        prm.enter_subsection("Body " + std::to_string(b + 1));
        bodies[b].parse_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }
} // namespace Signorini
