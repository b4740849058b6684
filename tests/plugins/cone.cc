// A rigid obstacle defined outside the library, built as a module that
// the stock `signorini` loads ('Additional shared libraries'; doc/
// extending.md, B.2): 'cone', a solid cone with its apex, the axis pointing
// from the apex into the solid, and its semi-angle alpha. No main():
// tests/obstacle_plugin.prm.in runs it against Sneddon's solution, and the
// invariant row obstacle_plugin_cone_level_set against the library's
// 'level set' obstacle with the cone's signed distance.
#include <signorini/contact/obstacles/interface.h>

#include <cmath>

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
                            "rigid solid cone (tests/plugins/cone.cc)")
