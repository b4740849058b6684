#include <signorini/contact/obstacles/sphere.h>

namespace Signorini
{
  namespace Obstacles
  {
    template <int dim>
    Sphere<dim>::Sphere(const Point<dim> &center, const double radius)
        : center(center)
        , radius(radius)
    {
      AssertThrow(radius > 0., ExcMessage("Sphere: radius must be > 0"));
    }


    template <int dim>
    void
    Sphere<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Sphere");
      prm.declare_entry("Centre",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "Centre c at t = 0 [m].");
      prm.declare_entry("Radius",
                        "1",
                        Patterns::Double(1e-300),
                        "Radius R [m].");
      prm.leave_subsection();
    }


    template <int dim>
    void
    Sphere<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Sphere");
      try
        {
          center = parse_point<dim>(prm, "Centre");
        }
      catch (const InputError &e)
        {
          prm.leave_subsection();
          throw InputError(std::string("subsection 'Sphere', ") + e.what());
        }
      radius = prm.get_double("Radius");
      prm.leave_subsection();
    }


    template <int dim>
    Projection<dim>
    Sphere<dim>::project_reference(const Point<dim> &p) const
    {
      const Tensor<1, dim> d    = p - center;
      const double         dist = d.norm();
      Tensor<1, dim>       e;
      if (dist > 0.)
        e = d / dist;
      else
        e[0] = 1.;
      Projection<dim> r;
      r.x_m    = center + radius * e;
      r.normal = -e;
      r.gap    = radius - dist;
      if (dist > 0.)
        {
          // dn/dp = -(I - e e)/|p - c|, dx^m/dp = R (I - e e)/|p - c|.
          const Tensor<2, dim> tangential =
            unit_symmetric_tensor<dim>() - outer_product(e, e);
          r.dnormal  = -tangential / dist;
          r.dclosest = radius / dist * tangential;
        }
      return r;
    }

    template class Sphere<2>;
    template class Sphere<3>;
  } // namespace Obstacles
} // namespace Signorini

SIGNORINI_REGISTER_OBSTACLE(Signorini::Obstacles::Sphere,
                            "sphere",
                            "rigid ball (a disc in 2D)")
