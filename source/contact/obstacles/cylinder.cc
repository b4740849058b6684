#include <signorini/contact/obstacles/cylinder.h>

namespace Signorini
{
  namespace Obstacles
  {
    template <int dim>
    Cylinder<dim>::Cylinder(const Point<dim>     &axis_point,
                            const Tensor<1, dim> &axis_direction,
                            const double          radius)
        : axis_point(axis_point)
        , radius(radius)
    {
      AssertThrow(radius > 0., ExcMessage("Cylinder: radius must be > 0"));
      if (dim == 3)
        {
          AssertThrow(axis_direction.norm() > 0.,
                      ExcMessage("Cylinder: zero axis direction"));
          this->axis_direction = axis_direction / axis_direction.norm();
        }
    }


    template <int dim>
    void
    Cylinder<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Cylinder");
      prm.declare_entry("Axis point",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "A point a of the axis at t = 0 [m] (2D: the centre "
                        "of the disc).");
      prm.declare_entry("Axis direction",
                        "0, 0, 1",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "Direction e of the axis (3D; in 2D the axis is "
                        "normal to the plane).");
      prm.declare_entry("Radius",
                        "1",
                        Patterns::Double(1e-300),
                        "Radius R [m].");
      prm.leave_subsection();
    }


    template <int dim>
    void
    Cylinder<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Cylinder");
      try
        {
          axis_point = parse_point<dim>(prm, "Axis point");
          if (dim == 3)
            axis_direction = parse_direction<dim>(prm, "Axis direction");
        }
      catch (const InputError &e)
        {
          prm.leave_subsection();
          throw InputError(std::string("subsection 'Cylinder', ") + e.what());
        }
      radius = prm.get_double("Radius");
      prm.leave_subsection();
    }


    template <int dim>
    Projection<dim>
    Cylinder<dim>::project_reference(const Point<dim> &p) const
    {
      // In 2D axis_direction is zero and the radial part is all of p - a.
      const Tensor<2, dim> across_axis =
        unit_symmetric_tensor<dim>() -
        outer_product(axis_direction, axis_direction);
      const Tensor<1, dim> d    = across_axis * (p - axis_point);
      const double         dist = d.norm();
      Tensor<1, dim>       e;
      if (dist > 0.)
        e = d / dist;
      else
        // the first coordinate direction not parallel to the axis
        for (unsigned int i = 0; i < dim; ++i)
          {
            const Tensor<1, dim> t = across_axis[i];
            if (t.norm() > 1e-3)
              {
                e = t / t.norm();
                break;
              }
          }
      Projection<dim> r;
      r.x_m    = p + (radius - dist) * e;
      r.normal = -e;
      r.gap    = radius - dist;
      if (dist > 0.)
        {
          // dn/dp = -(P_a - e e)/dist, dx^m/dp = I - e e + (R/dist - 1)
          // (P_a - e e), P_a = I - a a (a = 0 in 2D).
          const Tensor<2, dim> circumferential =
            across_axis - outer_product(e, e);
          r.dnormal  = -circumferential / dist;
          r.dclosest = unit_symmetric_tensor<dim>() - outer_product(e, e) +
                       (radius / dist - 1.) * circumferential;
        }
      return r;
    }

    template class Cylinder<2>;
    template class Cylinder<3>;
  } // namespace Obstacles
} // namespace Signorini

SIGNORINI_REGISTER_OBSTACLE(Signorini::Obstacles::Cylinder,
                            "cylinder",
                            "rigid solid cylinder (3D; a disc in 2D)")
