#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <signorini/base/format.h>
#include <signorini/postprocess/contact_checks.h>
#include <signorini/postprocess/field_slips.h>

#include "parsed_function.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace Signorini
{
  namespace Postprocess
  {
    namespace
    {
      template <int dim>
      using Records =
        std::vector<typename Contact::ContactProblem<dim>::PointRecord>;

      // A check of @p error against @p tolerance; @p text is its line up
      // to the verdict. @p value and @p reference where one number is
      // compared.
      CheckResult
      checked(const std::string &what,
              const double       error,
              const double       tolerance,
              const bool         pass,
              const std::string &text,
              const double       value     = CheckResult::none,
              const double       reference = CheckResult::none)
      {
        CheckResult r;
        r.what      = what;
        r.value     = value;
        r.reference = reference;
        r.error     = error;
        r.tolerance = tolerance;
        r.pass      = pass;
        r.text      = text + "): " + (pass ? "PASS" : "FAIL");
        return r;
      }

      // A check that does not apply at this step: said, not counted.
      CheckResult
      not_checked(const std::string &what, const std::string &text)
      {
        CheckResult r;
        r.what    = what;
        r.checked = false;
        r.text    = text;
        return r;
      }

      // "what = value (reference r) <kind> e (tolerance t): PASS|FAIL"
      CheckResult
      compared(const std::string &what,
               const double       value,
               const double       reference,
               const double       error,
               const double       tolerance,
               const char        *error_kind)
      {
        return checked(what,
                       error,
                       tolerance,
                       error <= tolerance,
                       what + " = " + format(value, 4) + " (reference " +
                         format(reference, 4) + ") " + error_kind + " " +
                         format(error, 2) + " (tolerance " +
                         format(tolerance, 1),
                       value,
                       reference);
      }

      // Components below 1e-10 of @p scale are round-off (sums of forces
      // that cancel) and printed as 0, so that the output does not depend
      // on the number of MPI ranks.
      template <int dim>
      std::string
      vector_text(const Tensor<1, dim> &v, const double scale)
      {
        std::string text = "(";
        for (unsigned int d = 0; d < dim; ++d)
          text += (d ? ", " : "") +
                  format(std::abs(v[d]) < 1e-10 * scale ? 0. : v[d], 4);
        return text + ")";
      }

      // Half-width of the closed (stick_only = false) or sticking zone
      // around centre: halfway between the farthest point of the zone and
      // the nearest point beyond it that is not in the zone (the zone's
      // farthest point if there is none).
      template <int dim>
      double
      zone_half_width(const Records<dim> &records,
                      const Point<dim>   &centre,
                      const bool          stick_only)
      {
        const auto inside = [stick_only](const auto &r) {
          return stick_only ? r.status == Contact::PointStatus::stick :
                              r.status != Contact::PointStatus::free;
        };
        double in = 0;
        for (const auto &r : records)
          if (inside(r))
            in = std::max(in, r.x.distance(centre));
        double out = std::numeric_limits<double>::max();
        for (const auto &r : records)
          if (!inside(r) && r.x.distance(centre) > in)
            out = std::min(out, r.x.distance(centre));
        return out < std::numeric_limits<double>::max() ? 0.5 * (in + out) : in;
      }

      // Radius of the disc with the area of the closed points (or of the
      // stick points): the sum of their weights over pi (3D stick zone).
      template <int dim>
      double
      zone_equivalent_radius(const Records<dim> &records, const bool stick_only)
      {
        double area = 0;
        for (const auto &r : records)
          if (stick_only ? r.status == Contact::PointStatus::stick :
                           r.status != Contact::PointStatus::free)
            area += r.weight;
        return std::sqrt(area / numbers::PI);
      }

      template <int dim>
      Point<dim>
      reference_centre(const ReferenceParameters &ref)
      {
        Point<dim> centre;
        for (unsigned int d = 0; d < dim && d < ref.contact_centre.size(); ++d)
          centre[d] = ref.contact_centre[d];
        return centre;
      }

      // Unit normal of 'Friction ratio normal'.
      template <int dim>
      Tensor<1, dim>
      reference_normal(const ReferenceParameters &ref)
      {
        Tensor<1, dim> n;
        for (unsigned int d = 0;
             d < dim && d < ref.friction_ratio_normal.size();
             ++d)
          n[d] = ref.friction_ratio_normal[d];
        if (n.norm() == 0)
          throw InputError("subsection 'Output/Reference checks', parameter "
                           "'Friction ratio normal': give a nonzero "
                           "direction.");
        return n / n.norm();
      }
    } // namespace


    template <int dim>
    ContactChecks<dim>::ContactChecks(const Parameters          &parameters,
                                      const ReferenceParameters &reference)
        : parameters(parameters)
        , reference(reference)
    {
      const auto &ref       = reference;
      const auto &constants = parameters.boundary_conditions.constants;
      if (!ref.contact_pressure.empty())
        exact_pressure = parsed<dim>({ref.contact_pressure}, constants);
      if (!ref.max_pressure.empty())
        exact_p0 = parsed<dim>({ref.max_pressure}, constants);
      if (!ref.half_width.empty())
        exact_a = parsed<dim>({ref.half_width}, constants);
      std::vector<std::string> force = ref.contact_force;
      for (unsigned int d = 0; d < dim; ++d)
        {
          force_compared[d] =
            d >= force.size() || Utilities::trim(force[d]) != "*";
          if (!force_compared[d])
            force[d] = "0";
        }
      exact_force = parsed<dim>(force, constants);
    }


    template <int dim>
    bool
    ContactChecks<dim>::is_last_step(const double time) const
    {
      const double t_final = parameters.load_stepping.step_times.back();
      return std::abs(time - t_final) <= 1e-12 * std::abs(t_final);
    }


    template <int dim>
    std::vector<CheckResult>
    ContactChecks<dim>::evaluate(const StepData<dim> &data)
    {
      const double             time    = data.time;
      const auto              &contact = *data.contact;
      const auto              &ref     = reference;
      std::vector<CheckResult> results;
      // p0 and a at this time (not checked where not positive).
      const auto at_time = [&](const std::unique_ptr<FunctionParser<dim>> &f) {
        if (!f)
          return 0.;
        f->set_time(time);
        return f->value(Point<dim>());
      };
      const double p0 = at_time(exact_p0), a = at_time(exact_a);
      const bool   needs_points = p0 > 0 || a > 0 || exact_pressure ||
                                ref.cattaneo_mindlin || ref.gap_tolerance > 0;
      const Records records =
        needs_points ? contact.gather_points() : Records();
      const auto summary = contact.summary();
      if (p0 > 0)
        results.push_back(check_max_pressure(records, p0));
      if (a > 0)
        results.push_back(check_half_width(records, a));
      if (ref.cattaneo_mindlin)
        check_stick_zone(records, contact, results);
      if (exact_pressure)
        results.push_back(check_pressure_profile(records, time));
      if (ref.friction_ratio > 0 && time >= ref.friction_ratio_from)
        results.push_back(check_friction_ratio(summary[0]));
      if (ref.force_variation_tolerance > 0 && time >= ref.friction_ratio_from)
        {
          steady_forces.push_back(summary[0].force);
          if (is_last_step(time))
            results.push_back(check_force_variation());
        }
      if (ref.gap_tolerance > 0)
        results.push_back(check_gaps(records, time));
      if (exact_force && time >= ref.contact_force_from)
        results.push_back(check_contact_force(summary[0], time));
      if (ref.action_reaction_tolerance > 0 || ref.slip_law_tolerance > 0)
        check_laws(data, results);
      return results;
    }


    template <int dim>
    std::vector<CheckResult>
    ContactChecks<dim>::point_values(
      const double time,
      const std::function<double(const Point<dim> &, const unsigned int)>
        &displacement_at) const
    {
      std::vector<CheckResult> results;
      if (time < reference.point_values_from)
        return results;
      for (const auto &pv : reference.point_values)
        results.push_back(check_point_value(pv, displacement_at));
      return results;
    }


    template <int dim>
    CheckResult
    ContactChecks<dim>::check_max_pressure(const Records &records,
                                           const double   exact) const
    {
      double p0 = 0;
      for (const auto &r : records)
        p0 = std::max(p0, r.p);
      return compared("max contact pressure p0",
                      p0,
                      exact,
                      std::abs(p0 - exact) / exact,
                      reference.pressure_tolerance,
                      "relative error");
    }


    template <int dim>
    CheckResult
    ContactChecks<dim>::check_half_width(const Records &records,
                                         const double   exact) const
    {
      const double a =
        zone_half_width<dim>(records, reference_centre<dim>(reference), false);
      return compared("contact half-width a",
                      a,
                      exact,
                      std::abs(a - exact),
                      reference.half_width_tolerance,
                      "absolute error");
    }


    template <int dim>
    CheckResult
    ContactChecks<dim>::check_pressure_profile(const Records &records,
                                               const double   time) const
    {
      const auto &ref = reference;
      exact_pressure->set_time(time);
      double e2 = 0, n2 = 0;
      for (const auto &r : records)
        {
          const double pe = exact_pressure->value(r.x);
          e2 += r.weight * std::pow(r.p - pe, 2);
          n2 += r.weight * pe * pe;
        }
      const double e    = n2 > 0 ? std::sqrt(e2 / n2) : std::sqrt(e2);
      const char  *what = "contact pressure relative L2 error";
      return checked(what,
                     e,
                     ref.pressure_l2_tolerance,
                     e <= ref.pressure_l2_tolerance,
                     std::string(what) + " = " + format(e, 2) + " (tolerance " +
                       format(ref.pressure_l2_tolerance, 1));
    }


    template <int dim>
    CheckResult
    ContactChecks<dim>::check_friction_ratio(const PairSummary &pair) const
    {
      const auto          &ref = reference;
      const Tensor<1, dim> n   = reference_normal<dim>(ref);
      const Tensor<1, dim> F   = pair.force;
      const double         F_n = F * n;
      double               ratio =
        std::abs(F_n) > 0 ? (F - F_n * n).norm() / std::abs(F_n) : 0.;
      if (ref.friction_ratio_contact_frame)
        ratio = pair.normal_force_local > 0 ?
                  pair.tangential_force_local / pair.normal_force_local :
                  0.;
      return compared(
        ref.friction_ratio_contact_frame ?
          "friction force ratio sum|f_t|/sum|f_n| (contact frames)" :
          "friction force ratio |F_t|/|F_n|",
        ratio,
        ref.friction_ratio,
        std::abs(ratio - ref.friction_ratio) / ref.friction_ratio,
        ref.friction_ratio_tolerance,
        "relative error");
    }


    // Steady sliding: the largest step-to-step change of the contact force
    // of pair 1 over the steady steps, against their mean.
    template <int dim>
    CheckResult
    ContactChecks<dim>::check_force_variation() const
    {
      const auto &ref  = reference;
      double      mean = 0, jump = 0;
      for (unsigned int k = 0; k < steady_forces.size(); ++k)
        {
          mean += steady_forces[k].norm() / steady_forces.size();
          if (k > 0)
            jump =
              std::max(jump, (steady_forces[k] - steady_forces[k - 1]).norm());
        }
      const double e = mean > 0 ? jump / mean : 0.;
      const bool   pass =
        e <= ref.force_variation_tolerance && steady_forces.size() > 1;
      return checked("largest step-to-step change of the contact force",
                     e,
                     ref.force_variation_tolerance,
                     pass,
                     "largest step-to-step change of the contact force over " +
                       std::to_string(steady_forces.size()) +
                       " steps = " + format(e, 2) + " of its mean (tolerance " +
                       format(ref.force_variation_tolerance, 1));
    }


    // The gap of closed points and the penetration of open ones. Before
    // the gap has closed only penetration is checked; at the last step the
    // gap must have closed.
    template <int dim>
    CheckResult
    ContactChecks<dim>::check_gaps(const Records &records,
                                   const double   time) const
    {
      const auto  &ref        = reference;
      double       closed_gap = 0, penetration = 0;
      unsigned int n_closed = 0;
      for (const auto &r : records)
        if (r.status != Contact::PointStatus::free)
          {
            ++n_closed;
            closed_gap = std::max(closed_gap, std::abs(r.gap));
          }
        else if (r.paired)
          penetration = std::max(penetration, r.gap);
      const double error = std::max(closed_gap, penetration);
      const bool   pass =
        (n_closed > 0 || !is_last_step(time)) && error <= ref.gap_tolerance;
      return checked("gap",
                     error,
                     ref.gap_tolerance,
                     pass,
                     "gap: " + std::to_string(n_closed) +
                       " closed points, largest |g| there = " +
                       format(closed_gap, 2) +
                       " m, largest penetration of an open point = " +
                       format(penetration, 2) + " m (tolerance " +
                       format(ref.gap_tolerance, 1));
    }


    // The total contact force of pair 1 on its master against 'Contact
    // force' (the compared components; '*' for the others).
    template <int dim>
    CheckResult
    ContactChecks<dim>::check_contact_force(const PairSummary &pair,
                                            const double       time) const
    {
      const auto &ref           = reference;
      const auto  compared_text = [this](const Tensor<1, dim> &v) {
        std::string text = "(";
        for (unsigned int d = 0; d < dim; ++d)
          text += (d ? ", " : "") +
                  (force_compared[d] ?
                      format(std::abs(v[d]) < 1e-10 * v.norm() ? 0. : v[d], 4) :
                      std::string("*"));
        return text + ")";
      };
      exact_force->set_time(time);
      Vector<double> values(dim);
      exact_force->vector_value(Point<dim>(), values);
      Tensor<1, dim> F_ref, F;
      for (unsigned int d = 0; d < dim; ++d)
        if (force_compared[d])
          {
            F_ref[d] = values[d];
            F[d]     = pair.force[d];
          }
      const double error =
        F_ref.norm() > 0 ? (F - F_ref).norm() / F_ref.norm() : F.norm();
      return checked("contact force on the master of pair 1",
                     error,
                     ref.contact_force_tolerance,
                     error <= ref.contact_force_tolerance,
                     "contact force on the master of pair 1 = " +
                       compared_text(F) + " (reference " +
                       compared_text(F_ref) + ") relative error " +
                       format(error, 2) + " (tolerance " +
                       format(ref.contact_force_tolerance, 1),
                     F.norm(),
                     F_ref.norm());
    }


    template <int dim>
    CheckResult
    ContactChecks<dim>::check_point_value(
      const ReferenceParameters::PointValue &pv,
      const std::function<double(const Point<dim> &, const unsigned int)>
        &displacement_at) const
    {
      const char *axis[] = {"x", "y", "z"};
      Point<dim>  p;
      for (unsigned int d = 0; d < dim && d < pv.point.size(); ++d)
        p[d] = pv.point[d];
      const double       value = displacement_at(p, pv.component);
      std::ostringstream what;
      what << "u_" << axis[pv.component] << "(";
      for (unsigned int d = 0; d < dim; ++d)
        what << (d ? ", " : "") << p[d];
      what << ")";
      return compared(what.str(),
                      value,
                      pv.value,
                      std::abs(value - pv.value) /
                        std::max(std::abs(pv.value), 1e-300),
                      pv.tolerance,
                      "relative error");
    }


    // Action = reaction and the direction of friction, per pair
    // (ContactProblem::law_checks()).
    template <int dim>
    void
    ContactChecks<dim>::check_laws(const StepData<dim>      &data,
                                   std::vector<CheckResult> &results) const
    {
      const auto  &ref         = reference;
      const double force_level = data.force_level;
      bool         friction    = false;
      for (const auto &pair : parameters.contact.pairs)
        friction = friction || pair.friction > 0;
      // The slip the friction is checked against: the bodies' own, from
      // the displacement field (field_slips.h).
      const auto checks =
        data.contact->law_checks(data.state,
                                 friction && ref.slip_law_tolerance > 0 ?
                                   field_slips(*data.contact, data) :
                                   std::vector<Tensor<1, dim>>());
      for (unsigned int p = 0; p < checks.size(); ++p)
        {
          const auto       &c    = checks[p];
          const std::string pair = "pair " + std::to_string(p + 1);
          if (ref.action_reaction_tolerance > 0)
            {
              // An open pair (both forces round-off) is measured against
              // the force level of the step.
              const double scale = std::max({c.force_rows.norm(),
                                             c.force_multipliers.norm(),
                                             1e-6 * force_level});
              const double e =
                scale > 0 ?
                  (c.force_rows - c.force_multipliers).norm() / scale :
                  0.;
              results.push_back(checked(
                "action = reaction, " + pair,
                e,
                ref.action_reaction_tolerance,
                e <= ref.action_reaction_tolerance,
                "action = reaction, " + pair +
                  ": force on the master from the displacement rows " +
                  vector_text(c.force_rows, scale) + ", from the multipliers " +
                  vector_text(c.force_multipliers, scale) +
                  ", relative difference " + format(e, 2) + " (tolerance " +
                  format(ref.action_reaction_tolerance, 1)));
            }
          if (ref.slip_law_tolerance == 0 ||
              parameters.contact.pairs[p].friction == 0)
            continue;
          const char *where = c.by_node ? "node" : "point";
          if (c.n_slipping == 0)
            {
              results.push_back(
                not_checked("slip law, " + pair,
                            "slip law, " + pair + ": no " + where +
                              " slips at this step (not checked)"));
              continue;
            }
          // The slip the law was given must be the bodies' slip: 1e-2 of
          // the largest (measured at most 3.5e-4: projections just outside
          // a master face, taken at its edge here; 2.2e-6 or below in the
          // scenes without such points).
          constexpr double slip_bar = 1e-2;
          const bool       pass     = c.n_opposed == c.n_slipping &&
                            c.max_deviation <= ref.slip_law_tolerance &&
                            c.max_slip_difference <= slip_bar;
          std::ostringstream text;
          text << "slip law, " << pair
               << ": friction against the bodies' slip (from the "
                  "displacement field; the law's own differs by "
               << format(c.max_slip_difference, 2)
               << " of the largest, at most " << format(slip_bar, 0) << ") at "
               << c.n_opposed << " of " << c.n_slipping << " slipping " << where
               << "s (smallest cosine " << std::fixed << std::setprecision(4)
               << c.min_cosine << "), |f_t| = mu |f_n| to "
               << format(c.max_deviation, 2) << " (tolerance "
               << format(ref.slip_law_tolerance, 1);
          results.push_back(checked("slip law, " + pair,
                                    c.max_deviation,
                                    ref.slip_law_tolerance,
                                    pass,
                                    text.str()));
        }
    }


    // Cattaneo-Mindlin partial slip (Johnson, Contact Mechanics, 7.1-7.2):
    // under a constant normal force P and a tangential force Q below mu P
    // the contact sticks in a central zone of half-width
    // c = a (1 - Q/(mu P))^(1/m) (m = 2 cylinder, 3 sphere); after Q turns
    // at Q*, the new stick zone is that of first loading with (Q* - Q)/2
    // (Masing).
    template <int dim>
    void
    ContactChecks<dim>::check_stick_zone(
      const Records                      &records,
      const Contact::ContactProblem<dim> &contact,
      std::vector<CheckResult>           &results)
    {
      const auto          &ref = reference;
      const Tensor<1, dim> n   = reference_normal<dim>(ref);
      const double         mu  = parameters.contact.pairs[0].friction;
      const Tensor<1, dim> F   = contact.summary()[0].force;
      const double         P   = std::abs(F * n);
      const Tensor<1, dim> F_t = F - (F * n) * n;
      if (mu == 0 || P == 0)
        {
          results.push_back(not_checked(
            "stick zone",
            std::string("stick zone: not checked (") +
              (mu == 0 ? "pair 1 is frictionless" : "no normal force") + ")"));
          return;
        }
      // A tangential force below 1e-4 mu P is no tangential load: it moves
      // c by less than 1e-4 a, and a symmetric pressing step can leave
      // one of about 5e-7 P that depends on round-off (anti-cycling
      // freezes on 2 ranks, where MUMPS sums in a varying order).
      const double small = 1e-4 * mu * P;
      // The tangent: across n in 2D, the first tangential force's
      // direction in 3D.
      if (mindlin_tangent.norm() == 0)
        {
          if (dim == 2)
            {
              mindlin_tangent[0] = n[1];
              mindlin_tangent[1] = -n[0];
            }
          else if (F_t.norm() > small)
            mindlin_tangent = F_t / F_t.norm();
        }
      const double Q = F * mindlin_tangent;
      if (mindlin_direction == 0 && std::abs(Q) > small)
        mindlin_direction = Q > 0 ? 1 : -1;
      else if (mindlin_direction != 0 &&
               (Q - mindlin_q_last) * mindlin_direction < -small)
        {
          mindlin_q_turn    = mindlin_q_last;
          mindlin_turned    = true;
          mindlin_direction = -mindlin_direction;
        }
      mindlin_q_last = Q;
      // Before the tangential load the theory (c = a) is not what this
      // check measures: points that close within a pressing step carry a
      // slip increment (doc/robustness.md, "Slip ring under a normal load").
      if (mindlin_direction == 0)
        {
          results.push_back(
            not_checked("stick zone",
                        "stick zone: no tangential force yet (not checked)"));
          return;
        }
      const double     load   = mindlin_turned ?
                                  std::abs(Q - mindlin_q_turn) / (2 * mu * P) :
                                  std::abs(Q) / (mu * P);
      const Point<dim> centre = reference_centre<dim>(ref);
      // 2D: half-widths midway between the farthest point inside and the
      // nearest point outside beyond it. 3D: area-equivalent radii
      // sqrt(A / pi) of the closed and of the stick points (A: the sum of
      // their weights), which average the zone over every direction in the
      // contact plane; the farthest stick point alone sits up to an element
      // beyond the mean boundary of a circle cut by a mesh.
      const double a = dim == 2 ? zone_half_width<dim>(records, centre, false) :
                                  zone_equivalent_radius<dim>(records, false);
      const double c = dim == 2 ? zone_half_width<dim>(records, centre, true) :
                                  zone_equivalent_radius<dim>(records, true);
      const double c_ref =
        load < 1 ? a * std::pow(1 - load, 1. / (dim == 2 ? 2 : 3)) : 0.;
      const double error = std::abs(c - c_ref);
      // Theory has a slip annulus wider than the tolerance: a state
      // without a slipping point fails whatever c says.
      unsigned int n_slip = 0;
      for (const auto &r : records)
        n_slip += r.status == Contact::PointStatus::slip;
      const bool slip_missing =
        a - c_ref > ref.half_width_tolerance && n_slip == 0;
      const bool pass = error <= ref.half_width_tolerance && !slip_missing;
      std::ostringstream what;
      what << (dim == 2 ? "stick zone half-width c = " :
                          "stick zone radius (area-equivalent) c = ")
           << format(c, 4) << ", c/a = " << std::fixed << std::setprecision(3)
           << (a > 0 ? c / a : 0.) << " (Cattaneo-Mindlin, "
           << (mindlin_turned ? "|Q - Q*|/(2 mu P)" : "Q/(mu P)") << " = "
           << load << std::defaultfloat << ": c = " << format(c_ref, 4)
           << ") absolute error " << format(error, 2);
      if (slip_missing)
        what << ", no slipping point where theory has a slip annulus of "
             << format(a - c_ref, 2);
      what << " (tolerance " << format(ref.half_width_tolerance, 1);
      results.push_back(checked("stick zone half-width c",
                                error,
                                ref.half_width_tolerance,
                                pass,
                                what.str(),
                                c,
                                c_ref));
    }


    template class ContactChecks<2>;
    template class ContactChecks<3>;
  } // namespace Postprocess
} // namespace Signorini
