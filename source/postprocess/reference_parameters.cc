// The references of the postprocessor 'reference checks' (subsection
// 'Output/Reference checks'): their declaration, reading and checks.
#include <deal.II/base/utilities.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameter_helpers.h>
#include <signorini/postprocess/reference_parameters.h>

namespace Signorini
{
  namespace Postprocess
  {
    using internal::component_index;
    using internal::point_pattern;
    using internal::to_doubles;

    namespace
    {
      const std::string where = "subsection 'Output/Reference checks'";
    } // namespace


    namespace
    {
      // Exact displacement and stress, the contact pressure and zone.
      void
      declare_field_references(ParameterHandler &prm)
      {
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
        prm.declare_entry(
          "History quantity",
          "",
          Patterns::Anything(),
          "Exact value of a history quantity of the materials (their "
          "history_output_names(): J2 plasticity has "
          "equivalent_plastic_strain), as 'name: expression' in x, y, z, t. "
          "Empty: none. The run prints its largest error over the largest "
          "reference value, at the bulk quadrature points of the cells whose "
          "material has it.");
        prm.declare_entry("Tolerance",
                          "1e-10",
                          Patterns::Double(0),
                          "Relative error below which the comparison is "
                          "reported as PASS.");
        prm.declare_entry("Maximum contact pressure",
                          "0",
                          Patterns::Anything(),
                          "Reference for the largest contact pressure p0 = "
                          "max(-lambda) at the contact points [Pa], an "
                          "expression of t (e.g. '5.07e9*sqrt(t)'), checked "
                          "at every written step where it is positive; 0: "
                          "not checked.");
        prm.declare_entry("Pressure tolerance",
                          "0.02",
                          Patterns::Double(0),
                          "Relative tolerance of the p0 check.");
        prm.declare_entry(
          "Contact half-width",
          "0",
          Patterns::Anything(),
          "Reference contact half-width a (or radius in 3D) [m], "
          "measured from 'Contact centre', an expression of t, "
          "checked at every written step where it is "
          "positive; 0: not checked. The computed a is midway "
          "between the farthest closed point and the nearest "
          "open point beyond it.");
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
      }


      // Friction: force ratio in sliding, force variation, stick zone;
      // displacement values at points.
      void
      declare_friction_references(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Friction force ratio",
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
        prm.declare_entry(
          "Friction ratio frame",
          "global",
          Patterns::Selection("global|contact"),
          "global: F_n and F_t are the parts of the total contact "
          "force along 'Friction ratio normal' and across it "
          "(a flat master). contact: F_n = sum of w |f . n| and "
          "F_t = sum of w |P f| over the contact points, each in "
          "its own contact frame (a curved master, e.g. an "
          "ironing die, whose total force also carries the "
          "tilted normal pressures).");
        prm.declare_entry(
          "Force variation tolerance",
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
          "cattaneo-mindlin: at every step with a tangential force, the "
          "half-width "
          "c of the stick zone of pair 1 (around 'Contact centre') is checked "
          "against Cattaneo-Mindlin partial slip under a constant normal force "
          "P, "
          "c = a (1 - |Q|/(mu P))^(1/m) while Q grows from 0 (first loading) "
          "and "
          "c = a (1 - |Q - Q*|/(2 mu P))^(1/m) after the tangential force Q "
          "turned at Q* (Masing), m = 2 in 2D (cylinder) and 3 in 3D (sphere); "
          "a "
          "is the measured contact half-width, P and Q the contact force of "
          "pair "
          "1 along 'Friction ratio normal' and across it, tolerance "
          "'Half-width "
          "tolerance'. 2D: a and c midway between the farthest point inside "
          "(closed; stick) and the nearest point outside beyond it. 3D: "
          "area-equivalent radii, a = sqrt(A_closed / pi) and c = "
          "sqrt(A_stick / pi) with A the summed weights of the closed and of "
          "the "
          "stick points. Valid for elastically similar bodies (no coupling of "
          "the "
          "normal and tangential problems).");
        prm.declare_entry("Friction ratio from time",
                          "0",
                          Patterns::Double(0),
                          "The friction force ratio is checked at the steps "
                          "with t >= this time (steady sliding).");
        prm.declare_entry(
          "Friction ratio tolerance",
          "0.01",
          Patterns::Double(0),
          "Relative tolerance of the friction force ratio check.");
        prm.declare_entry(
          "Point values",
          "",
          Patterns::Anything(),
          "Displacement values to check, separated by ';', each "
          "'x, y[, z] : component : value[ : tolerance]' with "
          "component x, y or z and an optional relative "
          "tolerance of its own (else 'Point value tolerance'), "
          "e.g. '0.00125, 0 : x : 2.72e-5 : 0.01'.");
        prm.declare_entry(
          "Point values from time",
          "0",
          Patterns::Double(),
          "The 'Point values' checks run at the steps with t >= "
          "this time (e.g. only the last step of a load path).");
        prm.declare_entry("Point value tolerance",
                          "0.05",
                          Patterns::Double(0),
                          "Relative tolerance of the point value checks.");
      }


      // Facts of every converged state (action = reaction, slip law, gaps) and
      // the total contact force.
      void
      declare_law_references(ParameterHandler &prm)
      {
        prm.declare_entry(
          "Action-reaction tolerance",
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
        prm.declare_entry(
          "Slip law tolerance",
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
        prm.declare_entry(
          "Contact force",
          "",
          Patterns::Anything(),
          "Reference for the total contact force on the master "
          "of pair 1 [N; N/m in 2D; axisymmetric: over the "
          "circumference], Dimension expressions of t separated "
          "by ';' (e.g. the applied load where the scene fixes "
          "it); a component written '*' is left out (e.g. the "
          "horizontal force of a half model). Empty: not "
          "checked.");
        prm.declare_entry(
          "Contact force from time",
          "0",
          Patterns::Double(),
          "The 'Contact force' check runs at the steps with t >= "
          "this time (e.g. the steady phase of a load path).");
        prm.declare_entry("Contact force tolerance",
                          "1e-3",
                          Patterns::Double(0),
                          "Relative tolerance of the 'Contact force' check: "
                          "|F - F_ref| / |F_ref|.");
        prm.declare_entry(
          "Gap tolerance",
          "0",
          Patterns::Double(0),
          "Check after each step that every closed contact point "
          "has |gap| below this value [m] and no open point "
          "penetrates by more; at least one point must be "
          "closed. 0: not checked.");
      }
    } // namespace


    void
    ReferenceParameters::declare_parameters(ParameterHandler &prm)
    {
      declare_field_references(prm);
      declare_friction_references(prm);
      declare_law_references(prm);
    }


    bool
    ReferenceParameters::any() const
    {
      return !displacement.empty() || !stress.empty() || !history.empty() ||
             !max_pressure.empty() || !half_width.empty() ||
             !contact_pressure.empty() || !point_values.empty() ||
             action_reaction_tolerance > 0 || slip_law_tolerance > 0 ||
             !contact_force.empty() || gap_tolerance > 0 ||
             friction_ratio > 0 || force_variation_tolerance > 0 ||
             cattaneo_mindlin;
    }


    void
    ReferenceParameters::parse_parameters(ParameterHandler &prm,
                                          const Parameters &parameters)
    {
      displacement = split_expressions(prm.get("Displacement"));
      stress       = split_expressions(prm.get("Stress"));
      history_name.clear();
      history.clear();
      if (const std::string text = Utilities::trim(prm.get("History quantity"));
          !text.empty())
        {
          const auto colon = text.find(':');
          if (colon == std::string::npos)
            throw InputError(where +
                             ", parameter "
                             "'History quantity': cannot read '" +
                             text +
                             "'. Write 'name: expression', e.g. "
                             "'equivalent_plastic_strain: 1e-3*t'.");
          history_name = Utilities::trim(text.substr(0, colon));
          history      = {Utilities::trim(text.substr(colon + 1))};
        }
      tolerance = prm.get_double("Tolerance");
      // "0" (the default) means not checked, as an empty entry.
      const auto expression_or_empty = [&](const std::string &name) {
        const std::string text = Utilities::trim(prm.get(name));
        return text == "0" ? std::string() : text;
      };
      max_pressure          = expression_or_empty("Maximum contact pressure");
      pressure_tolerance    = prm.get_double("Pressure tolerance");
      half_width            = expression_or_empty("Contact half-width");
      contact_centre        = to_doubles(prm.get("Contact centre"));
      half_width_tolerance  = prm.get_double("Half-width tolerance");
      contact_pressure      = prm.get("Contact pressure");
      pressure_l2_tolerance = prm.get_double("Pressure L2 tolerance");
      point_value_tolerance = prm.get_double("Point value tolerance");
      point_values_from     = prm.get_double("Point values from time");
      action_reaction_tolerance = prm.get_double("Action-reaction tolerance");
      slip_law_tolerance        = prm.get_double("Slip law tolerance");
      contact_force             = split_expressions(prm.get("Contact force"));
      contact_force_tolerance   = prm.get_double("Contact force tolerance");
      contact_force_from        = prm.get_double("Contact force from time");
      gap_tolerance             = prm.get_double("Gap tolerance");
      friction_ratio            = prm.get_double("Friction force ratio");
      friction_ratio_normal     = to_doubles(prm.get("Friction ratio normal"));
      friction_ratio_tolerance  = prm.get_double("Friction ratio tolerance");
      friction_ratio_from       = prm.get_double("Friction ratio from time");
      friction_ratio_contact_frame =
        prm.get("Friction ratio frame") == "contact";
      force_variation_tolerance = prm.get_double("Force variation tolerance");
      cattaneo_mindlin          = prm.get("Stick zone") == "cattaneo-mindlin";
      point_values.clear();
      for (const auto &entry : split_expressions(prm.get("Point values")))
        {
          const auto parts = Utilities::split_string_list(entry, ':');
          if ((parts.size() != 3 && parts.size() != 4) ||
              (parts[1] != "x" && parts[1] != "y" && parts[1] != "z"))
            throw InputError(where +
                             ", parameter "
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
      check(parameters);
    }


    // Sizes against the Dimension and the scene, and every expression
    // (parsed and evaluated once, as the other expressions of the input).
    void
    ReferenceParameters::check(const Parameters &parameters) const
    {
      const unsigned int dim = parameters.dimension;
      if (!displacement.empty() && displacement.size() != dim)
        throw InputError(where + ", parameter 'Displacement': give Dimension "
                                 "expressions.");
      if (!contact_force.empty() && contact_force.size() != dim)
        throw InputError(where + ", parameter 'Contact force': give Dimension "
                                 "expressions of t separated by ';' (the force "
                                 "components), or leave it empty.");
      if (!contact_force.empty() && parameters.contact.pairs.empty())
        throw InputError(where +
                         ", parameter 'Contact force': the scene has no "
                         "contact pair. Remove the reference or declare a "
                         "pair in subsection 'Contact'.");
      if (!stress.empty() && stress.size() != dim * dim)
        throw InputError(where + ", parameter 'Stress': give Dimension^2 "
                                 "expressions (row by row).");
      std::vector<ExpressionInput> inputs;
      inputs.push_back({where + ", parameter 'Displacement'",
                        displacement,
                        axis_labels(displacement.size())});
      ExpressionInput stress_input;
      stress_input.where       = where + ", parameter 'Stress'";
      stress_input.expressions = stress;
      for (unsigned int i = 0; i < stress.size(); ++i)
        stress_input.labels.push_back(
          i < dim * dim ? std::string(1, "xyz"[i / dim]) + "xyz"[i % dim] :
                          std::to_string(i + 1));
      inputs.push_back(stress_input);
      inputs.push_back(
        {where + ", parameter 'History quantity'", history, {history_name}});
      // '*': a component the check leaves out.
      std::vector<std::string> force = contact_force;
      for (auto &e : force)
        if (Utilities::trim(e) == "*")
          e = "0";
      inputs.push_back({where + ", parameter 'Contact force'",
                        force,
                        axis_labels(force.size())});
      for (const auto &[name, expression] :
           {std::make_pair("Contact pressure", contact_pressure),
            std::make_pair("Maximum contact pressure", max_pressure),
            std::make_pair("Contact half-width", half_width)})
        if (!expression.empty())
          inputs.push_back({where + ", parameter '" + std::string(name) + "'",
                            {expression},
                            {""}});
      check_expressions(inputs, parameters);
    }
  } // namespace Postprocess
} // namespace Signorini
