// A postprocessor defined outside the library, built as a module that the
// stock `signorini` loads ('Additional shared libraries'; doc/extending.md,
// B.4) and listed by name in 'Output/Postprocessors': 'pressure resultant'
// integrates the contact pressure over the closed points of every pair,
// F = sum of p w, checks it against its own parameter 'Expected resultant'
// and adds it as the column 'pressure_resultant' of statistics.csv. No
// main(): tests/postprocessor_plugin.prm.in runs it, and
// tests/bad_input/pressure_resultant_wrong.prm.in shows that its check
// bites.
#include <signorini/base/format.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/postprocess/interface.h>

#include <cmath>

namespace Example
{
  using namespace dealii;
  using Signorini::Postprocess::CheckResult;

  template <int dim>
  class PressureResultant : public Signorini::Postprocess::Interface<dim>
  {
  public:
    // Its own parameters, in subsection 'Output/Pressure resultant'.
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Pressure resultant");
      prm.declare_entry("Expected resultant",
                        "0",
                        Patterns::Double(0),
                        "The integral of the contact pressure [N/m in 2D].");
      prm.declare_entry("Tolerance",
                        "1e-10",
                        Patterns::Double(0),
                        "Relative tolerance of the resultant.");
      prm.leave_subsection();
    }

    void
    parse_parameters(const Signorini::Parameters &,
                     ParameterHandler &prm) override
    {
      prm.enter_subsection("Pressure resultant");
      expected  = prm.get_double("Expected resultant");
      tolerance = prm.get_double("Tolerance");
      prm.leave_subsection();
    }

    std::vector<CheckResult>
    execute(const Signorini::Postprocess::StepData<dim> &data) override
    {
      if (!data.contact)
        return {};
      // Every rank receives every point: the sum is the same on all.
      double resultant = 0;
      for (const auto &point : data.contact->gather_points())
        if (point.status != Signorini::Contact::PointStatus::free)
          resultant += point.p * point.weight;
      data.statistics.add("pressure_resultant", resultant);
      CheckResult check;
      check.what      = "pressure resultant";
      check.value     = resultant;
      check.reference = expected;
      check.error     = std::abs(resultant - expected) / expected;
      check.tolerance = tolerance;
      check.pass      = check.error <= tolerance;
      check.text =
        "pressure resultant = " + Signorini::Postprocess::format(resultant, 6) +
        " (reference " + Signorini::Postprocess::format(expected, 6) +
        ") relative error " + Signorini::Postprocess::format(check.error, 1) +
        (check.pass ? ": PASS" : ": FAIL");
      return {check};
    }

  private:
    double expected = 0, tolerance = 0;
  };
} // namespace Example

SIGNORINI_REGISTER_POSTPROCESSOR(Example::PressureResultant,
                                 "pressure resultant",
                                 "the integral of the contact pressure "
                                 "(tests/plugins/pressure_resultant.cc)")
