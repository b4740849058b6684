#ifndef signorini_contact_obstacles_motion_h
#define signorini_contact_obstacles_motion_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace Signorini
{
  namespace Obstacles
  {
    using namespace dealii;

    /**
     * A rigid motion x -> c + R (x - c) + u: rotation R about the centre c
     * (a point at t = 0), then translation u.
     */
    template <int dim>
    struct RigidMotion
    {
      Tensor<2, dim> rotation = unit_symmetric_tensor<dim>();
      Tensor<1, dim> translation;
      Point<dim>     centre;

      /** Where the point x of the obstacle at t = 0 is now. */
      Point<dim>
      apply(const Point<dim> &x) const
      {
        return centre + rotation * (x - centre) + translation;
      }

      /** Where the point now at y was at t = 0. */
      Point<dim>
      inverse(const Point<dim> &y) const
      {
        return centre + transpose(rotation) * (y - centre - translation);
      }
    };


    /**
     * The prescribed motion of a rigid obstacle as a function of t:
     * translation u(t) ('Obstacle motion', dim expressions) and rotation
     * ('Obstacle rotation': the angle [rad] about the out-of-plane axis in
     * 2D, counterclockwise; the rotation vector, axis times angle, in 3D)
     * about 'Rotation centre', a point given at t = 0 that moves with u.
     */
    template <int dim>
    class Motion
    {
    public:
      /**
       * @p translation: dim expressions of t; @p rotation: 1 (2D) or 3 (3D)
       * expressions of t, or the single expression "0" (no rotation);
       * @p centre: dim coordinates. @p where names the subsection for the
       * messages (InputError) of entries it cannot use.
       */
      Motion(const std::vector<std::string>      &translation,
             const std::vector<std::string>      &rotation,
             const std::vector<double>           &centre,
             const std::map<std::string, double> &constants,
             const std::string                   &where);

      RigidMotion<dim>
      at(const double t) const;

    private:
      std::unique_ptr<FunctionParser<dim>> translation, rotation;
      Point<dim>                           centre;
    };
  } // namespace Obstacles
} // namespace Signorini

#endif
