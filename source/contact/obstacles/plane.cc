#include <signorini/contact/obstacles/plane.h>

namespace Signorini
{
  namespace Obstacles
  {
    template <int dim>
    Plane<dim>::Plane(const Point<dim> &point, const Tensor<1, dim> &normal)
        : point(point)
        , outward_normal(normal / normal.norm())
    {
      AssertThrow(normal.norm() > 0., ExcMessage("Plane: zero normal"));
    }


    template <int dim>
    void
    Plane<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Plane");
      prm.declare_entry("Point",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "A point x_0 of the plane at t = 0 [m].");
      prm.declare_entry("Outward normal",
                        "0, 1, 0",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "Normal nu of the plane pointing out of the "
                        "obstacle, towards the slave body (normalised).");
      prm.leave_subsection();
    }


    template <int dim>
    void
    Plane<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Plane");
      try
        {
          point          = parse_point<dim>(prm, "Point");
          outward_normal = parse_direction<dim>(prm, "Outward normal");
        }
      catch (const InputError &e)
        {
          prm.leave_subsection();
          throw InputError(std::string("subsection 'Plane', ") + e.what());
        }
      prm.leave_subsection();
    }


    template <int dim>
    bool
    Plane<dim>::flat() const
    {
      return true;
    }


    template <int dim>
    Projection<dim>
    Plane<dim>::project_reference(const Point<dim> &p) const
    {
      const double    height = (p - point) * outward_normal;
      Projection<dim> r;
      r.x_m      = p - height * outward_normal;
      r.normal   = -outward_normal;
      r.gap      = -height;
      r.dclosest = unit_symmetric_tensor<dim>() -
                   outer_product(outward_normal, outward_normal);
      return r;
    }

    template class Plane<2>;
    template class Plane<3>;
  } // namespace Obstacles
} // namespace Signorini

SIGNORINI_REGISTER_OBSTACLE(Signorini::Obstacles::Plane,
                            "plane",
                            "rigid half-space behind a plane")
