// A rigid obstacle defined outside the library and selected by name
// (doc/extending.md, B.2): 'cone', a solid cone with its apex, the axis
// pointing from the apex into the solid, and its semi-angle alpha.
//
// Scene (axisymmetric, units mm, N, MPa; x is the radius r, y the axis z):
// a cylinder of radius and height 50 (E = 20000, nu = 0.3) with its top
// centre at the apex of a cone of semi-angle 80 degrees (its flank makes
// theta = 10 degrees with the top face), pushed against the cone by a
// pressure q on its bottom face. Sneddon's solution for a rigid cone on a
// half-space (E* = E / (1 - nu^2) = 21978 MPa):
//   P = (pi / 2) E* a^2 tan(theta),   p(r) = p_m acosh(a / r) for r < a,
//   p_m = E* tan(theta) / 2 = 1937.66 MPa.
// The load q = 19.3766 MPa on the radius-50 face is the force P = 152183 N
// for a = 5 mm. Checked facts:
// * the cone's contact radius against a = 5 mm to one element (0.078 mm;
//   measured 0.039 mm), and the force on the cone against P (the
//   reference checks of the .prm text below). The pressure is not checked
//   against p(r): measured, it is 2 to 10 % above Sneddon's between
//   r = 2.5 and 0.2 mm (Sneddon's linearised contact condition on a
//   half-space against the current configuration of a finite body), and
//   at the axis node p(0) is infinite;
// * the library's 'level set' obstacle with the cone's signed distance
//   phi = |x| cos(alpha) - (y - 50) sin(alpha) (derivatives by central
//   differences) gives the same contact: the same number of closed points
//   and the same largest pressure and contact force to 1e-8.
#include <deal.II/base/mpi.h>

#include <signorini/contact/obstacles/interface.h>
#include <signorini/core/parameters.h>
#include <signorini/core/simulation.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

namespace Example
{
  using namespace dealii;
  using Signorini::Obstacles::Projection;

  template <int dim>
  class Cone : public Signorini::Obstacles::Interface<dim>
  {
  public:
    // Its own parameters, in subsection 'Pair k/Cone'.
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Cone");
      prm.declare_entry("Apex",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "Apex at t = 0.");
      prm.declare_entry("Axis",
                        "0, 1, 0",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "Axis direction from the apex into the cone.");
      prm.declare_entry("Semi-angle",
                        "45",
                        Patterns::Double(0, 90),
                        "Angle between the axis and the flank [degrees].");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm) override
    {
      prm.enter_subsection("Cone");
      apex  = Signorini::Obstacles::parse_point<dim>(prm, "Apex");
      axis  = Signorini::Obstacles::parse_direction<dim>(prm, "Axis");
      alpha = prm.get_double("Semi-angle") * numbers::PI / 180.;
      prm.leave_subsection();
    }

  protected:
    // In the half plane of the axis and p: w = p - apex = z e + r u. The
    // flank through the apex along s u + c e (s = sin alpha, c = cos alpha)
    // has the outward normal nu = c u - s e, phi = w . nu the signed
    // distance to it; beyond the apex (w . (s u + c e) < 0) the apex is the
    // closest point. On the axis (r = 0) the normal is the axis, by
    // symmetry.
    Projection<dim>
    project_reference(const Point<dim> &p) const override
    {
      const Tensor<1, dim> w      = p - apex;
      const double         z      = w * axis;
      const Tensor<1, dim> radial = w - z * axis;
      const double         r      = radial.norm();
      const double         c = std::cos(alpha), s = std::sin(alpha);
      const auto           I = unit_symmetric_tensor<dim>();
      Projection<dim>      result;
      if (r == 0.)
        {
          result.normal   = axis;
          result.gap      = z;
          result.x_m      = p - z * axis;
          result.dclosest = I - outer_product(axis, axis);
          return result;
        }
      const Tensor<1, dim> u  = radial / r;
      const Tensor<1, dim> nu = c * u - s * axis;
      if (w * (s * u + c * axis) >= 0.)
        {
          // dnu/dp = c (I - e e - u u) / r; grad phi = nu.
          const double         phi = w * nu;
          const Tensor<2, dim> dnu =
            c / r * (I - outer_product(axis, axis) - outer_product(u, u));
          result.normal   = -nu;
          result.gap      = -phi;
          result.x_m      = p - phi * nu;
          result.dnormal  = -dnu;
          result.dclosest = I - outer_product(nu, nu) - phi * dnu;
        }
      else
        {
          const double distance = w.norm();
          result.normal         = -w / distance;
          result.gap            = -distance;
          result.x_m            = apex;
          result.dnormal =
            -(I - outer_product(result.normal, result.normal)) / distance;
        }
      return result;
    }

  private:
    Point<dim>     apex;
    Tensor<1, dim> axis;
    double         alpha = numbers::PI / 4;
  };
} // namespace Example

SIGNORINI_REGISTER_OBSTACLE(Example::Cone,
                            "cone",
                            "rigid solid cone (tests/obstacle_plugin.cc)")

namespace
{
  // The Sneddon scene with the master @p master and its subsection.
  std::string
  scene(const std::string &master)
  {
    std::ostringstream text;
    text << "set Dimension = 2\nset Axisymmetric = true\n"
            "subsection Geometry\n"
            " set Global refinements = 2\n set Local refinements = 4\n"
            " set Refinement region = 8 - sqrt(x^2 + (y - 50)^2)\n"
            " subsection Body 1\n  set Shape = block\n"
            "  set Upper corner = 50, 50\n  set Subdivisions = 10, 10\n"
            " end\nend\n"
            "subsection Materials\n subsection Material 1\n"
            "  set Young's modulus = 20000\n  set Poisson's ratio = 0.3\n"
            " end\nend\n"
            "subsection Boundary conditions\n"
            " set Number of Dirichlet conditions = 1\n"
            " set Number of Neumann conditions = 1\n"
            " subsection Dirichlet 1\n  set Boundary id = 10\n"
            "  set Components = x\n  set Values = 0\n end\n"
            " subsection Neumann 1\n  set Boundary id = 12\n"
            "  set Type = pressure\n  set Values = 19.376591*t\n end\n"
            "end\n"
            "subsection Contact\n set Number of contact pairs = 1\n"
            " set Integration rule = nodal\n set Initial status = closed\n"
            " subsection Pair 1\n  set Slave boundary id = 13\n"
            "  set Master = "
         << master << "\n"
         << (master == "cone" ?
               "  subsection Cone\n   set Apex = 0, 50\n"
               "   set Axis = 0, 1\n   set Semi-angle = 80\n  end\n" :
               "  subsection Level set\n"
               "   set Function = abs(x)*cos(alpha) - (y - 50)*sin(alpha)\n"
               "   set Function constants = alpha: 1.3962634015954636\n"
               "  end\n")
         << " end\nend\n"
            "subsection Reference solution\n"
            " set Contact half-width = 5\n set Contact centre = 0, 50\n"
            " set Half-width tolerance = 0.08\n"
            " set Contact force = *; 152183.39*t\n"
            " set Contact force tolerance = 1e-8\n"
            " set Action-reaction tolerance = 1e-8\nend\n"
            "subsection Output\n set Verbosity = quiet\n"
            " set Postprocessors = reference checks\n set Write CSV = false\n"
            " set Timing summary = false\nend\n";
    return text.str();
  }

  using Summary = Signorini::Contact::ContactProblem<2>::PairSummary;

  Summary
  run(std::ostream &out, const std::string &master)
  {
    dealii::ParameterHandler    prm;
    const Signorini::Parameters parameters =
      Signorini::read_parameters_from_string(scene(master), prm);
    Signorini::Simulation<2> simulation(parameters, prm, MPI_COMM_WORLD);
    simulation.run();
    const Summary s = simulation.contact_summary().at(0);
    out << master << ": " << s.n_contact << " of " << s.n_points
        << " points closed, largest pressure " << std::scientific
        << std::setprecision(6) << s.p_max << " MPa, force on the cone "
        << s.force[1] << " N (Sneddon 1.521834e+05), failed reference checks "
        << simulation.failed_checks() << std::defaultfloat << "\n";
    AssertThrow(simulation.failed_checks() == 0,
                dealii::ExcMessage(master + ": a reference check failed"));
    return s;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                            out("output");
  const Summary                            cone      = run(out, "cone");
  const Summary                            level_set = run(out, "level set");
  const double dp = std::abs(cone.p_max - level_set.p_max) / cone.p_max;
  const double df = (cone.force - level_set.force).norm() / cone.force.norm();
  const bool   same =
    cone.n_contact == level_set.n_contact && dp <= 1e-8 && df <= 1e-8;
  out << "level set = cone: closed points " << cone.n_contact << " and "
      << level_set.n_contact << ", largest pressure differs by "
      << std::scientific << std::setprecision(1) << std::max(dp, 1e-16)
      << ", force by " << std::max(df, 1e-16)
      << " (tolerance 1e-8): " << (same ? "PASS" : "FAIL") << "\n";
  AssertThrow(same, dealii::ExcMessage("level set and cone differ"));
  return 0;
}
