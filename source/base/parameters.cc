// The parameters of every subsection: declaration with patterns and
// documentation, and parsing (geometry: parameters_geometry.cc; contact:
// parameters_contact.cc; consistency checks and reading files:
// parameters_input.cc). The references of the postprocessor 'reference
// checks' are its own (postprocess/reference_parameters.h).
#include <deal.II/base/utilities.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameters.h>
#include <signorini/base/plugins.h>
#include <signorini/base/shared_libraries.h>

#include <signorini/base/parameter_helpers.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>

namespace Signorini
{
  using internal::component_index;
  using internal::point_pattern;
  using internal::to_doubles;
  using internal::to_unsigned;

  namespace
  {
    using internal::SelectionTable;
    // One table per selection entry (its pattern and its parsing).
    const SelectionTable<NeumannType> neumann_types{
      {"traction", NeumannType::traction},
      {"pressure", NeumannType::pressure}};
    const SelectionTable<LinearSolverType> solver_types{
      {"direct", LinearSolverType::direct},
      {"CG", LinearSolverType::cg},
      {"GMRES", LinearSolverType::gmres}};
    const SelectionTable<Verbosity> verbosities{{"quiet", Verbosity::quiet},
                                                {"normal", Verbosity::normal},
                                                {"verbose",
                                                 Verbosity::verbose}};
    using AdaptedSteps = AdaptivityParameters::Steps;
    const SelectionTable<AdaptedSteps> adapted_steps{
      {"last", AdaptedSteps::last},
      {"every", AdaptedSteps::every},
      {"between", AdaptedSteps::between}};
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
      throw InputError(
        where + ": expected " + std::to_string(dim) +
        " coordinates (Dimension = " + std::to_string(dim) + ") but got " +
        std::to_string(values.size()) +
        ". Give one number per coordinate, separated by commas.");
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = values[d];
    return p;
  }
  template Point<2>
  to_point<2>(const std::vector<double> &, const std::string &);
  template Point<3>
  to_point<3>(const std::vector<double> &, const std::string &);


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
                      Patterns::Double(1e-20, 1e20),
                      "Young's modulus E [Pa], 1e-20 to 1e20 (any unit "
                      "system of a solid: outside, the displacements load / "
                      "E and the stiffness leave the range where double "
                      "precision resolves them next to the positions).");
    prm.declare_entry("Poisson's ratio",
                      "0.3",
                      Patterns::Double(-0.999999, 0.499999),
                      "Poisson's ratio nu [-], -1 < nu < 0.5 (plane strain "
                      "in 2D).");
    prm.declare_entry(
      "Kinematics",
      "small strain",
      Patterns::Selection("small strain|finite strain"),
      "'small strain': linearised kinematics, eps = sym grad u (the "
      "contact geometry still follows x = X + u). 'finite strain': total "
      "Lagrangian, stress from the deformation gradient F = I + Grad u "
      "with the geometric stiffness, and Neumann pressures that follow the "
      "deformed surface; needs a model that implements it (neo-Hookean).");
    prm.declare_entry("Body force",
                      "0; 0; 0",
                      Patterns::Anything(),
                      "Body force per unit volume [N/m^3] on the cells of "
                      "this material (e.g. its weight, density times "
                      "gravity): Dimension expressions separated by ';' "
                      "(extra ones ignored), functions of x, y, z and t.");
    Plugins::declare(Plugins::Family::material, prm);
  }


  void
  MaterialParameters::parse_parameters(ParameterHandler &prm)
  {
    material_id    = prm.get_integer("Material id");
    model          = prm.get("Model");
    finite_strain  = prm.get("Kinematics") == "finite strain";
    youngs_modulus = prm.get_double("Young's modulus");
    poissons_ratio = prm.get_double("Poisson's ratio");
    body_force     = split_expressions(prm.get("Body force"));
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
    prm.declare_entry(
      "Components",
      "x, y",
      Patterns::MultipleSelection("x|y|z|normal|tangential|direction"),
      "What is prescribed: Cartesian displacement components, e.g. 'y' or "
      "'x, y'; or, alone, 'normal': the displacement along the boundary's "
      "outward normal (u.n = v.n, tangential sliding free: a roller on an "
      "inclined or curved wall), 'tangential': the part tangential to the "
      "boundary (u - (u.n)n = v - (v.n)n, normal free), 'direction': the "
      "component along 'Direction' (u.d = value, the rest free). The normal "
      "at a node is the average of the normals of its faces on the listed "
      "boundaries (deal.II's normal-flux constraints), so list the faces of "
      "one smooth surface in one condition; a sharp corner between two such "
      "surfaces needs two conditions.");
    prm.declare_entry(
      "Values",
      "0; 0",
      Patterns::Anything(),
      "Prescribed displacement [m] as functions of x, y, z and the load "
      "time t (deal.II FunctionParser syntax), separated by ';': one "
      "expression per listed Cartesian component, e.g. '0; -0.1*t'; for "
      "normal and tangential the Dimension components of a vector v whose "
      "normal (tangential) part is imposed, e.g. '0; 0' for a fixed wall; "
      "for direction one expression, the displacement along 'Direction'.");
    prm.declare_entry("Direction",
                      "",
                      point_pattern(),
                      "For Components = direction: the direction d (any "
                      "length but 0, normalised), Dimension numbers.");
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
    component_names = Utilities::split_string_list(prm.get("Components"), ',');
    frame           = DirichletFrame::cartesian;
    for (const auto &c : component_names)
      if (c == "normal")
        frame = DirichletFrame::normal;
      else if (c == "tangential")
        frame = DirichletFrame::tangential;
      else if (c == "direction")
        frame = DirichletFrame::direction;
      else
        components.push_back(component_index(c));
    direction = to_doubles(prm.get("Direction"));
    values    = split_expressions(prm.get("Values"));
    at_point  = to_doubles(prm.get("At point"));
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
                      neumann_types.pattern(),
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
    type         = neumann_types.value(prm.get("Type"));
    values       = split_expressions(prm.get("Values"));
  }


  void
  BoundaryConditionParameters::declare_parameters(ParameterHandler &prm,
                                                  const Counts     &counts)
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
                                                const Counts     &counts)
  {
    prm.enter_subsection("Boundary conditions");
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
                      "state plus the increment of the last converged step, "
                      "displacements and multipliers, scaled so that its "
                      "Dirichlet values and loads best match the new "
                      "step's (the ratio of the step sizes for proportional "
                      "data, negative where the prescribed motion or the "
                      "load reverses; where neither moved, the ratio of the "
                      "step sizes) (extrapolated: starts sliding contacts "
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
    max_cuts    = prm.get_integer("Maximum step cuts");
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
                      "no fraction beats it). A trial whose residual is not "
                      "finite (an inverted element at finite strain) is "
                      "halved again without counting, down to 2^-20. "
                      "Statuses follow each trial. "
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
    max_iterations             = prm.get_integer("Maximum iterations");
    relative_tolerance         = prm.get_double("Relative tolerance");
    absolute_tolerance         = prm.get_double("Absolute tolerance");
    check_jacobian             = prm.get_bool("Check Jacobian");
    line_search_steps          = prm.get_integer("Line search steps");
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
                      solver_types.pattern(),
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
    type = solver_types.value(prm.get("Type"));
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
                      verbosities.pattern(),
                      "quiet: summary only; normal: one block per load step; "
                      "verbose: every Newton iteration with its residuals.");
    Plugins::declare(Plugins::Family::postprocessor, prm);
    prm.leave_subsection();
  }


  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory      = prm.get("Directory");
    write_csv      = prm.get_bool("Write CSV");
    timing_summary = prm.get_bool("Timing summary");
    verbosity      = verbosities.value(prm.get("Verbosity"));
    postprocessors = Utilities::split_string_list(prm.get("Postprocessors"));
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
                      adapted_steps.pattern(),
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
                      "contact zone (slave faces with a point in contact "
                      "and the master faces those points are paired with) "
                      "and every coarser cell whose centre lies within its "
                      "own diameter of a zone cell, so that each coarser "
                      "level lies two cells deep under the zone. The Kelly "
                      "indicator alone ignores the contact traction, which "
                      "acts on boundary faces.");
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
    steps               = adapted_steps.value(prm.get("Steps"));
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
                      "Space dimension: 2 (plane strain, or plane stress "
                      "with 'Plane stress', or axisymmetric with "
                      "'Axisymmetric') or 3.");
    prm.declare_entry(shared_libraries_entry,
                      "",
                      Patterns::List(Patterns::FileName()),
                      shared_libraries_documentation);
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
    prm.declare_entry("Plane stress",
                      "false",
                      Patterns::Bool(),
                      "Dimension = 2 only: the stress normal to the plane is "
                      "zero (thin parts, plates loaded in their plane) "
                      "instead of the strain (plane strain). Every "
                      "small-strain model runs so: at each point the normal "
                      "strain is solved for sigma_33 = 0 with the model's "
                      "own stress and tangent (also in plasticity). Forces "
                      "are per unit thickness, as in plane strain.");
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
      "doc/robustness.md). At finite strain the projected quantity is ln "
      "J and the model sees F_bar = exp((theta_bar - ln J) / 3) F (F-bar); "
      "it also removes the locking of isochoric plastic flow. The stresses "
      "written and checked take their volumetric part from the "
      "projection, as the equilibrium does.");
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
  }


  void
  Parameters::parse_parameters(ParameterHandler &prm, const Counts &counts)
  {
    dimension    = prm.get_integer("Dimension");
    axisymmetric = prm.get_bool("Axisymmetric");
    plane_stress = prm.get_bool("Plane stress");
    prm.enter_subsection("Finite element");
    fe_degree                   = prm.get_integer("Degree");
    projected_volumetric_strain = prm.get("Volumetric strain") == "projected";
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
    check_consistency();
    check_expressions(*this);
  }


} // namespace Signorini
