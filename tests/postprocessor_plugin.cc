// A postprocessor defined outside the library and listed by name in
// 'Output/Postprocessors' (doc/extending.md, B.4): 'pressure resultant'
// integrates the contact pressure over the contact points of every pair,
// F = sum of p w over the closed points, and checks it against its own
// parameter 'Expected resultant'. The scene is the B1 contact patch (two
// blocks, E = 2e6 Pa, nu = 0, mortar rule, the top pushed down by 0.1 m):
// the pressure is p = E 0.05 = 1e5 Pa on the face of width 1 m, so
// F = 1e5 N/m. It also adds F as the column 'pressure_resultant' of
// statistics.csv. Checked facts: F = 1e5 N/m to 1e-10 in the check and to
// the 7 digits of the CSV in the column; and the check bites: a wrong expected
// value fails it and the run counts one failed check more.
#include <deal.II/base/mpi.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/core/parameters.h>
#include <signorini/core/simulation.h>
#include <signorini/postprocess/format.h>
#include <signorini/postprocess/interface.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

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
                                 "(tests/postprocessor_plugin.cc)")

namespace Example
{
  // A faulty postprocessor: its statistics column changes name after the
  // first step, which the run must refuse with a message.
  template <int dim>
  class RenamedColumn : public Signorini::Postprocess::Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &)
    {
    }

    std::vector<CheckResult>
    execute(const Signorini::Postprocess::StepData<dim> &data) override
    {
      data.statistics.add(data.step == 1 ? "first" : "second", data.time);
      return {};
    }
  };
} // namespace Example

SIGNORINI_REGISTER_POSTPROCESSOR(Example::RenamedColumn,
                                 "renamed column",
                                 "a faulty statistics column "
                                 "(tests/postprocessor_plugin.cc)")

namespace
{
  // The patch scene; 'pressure resultant' expects @p expected.
  std::string
  scene(const double expected, const std::string &postprocessors)
  {
    std::ostringstream text;
    text << "set Dimension = 2\n"
            "subsection Geometry\n set Number of bodies = 2\n"
            " subsection Body 1\n  set Shape = block\n"
            "  set Upper corner = 1, 1\n  set Subdivisions = 5, 2\n end\n"
            " subsection Body 2\n  set Shape = block\n"
            "  set Lower corner = 0, 1\n  set Upper corner = 1, 2\n"
            "  set Subdivisions = 4, 2\n end\nend\n"
            "subsection Materials\n set Number of materials = 2\n"
            " subsection Material 1\n  set Material id = 1\n"
            "  set Young's modulus = 2e6\n  set Poisson's ratio = 0\n end\n"
            " subsection Material 2\n  set Material id = 2\n"
            "  set Young's modulus = 2e6\n  set Poisson's ratio = 0\n end\n"
            "end\n"
            "subsection Boundary conditions\n"
            " set Number of Dirichlet conditions = 3\n"
            " subsection Dirichlet 1\n  set Boundary id = 12\n"
            "  set Components = y\n  set Values = 0\n end\n"
            " subsection Dirichlet 2\n  set Boundary id = 10, 20\n"
            "  set Components = x\n  set Values = 0\n end\n"
            " subsection Dirichlet 3\n  set Boundary id = 23\n"
            "  set Components = y\n  set Values = -0.1*t\n end\nend\n"
            "subsection Contact\n set Number of contact pairs = 1\n"
            " subsection Pair 1\n  set Slave boundary id = 22\n"
            "  set Master = body\n  set Master boundary id = 13\n end\nend\n"
            "subsection Reference solution\n"
            " set Maximum contact pressure = 1e5\n"
            " set Pressure tolerance = 1e-8\nend\n"
            "subsection Output\n set Verbosity = quiet\n"
            " set Directory = results\n"
            " set Timing summary = false\n"
            " set Postprocessors = "
         << postprocessors
         << "\n"
            " subsection Pressure resultant\n  set Expected resultant = "
         << expected << "\n end\nend\n";
    return text.str();
  }

  void
  run(std::ostream &out, const double expected)
  {
    dealii::ParameterHandler    prm;
    const Signorini::Parameters parameters =
      Signorini::read_parameters_from_string(
        scene(expected, "reference checks, pressure resultant"), prm);
    Signorini::Simulation<2> simulation(parameters, prm, MPI_COMM_WORLD);
    simulation.run();
    for (const auto &check : simulation.last_step_checks())
      if (check.what == "pressure resultant")
        out << "pressure resultant "
            << Signorini::Postprocess::format(check.value, 8)
            << " N/m, expected " << expected << ": relative error "
            << (check.error < 1e-10 ?
                  std::string("below 1e-10") :
                  Signorini::Postprocess::format(check.error, 2))
            << ", " << (check.pass ? "PASS" : "FAIL") << "; failed checks "
            << simulation.failed_checks() << "\n";
    // The column of the last step in statistics.csv (rank 0 writes it).
    std::ifstream csv("results/statistics.csv");
    std::string   header, row, name, value;
    std::getline(csv, header);
    for (std::string line; std::getline(csv, line);)
      row = line;
    std::istringstream names(header), values(row);
    while (std::getline(names, name, ',') && std::getline(values, value, ','))
      if (name == "pressure_resultant")
        out << "statistics.csv: pressure_resultant = " << value
            << " N/m: equal to 1e5 to the 7 digits of the CSV: "
            << (std::abs(std::stod(value) - 1e5) <= 5e-7 * 1e5 ? "yes" : "NO")
            << "\n";
  }

  // Two load steps with 'renamed column': the second step's row does not
  // match the header, and the run stops with a message.
  void
  run_renamed(std::ostream &out)
  {
    dealii::ParameterHandler    prm;
    const Signorini::Parameters parameters =
      Signorini::read_parameters_from_string(
        scene(1e5, "reference checks, renamed column") +
          "subsection Load stepping\n set Number of steps = 2\nend\n",
        prm);
    Signorini::Simulation<2> simulation(parameters, prm, MPI_COMM_WORLD);
    try
      {
        simulation.run();
        out << "renamed column: the run did not stop\n";
      }
    catch (const Signorini::RunError &e)
      {
        out << "renamed column: " << e.what() << "\n";
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                            out("output");
  run(out, 1e5);   // the exact resultant: passes
  run(out, 1.1e5); // 10 % off: fails, and the run counts it
  run_renamed(out);
  return 0;
}
