// The parameters of the subsection Geometry (with Body k): the bodies'
// shapes, meshes, ids and placement, and the refinement of the joined mesh.
#include <deal.II/base/utilities.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameters.h>

#include <signorini/base/parameter_helpers.h>

namespace Signorini
{
  using internal::point_pattern;
  using internal::to_doubles;
  using internal::to_unsigned;

  namespace
  {
    using internal::SelectionTable;
    const SelectionTable<BodyShape> body_shapes{
      {"block", BodyShape::block},
      {"ball segment", BodyShape::ball_segment},
      {"cylinder segment", BodyShape::cylinder_segment},
      {"file", BodyShape::file}};
    const SelectionTable<Segment>     segments{{"full", Segment::full},
                                           {"half", Segment::half},
                                           {"quarter", Segment::quarter}};
    const SelectionTable<CurvedShape> curved_shapes{
      {"none", CurvedShape::none},
      {"sphere", CurvedShape::sphere},
      {"cylinder", CurvedShape::cylinder}};
  } // namespace


  // ------------------------------------------------------------------ Body
  void
  BodyParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Shape",
      "block",
      body_shapes.pattern(),
      "How this body's mesh is made. block: rectangle (2D) or box (3D) between "
      "'Lower corner' and 'Upper corner' with 'Subdivisions' cells per "
      "direction; boundary faces numbered 0..3 (2D: x-, x+, y-, y+) or 0..5 "
      "(3D: x-, x+, y-, y+, z-, z+). ball segment: disc (2D) or ball (3D) of "
      "'Radius' around 'Centre', cut to the 'Segment' below the centre (its "
      "flat face on top, curved face down); faces: 0 curved, 1 flat top (y = "
      "centre), for a quarter 2 the flat side x = centre and (3D) 3 the flat "
      "side z = centre. cylinder segment: the 2D disc segment extruded along "
      "z over 'Length' (3D; same as ball segment in 2D); faces: 0 curved, 1 "
      "top, 2 side x = centre (quarter), 3 z-, 4 z+. file: "
      "'Mesh file' read by deal.II's GridIn.");
    prm.declare_entry("Lower corner",
                      "0, 0, 0",
                      point_pattern(),
                      "Lower corner of a block [m]; the first Dimension "
                      "numbers are used.");
    prm.declare_entry("Upper corner",
                      "1, 1, 1",
                      point_pattern(),
                      "Upper corner of a block [m]; the first Dimension "
                      "numbers are used.");
    prm.declare_entry("Subdivisions",
                      "1, 1, 1",
                      Patterns::List(Patterns::Integer(1, 10000), 1, 3, ","),
                      "Number of cells of a block per coordinate direction "
                      "[-]; the first Dimension numbers are used.");
    prm.declare_entry("Centre",
                      "0, 0, 0",
                      point_pattern(),
                      "Centre of a ball or cylinder segment [m] (for a "
                      "cylinder the z coordinate is the start of its axis).");
    prm.declare_entry("Radius",
                      "1",
                      Patterns::Double(1e-300),
                      "Radius of a ball or cylinder segment [m].");
    prm.declare_entry("Inner radius",
                      "0",
                      Patterns::Double(0),
                      "Inner radius of a hollow ball or cylinder segment [m] "
                      "(a shell or tube), below 'Radius'; 0: solid. The inner "
                      "curved face is the last face group: ball segment 1 "
                      "(full), 2 (half), 3 (quarter, 2D) or 4 (quarter, 3D); "
                      "cylinder segment (3D) 5.");
    prm.declare_entry("Segment",
                      "half",
                      segments.pattern(),
                      "Part of the disc/ball kept: full, the half below the "
                      "centre, or the quarter below the centre with x >= "
                      "centre (for symmetric models).");
    prm.declare_entry("Length",
                      "1",
                      Patterns::Double(1e-300),
                      "Axial length of a cylinder segment in 3D [m].");
    prm.declare_entry("Mesh file",
                      "",
                      Patterns::FileName(),
                      "Mesh file for Shape = file: Gmsh (.msh) or Abaqus "
                      "(.inp). Relative paths are taken from the directory "
                      "of the parameter file.");
    prm.declare_entry(
      "Boundary id map",
      "",
      Patterns::Map(Patterns::Integer(0, 255), Patterns::Integer(0, 255)),
      "For Shape = file: physical group (Gmsh tag / Abaqus surface number) -> "
      "boundary id, as 'tag: id, tag: id'. Tags not listed keep their number.");
    prm.declare_entry(
      "Manifold",
      "none",
      curved_shapes.pattern(),
      "For Shape = file: the exact surface that the faces with 'Manifold "
      "boundary ids' lie on, so that refinement (global, local, adaptive) "
      "puts new nodes on it; without it the flat faces of the file stay flat "
      "when refined. sphere: a sphere (2D: a circle) about 'Centre'; "
      "cylinder (3D): about the line through 'Centre' along 'Manifold "
      "axis'. 'Centre' and the axis are in the file's coordinates (before "
      "'Shift' and 'Rotation angle'). The body's cells then follow the "
      "surface by transfinite interpolation, as in a generated ball "
      "segment. Generated shapes have their curved surfaces already.");
    prm.declare_entry("Manifold boundary ids",
                      "",
                      Patterns::List(Patterns::Integer(0, 255), 0, 255, ","),
                      "Boundary ids (after 'Boundary id map') of the faces "
                      "on the 'Manifold' surface; each face's vertices must "
                      "lie on one sphere (cylinder) about it.");
    prm.declare_entry("Manifold axis",
                      "0, 0, 1",
                      point_pattern(),
                      "Direction of the axis of a 'Manifold = cylinder' "
                      "(3D; any length but 0).");
    prm.declare_entry(
      "Boundary ids",
      "",
      Patterns::List(Patterns::Integer(0, 255), 0, 6, ","),
      "Boundary ids given to the faces of a generated shape, in the order of "
      "the shape's own face numbers (see Shape). Empty: 10*k + face number "
      "for Body k, so that bodies never share a boundary id.");
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
                      "Point the rotation turns about [m] (e.g. the body's "
                      "'Centre' to turn a segment in place); the first "
                      "Dimension numbers are used.");
  }


  void
  BodyParameters::parse_parameters(ParameterHandler &prm)
  {
    shape        = body_shapes.value(prm.get("Shape"));
    lower_corner = to_doubles(prm.get("Lower corner"));
    upper_corner = to_doubles(prm.get("Upper corner"));
    subdivisions = to_unsigned(prm.get("Subdivisions"));
    centre       = to_doubles(prm.get("Centre"));
    radius       = prm.get_double("Radius");
    inner_radius = prm.get_double("Inner radius");
    segment      = segments.value(prm.get("Segment"));
    length       = prm.get_double("Length");
    mesh_file    = prm.get("Mesh file");
    boundary_id_map.clear();
    for (const auto &entry :
         Utilities::split_string_list(prm.get("Boundary id map"), ','))
      {
        const auto kv = Utilities::split_string_list(entry, ':');
        boundary_id_map[Utilities::string_to_int(kv[0])] =
          Utilities::string_to_int(kv[1]);
      }
    manifold              = curved_shapes.value(prm.get("Manifold"));
    manifold_boundary_ids = to_unsigned(prm.get("Manifold boundary ids"));
    manifold_axis         = to_doubles(prm.get("Manifold axis"));
    boundary_ids          = to_unsigned(prm.get("Boundary ids"));
    material_id           = prm.get_integer("Material id");
    shift                 = to_doubles(prm.get("Shift"));
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
