#ifndef signorini_contact_obstacles_interface_h
#define signorini_contact_obstacles_interface_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <signorini/base/parameter_helpers.h>
#include <signorini/base/parameters.h>
#include <signorini/base/plugins.h>
#include <signorini/contact/obstacles/motion.h>

#include <memory>
#include <string>
#include <vector>

/**
 * Rigid obstacles: the master surface of a contact pair that is not a meshed
 * body ('Contact/Pair k/Master' names the obstacle). A plug-in family
 * (base/plugins.h): each obstacle is a class derived from
 * Obstacles::Interface<dim>, registered from its own source file with
 *
 *   SIGNORINI_REGISTER_OBSTACLE(Class, "name", "description")
 *
 * and reads its own parameters from a subsection of 'Pair k' named after
 * it, capitalised ('level set': 'Level set'; doc/extending.md). The
 * library registers 'plane', 'sphere', 'cylinder' and 'level set'.
 */
namespace Signorini
{
  namespace Obstacles
  {
    using namespace dealii;

    /**
     * Closest point, normal and gap of a point with respect to a rigid
     * obstacle surface (doc/theory.md section 2), with the derivatives the
     * Newton linearisation of the geometry needs.
     */
    template <int dim>
    struct Projection
    {
      /** Closest point x^m on the obstacle surface [m]. */
      Point<dim> x_m;

      /** Unit normal at x^m pointing into the obstacle (the master body). */
      Tensor<1, dim> normal;

      /** g = (p - x^m) . n [m]; g > 0 iff p penetrates the obstacle. */
      double gap = 0.;

      /** dn/dp: derivative of the normal with respect to the point. */
      Tensor<2, dim> dnormal;

      /** dx^m/dp: derivative of the closest point. */
      Tensor<2, dim> dclosest;
    };


    /**
     * A rigid obstacle. Its geometry is given in a reference position (at
     * t = 0) and moved rigidly by the motion the contact problem sets for
     * the load time ('Obstacle motion', 'Obstacle rotation' and 'Rotation
     * centre' of the pair).
     */
    template <int dim>
    class Interface
    {
    public:
      virtual ~Interface() = default;

      /**
       * Reads the obstacle's parameters; @p prm is in the subsection
       * 'Contact/Pair k' (the obstacle enters its own subsection). Throws
       * InputError naming the parameter on a value it cannot use.
       */
      virtual void
      parse_parameters(ParameterHandler &prm) = 0;

      /**
       * Called once with the mean slave face size h [m] of the pair, before
       * any projection: a length scale for obstacles that need one (the
       * level set's difference steps).
       */
      virtual void
      set_length_scale(const double h);

      /**
       * True if the normal is the same everywhere (a plane): with a
       * frictionless law the contact statuses are then linear in the
       * displacement.
       */
      virtual bool
      flat() const;

      /**
       * Empty if project() returns exact derivatives; otherwise says how
       * they are approximated (the run prints it: the Jacobian is then not
       * exact, and Newton does not count on it).
       */
      virtual std::string
      approximate_derivatives() const;

      /** Sets the current rigid motion from the reference position (the
       * obstacle at t = 0). */
      void
      set_motion(const RigidMotion<dim> &motion);

      /** A translation [m] without rotation. */
      void
      set_translation(const Tensor<1, dim> &translation);

      const RigidMotion<dim> &
      get_motion() const;

      /**
       * Closest point, inward normal, gap and their derivatives at p [m],
       * for the obstacle in its current position: p is mapped back to the
       * reference position, projected there, and the result is mapped
       * forward (normal R n, dn/dp = R dn R^T, dx^m/dp = R dx^m R^T).
       */
      Projection<dim>
      project(const Point<dim> &p) const;

    protected:
      /** The projection in the reference position (translation zero). */
      virtual Projection<dim>
      project_reference(const Point<dim> &p) const = 0;

    private:
      RigidMotion<dim> motion;
    };


    template <int dim>
    using Registry = Plugins::Registry<Interface<dim>>;

    /**
     * Declares 'Master' (body, or the name of a registered obstacle) and
     * every obstacle's subsection, in the current subsection 'Pair k'.
     */
    void
    declare_master_parameters(ParameterHandler &prm);

    /**
     * The obstacle of every pair (nullptr for Master = body), created from
     * the registry and given its parameters from 'Contact/Pair k'.
     */
    template <int dim>
    std::vector<std::unique_ptr<Interface<dim>>>
    make_obstacles(const Parameters &parameters, ParameterHandler &prm);

    /** A point of dim coordinates from an entry, and a direction
     * (normalised, nonzero): base/parameter_helpers.h. */
    using internal::parse_direction;
    using internal::parse_point;
  } // namespace Obstacles
} // namespace Signorini


/**
 * Registers the obstacle class template @p classname (derived from
 * Obstacles::Interface<dim>, default constructible, with a static
 * declare_parameters(ParameterHandler &)) under @p name for 2D and 3D.
 */
#define SIGNORINI_REGISTER_OBSTACLE(classname, name, description)        \
  namespace                                                              \
  {                                                                      \
    const ::Signorini::Plugins::                                         \
      Registration<::Signorini::Obstacles::Interface<2>, classname<2>>   \
        SIGNORINI_PLUGIN_NAME(signorini_obstacle_2_)(name, description); \
    const ::Signorini::Plugins::                                         \
      Registration<::Signorini::Obstacles::Interface<3>, classname<3>>   \
        SIGNORINI_PLUGIN_NAME(signorini_obstacle_3_)(name, description); \
  }

#endif
