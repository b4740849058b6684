#ifndef signorini_contact_obstacles_sphere_h
#define signorini_contact_obstacles_sphere_h

#include <signorini/contact/obstacles/interface.h>

namespace Signorini
{
  namespace Obstacles
  {
    /**
     * Rigid ball {x : |x - c| < R} (a disc in 2D): g = R - |p - c|,
     * n = -(p - c)/|p - c|; at p = c the direction is undefined and e_0 is
     * used. Parameters: subsection 'Sphere'.
     */
    template <int dim>
    class Sphere : public Interface<dim>
    {
    public:
      Sphere() = default;

      /** @param radius R > 0 [m] */
      Sphere(const Point<dim> &center, const double radius);

      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

    protected:
      Projection<dim>
      project_reference(const Point<dim> &p) const override;

    private:
      Point<dim> center;
      double     radius = 1.;
    };
  } // namespace Obstacles
} // namespace Signorini

#endif
