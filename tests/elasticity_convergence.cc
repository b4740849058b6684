// Convergence of the elasticity solver under uniform refinement for the
// manufactured solution u = (s, s), s = sin(pi x) sin(pi y) (lambda = mu = 1):
// the L2 error must fall at the theoretical rate p + 1 for Q1 and Q2. The
// test drives the library through a parameter text, as a user's program
// would, and checks each observed rate within 0.1 of the theory.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <signorini/base/parameters.h>
#include <signorini/driver/simulation.h>

#include <cmath>
#include <fstream>
#include <iomanip>

namespace
{
  std::string
  parameter_text(const unsigned int degree, const unsigned int refinements)
  {
    const std::string f = "2*pi^2*(2*sin(pi*x)*sin(pi*y)-cos(pi*x)*cos(pi*y))";
    return "set Dimension = 2\n"
           "subsection Finite element\n set Degree = " +
           std::to_string(degree) +
           "\nend\n"
           "subsection Geometry\n set Global refinements = " +
           std::to_string(refinements) +
           "\n subsection Body 1\n  set Shape = block\n"
           "  subsection Block\n   set Upper corner = 1, 1\n  end\n end\nend\n"
           "subsection Materials\n subsection Material 1\n"
           "  set Young's modulus = 2.5\n  set Poisson's ratio = 0.25\n"
           "  set Body force = " +
           f + "; " + f +
           "\n end\nend\n"
           "subsection Boundary conditions\n"
           " set Function constants = pi: 3.141592653589793\n"
           " subsection Dirichlet 1\n  set Boundary id = 10, 11, 12, 13\n"
           "  set Components = x, y\n  set Values = 0; 0\n end\nend\n"
           "subsection Output\n set Verbosity = quiet\n"
           " set Postprocessors = reference checks\n set Write CSV = false\n"
           " set Timing summary = false\n"
           " subsection Reference checks\n"
           "  set Displacement = sin(pi*x)*sin(pi*y); sin(pi*x)*sin(pi*y)\n"
           " end\nend\n";
  }
} // namespace

int
main(int argc, char **argv)
{
  using namespace dealii;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                    out("output");
  out << std::fixed << std::setprecision(2);

  for (const unsigned int degree : {1u, 2u})
    {
      out << "Q" << degree << ": expected L2 rate " << degree + 1 << "\n";
      double previous = 0;
      for (unsigned int refinements = 2; refinements <= 5; ++refinements)
        {
          ParameterHandler            prm;
          const Signorini::Parameters parameters =
            Signorini::read_parameters_from_string(parameter_text(degree,
                                                                  refinements),
                                                   prm);
          Signorini::Simulation<2> simulation(parameters, prm, MPI_COMM_WORLD);
          simulation.run();
          const double error =
            simulation.last_check_error("displacement L2 relative error");
          out << "  h = 1/" << (1u << refinements) << ": L2 error "
              << std::scientific << std::setprecision(3) << error << std::fixed
              << std::setprecision(2);
          if (previous > 0)
            {
              const double rate = std::log2(previous / error);
              const bool   ok   = std::abs(rate - (degree + 1)) < 0.1;
              out << ", rate " << rate << (ok ? " (ok)" : " (WRONG)");
              AssertThrow(ok,
                          ExcMessage("L2 rate " + std::to_string(rate) +
                                     " differs from the theoretical " +
                                     std::to_string(degree + 1)));
            }
          out << "\n";
          previous = error;
        }
    }
  return 0;
}
