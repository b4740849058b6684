#include <deal.II/base/function_parser.h>

#include <signorini/base/input_checks.h>
#include <signorini/contact/obstacles/level_set.h>

#include <sstream>

namespace Signorini
{
  namespace Obstacles
  {
    namespace
    {
      // Difference steps relative to the slave face size h: the gradient's
      // truncation error (1e-5)^2 and round-off 1e-16/1e-5 are both below
      // 1e-10 relative; the Hessian's (1e-3)^2 and 1e-16/(1e-3)^2 below
      // 1e-6 relative for a surface curved on the scale of h or more.
      constexpr double gradient_step = 1e-5;
      constexpr double hessian_step  = 1e-3;
    } // namespace


    template <int dim>
    void
    LevelSet<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Level set");
      prm.declare_entry("Function",
                        "",
                        Patterns::Anything(),
                        "Level set phi as an expression of x, y (and z) "
                        "[m] at t = 0: the obstacle is where phi < 0. A "
                        "signed distance (|grad phi| = 1) gives the exact "
                        "gap; any other phi a first-order estimate "
                        "-phi/|grad phi|.");
      prm.declare_entry("Function constants",
                        "",
                        Patterns::Anything(),
                        "Constants of 'Function', as 'name: value, ...'.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    LevelSet<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Level set");
      const std::string expression = prm.get("Function");
      const std::string constants  = prm.get("Function constants");
      prm.leave_subsection();
      const std::string where = "subsection 'Level set', parameter ";
      if (Utilities::trim(expression).empty())
        throw InputError(where + "'Function': give phi(x, y" +
                         (dim == 3 ? ", z" : "") +
                         "), negative inside the obstacle.");
      const std::map<std::string, double> values =
        parse_function_constants(constants, where + "'Function constants': ");
      auto function = std::make_shared<FunctionParser<dim>>(1);
      try
        {
          // muparser's diagnostics go to std::cerr: into the message.
          CerrCapture capture;
          function->initialize(dim == 2 ? "x,y" : "x,y,z", expression, values);
          function->value(Point<dim>());
        }
      catch (const ExceptionBase &)
        {
          throw InputError(where + "'Function': '" + expression +
                           "' is not an expression of x, y" +
                           (dim == 3 ? ", z" : "") + " and the constants.");
        }
      set_function(function, false, false);
    }


    template <int dim>
    void
    LevelSet<dim>::set_function(
      const std::shared_ptr<const Function<dim>> &function,
      const bool                                  gradient_given,
      const bool                                  hessian_given)
    {
      phi            = function;
      exact_gradient = gradient_given;
      exact_hessian  = hessian_given;
    }


    template <int dim>
    void
    LevelSet<dim>::set_length_scale(const double h)
    {
      length_scale = h;
    }


    template <int dim>
    std::string
    LevelSet<dim>::approximate_derivatives() const
    {
      if (exact_gradient && exact_hessian)
        return "";
      std::ostringstream text;
      text << "level set "
           << (exact_gradient ? "Hessian" : "gradient and Hessian")
           << " by central differences (steps " << gradient_step * length_scale
           << ", " << hessian_step * length_scale << " m)";
      return text.str();
    }


    template <int dim>
    Tensor<1, dim>
    LevelSet<dim>::gradient(const Point<dim> &p) const
    {
      if (exact_gradient)
        return phi->gradient(p);
      Assert(length_scale > 0., ExcMessage("set_length_scale() first"));
      const double   h = gradient_step * length_scale;
      Tensor<1, dim> g;
      for (unsigned int i = 0; i < dim; ++i)
        {
          Point<dim> plus = p, minus = p;
          plus[i] += h;
          minus[i] -= h;
          g[i] = (phi->value(plus) - phi->value(minus)) / (2. * h);
        }
      return g;
    }


    template <int dim>
    Tensor<2, dim>
    LevelSet<dim>::hessian(const Point<dim> &p) const
    {
      if (exact_hessian)
        return phi->hessian(p);
      Assert(length_scale > 0., ExcMessage("set_length_scale() first"));
      const double   h = hessian_step * length_scale;
      Tensor<2, dim> H;
      const auto     shifted =
        [&](const int si, const int i, const int sj, const int j) {
          Point<dim> q = p;
          q[i] += si * h;
          q[j] += sj * h;
          return phi->value(q);
        };
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          {
            H[i][j] = (shifted(1, i, 1, j) - shifted(1, i, -1, j) -
                       shifted(-1, i, 1, j) + shifted(-1, i, -1, j)) /
                      (4. * h * h);
            H[j][i] = H[i][j];
          }
      return H;
    }


    template <int dim>
    Projection<dim>
    LevelSet<dim>::project_reference(const Point<dim> &p) const
    {
      const Tensor<1, dim> grad      = gradient(p);
      const double         grad_norm = grad.norm();
      Projection<dim>      r;
      if (!(grad_norm > 0.) || !std::isfinite(grad_norm))
        {
          // No direction: a point where phi is flat cannot be projected.
          r.x_m       = p;
          r.normal[0] = 1.;
          r.gap       = -1e30; // as a point with no master in reach
          return r;
        }
      const Tensor<2, dim> H = hessian(p);
      r.normal               = -grad / grad_norm;
      r.gap                  = -phi->value(p) / grad_norm;
      r.x_m                  = p - r.gap * r.normal;
      const Tensor<2, dim> tangential =
        unit_symmetric_tensor<dim>() - outer_product(r.normal, r.normal);
      r.dnormal                 = -tangential * H / grad_norm;
      const Tensor<1, dim> dgap = r.normal + r.gap / grad_norm * (H * r.normal);
      r.dclosest                = unit_symmetric_tensor<dim>() -
                   outer_product(r.normal, dgap) - r.gap * r.dnormal;
      return r;
    }

    template class LevelSet<2>;
    template class LevelSet<3>;
  } // namespace Obstacles
} // namespace Signorini

SIGNORINI_REGISTER_OBSTACLE(Signorini::Obstacles::LevelSet,
                            "level set",
                            "rigid obstacle where an expression phi(x) < 0")
