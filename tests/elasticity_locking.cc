// Volumetric locking and its cure (Finite element/Volumetric strain). The
// divergence-free manufactured solution u = curl(psi), psi = (sin(pi x)
// sin(pi y))^2, on the unit square with u = 0 on the boundary:
//   u_x =  pi sin^2(pi x) sin(2 pi y),  u_y = -pi sin(2 pi x) sin^2(pi y),
// div u = 0, so the body force f = -mu Laplace(u) does not depend on lambda:
//   f_x = -2 mu pi^3 sin(2 pi y) (2 cos(2 pi x) - 1),
//   f_y =  2 mu pi^3 sin(2 pi x) (2 cos(2 pi y) - 1),
// with mu = 1 and nu = 0.3 or 0.4999 (E = 2 (1 + nu)). Checked facts:
// * projected (B-bar): the L2 error falls at the rate p + 1 (within 0.15)
//   for Q1 and Q2 at nu = 0.4999, and on the finest mesh it is within 30 %
//   of the nu = 0.3 error: the discretisation does not lock;
// * full (pointwise volumetric strain): at nu = 0.4999 the error on the
//   finest mesh is more than 10 times the projected one, for Q1 and Q2
//   (locking; measured 193 and 26 times).
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <signorini/base/parameters.h>
#include <signorini/driver/simulation.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>

namespace
{
  std::string
  parameter_text(const unsigned int degree,
                 const unsigned int refinements,
                 const double       nu,
                 const std::string &volumetric)
  {
    std::ostringstream text;
    text << std::setprecision(17);
    text << "set Dimension = 2\n"
         << "subsection Finite element\n set Degree = " << degree
         << "\n set Volumetric strain = " << volumetric << "\nend\n"
         << "subsection Geometry\n set Global refinements = " << refinements
         << "\n subsection Body 1\n  set Shape = block\n"
            "  subsection Block\n   set Upper corner = 1, 1\n  end\n end\nend\n"
            "subsection Materials\n subsection Material 1\n"
            "  set Young's modulus = "
         << 2 * (1 + nu) << "\n  set Poisson's ratio = " << nu
         << "\n  set Body force = -2*pi^3*sin(2*pi*y)*(2*cos(2*pi*x)-1); "
            "2*pi^3*sin(2*pi*x)*(2*cos(2*pi*y)-1)\n"
            " end\nend\n"
            "subsection Boundary conditions\n"
            " set Function constants = pi: 3.141592653589793\n"
            " subsection Dirichlet 1\n  set Boundary id = 10, 11, 12, 13\n"
            "  set Components = x, y\n  set Values = 0; 0\n end\nend\n"
            "subsection Output\n set Verbosity = quiet\n"
            " set Postprocessors = reference checks\n set Write CSV = false\n"
            " set Timing summary = false\n"
            " subsection Reference checks\n"
            "  set Displacement = pi*sin(pi*x)^2*sin(2*pi*y); "
            "-pi*sin(2*pi*x)*sin(pi*y)^2\n"
            " end\nend\n";
    return text.str();
  }

  double
  l2_error(const unsigned int degree,
           const unsigned int refinements,
           const double       nu,
           const std::string &volumetric)
  {
    dealii::ParameterHandler    prm;
    const Signorini::Parameters parameters =
      Signorini::read_parameters_from_string(
        parameter_text(degree, refinements, nu, volumetric), prm);
    Signorini::Simulation<2> simulation(parameters, prm, MPI_COMM_WORLD);
    simulation.run();
    return simulation.last_check_error("displacement L2 relative error");
  }
} // namespace

int
main(int argc, char **argv)
{
  using namespace dealii;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                    out("output");
  const unsigned int               finest = 5;

  for (const unsigned int degree : {1u, 2u})
    {
      out << "Q" << degree << ", nu = 0.4999, projected: expected L2 rate "
          << degree + 1 << "\n";
      double previous = 0, error = 0;
      for (unsigned int refinements = 2; refinements <= finest; ++refinements)
        {
          error = l2_error(degree, refinements, 0.4999, "projected");
          out << "  h = 1/" << (1u << refinements) << ": L2 error "
              << std::scientific << std::setprecision(3) << error;
          if (previous > 0)
            {
              const double rate = std::log2(previous / error);
              const bool   ok   = std::abs(rate - (degree + 1)) < 0.15;
              out << std::fixed << std::setprecision(2) << ", rate " << rate
                  << (ok ? " (ok)" : " (WRONG)");
              AssertThrow(ok,
                          ExcMessage("B-bar L2 rate " + std::to_string(rate)));
            }
          out << "\n";
          previous = error;
        }
      const double compressible = l2_error(degree, finest, 0.3, "projected");
      const double ratio        = error / compressible;
      out << "  h = 1/" << (1u << finest) << ", nu = 0.3: L2 error "
          << std::scientific << std::setprecision(3) << compressible
          << std::fixed << std::setprecision(2)
          << "; nu = 0.4999 / nu = 0.3: " << ratio
          << (ratio < 1.3 ? " (ok, below 1.3)" : " (LOCKS)") << "\n";
      AssertThrow(ratio < 1.3, ExcMessage("B-bar error grows with nu"));
      const double full = l2_error(degree, finest, 0.4999, "full");
      out << "  h = 1/" << (1u << finest) << ", nu = 0.4999, full: L2 error "
          << std::scientific << std::setprecision(3) << full << std::fixed
          << std::setprecision(1) << ", " << full / error
          << " times the projected"
          << (full / error > 10 ? " (locks, ok)" : " (NO LOCKING?)") << "\n";
      AssertThrow(full / error > 10,
                  ExcMessage("full integration did not lock"));
    }
  return 0;
}
