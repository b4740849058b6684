#ifndef signorini_base_parameters_h
#define signorini_base_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <signorini/base/errors.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

/**
 * Input parameters of a Signorini run, one small struct per subsection of the
 * parameter file (the step-44 pattern): each has declare_parameters() and
 * parse_parameters(). Selections are parsed once into enum classes.
 *
 * Numbered subsections (Body 1, Material 1, Dirichlet 1, ...) are declared as
 * many times as the matching "Number of ..." entry says; that count is read by
 * a tolerant pre-pass over the file (read_counts()) before the strict parse.
 *
 * Units: the code is unit-agnostic; the documentation strings quote SI units,
 * any consistent set (e.g. mm-N-MPa) works.
 */
namespace Signorini
{
  using namespace dealii;

  /** Counts of the numbered subsections, read before the strict parse. */
  struct Counts
  {
    unsigned int n_bodies    = 1;
    unsigned int n_materials = 1;
    unsigned int n_dirichlet = 1;
    unsigned int n_neumann   = 0;
    unsigned int n_pairs     = 0;

    /** One subsection of each numbered kind: the parameter listing
     * (--print-parameters, doc/parameters.md). */
    static Counts
    listing()
    {
      return {1, 1, 1, 1, 1};
    }
  };

  /** One body (subsection Geometry/Body k): its shape, which reads its
   * own subsection, and what every body shares: the names of its faces, its
   * material id and its placement. */
  struct BodyParameters
  {
    std::string shape; // a name of the Shape plug-in family; its own
                       // parameters are read by Geometry::Shapes
    std::vector<unsigned int> boundary_ids;
    int                       material_id;
    std::vector<double>       shift;
    // Rotation after the shift: angle [rad], axis (3D), about a point.
    double              rotation_angle;
    std::vector<double> rotation_axis, rotation_centre;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct GeometryParameters
  {
    unsigned int                global_refinements;
    unsigned int                local_refinements;
    unsigned long long          maximum_cells;     // refinement beyond: refused
    std::string                 refinement_region; // f(x, y, z) > 0: refine
    std::vector<BodyParameters> bodies;

    static void
    declare_parameters(ParameterHandler &prm, const Counts &counts);
    void
    parse_parameters(ParameterHandler &prm, const Counts &counts);
  };

  struct MaterialParameters
  {
    unsigned int material_id;
    std::string  model;         // a name of the Material plug-in family
    bool         finite_strain; // 'Kinematics = finite strain'
    double       youngs_modulus;
    double       poissons_ratio;
    // Body force per unit volume on the cells of this material: dim or
    // more expressions of x, y, z, t (the extra ones ignored).
    std::vector<std::string> body_force;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** A Dirichlet condition on some components of one boundary (or one point of
   * it). */
  /** What a Dirichlet condition prescribes: Cartesian components, the
   * normal or the tangential part of a vector, or the component along a
   * fixed direction. */
  enum class DirichletFrame
  {
    cartesian,
    normal,
    tangential,
    direction
  };

  struct DirichletParameters
  {
    std::vector<unsigned int> boundary_ids;
    DirichletFrame            frame;
    std::vector<unsigned int> components;      // cartesian: 0 = x, 1 = y, 2 = z
    std::vector<std::string>  component_names; // as listed
    std::vector<double>       direction;       // frame direction
    // cartesian: one expression per entry of components; normal and
    // tangential: the dim components of a vector; direction: one.
    std::vector<std::string> values;
    std::vector<double>      at_point; // empty: the whole boundary

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  enum class NeumannType
  {
    traction,
    pressure
  };

  struct NeumannParameters
  {
    std::vector<unsigned int> boundary_ids;
    NeumannType               type;
    std::vector<std::string>
      values; // dim expressions (traction) or 1 (pressure)

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct BoundaryConditionParameters
  {
    std::vector<DirichletParameters> dirichlet;
    std::vector<NeumannParameters>   neumann;
    std::map<std::string, double>    constants;

    static void
    declare_parameters(ParameterHandler &prm, const Counts &counts);
    void
    parse_parameters(ParameterHandler &prm, const Counts &counts);
  };

  struct LoadSteppingParameters
  {
    std::vector<double> step_times; // end times of the steps, increasing
    unsigned int        max_cuts;
    bool                extrapolate;            // Predictor = extrapolated
    bool                explicit_times = false; // the user gave 'Step times'

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Adaptive refinement after load steps ('Adaptive refinement'). */
  struct AdaptivityParameters
  {
    // 'Steps': the last step solved again on its adapted mesh, every step
    // solved again, or the mesh adapted between steps (no second solve).
    enum class Steps
    {
      last,
      every,
      between
    };
    unsigned int cycles; // refine-and-resolve cycles, 0: off
    Steps        steps;
    double       refinement_fraction; // of the active cells, by count
    double       coarsening_fraction;
    bool         refine_contact_zone;
    unsigned int maximum_level; // finest level of a cell, 0: automatic

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct NewtonParameters
  {
    unsigned int max_iterations;
    double       relative_tolerance;
    double       absolute_tolerance;
    bool         check_jacobian;
    unsigned int line_search_steps; // 0: full Newton updates
    double       tolerance_between_pairings;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  enum class LinearSolverType
  {
    direct,
    cg,
    gmres
  };

  struct LinearSolverParameters
  {
    LinearSolverType type;
    std::string      direct_package; // Amesos name, e.g. "Amesos_Mumps"
    double           relative_tolerance;
    unsigned int     max_iterations;
    bool             rigid_body_modes;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  enum class Verbosity
  {
    quiet,
    normal,
    verbose
  };

  struct OutputParameters
  {
    std::string              directory;
    bool                     write_csv;
    bool                     timing_summary;
    Verbosity                verbosity;
    std::vector<std::string> postprocessors; // names, in the listed order

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** One contact pair (subsection Contact/Pair k), theory.md F2. */
  struct ContactPairParameters
  {
    std::vector<unsigned int> slave_ids;
    std::string               master; // "body" or a registered obstacle
    std::vector<unsigned int> master_ids;
    std::vector<std::string>  obstacle_motion;   // dim expressions of t
    std::vector<std::string>  obstacle_rotation; // 1 (2D) or 3 (3D), or "0"
    std::vector<double>       rotation_centre;   // at t = 0
    double                    friction;
    double                    rho_n_factor, rho_t_factor;
    double                    gap_offset;

    /** The master is a meshed body (not a rigid obstacle). */
    bool
    master_is_body() const
    {
      return master == "body";
    }

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Integration rule on the slave surface (theory.md F6). */
  enum class IntegrationRule
  {
    nodal,
    gauss,
    simpson,
    newton_cotes,
    mortar
  };

  enum class InitialStatus
  {
    open,
    penetrating,
    closed
  };

  struct ContactParameters
  {
    std::vector<ContactPairParameters> pairs;
    IntegrationRule                    rule;
    unsigned int                       order;
    InitialStatus                      initial_status;
    double                             projection_tolerance;
    double                             geometric_tolerance;
    unsigned int                       max_geometric_iterations;
    // Anti-cycling (theory.md F8): a contact point whose status returns
    // to the one it had two Newton iterates before (stick/slip/stick,
    // contact/free/contact, slip direction reversed and back) this many
    // times in one Newton solve is frozen: kept in contact, or kept
    // slipping in its last slip direction; a frozen point that the plain
    // law contradicts at convergence is released and Newton goes on.
    // Across pairings, a point back at its converged status (or master
    // face) of two pairings before keeps it for the rest of the load step.
    // Measured over the hard-case table (doc/robustness.md): 2, 3 and 5
    // cycles give the same runs, never freezing fails a 2D
    // Cattaneo-Mindlin step.
    static constexpr unsigned int freeze_after_cycles = 3;

    static void
    declare_parameters(ParameterHandler &prm, const Counts &counts);
    void
    parse_parameters(ParameterHandler &prm, const Counts &counts);
  };

  struct Parameters
  {
    unsigned int dimension;
    bool         axisymmetric; // 2D: x = r, y = z
    bool         plane_stress; // 2D: sigma_33 = 0 (else plane strain)
    unsigned int fe_degree;
    bool         projected_volumetric_strain; // B-bar: theta projected per cell
    GeometryParameters              geometry;
    std::vector<MaterialParameters> materials;
    BoundaryConditionParameters     boundary_conditions;
    ContactParameters               contact;
    LoadSteppingParameters          load_stepping;
    AdaptivityParameters            adaptivity;
    NewtonParameters                newton;
    LinearSolverParameters          linear_solver;
    OutputParameters                output;
    std::string input_directory = "."; // for relative mesh paths
    // The parameter file read (empty: parameters from a string); the
    // parameter echo must not overwrite it.
    std::string input_file;

    static void
    declare_parameters(ParameterHandler &prm, const Counts &counts);
    void
    parse_parameters(ParameterHandler &prm, const Counts &counts);

    /** Checks across subsections that patterns cannot express. */
    void
    check_consistency() const;
    /** The contact part of check_consistency(). */
    void
    check_contact() const;
  };

  /**
   * Reads and checks a parameter file. Throws InputError with a message naming
   * file, line, subsection and parameter. On success @p prm holds the full,
   * declared parameter set (for echoing into the output directory).
   */
  Parameters
  read_parameters(const std::string &filename, ParameterHandler &prm);

  /** Same from a string (used by unit tests and the library interface). */
  Parameters
  read_parameters_from_string(const std::string &text, ParameterHandler &prm);

  /** Splits "a; b; c" into trimmed expressions (empty string -> empty list). */
  std::vector<std::string>
  split_expressions(const std::string &text);

  /** A point of dimension @p dim from a list of numbers, with a clear error. */
  template <int dim>
  Point<dim>
  to_point(const std::vector<double> &values, const std::string &where);
} // namespace Signorini

#endif
