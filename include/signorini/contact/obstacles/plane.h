#ifndef signorini_contact_obstacles_plane_h
#define signorini_contact_obstacles_plane_h

#include <signorini/contact/obstacles/interface.h>

namespace Signorini
{
  namespace Obstacles
  {
    /**
     * Rigid half-space {x : (x - x_0) . nu < 0}: the side behind the plane
     * through x_0 with outward normal nu. The contact normal is n = -nu and
     * g = -(p - x_0) . nu. Parameters: subsection 'Plane'.
     */
    template <int dim>
    class Plane : public Interface<dim>
    {
    public:
      Plane() = default;

      /** @param outward_normal nu, normalised here (nonzero) */
      Plane(const Point<dim> &point, const Tensor<1, dim> &outward_normal);

      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      bool
      flat() const override;

    protected:
      Projection<dim>
      project_reference(const Point<dim> &p) const override;

    private:
      Point<dim>     point;
      Tensor<1, dim> outward_normal;
    };
  } // namespace Obstacles
} // namespace Signorini

#endif
