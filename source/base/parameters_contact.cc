// The parameters of the subsection Contact (with Pair k).
#include <deal.II/base/utilities.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameters.h>
#include <signorini/base/plugins.h>

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
    const SelectionTable<IntegrationRule> integration_rules{
      {"nodal", IntegrationRule::nodal},
      {"gauss", IntegrationRule::gauss},
      {"simpson", IntegrationRule::simpson},
      {"newton-cotes", IntegrationRule::newton_cotes},
      {"mortar", IntegrationRule::mortar}};
    const SelectionTable<InitialStatus> initial_statuses{
      {"open", InitialStatus::open},
      {"penetrating", InitialStatus::penetrating},
      {"closed", InitialStatus::closed}};
  } // namespace

  // --------------------------------------------------------------- Contact
  void
  ContactPairParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Slave boundary id",
                      "",
                      Patterns::List(Patterns::Integer(0, 255), 0),
                      "Boundary id(s) of the slave surface (one body): the "
                      "contact multipliers live on its nodes.");
    Plugins::declare(Plugins::Family::obstacle, prm);
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
                      "changes the convergence path, not the solution.");
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
    slave_ids         = to_unsigned(prm.get("Slave boundary id"));
    master_ids        = to_unsigned(prm.get("Master boundary id"));
    master            = prm.get("Master");
    obstacle_motion   = split_expressions(prm.get("Obstacle motion"));
    obstacle_rotation = split_expressions(prm.get("Obstacle rotation"));
    rotation_centre   = to_doubles(prm.get("Rotation centre"));
    friction          = prm.get_double("Friction coefficient");
    rho_n_factor      = prm.get_double("Normal coefficient");
    rho_t_factor      = prm.get_double("Tangential coefficient");
    gap_offset        = prm.get_double("Gap offset");
  }


  void
  ContactParameters::declare_parameters(ParameterHandler &prm,
                                        const Counts     &counts)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry("Number of contact pairs",
                      "0",
                      Patterns::Integer(0, 64),
                      "Number of subsections 'Pair k', k = 1..N. 0: no "
                      "contact.");
    prm.declare_entry("Integration rule",
                      "mortar",
                      integration_rules.pattern(),
                      "Contact points on the slave faces (theory.md F6): "
                      "nodal (the face nodes: trapezoid for Q1, Simpson for "
                      "Q2), gauss (Gauss-Legendre with 'Integration order' "
                      "points per direction), simpson (composite Simpson "
                      "with 'Integration order' panels per direction), "
                      "newton-cotes (closed Newton-Cotes of degree "
                      "'Integration order' = 1, 2, 4 or 6), mortar "
                      "(segment-based: each slave face cut by the master "
                      "faces it overlaps, on every piece the Gauss rule "
                      "exact for psi x N^m on flat faces; passes the contact "
                      "patch test on non-matching "
                      "meshes).");
    prm.declare_entry("Integration order",
                      "2",
                      Patterns::Integer(1, 12),
                      "Order of the gauss, simpson or newton-cotes rule. "
                      "gauss and newton-cotes need as many points per face "
                      "direction as a face has multiplier nodes (Q1: gauss "
                      ">= 2; Q2: gauss >= 3, newton-cotes >= 2).");
    prm.declare_entry("Initial status",
                      "penetrating",
                      initial_statuses.pattern(),
                      "Status of the contact points at the first Newton "
                      "iteration of the run: open, closed where penetrating "
                      "or touching (g >= 0, to 1e-8 of the face size), or "
                      "all closed (for a body that its touching points "
                      "cannot hold: the first iterate pulls every paired "
                      "point onto the master, which at finite strain can "
                      "invert cells; open points are released by Newton).");
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
                                      const Counts     &counts)
  {
    prm.enter_subsection("Contact");
    rule                 = integration_rules.value(prm.get("Integration rule"));
    order                = prm.get_integer("Integration order");
    initial_status       = initial_statuses.value(prm.get("Initial status"));
    projection_tolerance = prm.get_double("Projection tolerance");
    geometric_tolerance  = prm.get_double("Geometric tolerance");
    max_geometric_iterations = prm.get_integer("Maximum geometric iterations");
    pairs.resize(counts.n_pairs);
    for (unsigned int k = 0; k < counts.n_pairs; ++k)
      {
        prm.enter_subsection("Pair " + std::to_string(k + 1));
        pairs[k].parse_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


} // namespace Signorini
