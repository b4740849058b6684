#include <deal.II/base/quadrature_lib.h>

#include <signorini/contact/integration_rule.h>

namespace Signorini
{
  namespace Contact
  {
    namespace
    {
      // Closed Newton-Cotes rule of degree 1, 2, 4 or 6 on [0,1]^d.
      template <int d>
      Quadrature<d>
      newton_cotes(const unsigned int order)
      {
        switch (order)
          {
            case 1:
              return QTrapezoid<d>();
            case 2:
              return QSimpson<d>();
            case 4:
              return QMilne<d>();
            default:
              return QWeddle<d>();
          }
      }
    } // namespace


    template <int dim>
    FixedRule<dim>::FixedRule(const IntegrationRule rule,
                              const unsigned int    order,
                              const unsigned int    fe_degree)
        : nodal(rule == IntegrationRule::nodal)
    {
      const std::string per_direction =
        dim == 3 ? " per direction" : std::string();
      switch (rule)
        {
          case IntegrationRule::nodal:
            // FE_Q places its support points at the Gauss-Lobatto points, so
            // this rule collocates at the face nodes: trapezoid for Q1,
            // Simpson for Q2.
            quadrature  = QGaussLobatto<dim - 1>(fe_degree + 1);
            description = "nodal (Gauss-Lobatto, " +
                          std::to_string(fe_degree + 1) + " points" +
                          per_direction + ")";
            break;
          case IntegrationRule::gauss:
            quadrature  = QGauss<dim - 1>(order);
            description = "gauss (" + std::to_string(order) + " points" +
                          per_direction + ")";
            break;
          case IntegrationRule::simpson:
            quadrature  = QIterated<dim - 1>(QSimpson<1>(), order);
            description = "simpson (" + std::to_string(order) + " panels" +
                          per_direction + ")";
            break;
          case IntegrationRule::newton_cotes:
            quadrature  = newton_cotes<dim - 1>(order);
            description = "newton-cotes (degree " + std::to_string(order) + ")";
            break;
          case IntegrationRule::mortar:
            // Segment-based: built per face at every pairing by
            // ContactProblem (segmentation.h), not a fixed rule.
            Assert(false, ExcInternalError());
            break;
        }
    }

    template class FixedRule<2>;
    template class FixedRule<3>;
  } // namespace Contact
} // namespace Signorini
