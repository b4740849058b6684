#ifndef signorini_contact_obstacles_cylinder_h
#define signorini_contact_obstacles_cylinder_h

#include <signorini/contact/obstacles/interface.h>

namespace Signorini
{
  namespace Obstacles
  {
    /**
     * Rigid solid cylinder {x : |P_a (x - a)| < R}, P_a = I - e (x) e the
     * projector orthogonal to the axis direction e through a:
     * g = R - |P_a (p - a)|, n = -P_a (p - a)/|P_a (p - a)|. In 2D the axis
     * is normal to the plane (the cylinder is the disc of radius R around
     * a). On the axis the direction is undefined and the first coordinate
     * direction not parallel to e is used. Parameters: subsection
     * 'Cylinder'.
     */
    template <int dim>
    class Cylinder : public Interface<dim>
    {
    public:
      Cylinder() = default;

      /** @param axis_direction e (3D; ignored in 2D), normalised here
       * @param radius R > 0 [m] */
      Cylinder(const Point<dim>     &axis_point,
               const Tensor<1, dim> &axis_direction,
               const double          radius);

      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

    protected:
      Projection<dim>
      project_reference(const Point<dim> &p) const override;

    private:
      Point<dim>     axis_point;
      Tensor<1, dim> axis_direction; // zero in 2D
      double         radius = 1.;
    };
  } // namespace Obstacles
} // namespace Signorini

#endif
