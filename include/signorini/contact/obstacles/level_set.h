#ifndef signorini_contact_obstacles_level_set_h
#define signorini_contact_obstacles_level_set_h

#include <deal.II/base/function.h>

#include <signorini/contact/obstacles/interface.h>

#include <memory>

namespace Signorini
{
  namespace Obstacles
  {
    /**
     * Rigid obstacle {x : phi(x) < 0} given by a level set phi, ideally a
     * signed distance (|grad phi| = 1). At a point p:
     *
     *   n = -grad phi / |grad phi|,   g = -phi / |grad phi|,
     *   x^m = p - g n,
     *   dn/dp = -(I - n n) H / |grad phi|,   H = hess phi,
     *   dx^m/dp = I - n (x) dg/dp - g dn/dp,
     *   dg/dp = n + g (H n) / |grad phi|.
     *
     * For a signed distance x^m is the closest point of the surface and g
     * the distance; otherwise they are first-order estimates, consistent
     * with their derivatives (Newton stays quadratic).
     *
     * The gradient and Hessian come from the function where it has them
     * (for example Functions::SignedDistance::Sphere); where it has none
     * they are central differences with steps 1e-5 h and 1e-3 h (h the
     * slave face size): then approximate_derivatives() says so. The
     * registered plug-in 'level set' takes phi as an expression
     * (subsection 'Level set'); a plug-in of its own can derive from this
     * class and call set_function().
     */
    template <int dim>
    class LevelSet : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      set_length_scale(const double h) override;

      std::string
      approximate_derivatives() const override;

      /**
       * Uses @p phi; @p exact_gradient / @p exact_hessian say whether its
       * gradient() / hessian() are implemented (else: differences).
       */
      void
      set_function(const std::shared_ptr<const Function<dim>> &phi,
                   const bool                                  exact_gradient,
                   const bool                                  exact_hessian);

    protected:
      Projection<dim>
      project_reference(const Point<dim> &p) const override;

    private:
      Tensor<1, dim>
      gradient(const Point<dim> &p) const;

      Tensor<2, dim>
      hessian(const Point<dim> &p) const;

      std::shared_ptr<const Function<dim>> phi;
      bool   exact_gradient = false, exact_hessian = false;
      double length_scale = 0.;
    };
  } // namespace Obstacles
} // namespace Signorini

#endif
