#ifndef signorini_postprocess_reference_parameters_h
#define signorini_postprocess_reference_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <signorini/base/parameters.h>

#include <string>
#include <vector>

namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    /**
     * The references of the postprocessor 'reference checks' (subsection
     * 'Output/Reference checks'): exact solutions and closed forms the run
     * compares itself against. Written by parse_parameters() only; read by
     * the checks (SolutionErrors, ContactChecks).
     */
    struct ReferenceParameters
    {
      std::vector<std::string> displacement; // empty: no reference
      std::vector<std::string> stress;       // dim*dim expressions, row-major
      std::string              history_name; // a history quantity, or empty
      std::vector<std::string> history;      // its expression (one or none)
      double                   tolerance;
      // Contact checks (0 / empty: not checked). p0 and a: expressions of t
      // ("" when not checked).
      std::string         max_pressure;
      double              pressure_tolerance;
      double              friction_ratio, friction_ratio_tolerance;
      double              friction_ratio_from; // first time checked
      std::vector<double> friction_ratio_normal;
      bool                friction_ratio_contact_frame;
      double              force_variation_tolerance; // 0: not checked
      bool                cattaneo_mindlin;          // stick zone check
      std::string         half_width;
      double              half_width_tolerance;
      std::vector<double> contact_centre;
      std::string         contact_pressure;
      double              pressure_l2_tolerance;
      struct PointValue
      {
        std::vector<double> point;
        unsigned int        component;
        double              value;
        double              tolerance; // relative
      };
      std::vector<PointValue>  point_values;
      double                   point_value_tolerance;
      double                   point_values_from;         // first time checked
      double                   action_reaction_tolerance; // 0: not checked
      double                   slip_law_tolerance;        // 0: not checked
      std::vector<std::string> contact_force;             // empty: not checked
      double                   contact_force_tolerance;
      double                   contact_force_from; // first time checked
      double                   gap_tolerance;      // 0: not checked

      /** Some reference is given (a check is asked for). */
      bool
      any() const;

      /** Declares the entries in the current subsection of @p prm. */
      static void
      declare_parameters(ParameterHandler &prm);
      /** Reads them from the current subsection of @p prm, and checks them
       * against the run's @p parameters (sizes, expressions). */
      void
      parse_parameters(ParameterHandler &prm, const Parameters &parameters);

    private:
      void
      check(const Parameters &parameters) const;
    };
  } // namespace Postprocess
} // namespace Signorini

#endif
