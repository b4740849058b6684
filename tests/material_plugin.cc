// A constitutive model defined outside the library and selected by name
// (doc/extending.md, B.3): 'scaled elastic' is linear elasticity with its
// stress multiplied by its own parameter 'Stiffness factor', which it
// delegates to the library's 'linear elastic'. The scene is the B1 contact
// patch (two blocks, E = 2e6 Pa, nu = 0, mortar rule, the top pushed down by
// 0.1 m): the displacement is u_y = -0.05 y whatever the stiffness, and the
// stress and the contact pressure scale with it. Checked facts: with factor
// 1 the model gives what 'linear elastic' gives (sigma_yy = p = 1e5 Pa, to
// 1e-8); with factor 2, sigma_yy = p = 2e5 Pa and the same displacement;
// every reference check passes.
#include <deal.II/base/mpi.h>

#include <signorini/core/parameters.h>
#include <signorini/core/simulation.h>
#include <signorini/material/linear_elastic.h>

#include <fstream>
#include <iomanip>
#include <string>

namespace Example
{
  using namespace dealii;

  template <int dim>
  class ScaledElastic : public Signorini::Material::Interface<dim>
  {
  public:
    // Its own parameters, in subsection 'Material k/Scaled elastic'.
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Scaled elastic");
      prm.declare_entry("Stiffness factor",
                        "1",
                        Patterns::Double(0),
                        "The stress of linear elasticity times this factor.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm) override
    {
      prm.enter_subsection("Scaled elastic");
      factor = prm.get_double("Stiffness factor");
      prm.leave_subsection();
      elastic.set_elastic_constants(this->youngs_modulus(),
                                    this->poissons_ratio());
    }

    void
    evaluate(const SymmetricTensor<2, 3>   &strain,
             const ArrayView<const double> &history,
             SymmetricTensor<2, 3>         &stress,
             SymmetricTensor<4, 3>         *tangent) const override
    {
      elastic.evaluate(strain, history, stress, tangent);
      stress *= factor;
      if (tangent)
        *tangent *= factor;
    }

    bool
    is_linear() const override
    {
      return true;
    }

    double
    representative_modulus() const override
    {
      return factor * this->youngs_modulus();
    }

  private:
    double                                  factor = 1;
    Signorini::Material::LinearElastic<dim> elastic;
  };
} // namespace Example

SIGNORINI_REGISTER_MATERIAL(Example::ScaledElastic,
                            "scaled elastic",
                            "linear elasticity times 'Stiffness factor' "
                            "(tests/material_plugin.cc)")

namespace
{
  // The patch scene with both blocks of model @p model; the exact stress
  // and pressure are @p p.
  std::string
  scene(const std::string &model, const double factor, const double p)
  {
    std::ostringstream text;
    text << "set Dimension = 2\n"
            "subsection Geometry\n set Number of bodies = 2\n"
            " subsection Body 1\n  set Shape = block\n"
            "  set Upper corner = 1, 1\n  set Subdivisions = 5, 2\n end\n"
            " subsection Body 2\n  set Shape = block\n"
            "  set Lower corner = 0, 1\n  set Upper corner = 1, 2\n"
            "  set Subdivisions = 4, 2\n end\nend\n"
            "subsection Materials\n set Number of materials = 2\n";
    for (unsigned int k = 1; k <= 2; ++k)
      text << " subsection Material " << k << "\n  set Material id = " << k
           << "\n  set Model = " << model
           << "\n  set Young's modulus = 2e6\n  set Poisson's ratio = 0\n"
           << "  subsection Scaled elastic\n   set Stiffness factor = "
           << factor << "\n  end\n end\n";
    text << "end\n"
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
            " set Displacement = 0; -0.05*y\n"
            " set Stress = 0; 0; 0; "
         << -p
         << "\n set Tolerance = 1e-8\n"
            " set Maximum contact pressure = "
         << p
         << "\n set Pressure tolerance = 1e-8\n"
            " set Action-reaction tolerance = 1e-8\nend\n"
            "subsection Output\n set Verbosity = quiet\n"
            " set Postprocessors = reference checks\n set Write CSV = false\n"
            " set Timing summary = false\nend\n";
    return text.str();
  }

  void
  run(std::ostream      &out,
      const std::string &model,
      const double       factor,
      const double       p)
  {
    dealii::ParameterHandler    prm;
    const Signorini::Parameters parameters =
      Signorini::read_parameters_from_string(scene(model, factor, p), prm);
    Signorini::Simulation<2> simulation(parameters, prm, MPI_COMM_WORLD);
    simulation.run();
    out << model << " (factor " << factor
        << "), expected sigma_yy = p = " << std::scientific
        << std::setprecision(1) << p << " Pa: displacement error "
        << std::setprecision(1)
        << std::max(simulation.last_check_error(
                      "displacement L2 relative error"),
                    1e-16)
        << ", stress error "
        << std::max(simulation.last_check_error("stress max relative error"),
                    1e-16)
        << ", failed reference checks " << simulation.failed_checks()
        << std::defaultfloat << "\n";
    AssertThrow(simulation.failed_checks() == 0,
                dealii::ExcMessage(model + ": a reference check failed"));
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                            out("output");
  run(out, "linear elastic", 1, 1e5);
  run(out, "scaled elastic", 1, 1e5);
  run(out, "scaled elastic", 2, 2e5);
  return 0;
}
