#include <deal.II/base/utilities.h>

#include <signorini/core/input_checks.h>
#include <signorini/core/parameters.h>
#include <signorini/contact/obstacles/interface.h>
#include <signorini/material/interface.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>

namespace Signorini
{
  namespace
  {
    std::vector<double>
    to_doubles(const std::string &text)
    {
      return Utilities::string_to_double(
        Utilities::split_string_list(text, ','));
    }

    std::vector<unsigned int>
    to_unsigned(const std::string &text)
    {
      std::vector<unsigned int> result;
      for (const int v :
           Utilities::string_to_int(Utilities::split_string_list(text, ',')))
        result.push_back(static_cast<unsigned int>(v));
      return result;
    }

    // Pattern for a comma separated list of doubles: empty or 1..3 numbers.
    Patterns::List
    point_pattern(const unsigned int min = 0)
    {
      return Patterns::List(Patterns::Double(), min, 3, ",");
    }

    unsigned int
    component_index(const std::string &name)
    {
      if (name == "x")
        return 0;
      if (name == "y")
        return 1;
      return 2;
    }
  } // namespace


  std::vector<std::string>
  split_expressions(const std::string &text)
  {
    if (Utilities::trim(text).empty())
      return {};
    return Utilities::split_string_list(text, ';');
  }


  template <int dim>
  Point<dim>
  to_point(const std::vector<double> &values, const std::string &where)
  {
    if (values.size() != dim)
      throw InputError(where + ": expected " + std::to_string(dim) +
                       " coordinates (Dimension = " + std::to_string(dim) +
                       ") but got " + std::to_string(values.size()) +
                       ". Give one number per coordinate, separated by commas.");
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = values[d];
    return p;
  }
  template Point<2> to_point<2>(const std::vector<double> &, const std::string &);
  template Point<3> to_point<3>(const std::vector<double> &, const std::string &);


  // ------------------------------------------------------------------ Body
  void
  BodyParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Shape",
      "block",
      Patterns::Selection("block|ball segment|cylinder segment|file"),
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
    prm.declare_entry("Segment",
                      "half",
                      Patterns::Selection("full|half|quarter"),
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
  }


  void
  BodyParameters::parse_parameters(ParameterHandler &prm)
  {
    const std::string s = prm.get("Shape");
    shape               = s == "block"            ? BodyShape::block :
                          s == "ball segment"     ? BodyShape::ball_segment :
                          s == "cylinder segment" ? BodyShape::cylinder_segment :
                                                    BodyShape::file;
    lower_corner = to_doubles(prm.get("Lower corner"));
    upper_corner = to_doubles(prm.get("Upper corner"));
    subdivisions = to_unsigned(prm.get("Subdivisions"));
    centre       = to_doubles(prm.get("Centre"));
    radius       = prm.get_double("Radius");
    const std::string seg = prm.get("Segment");
    segment     = seg == "full" ? Segment::full :
                  seg == "half" ? Segment::half :
                                  Segment::quarter;
    length      = prm.get_double("Length");
    mesh_file   = prm.get("Mesh file");
    boundary_id_map.clear();
    for (const auto &entry :
         Utilities::split_string_list(prm.get("Boundary id map"), ','))
      {
        const auto kv = Utilities::split_string_list(entry, ':');
        boundary_id_map[Utilities::string_to_int(kv[0])] =
          Utilities::string_to_int(kv[1]);
      }
    boundary_ids = to_unsigned(prm.get("Boundary ids"));
    material_id  = prm.get_integer("Material id");
    shift        = to_doubles(prm.get("Shift"));
  }


  void
  GeometryParameters::declare_parameters(ParameterHandler &prm,
                                         const Counts &    counts)
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
                      "Expression in x, y(, z) and 'Function constants': a "
                      "cell is refined in each local cycle iff it is > 0 at "
                      "the cell centre or at one of its vertices, e.g. "
                      "'0.02 - sqrt(x^2 + y^2)'.");
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
                                       const Counts &    counts)
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


  // ------------------------------------------------------------- Materials
  void
  MaterialParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Material id",
                      "1",
                      Patterns::Integer(0, 255),
                      "Cells with this material id use this material.");
    prm.declare_entry("Young's modulus",
                      "1",
                      Patterns::Double(1e-300),
                      "Young's modulus E [Pa], > 0.");
    prm.declare_entry("Poisson's ratio",
                      "0.3",
                      Patterns::Double(-0.999999, 0.499999),
                      "Poisson's ratio nu [-], -1 < nu < 0.5 (plane strain "
                      "in 2D).");
    Material::declare_model_parameters(prm);
  }


  void
  MaterialParameters::parse_parameters(ParameterHandler &prm)
  {
    material_id    = prm.get_integer("Material id");
    model          = prm.get("Model");
    youngs_modulus = prm.get_double("Young's modulus");
    poissons_ratio = prm.get_double("Poisson's ratio");
  }


  // --------------------------------------------------- Boundary conditions
  void
  DirichletParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Boundary id",
                      "0",
                      Patterns::List(Patterns::Integer(0, 255), 1, 256, ","),
                      "Boundary id(s) on which displacements are prescribed, "
                      "e.g. '12' or '12, 22'.");
    prm.declare_entry("Components",
                      "x, y",
                      Patterns::MultipleSelection("x|y|z"),
                      "Displacement components prescribed, e.g. 'y' or "
                      "'x, y'.");
    prm.declare_entry(
      "Values",
      "0; 0",
      Patterns::Anything(),
      "Prescribed displacement [m], one expression per listed component, "
      "separated by ';', as functions of x, y, z and the load time t "
      "(deal.II FunctionParser syntax), e.g. '0; -0.1*t'.");
    prm.declare_entry("At point",
                      "",
                      point_pattern(),
                      "If not empty: only the mesh nodes of this boundary at "
                      "this point [m] are constrained (e.g. one corner to "
                      "remove a rigid-body mode).");
  }


  void
  DirichletParameters::parse_parameters(ParameterHandler &prm)
  {
    boundary_ids = to_unsigned(prm.get("Boundary id"));
    components.clear();
    for (const auto &c :
         Utilities::split_string_list(prm.get("Components"), ','))
      components.push_back(component_index(c));
    values   = split_expressions(prm.get("Values"));
    at_point = to_doubles(prm.get("At point"));
  }


  void
  NeumannParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Boundary id",
                      "0",
                      Patterns::List(Patterns::Integer(0, 255), 1, 256, ","),
                      "Boundary id(s) loaded by this condition.");
    prm.declare_entry("Type",
                      "traction",
                      Patterns::Selection("traction|pressure"),
                      "traction: a surface force vector; pressure: a scalar "
                      "acting against the outward normal (positive "
                      "compresses).");
    prm.declare_entry("Values",
                      "0; 0",
                      Patterns::Anything(),
                      "Traction [Pa]: Dimension expressions separated by "
                      "';'; pressure [Pa]: one expression; functions of x, "
                      "y, z and the load time t.");
  }


  void
  NeumannParameters::parse_parameters(ParameterHandler &prm)
  {
    boundary_ids = to_unsigned(prm.get("Boundary id"));
    type   = prm.get("Type") == "traction" ? NeumannType::traction :
                                             NeumannType::pressure;
    values = split_expressions(prm.get("Values"));
  }


  void
  BoundaryConditionParameters::declare_parameters(ParameterHandler &prm,
                                                  const Counts &    counts)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("Number of Dirichlet conditions",
                      "1",
                      Patterns::Integer(0, 64),
                      "Number of subsections 'Dirichlet k', k = 1..N.");
    prm.declare_entry("Number of Neumann conditions",
                      "0",
                      Patterns::Integer(0, 64),
                      "Number of subsections 'Neumann k', k = 1..N.");
    prm.declare_entry("Body force",
                      "0; 0; 0",
                      Patterns::Anything(),
                      "Body force per unit volume [N/m^3]: Dimension "
                      "expressions separated by ';' (extra ones ignored), "
                      "functions of x, y, z and t.");
    // Checked by parse_function_constants(), which names what is wrong
    // (a Patterns::Map only says that the whole entry does not match).
    prm.declare_entry(
      "Function constants",
      "",
      Patterns::Anything(),
      "Named constants usable in every expression, e.g. 'p0: 1e5, R: 0.1'. "
      "A name starts with a letter, followed by letters, digits or "
      "underscores, and is neither x, y, z, t nor a built-in function "
      "name (sin, exp, if, ...); a value is a number.");
    for (unsigned int k = 1; k <= counts.n_dirichlet; ++k)
      {
        prm.enter_subsection("Dirichlet " + std::to_string(k));
        DirichletParameters::declare_parameters(prm);
        prm.leave_subsection();
      }
    for (unsigned int k = 1; k <= counts.n_neumann; ++k)
      {
        prm.enter_subsection("Neumann " + std::to_string(k));
        NeumannParameters::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  void
  BoundaryConditionParameters::parse_parameters(ParameterHandler &prm,
                                                const Counts &    counts)
  {
    prm.enter_subsection("Boundary conditions");
    body_force = split_expressions(prm.get("Body force"));
    constants = parse_function_constants(prm.get("Function constants"));
    dirichlet.resize(counts.n_dirichlet);
    for (unsigned int k = 0; k < counts.n_dirichlet; ++k)
      {
        prm.enter_subsection("Dirichlet " + std::to_string(k + 1));
        dirichlet[k].parse_parameters(prm);
        prm.leave_subsection();
      }
    neumann.resize(counts.n_neumann);
    for (unsigned int k = 0; k < counts.n_neumann; ++k)
      {
        prm.enter_subsection("Neumann " + std::to_string(k + 1));
        neumann[k].parse_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  // ---------------------------------------------------------- Load stepping
  void
  LoadSteppingParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Load stepping");
    prm.declare_entry("Number of steps",
                      "1",
                      Patterns::Integer(1, 100000),
                      "Number of equal load steps from t = 0 to 'Final "
                      "time'.");
    prm.declare_entry("Final time",
                      "1",
                      Patterns::Double(1e-300),
                      "Load time at the end of the run [pseudo-time; loads "
                      "are functions of t].");
    prm.declare_entry("Step times",
                      "",
                      Patterns::List(Patterns::Double(0), 0, 100000, ","),
                      "If not empty: the end times of the load steps, "
                      "increasing and > 0 (overrides 'Number of steps' and "
                      "'Final time').");
    prm.declare_entry("Maximum step cuts",
                      "5",
                      Patterns::Integer(0, 30),
                      "How often a load step that fails to converge is "
                      "halved and retried before the run stops.");
    prm.declare_entry("Predictor",
                      "extrapolated",
                      Patterns::Selection("constant|extrapolated"),
                      "First iterate of a load step: the last converged "
                      "state plus the increment of the last converged step "
                      "scaled to the new step size, displacements and "
                      "multipliers (extrapolated: starts sliding contacts "
                      "with their slip direction and a growing contact "
                      "zone with its pressures), or the last converged "
                      "state (constant). Dirichlet values are those of the "
                      "new time either way; the first step is constant.");
    prm.leave_subsection();
  }


  void
  LoadSteppingParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Load stepping");
    step_times     = to_doubles(prm.get("Step times"));
    explicit_times = !step_times.empty();
    if (step_times.empty())
      {
        const unsigned int n = prm.get_integer("Number of steps");
        const double       T = prm.get_double("Final time");
        for (unsigned int k = 1; k <= n; ++k)
          step_times.push_back(T * k / n);
      }
    for (unsigned int k = 0; k < step_times.size(); ++k)
      if (step_times[k] <= (k == 0 ? 0. : step_times[k - 1]))
        throw InputError(
          "subsection 'Load stepping', parameter 'Step times': the times "
          "must be > 0 and strictly increasing; entry " +
          std::to_string(k + 1) + " is not.");
    max_cuts = prm.get_integer("Maximum step cuts");
    extrapolate = prm.get("Predictor") == "extrapolated";
    prm.leave_subsection();
  }


  // ----------------------------------------------------------------- Newton
  void
  NewtonParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton");
    prm.declare_entry("Maximum iterations",
                      "25",
                      Patterns::Integer(1, 1000),
                      "Newton iterations allowed per load step before the "
                      "step is cut.");
    prm.declare_entry("Relative tolerance",
                      "1e-10",
                      Patterns::Double(0, 1),
                      "Converged when the residual norm is below this "
                      "factor times the force level of the load step (the "
                      "largest internal or external force norm of its "
                      "iterates) [-].");
    prm.declare_entry("Absolute tolerance",
                      "1e-30",
                      Patterns::Double(0),
                      "Converged when the residual norm is below this value "
                      "[N].");
    prm.declare_entry("Check Jacobian",
                      "false",
                      Patterns::Bool(),
                      "At every Newton iteration with contact, compare each "
                      "column of the assembled contact Jacobian with central "
                      "finite differences of the contact residual and print "
                      "the largest relative difference (slow: two residual "
                      "evaluations per coupled unknown; for development and "
                      "tests).");
    prm.declare_entry("Tolerance between pairings",
                      "1e-6",
                      Patterns::Double(0, 1),
                      "Contact: relative residual at which a Newton solve "
                      "with settled statuses hands over to the next pairing "
                      "(geometric iteration) instead of converging to "
                      "'Relative tolerance' on a pairing that is about to "
                      "change. The last geometric iteration of a step always "
                      "ends at 'Relative tolerance'. 0: every solve to "
                      "'Relative tolerance'.");
    prm.declare_entry("Line search steps",
                      "2",
                      Patterns::Integer(0, 20),
                      "Backtracking line search on the residual norm: when "
                      "the full Newton update makes the residual grow, try "
                      "1/2, 1/4, ... of it, at most this many times, and take "
                      "the first that decreases the residual (if none does: "
                      "the one with the smallest residual; the full update if "
                      "no fraction beats it). Statuses follow each trial. "
                      "The evaluation of the next iterate is the trial of "
                      "the full update, so an update that decreases the "
                      "residual costs nothing extra. 0: full updates "
                      "always.");
    prm.leave_subsection();
  }


  void
  NewtonParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton");
    max_iterations     = prm.get_integer("Maximum iterations");
    relative_tolerance = prm.get_double("Relative tolerance");
    absolute_tolerance = prm.get_double("Absolute tolerance");
    check_jacobian     = prm.get_bool("Check Jacobian");
    line_search_steps  = prm.get_integer("Line search steps");
    tolerance_between_pairings = prm.get_double("Tolerance between pairings");
    prm.leave_subsection();
  }


  // ---------------------------------------------------------- Linear solver
  void
  LinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type",
                      "direct",
                      Patterns::Selection("direct|CG|GMRES"),
                      "direct: sparse LU (MUMPS by default); CG or GMRES: "
                      "Krylov method preconditioned by Trilinos ML AMG with "
                      "rigid-body modes. With contact: GMRES only, with a "
                      "block lower-triangular preconditioner (AMG on the "
                      "displacement block, the Schur complement D - C "
                      "diag(A)^-1 B^T of the multipliers factorised by the "
                      "'Direct solver').");
    prm.declare_entry("Direct solver",
                      "MUMPS",
                      Patterns::Selection("MUMPS|KLU"),
                      "Amesos package for Type = direct (Amesos_Mumps or "
                      "Amesos_Klu).");
    prm.declare_entry("Relative tolerance",
                      "1e-12",
                      Patterns::Double(0, 1),
                      "Krylov stopping tolerance relative to the right hand "
                      "side norm [-].");
    prm.declare_entry("Maximum iterations",
                      "2000",
                      Patterns::Integer(1),
                      "Krylov iteration cap.");
    prm.declare_entry("Rigid body modes",
                      "true",
                      Patterns::Bool(),
                      "Give AMG the rigid-body modes (translations and "
                      "rotations) as near-null space; false: translations "
                      "only.");
    prm.leave_subsection();
  }


  void
  LinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    const std::string t = prm.get("Type");
    type = t == "direct" ? LinearSolverType::direct :
           t == "CG"     ? LinearSolverType::cg :
                           LinearSolverType::gmres;
    direct_package =
      prm.get("Direct solver") == "MUMPS" ? "Amesos_Mumps" : "Amesos_Klu";
    relative_tolerance = prm.get_double("Relative tolerance");
    max_iterations     = prm.get_integer("Maximum iterations");
    rigid_body_modes   = prm.get_bool("Rigid body modes");
    prm.leave_subsection();
  }


  // ----------------------------------------------------------------- Output
  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory",
                      "results",
                      Patterns::DirectoryName(),
                      "Directory for VTU/PVTU, CSV and the echoed parameter "
                      "file; created if missing.");
    prm.declare_entry("Write VTU",
                      "true",
                      Patterns::Bool(),
                      "Write a VTU/PVTU solution file per load step.");
    prm.declare_entry("Write CSV",
                      "true",
                      Patterns::Bool(),
                      "Write the per-step statistics table as CSV.");
    prm.declare_entry("Timing summary",
                      "true",
                      Patterns::Bool(),
                      "Print the wall-time table at the end of the run.");
    prm.declare_entry("Verbosity",
                      "normal",
                      Patterns::Selection("quiet|normal|verbose"),
                      "quiet: summary only; normal: one block per load step; "
                      "verbose: every Newton iteration with its residuals.");
    prm.leave_subsection();
  }


  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory      = prm.get("Directory");
    write_vtu      = prm.get_bool("Write VTU");
    write_csv      = prm.get_bool("Write CSV");
    timing_summary = prm.get_bool("Timing summary");
    const std::string v = prm.get("Verbosity");
    verbosity = v == "quiet"  ? Verbosity::quiet :
                v == "normal" ? Verbosity::normal :
                                Verbosity::verbose;
    prm.leave_subsection();
  }


  // ------------------------------------------------------ Reference solution
  // --------------------------------------------------------------- Contact
  void
  ContactPairParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Slave boundary id",
                      "",
                      Patterns::List(Patterns::Integer(0, 255), 0),
                      "Boundary id(s) of the slave surface (one body): the "
                      "contact multipliers live on its nodes.");
    Obstacles::declare_master_parameters(prm);
    prm.declare_entry("Master boundary id",
                      "",
                      Patterns::List(Patterns::Integer(0, 255), 0),
                      "Boundary id(s) of the master surface for Master = "
                      "body.");
    prm.declare_entry("Obstacle motion",
                      "0; 0; 0",
                      Patterns::Anything(),
                      "Translation of a rigid obstacle from its position "
                      "at t = 0, as Dimension "
                      "expressions of t (and 'Function constants') "
                      "separated by ';' [m].");
    prm.declare_entry("Obstacle rotation",
                      "0",
                      Patterns::Anything(),
                      "Rotation of a rigid obstacle from its position at "
                      "t = 0 about 'Rotation centre', as expressions of t: "
                      "in 2D the angle [rad] (counterclockwise), in 3D the "
                      "rotation vector (axis times angle [rad], 3 "
                      "expressions separated by ';'). 0: none.");
    prm.declare_entry("Rotation centre",
                      "0, 0, 0",
                      point_pattern(),
                      "Centre of 'Obstacle rotation' at t = 0 [m]; it moves "
                      "with 'Obstacle motion'.");
    prm.declare_entry("Friction coefficient",
                      "0",
                      Patterns::Double(0),
                      "Coulomb coefficient mu [-]. 0: frictionless, and no "
                      "friction unknowns are created.");
    prm.declare_entry("Normal coefficient",
                      "1",
                      Patterns::Double(1e-300),
                      "Dimensionless factor c_n of the normal augmentation "
                      "rho_n = c_n E / h, with E the largest Young's modulus "
                      "of the slave cells (or of the master cells when the "
                      "master body is softer) and h the mean slave face "
                      "size. It "
                      "changes the convergence path, not the solution. With "
                      "'Penalty = true' it scales the penalty stiffness.");
    prm.declare_entry("Tangential coefficient",
                      "1",
                      Patterns::Double(1e-300),
                      "Dimensionless factor c_t of the friction augmentation "
                      "rho_t = c_t rho_n / (mu p_ref) [1/m], p_ref the RMS "
                      "contact pressure of the closed slave nodes at the "
                      "current iterate (1e-3 E before contact closes): a "
                      "sticking point then has a tangential stiffness of "
                      "about c_t rho_n. Like c_n it changes the convergence "
                      "path, not the solution.");
    prm.declare_entry("Gap offset",
                      "0",
                      Patterns::Double(),
                      "Constant g_0 added to the gap [m] (g > 0 means "
                      "interpenetration).");
  }


  void
  ContactPairParameters::parse_parameters(ParameterHandler &prm)
  {
    slave_ids  = to_unsigned(prm.get("Slave boundary id"));
    master_ids = to_unsigned(prm.get("Master boundary id"));
    master          = prm.get("Master");
    obstacle_motion   = split_expressions(prm.get("Obstacle motion"));
    obstacle_rotation = split_expressions(prm.get("Obstacle rotation"));
    rotation_centre   = to_doubles(prm.get("Rotation centre"));
    friction        = prm.get_double("Friction coefficient");
    rho_n_factor    = prm.get_double("Normal coefficient");
    rho_t_factor    = prm.get_double("Tangential coefficient");
    gap_offset      = prm.get_double("Gap offset");
  }


  void
  ContactParameters::declare_parameters(ParameterHandler &prm,
                                        const Counts &    counts)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry("Number of contact pairs",
                      "0",
                      Patterns::Integer(0, 64),
                      "Number of subsections 'Pair k', k = 1..N. 0: no "
                      "contact.");
    prm.declare_entry("Integration rule",
                      "mortar",
                      Patterns::Selection(
                        "nodal|gauss|simpson|newton-cotes|mortar"),
                      "Contact points on the slave faces (formulation.md 6): "
                      "nodal (the face nodes: trapezoid for Q1, Simpson for "
                      "Q2), gauss (Gauss-Legendre with 'Integration order' "
                      "points per direction), simpson (composite Simpson "
                      "with 'Integration order' panels per direction), "
                      "newton-cotes (closed Newton-Cotes of degree "
                      "'Integration order' = 1, 2, 4 or 6), mortar "
                      "(segment-based: each slave face cut by the master "
                      "faces it overlaps, 'Segment order' points on every "
                      "piece; passes the contact patch test on non-matching "
                      "meshes).");
    prm.declare_entry("Integration order",
                      "2",
                      Patterns::Integer(1, 12),
                      "Order of the gauss, simpson or newton-cotes rule.");
    prm.declare_entry("Segment order",
                      "0",
                      Patterns::Integer(0, 7),
                      "Mortar rule: Gauss points per segment (2D) or points "
                      "per direction of the triangle rule (3D), exact to "
                      "degree 2n-1. 0: the smallest order that integrates "
                      "psi x N^m exactly on flat faces (2D: degree+1, 3D: "
                      "2 degree+1).");
    prm.declare_entry("Normal",
                      "master",
                      Patterns::Selection("master|slave|average"),
                      "Contact normal: the master normal at the projection "
                      "(any rule), or the slave normal / the average of both "
                      "(nodal rule only).");
    prm.declare_entry("Initial status",
                      "penetrating",
                      Patterns::Selection("open|penetrating|closed"),
                      "Status of the contact points at the first Newton "
                      "iteration of the run: open, closed where penetrating "
                      "or touching (g >= 0, to 1e-8 of the face size), or "
                      "all closed (holds bodies that only "
                      "contact supports; open points are released by "
                      "Newton).");
    prm.declare_entry("Statuses",
                      "node",
                      Patterns::Selection("point|node"),
                      "Where the contact/free and the stick/slip statuses "
                      "are decided with the integration-point rules (gauss, "
                      "simpson, newton-cotes, mortar) on pairs with a meshed "
                      "master: per multiplier node (node: active nodes close "
                      "their weighted gap, free nodes carry lambda = 0; "
                      "sticking nodes close their weighted slip, slipping "
                      "nodes carry Lambda along it, free nodes Lambda = 0; "
                      "the converged solution does not depend on the "
                      "'Normal coefficient' nor on the 'Tangential "
                      "coefficient', as with the nodal rule), or per "
                      "contact point (point: the law of every integration "
                      "point for itself, theory.md). Node needs 'Friction "
                      "threshold = newton' on frictional pairs. The nodal "
                      "rule and rigid obstacles have one law per node "
                      "anyway.");
    prm.declare_entry("Friction threshold",
                      "newton",
                      Patterns::Selection("newton|frozen"),
                      "lambda_f = current lambda (newton, formulation.md 3.3) "
                      "or lambda of the previous geometric iteration "
                      "(frozen).");
    prm.declare_entry("Geometric linearisation",
                      "auto",
                      Patterns::Selection("auto|fixed point|newton"),
                      "Rigid obstacles: the projection, normal and tangents "
                      "frozen within each geometric iteration (fixed point, "
                      "formulation.md 7) or updated at every Newton iterate "
                      "with their derivatives in the Jacobian (newton: the "
                      "curvature of a ball or cylinder no longer costs "
                      "geometric iterations). auto: newton for frictionless "
                      "rigid pairs, fixed point for frictional ones (with "
                      "friction the rotating normal makes the stick/slip "
                      "search harder, doc/robustness.md) and for meshed "
                      "masters. newton: also frictional rigid pairs, and "
                      "frictionless meshed masters (except the mortar "
                      "rule): each point projected again onto its master "
                      "face at every iterate, with the derivatives of the "
                      "projection in the Jacobian; the geometric loop only "
                      "changes faces.");
    prm.declare_entry("Threshold coupling",
                      "true",
                      Patterns::Bool(),
                      "Keep K_fc, the derivative of the friction rows with "
                      "respect to lambda (exact Jacobian; code_aster drops "
                      "it).");
    prm.declare_entry("Penalty",
                      "false",
                      Patterns::Bool(),
                      "Penalty variant of the normal law: the contact force "
                      "is rho_n g; lambda is post-processed.");
    prm.declare_entry("Projection tolerance",
                      "0.05",
                      Patterns::Double(0),
                      "A projection outside a master face by at most this "
                      "fraction of the face's parameter range is accepted "
                      "(closest of the candidates).");
    prm.declare_entry("Geometric tolerance",
                      "0.01",
                      Patterns::Double(0),
                      "The geometric loop (re-pairing) stops when the "
                      "largest displacement change since the last pairing "
                      "is at most this fraction of the step's displacement "
                      "increment.");
    prm.declare_entry("Maximum geometric iterations",
                      "10",
                      Patterns::Integer(1, 1000),
                      "Cap of the geometric loop; reaching it fails the step "
                      "(which is then cut).");
    prm.declare_entry("Freeze after cycles",
                      "3",
                      Patterns::Integer(0, 100),
                      "Anti-cycling (formulation.md 8): a contact point "
                      "whose status returns to the one it had two Newton "
                      "iterates before (stick/slip/stick, contact/free/"
                      "contact, slip direction reversed and back) this many "
                      "times in one Newton solve is frozen: kept in contact, "
                      "or kept slipping in its last slip direction. A frozen "
                      "point that the plain law contradicts at convergence "
                      "is released and Newton goes on. Across pairings "
                      "(geometric loop), a point back at its converged "
                      "status of two pairings before keeps one status, and "
                      "a point back on its master face of two pairings "
                      "before stays on that face, for the rest of the load "
                      "step. 0: never freeze.");
    prm.declare_entry(
      "Release extrapolation",
      "true",
      Patterns::Bool(),
      "Active-set search on frictionless pairs (doc/robustness.md, "
      "'Release extrapolation'): while a contact zone only shrinks, a "
      "point (or multiplier node) still in compression whose mirror image "
      "across its nearest point that went into tension lies in that "
      "tension band is opened for the next solve too (the band would "
      "halve per solve otherwise): at most as many as the band holds and "
      "half of those in compression, the nearest first; one that closes "
      "again is not opened early again in that Newton solve. The "
      "converged state is unchanged. false: plain primal-dual active set.");
    prm.declare_entry(
      "Pairing at status changes",
      "false",
      Patterns::Bool(),
      "Frictionless pairs with a meshed master and a point rule (not "
      "mortar): pair again at every Newton iterate whose statuses "
      "changed, before its solve (that iterate needs a solve anyway), so "
      "that the pairing follows the active-set search and the geometric "
      "loop starts from a pairing at most one solve old (one solve less "
      "per step, doc/robustness.md). The pairing accepted then depends on "
      "the path of the search, within the 'Geometric tolerance' (p0 "
      "differs by 2e-4 across the Normal coefficient), and at c_n = 1e6 "
      "the statuses chatter. false: the pairing is renewed only between "
      "Newton solves (formulation.md 7).");
    for (unsigned int k = 1; k <= counts.n_pairs; ++k)
      {
        prm.enter_subsection("Pair " + std::to_string(k));
        ContactPairParameters::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  void
  ContactParameters::parse_parameters(ParameterHandler &prm,
                                      const Counts &    counts)
  {
    prm.enter_subsection("Contact");
    const std::string r = prm.get("Integration rule");
    rule  = r == "nodal"   ? IntegrationRule::nodal :
            r == "gauss"   ? IntegrationRule::gauss :
            r == "simpson" ? IntegrationRule::simpson :
            r == "mortar"  ? IntegrationRule::mortar :
                             IntegrationRule::newton_cotes;
    order         = prm.get_integer("Integration order");
    segment_order = prm.get_integer("Segment order");
    const std::string n = prm.get("Normal");
    normal = n == "master" ? NormalChoice::master :
             n == "slave"  ? NormalChoice::slave :
                             NormalChoice::average;
    const std::string i = prm.get("Initial status");
    initial_status = i == "open"        ? InitialStatus::open :
                     i == "penetrating" ? InitialStatus::penetrating :
                                          InitialStatus::closed;
    node_status              = prm.get("Statuses") == "node";
    frozen_threshold         = prm.get("Friction threshold") == "frozen";
    newton_geometry = prm.get("Geometric linearisation") != "fixed point";
    newton_geometry_all =
      prm.get("Geometric linearisation") == "newton";
    threshold_coupling       = prm.get_bool("Threshold coupling");
    penalty                  = prm.get_bool("Penalty");
    projection_tolerance     = prm.get_double("Projection tolerance");
    geometric_tolerance      = prm.get_double("Geometric tolerance");
    max_geometric_iterations = prm.get_integer("Maximum geometric iterations");
    freeze_after_cycles      = prm.get_integer("Freeze after cycles");
    release_extrapolation    = prm.get_bool("Release extrapolation");
    pairing_at_status_changes = prm.get_bool("Pairing at status changes");
    pairs.resize(counts.n_pairs);
    for (unsigned int k = 0; k < counts.n_pairs; ++k)
      {
        prm.enter_subsection("Pair " + std::to_string(k + 1));
        pairs[k].parse_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
    // The statuses per node apply to pairs with a meshed master under an
    // integration-point rule; with friction they need the Newton threshold.
    for (unsigned int k = 0; k < pairs.size(); ++k)
      if (node_status && frozen_threshold && rule != IntegrationRule::nodal &&
          pairs[k].master_is_body() && pairs[k].friction > 0)
        throw InputError(
          "subsection 'Contact', parameter 'Friction threshold' = frozen: "
          "pair " + std::to_string(k + 1) + " (friction on a meshed master, "
          "integration rule '" + r + "') decides its statuses per node "
          "('Statuses = node'), which needs the Newton threshold: set "
          "'Friction threshold = newton', or 'Statuses = point'.");
  }


  // ------------------------------------------------------------- Reference
  void
  ReferenceParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Reference solution");
    prm.declare_entry("Displacement",
                      "",
                      Patterns::Anything(),
                      "Exact displacement [m] for verification: Dimension "
                      "expressions separated by ';' in x, y, z, t. Empty: "
                      "none. The run prints the relative L2 error.");
    prm.declare_entry("Stress",
                      "",
                      Patterns::Anything(),
                      "Exact Cauchy stress [Pa]: Dimension^2 expressions, "
                      "row by row, separated by ';'. Empty: none. The run "
                      "prints the largest relative error at quadrature "
                      "points.");
    prm.declare_entry("Tolerance",
                      "1e-10",
                      Patterns::Double(0),
                      "Relative error below which the comparison is "
                      "reported as PASS.");
    prm.declare_entry("Maximum contact pressure",
                      "0",
                      Patterns::Double(0),
                      "Reference for the largest contact pressure p0 = "
                      "max(-lambda) at the contact points [Pa]; 0: not "
                      "checked.");
    prm.declare_entry("Pressure tolerance",
                      "0.02",
                      Patterns::Double(0),
                      "Relative tolerance of the p0 check.");
    prm.declare_entry("Contact half-width",
                      "0",
                      Patterns::Double(0),
                      "Reference contact half-width a (or radius in 3D) [m], "
                      "measured from 'Contact centre'; 0: not checked. The "
                      "computed a is midway between the farthest closed "
                      "point and the nearest open point beyond it.");
    prm.declare_entry("Contact centre",
                      "0, 0, 0",
                      point_pattern(),
                      "Centre of the contact zone for the half-width [m].");
    prm.declare_entry("Half-width tolerance",
                      "0",
                      Patterns::Double(0),
                      "Absolute tolerance of the half-width check [m] "
                      "(typically one slave element).");
    prm.declare_entry("Contact pressure",
                      "",
                      Patterns::Anything(),
                      "Exact contact pressure p(x, y, z) [Pa] on the slave "
                      "surface; empty: not checked. The run prints the "
                      "relative L2 error over the contact points.");
    prm.declare_entry("Pressure L2 tolerance",
                      "0.05",
                      Patterns::Double(0),
                      "Tolerance of the relative L2 pressure error.");
    prm.declare_entry("Friction force ratio",
                      "0",
                      Patterns::Double(0),
                      "Reference for |F_t| / |F_n| of the contact force on "
                      "the slave of pair 1, F_n its component along 'Friction "
                      "ratio normal' and F_t the rest (= mu in full sliding); "
                      "0: not checked.");
    prm.declare_entry("Friction ratio normal",
                      "0, 1, 0",
                      point_pattern(),
                      "Direction of the normal force for 'Friction force "
                      "ratio' (normalised).");
    prm.declare_entry("Friction ratio frame",
                      "global",
                      Patterns::Selection("global|contact"),
                      "global: F_n and F_t are the parts of the total contact "
                      "force along 'Friction ratio normal' and across it "
                      "(a flat master). contact: F_n = sum of w |f . n| and "
                      "F_t = sum of w |P f| over the contact points, each in "
                      "its own contact frame (a curved master, e.g. an "
                      "ironing die, whose total force also carries the "
                      "tilted normal pressures).");
    prm.declare_entry("Force variation tolerance",
                      "0",
                      Patterns::Double(0),
                      "If > 0: at the last step, the largest change of the "
                      "total contact force of pair 1 between consecutive "
                      "steps with t >= 'Friction ratio from time', relative "
                      "to its mean magnitude over these steps, is checked "
                      "against this value (no spikes from status "
                      "chattering).");
    prm.declare_entry(
      "Stick zone",
      "none",
      Patterns::Selection("none|cattaneo-mindlin"),
      "cattaneo-mindlin: at every step with a tangential force, the half-width "
      "c of the stick zone of pair 1 (around 'Contact centre') is checked "
      "against Cattaneo-Mindlin partial slip under a constant normal force P, "
      "c = a (1 - |Q|/(mu P))^(1/m) while Q grows from 0 (first loading) and "
      "c = a (1 - |Q - Q*|/(2 mu P))^(1/m) after the tangential force Q "
      "turned at Q* (Masing), m = 2 in 2D (cylinder) and 3 in 3D (sphere); a "
      "is the measured contact half-width, P and Q the contact force of pair "
      "1 along 'Friction ratio normal' and across it, tolerance 'Half-width "
      "tolerance'. 2D: a and c midway between the farthest point inside "
      "(closed; stick) and the nearest point outside beyond it. 3D: "
      "area-equivalent radii, a = sqrt(A_closed / pi) and c = "
      "sqrt(A_stick / pi) with A the summed weights of the closed and of the "
      "stick points. Valid for elastically similar bodies (no coupling of the "
      "normal and tangential problems).");
    prm.declare_entry("Friction ratio from time",
                      "0",
                      Patterns::Double(0),
                      "The friction force ratio is checked at the steps "
                      "with t >= this time (steady sliding).");
    prm.declare_entry("Friction ratio tolerance",
                      "0.01",
                      Patterns::Double(0),
                      "Relative tolerance of the friction force ratio check.");
    prm.declare_entry("Point values",
                      "",
                      Patterns::Anything(),
                      "Displacement values to check, separated by ';', each "
                      "'x, y[, z] : component : value[ : tolerance]' with "
                      "component x, y or z and an optional relative "
                      "tolerance of its own (else 'Point value tolerance'), "
                      "e.g. '0.00125, 0 : x : 2.72e-5 : 0.01'.");
    prm.declare_entry("Point value tolerance",
                      "0.05",
                      Patterns::Double(0),
                      "Relative tolerance of the point value checks.");
    prm.declare_entry("Action-reaction tolerance",
                      "0",
                      Patterns::Double(0),
                      "Check after each step, for every contact pair, that "
                      "the force the displacement rows carry (what the "
                      "master receives) equals the force the multipliers "
                      "stand for, recomputed from them alone (the traction "
                      "lambda n + mu lambda T Lambda): their difference over "
                      "the larger must be below this value. The two differ "
                      "by the augmentation terms, which vanish at a "
                      "converged state, and by any error of the contact law "
                      "in the rows. 0: not checked.");
    prm.declare_entry("Slip law tolerance",
                      "0",
                      Patterns::Double(0),
                      "Check after each step, for every pair with friction, "
                      "Coulomb's law where the contact slips: at every "
                      "slipping contact point (statuses per point) or "
                      "slipping multiplier node (statuses per node: its "
                      "force against its weighted slip) the friction force "
                      "on the slave opposes the slip increment, and "
                      "|f_t| = mu |f_n| within this relative tolerance. A "
                      "step without slipping point says so. 0: not "
                      "checked.");
    prm.declare_entry("Contact force",
                      "",
                      Patterns::Anything(),
                      "Reference for the total contact force on the master "
                      "of pair 1 [N; N/m in 2D; axisymmetric: over the "
                      "circumference], Dimension expressions of t separated "
                      "by ';' (e.g. the applied load where the scene fixes "
                      "it); a component written '*' is left out (e.g. the "
                      "horizontal force of a half model). Empty: not "
                      "checked.");
    prm.declare_entry("Contact force from time",
                      "0",
                      Patterns::Double(),
                      "The 'Contact force' check runs at the steps with t >= "
                      "this time (e.g. the steady phase of a load path).");
    prm.declare_entry("Contact force tolerance",
                      "1e-3",
                      Patterns::Double(0),
                      "Relative tolerance of the 'Contact force' check: "
                      "|F - F_ref| / |F_ref|.");
    prm.declare_entry("Gap tolerance",
                      "0",
                      Patterns::Double(0),
                      "Check after each step that every closed contact point "
                      "has |gap| below this value [m] and no open point "
                      "penetrates by more; at least one point must be "
                      "closed. 0: not checked.");
    prm.leave_subsection();
  }


  void
  ReferenceParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Reference solution");
    displacement = split_expressions(prm.get("Displacement"));
    stress       = split_expressions(prm.get("Stress"));
    tolerance    = prm.get_double("Tolerance");
    max_pressure           = prm.get_double("Maximum contact pressure");
    pressure_tolerance     = prm.get_double("Pressure tolerance");
    half_width             = prm.get_double("Contact half-width");
    contact_centre         = to_doubles(prm.get("Contact centre"));
    half_width_tolerance   = prm.get_double("Half-width tolerance");
    contact_pressure       = prm.get("Contact pressure");
    pressure_l2_tolerance  = prm.get_double("Pressure L2 tolerance");
    point_value_tolerance  = prm.get_double("Point value tolerance");
    action_reaction_tolerance = prm.get_double("Action-reaction tolerance");
    slip_law_tolerance        = prm.get_double("Slip law tolerance");
    contact_force             = split_expressions(prm.get("Contact force"));
    contact_force_tolerance   = prm.get_double("Contact force tolerance");
    contact_force_from        = prm.get_double("Contact force from time");
    gap_tolerance           = prm.get_double("Gap tolerance");
    friction_ratio         = prm.get_double("Friction force ratio");
    friction_ratio_normal  = to_doubles(prm.get("Friction ratio normal"));
    friction_ratio_tolerance = prm.get_double("Friction ratio tolerance");
    friction_ratio_from      = prm.get_double("Friction ratio from time");
    friction_ratio_contact_frame = prm.get("Friction ratio frame") == "contact";
    force_variation_tolerance = prm.get_double("Force variation tolerance");
    cattaneo_mindlin = prm.get("Stick zone") == "cattaneo-mindlin";
    point_values.clear();
    for (const auto &entry : split_expressions(prm.get("Point values")))
      {
        const auto parts = Utilities::split_string_list(entry, ':');
        if ((parts.size() != 3 && parts.size() != 4) ||
            (parts[1] != "x" && parts[1] != "y" && parts[1] != "z"))
          throw InputError("subsection 'Reference solution', parameter "
                           "'Point values': cannot read '" +
                           entry +
                           "'. Write 'x, y[, z] : component : value[ : "
                           "tolerance]' with component x, y or z.");
        PointValue v;
        v.point     = to_doubles(parts[0]);
        v.component = component_index(parts[1]);
        v.value     = Utilities::string_to_double(parts[2]);
        v.tolerance = parts.size() == 4 ?
                        Utilities::string_to_double(parts[3]) :
                        point_value_tolerance;
        point_values.push_back(v);
      }
    prm.leave_subsection();
  }


  // ------------------------------------------------- Adaptive refinement
  void
  AdaptivityParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Adaptive refinement");
    prm.declare_entry("Cycles",
                      "0",
                      Patterns::Integer(0, 20),
                      "Refine-and-resolve cycles after an adapted load step "
                      "(0: no adaptivity). Each cycle marks cells by the "
                      "Kelly indicator of the displacement and by the "
                      "active contact zone, refines, transfers the converged "
                      "state and the state at the start of the step "
                      "(displacements and multipliers) to the new mesh and "
                      "solves the step again (with 'Steps = between': "
                      "refinement cycles between two steps, no solve).");
    prm.declare_entry("Steps",
                      "last",
                      Patterns::Selection("last|every|between"),
                      "Which load steps are adapted: the last one only "
                      "(a mesh for the final state, e.g. Hertz); every "
                      "one, solved again on its adapted mesh (the mesh "
                      "follows a moving contact zone; cells are also "
                      "coarsened if 'Coarsening fraction' > 0); or between "
                      "steps: the mesh is adapted to each converged step "
                      "after its output and the next step starts on it "
                      "from the transferred state (one solve per step, "
                      "the mesh one step behind the contact zone).");
    prm.declare_entry("Refinement fraction",
                      "0.1",
                      Patterns::Double(0, 1),
                      "Fraction of the active cells, by count, with the "
                      "largest Kelly indicator that are refined per cycle.");
    prm.declare_entry("Coarsening fraction",
                      "0",
                      Patterns::Double(0, 1),
                      "Fraction of the active cells, by count, with the "
                      "smallest Kelly indicator that are coarsened per "
                      "cycle (never cells of the contact zone).");
    prm.declare_entry("Refine contact zone",
                      "true",
                      Patterns::Bool(),
                      "Also refine every cell with a face in the active "
                      "contact zone: slave faces with a point in contact "
                      "and the master faces those points are paired with. "
                      "The Kelly indicator alone ignores the contact "
                      "traction, which acts on boundary faces.");
    prm.declare_entry("Maximum level",
                      "0",
                      Patterns::Integer(0, 30),
                      "Cells at this refinement level (counted from the "
                      "coarse mesh, global and local refinements included) "
                      "are not refined further. 0: the finest level of the "
                      "initial mesh plus 'Cycles', so that with 'Steps = "
                      "every' the contact zone stays 'Cycles' levels finer "
                      "than the initial mesh while it moves.");
    prm.leave_subsection();
  }


  void
  AdaptivityParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Adaptive refinement");
    cycles              = prm.get_integer("Cycles");
    const std::string s = prm.get("Steps");
    steps = s == "every"   ? Steps::every :
            s == "between" ? Steps::between :
                             Steps::last;
    refinement_fraction = prm.get_double("Refinement fraction");
    coarsening_fraction = prm.get_double("Coarsening fraction");
    refine_contact_zone = prm.get_bool("Refine contact zone");
    maximum_level       = prm.get_integer("Maximum level");
    prm.leave_subsection();
    if (refinement_fraction + coarsening_fraction > 1)
      throw InputError(
        "subsection 'Adaptive refinement': 'Refinement fraction' + "
        "'Coarsening fraction' = " +
        std::to_string(refinement_fraction + coarsening_fraction) +
        " is more than 1 (the share of the cells marked). Lower one of "
        "them.");
  }


  // ------------------------------------------------------------- Everything
  void
  Parameters::declare_parameters(ParameterHandler &prm, const Counts &counts)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Space dimension: 2 (plane strain) or 3.");
    prm.declare_entry("Axisymmetric",
                      "false",
                      Patterns::Bool(),
                      "Dimension = 2 only: the mesh is a meridian section, x "
                      "the radius r >= 0 and y the axis z. Volume and "
                      "surface integrals carry 2 pi r and the hoop strain "
                      "u_r / r is included, so forces and reactions are "
                      "totals over the full circumference [N]. Put a "
                      "Dirichlet condition on x (= u_r = 0) on the faces on "
                      "the axis r = 0.");
    prm.enter_subsection("Finite element");
    prm.declare_entry("Degree",
                      "1",
                      Patterns::Integer(1, 3),
                      "Polynomial degree of the displacement (1: Q1, 2: Q2).");
    prm.declare_entry(
      "Volumetric strain",
      "full",
      Patterns::Selection("full|projected"),
      "Volumetric strain theta = tr(eps) in the term lambda theta^2 of the "
      "bulk energy: full (pointwise) or projected (B-bar: in each cell the "
      "L2 projection of theta onto polynomials of one degree less, a "
      "constant for Q1, the mean dilatation). Pure-displacement elements "
      "lock as nu -> 0.5 (B2 Hertz at nu = 0.4999: p0 32 % high in 2D, 2.5 "
      "times Hertz in 3D); projected removes the locking (0.5 % and 3 %, "
      "doc/robustness.md). The stresses written and checked take their "
      "volumetric part from the projection, as the equilibrium does.");
    prm.leave_subsection();
    GeometryParameters::declare_parameters(prm, counts);
    prm.enter_subsection("Materials");
    prm.declare_entry("Number of materials",
                      "1",
                      Patterns::Integer(1, 64),
                      "Number of subsections 'Material k', k = 1..N.");
    for (unsigned int k = 1; k <= counts.n_materials; ++k)
      {
        prm.enter_subsection("Material " + std::to_string(k));
        MaterialParameters::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
    BoundaryConditionParameters::declare_parameters(prm, counts);
    ContactParameters::declare_parameters(prm, counts);
    LoadSteppingParameters::declare_parameters(prm);
    AdaptivityParameters::declare_parameters(prm);
    NewtonParameters::declare_parameters(prm);
    LinearSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm);
    ReferenceParameters::declare_parameters(prm);
  }


  void
  Parameters::parse_parameters(ParameterHandler &prm, const Counts &counts)
  {
    dimension    = prm.get_integer("Dimension");
    axisymmetric = prm.get_bool("Axisymmetric");
    prm.enter_subsection("Finite element");
    fe_degree = prm.get_integer("Degree");
    projected_volumetric_strain =
      prm.get("Volumetric strain") == "projected";
    prm.leave_subsection();
    geometry.parse_parameters(prm, counts);
    prm.enter_subsection("Materials");
    materials.resize(counts.n_materials);
    for (unsigned int k = 0; k < counts.n_materials; ++k)
      {
        prm.enter_subsection("Material " + std::to_string(k + 1));
        materials[k].parse_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
    boundary_conditions.parse_parameters(prm, counts);
    contact.parse_parameters(prm, counts);
    load_stepping.parse_parameters(prm);
    adaptivity.parse_parameters(prm);
    newton.parse_parameters(prm);
    linear_solver.parse_parameters(prm);
    output.parse_parameters(prm);
    reference.parse_parameters(prm);
    check_consistency();
    check_expressions(*this);
  }


  void
  Parameters::check_consistency() const
  {
    const unsigned int dim = dimension;
    for (unsigned int k = 0; k < boundary_conditions.dirichlet.size(); ++k)
      {
        const auto &      d = boundary_conditions.dirichlet[k];
        const std::string where =
          "subsection 'Boundary conditions/Dirichlet " + std::to_string(k + 1) +
          "'";
        for (const unsigned int c : d.components)
          if (c >= dim)
            throw InputError(where +
                             ", parameter 'Components': component z does not "
                             "exist for Dimension = 2. Use x and/or y.");
        // A component listed twice would take the value of its first
        // expression only, silently.
        for (unsigned int i = 0; i < d.components.size(); ++i)
          if (std::count(d.components.begin(),
                         d.components.begin() + i,
                         d.components[i]))
            throw InputError(where + ", parameter 'Components': component " +
                             std::string(1, "xyz"[d.components[i]]) +
                             " is listed twice. List each component once, "
                             "with one expression per listed component in "
                             "'Values'.");
        if (d.values.size() != d.components.size())
          throw InputError(where + ", parameter 'Values': " +
                           std::to_string(d.values.size()) +
                           " expression(s) for " +
                           std::to_string(d.components.size()) +
                           " component(s). Give one expression per listed "
                           "component, separated by ';'.");
        if (!d.at_point.empty() && d.at_point.size() != dim)
          throw InputError(where + ", parameter 'At point': give " +
                           std::to_string(dim) + " coordinates.");
      }
    for (unsigned int k = 0; k < boundary_conditions.neumann.size(); ++k)
      {
        const auto &       n = boundary_conditions.neumann[k];
        const unsigned int expected =
          n.type == NeumannType::traction ? dim : 1;
        if (n.values.size() != expected)
          throw InputError("subsection 'Boundary conditions/Neumann " +
                           std::to_string(k + 1) + "', parameter 'Values': " +
                           std::to_string(n.values.size()) +
                           " expression(s) given, " + std::to_string(expected) +
                           " expected for this Type and Dimension.");
      }
    if (boundary_conditions.body_force.size() < dim)
      throw InputError("subsection 'Boundary conditions', parameter 'Body "
                       "force': give at least Dimension expressions separated "
                       "by ';'.");
    if (!reference.displacement.empty() && reference.displacement.size() != dim)
      throw InputError("subsection 'Reference solution', parameter "
                       "'Displacement': give Dimension expressions.");
    if (!reference.contact_force.empty() &&
        reference.contact_force.size() != dim)
      throw InputError("subsection 'Reference solution', parameter 'Contact "
                       "force': give Dimension expressions of t separated by "
                       "';' (the force components), or leave it empty.");
    if (!reference.contact_force.empty() && contact.pairs.empty())
      throw InputError("subsection 'Reference solution', parameter 'Contact "
                       "force': the scene has no contact pair. Remove the "
                       "reference or declare a pair in subsection 'Contact'.");
    if (!reference.stress.empty() && reference.stress.size() != dim * dim)
      throw InputError("subsection 'Reference solution', parameter 'Stress': "
                       "give Dimension^2 expressions (row by row).");
    std::map<unsigned int, unsigned int> seen;
    for (unsigned int k = 0; k < materials.size(); ++k)
      if (!seen.emplace(materials[k].material_id, k).second)
        throw InputError("subsection 'Materials/Material " +
                         std::to_string(k + 1) +
                         "', parameter 'Material id': id " +
                         std::to_string(materials[k].material_id) +
                         " is already used by Material " +
                         std::to_string(seen[materials[k].material_id] + 1) +
                         ".");
    for (unsigned int b = 0; b < geometry.bodies.size(); ++b)
      if (geometry.bodies[b].shape == BodyShape::file &&
          geometry.bodies[b].mesh_file.empty())
        throw InputError("subsection 'Geometry/Body " + std::to_string(b + 1) +
                         "', parameter 'Mesh file': Shape = file needs a mesh "
                         "file name.");

    // Contact.
    const auto &c = contact;
    if (c.rule == IntegrationRule::newton_cotes && c.order != 1 &&
        c.order != 2 && c.order != 4 && c.order != 6)
      throw InputError("subsection 'Contact', parameter 'Integration order': "
                       "the newton-cotes rule exists for orders 1, 2, 4 and 6 "
                       "(trapezoid, Simpson, Milne, Weddle), not " +
                       std::to_string(c.order) + ".");
    if (c.normal != NormalChoice::master && c.rule != IntegrationRule::nodal)
      throw InputError("subsection 'Contact', parameter 'Normal': the slave "
                       "and average normals are defined at nodes and need "
                       "'Integration rule = nodal'. Set 'Normal = master' or "
                       "'Integration rule = nodal'.");
    if (axisymmetric && dimension != 2)
      throw InputError("parameter 'Axisymmetric': an axisymmetric model is a "
                       "2D meridian section; set 'Dimension = 2' or "
                       "'Axisymmetric = false'.");
    if (!c.pairs.empty() && fe_degree > 2)
      throw InputError("subsection 'Finite element', parameter 'Degree': "
                       "contact supports Q1 and Q2 slave and master faces; "
                       "set 'Degree = 1' or '2' when 'Contact/Number of "
                       "contact pairs' > 0 (Q3 is available without "
                       "contact).");
    if (!c.pairs.empty() && linear_solver.type == LinearSolverType::cg)
      throw InputError("subsection 'Linear solver', parameter 'Type': contact "
                       "systems (u | lambda | Lambda) are unsymmetric "
                       "saddle-point systems, which CG cannot solve; set "
                       "'Type = GMRES' (block preconditioner) or 'direct' "
                       "when 'Contact/Number of contact pairs' > 0.");
    for (unsigned int k = 0; k < c.pairs.size(); ++k)
      {
        const auto &      p = c.pairs[k];
        const std::string where =
          "subsection 'Contact/Pair " + std::to_string(k + 1) + "'";
        if (p.slave_ids.empty())
          throw InputError(where + ", parameter 'Slave boundary id': give "
                                   "the boundary id(s) of the slave surface.");
        if (p.master_is_body())
          {
            if (p.master_ids.empty())
              throw InputError(where + ", parameter 'Master boundary id': "
                                       "Master = body needs the boundary "
                                       "id(s) of the master surface.");
            for (const auto id : p.master_ids)
              if (std::count(p.slave_ids.begin(), p.slave_ids.end(), id))
                throw InputError(
                  where + ": boundary id " + std::to_string(id) +
                  " is both slave and master. The slave and master surfaces "
                  "must be different boundaries (of different bodies).");
          }
        else
          {
            if (p.obstacle_motion.size() < dim)
              throw InputError(where + ", parameter 'Obstacle motion': give " +
                               std::to_string(dim) +
                               " expressions separated by ';'.");
            const bool no_rotation = p.obstacle_rotation.size() == 1 &&
                                     Utilities::trim(p.obstacle_rotation[0]) ==
                                       "0";
            if (!no_rotation &&
                p.obstacle_rotation.size() != (dim == 2 ? 1u : 3u))
              throw InputError(
                where + ", parameter 'Obstacle rotation': give " +
                (dim == 2 ? std::string("the angle [rad] as one expression "
                                        "of t") :
                            std::string("the rotation vector (axis times "
                                        "angle [rad]) as 3 expressions of t "
                                        "separated by ';'")) +
                ", or 0.");
            if (p.rotation_centre.size() < dim)
              throw InputError(where + ", parameter 'Rotation centre': give " +
                               std::to_string(dim) + " coordinates.");
          }
      }
  }


  // ------------------------------------------------------------ File reading
  namespace
  {
    // The subsection path that is open at line @p line_no of @p text.
    std::string
    subsection_at_line(const std::string &text, const unsigned int line_no)
    {
      std::istringstream       in(text);
      std::vector<std::string> stack;
      std::string              line;
      for (unsigned int n = 1; n < line_no && std::getline(in, line); ++n)
        {
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (line.rfind("subsection ", 0) == 0)
            stack.push_back(Utilities::trim(line.substr(11)));
          else if (line == "end" && !stack.empty())
            stack.pop_back();
        }
      std::string path;
      for (const auto &s : stack)
        path += (path.empty() ? "" : "/") + s;
      return path.empty() ? "top level" : "subsection '" + path + "'";
    }

    // Turn deal.II's parse exception into one message naming line and
    // subsection, with a hint for the cases users hit most.
    std::string
    explain_parse_error(const ExceptionBase &           e,
                        const std::string &             text,
                        const std::string &             source,
                        const std::vector<std::string> &origins)
    {
      std::ostringstream info;
      e.print_info(info);
      std::string message = info.str();
      // print_info() indents and wraps; put it on one line.
      message = std::regex_replace(message, std::regex("\\s+"), " ");
      message = Utilities::trim(message);

      std::smatch m;
      std::string where = source;
      if (std::regex_search(message, m, std::regex("Line <(\\d+)>")))
        {
          const unsigned int line_no = std::stoi(m[1]);
          where = (line_no >= 1 && line_no <= origins.size() ?
                     origins[line_no - 1] :
                     source + ", line " + std::string(m[1])) +
                  " (" + subsection_at_line(text, line_no) + ")";
        }
      message = std::regex_replace(message,
                                   std::regex("Line <\\d+> of file <[^>]*>: "),
                                   "");
      std::string hint;
      if (message.find("No entry with name") != std::string::npos ||
          message.find("has not been declared") != std::string::npos ||
          message.find("No such subsection") != std::string::npos ||
          message.find("not been declared") != std::string::npos)
        hint = " Check the spelling against 'signorini --print-parameters'; "
               "numbered subsections (Body k, Material k, Dirichlet k, "
               "Neumann k, Pair k) must not exceed their 'Number of ...' entry.";
      else if (message.find("does not match the given pattern") !=
               std::string::npos)
        hint = message.find("named Dimension") != std::string::npos ?
                 " Set Dimension = 2 (plane strain) or 3." :
                 " Change the value to one the pattern allows.";
      return "Error in " + where + ": " + message + hint;
    }

    Parameters
    parse_text(const std::string &             text,
               const std::string &             source,
               ParameterHandler &              prm,
               const std::vector<std::string> &origins = {})
    {
      check_parameter_text(text, source);
      // Pre-pass: only the counts, ignoring everything else.
      Counts counts;
      {
        ParameterHandler pre;
        pre.declare_entry("Dimension", "2", Patterns::Anything());
        pre.enter_subsection("Geometry");
        pre.declare_entry("Number of bodies", "1", Patterns::Integer(1, 16));
        pre.leave_subsection();
        pre.enter_subsection("Materials");
        pre.declare_entry("Number of materials", "1", Patterns::Integer(1, 64));
        pre.leave_subsection();
        pre.enter_subsection("Boundary conditions");
        pre.declare_entry("Number of Dirichlet conditions",
                          "1",
                          Patterns::Integer(0, 64));
        pre.declare_entry("Number of Neumann conditions",
                          "0",
                          Patterns::Integer(0, 64));
        pre.leave_subsection();
        pre.enter_subsection("Contact");
        pre.declare_entry("Number of contact pairs",
                          "0",
                          Patterns::Integer(0, 64));
        pre.leave_subsection();
        try
          {
            pre.parse_input_from_string(text, "", true);
          }
        catch (const ExceptionBase &e)
          {
            throw InputError(explain_parse_error(e, text, source, origins));
          }
        pre.enter_subsection("Geometry");
        counts.n_bodies = pre.get_integer("Number of bodies");
        pre.leave_subsection();
        pre.enter_subsection("Materials");
        counts.n_materials = pre.get_integer("Number of materials");
        pre.leave_subsection();
        pre.enter_subsection("Boundary conditions");
        counts.n_dirichlet = pre.get_integer("Number of Dirichlet conditions");
        counts.n_neumann   = pre.get_integer("Number of Neumann conditions");
        pre.leave_subsection();
        pre.enter_subsection("Contact");
        counts.n_pairs = pre.get_integer("Number of contact pairs");
        pre.leave_subsection();
      }

      Parameters::declare_parameters(prm, counts);
      try
        {
          prm.parse_input_from_string(text, "", false);
        }
      catch (const ExceptionBase &e)
        {
          throw InputError(explain_parse_error(e, text, source, origins));
        }
      check_numbered_subsections(text, counts, source);
      Parameters parameters;
      parameters.parse_parameters(prm, counts);
      return parameters;
    }
  } // namespace


  namespace
  {
    // The directory of @p filename ("." for a bare name).
    std::string
    directory_of(const std::string &filename)
    {
      const auto slash = filename.find_last_of('/');
      return slash == std::string::npos ? "." : filename.substr(0, slash);
    }

    // ParameterHandler's 'include <file>' lines replaced by the file's text,
    // recursively, with relative paths taken from the directory of the file
    // that includes it (as 'Mesh file'; ParameterHandler itself would take
    // them from the working directory). @p origins gets "file 'f', line n"
    // for every line of the result, for messages.
    std::string
    expand_includes(const std::string &       text,
                    const std::string &       filename,
                    std::vector<std::string> &origins,
                    const unsigned int        depth = 0)
    {
      std::istringstream in(text);
      std::string        line, result;
      for (unsigned int n = 1; std::getline(in, line); ++n)
        {
          const std::string where =
            "parameter file '" + filename + "', line " + std::to_string(n);
          const std::string code =
            Utilities::trim(line.substr(0, line.find('#')));
          if (code.rfind("include", 0) != 0 ||
              (code.size() > 7 && !std::isspace(code[7])))
            {
              result += line + "\n";
              origins.push_back(where);
              continue;
            }
          std::string name = Utilities::trim(code.substr(7));
          if (name.empty())
            throw InputError(where + ": 'include' needs a file name.");
          if (depth >= 8)
            throw InputError(where + ": 'include' nested deeper than 8 "
                                     "files (does a file include itself?).");
          if (name[0] != '/')
            name = directory_of(filename) + "/" + name;
          std::ifstream included(name);
          if (!included || std::filesystem::is_directory(name))
            throw InputError(where + ": cannot read the included file '" +
                             name +
                             "'. Relative paths start at the directory of "
                             "the file that includes it.");
          std::stringstream buffer;
          buffer << included.rdbuf();
          check_parameter_text(buffer.str(), "included file '" + name + "'");
          result += expand_includes(buffer.str(), name, origins, depth + 1);
        }
      return result;
    }
  } // namespace


  Parameters
  read_parameters(const std::string &filename, ParameterHandler &prm)
  {
    if (std::filesystem::is_directory(filename))
      throw InputError("'" + filename +
                       "' is a directory, not a parameter file. Give the "
                       "path of a .prm file.");
    std::ifstream in(filename);
    if (!in)
      throw InputError("Cannot open the parameter file '" + filename +
                       "'. Give the path of an existing .prm file.");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string source = "parameter file '" + filename + "'";
    check_parameter_text(buffer.str(), source);
    std::vector<std::string> origins;
    const std::string        text =
      expand_includes(buffer.str(), filename, origins);
    Parameters parameters = parse_text(text, source, prm, origins);
    parameters.input_directory = directory_of(filename);
    parameters.input_file = filename;
    return parameters;
  }


  Parameters
  read_parameters_from_string(const std::string &text, ParameterHandler &prm)
  {
    return parse_text(text, "parameter text", prm);
  }
} // namespace Signorini
