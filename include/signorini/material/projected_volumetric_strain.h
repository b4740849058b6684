#ifndef signorini_material_projected_volumetric_strain_h
#define signorini_material_projected_volumetric_strain_h

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <signorini/material/interface.h>

#include <cmath>
#include <vector>

/**
 * B-bar against volumetric locking (`Finite element/Volumetric strain =
 * projected`): the volumetric strain theta = tr(eps) (plus the hoop strain
 * u_r / r of an axisymmetric model) is replaced in each cell by its L2
 * projection theta_bar onto the polynomials of one degree less in the unit
 * cell (a constant for Q1, the mean dilatation; Q1 in each unit coordinate
 * for Q2), with the weight of the cell's volume (2 pi r dA axisymmetric):
 *
 *   M_ab = int phi_a phi_b,   G_ai = int phi_a theta(N_i),
 *   theta_bar(u) = phi^T M^-1 G u.
 *
 * The bulk assembler (Bulk::Assembler) gives every constitutive model the
 * strain eps_bar = eps + (theta_bar - theta) / 3 I (Bulk::point_strain())
 * and uses the matching operator d eps_bar / d u_i in the Jacobian
 * (value_at(), derivatives_at()); the stresses written and checked take the
 * same strain. Unlike selective reduced integration, the projection keeps
 * the constant-stress patch test of an axisymmetric model.
 *
 * At finite strain the volumetric strain is ln J, not linear in u: the
 * same projection acts on its values at the points of the rule
 * (coefficients_of(), projection_matrix()), and the bulk assembler forms
 * F_bar = exp((theta_bar - ln J) / 3) F (an F-bar method whose F_bar is
 * the gradient of a potential for hyperelastic models; Bulk::Assembler).
 */
namespace Signorini
{
  namespace Material
  {
    using namespace dealii;

    template <int dim>
    class ProjectedVolumetricStrain
    {
    public:
      /** @p quadrature: the rule of the FEValues given to reinit().
       * @p axisymmetric: x = r, the hoop strain enters theta and the weight
       * 2 pi r the integrals. */
      ProjectedVolumetricStrain(const FiniteElement<dim> &fe,
                                const Quadrature<dim>    &quadrature,
                                const bool                axisymmetric)
          : fe(fe)
          , quadrature(quadrature)
          , basis(fe.degree - 1)
          , axisymmetric(axisymmetric)
          , n_basis(basis.n_dofs_per_cell())
          , phi(n_basis, quadrature.size())
          , M(n_basis, n_basis)
          , M_inv(n_basis, n_basis)
          , G(n_basis, fe.n_dofs_per_cell())
          , M_inv_G(n_basis, fe.n_dofs_per_cell())
      {
        for (unsigned int a = 0; a < n_basis; ++a)
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            phi(a, q) = basis.shape_value(a, quadrature.point(q));
      }

      /** M, G and M^-1 G of the cell of @p fe_values (values, gradients,
       * quadrature points and JxW on the rule given to the constructor). */
      void
      reinit(const FEValues<dim> &fe_values)
      {
        const FEValuesExtractors::Vector displacement(0);
        std::vector<double>              theta(fe.n_dofs_per_cell());
        start_cell();
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            const double r = fe_values.quadrature_point(q)[0];
            for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
              {
                theta[i] = fe_values[displacement].divergence(i, q);
                if (axisymmetric && fe.system_to_component_index(i).first == 0)
                  theta[i] += fe_values.shape_value(i, q) / r;
              }
            add_point(q,
                      fe_values.JxW(q) *
                        (axisymmetric ? 2 * numbers::PI * r : 1.),
                      theta);
          }
        finish_cell();
      }

      /** The same in three parts, for an assembly loop that has theta(N_i)
       * at hand: start_cell(), add_point() at every point q of the rule
       * with its volume dV, finish_cell(). */
      void
      start_cell()
      {
        M = 0;
        G = 0;
        dV.assign(quadrature.size(), 0.);
      }

      void
      add_point(const unsigned int         q,
                const double               dV,
                const std::vector<double> &theta)
      {
        this->dV[q] = dV;
        for (unsigned int a = 0; a < n_basis; ++a)
          {
            const double phi_dV = phi(a, q) * dV;
            for (unsigned int b = 0; b < n_basis; ++b)
              M(a, b) += phi_dV * phi(b, q);
            for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
              G(a, i) += phi_dV * theta[i];
          }
      }

      void
      finish_cell()
      {
        M_inv.invert(M);
        M_inv.mmult(M_inv_G, G);
      }

      /** Coefficients of theta_bar for the cell's DoF values @p u. */
      void
      coefficients(const Vector<double> &u, Vector<double> &theta) const
      {
        theta.reinit(n_basis);
        M_inv_G.vmult(theta, u);
      }

      /** theta_bar at a unit point, from its coefficients. */
      double
      value(const Vector<double> &theta, const Point<dim> &unit_point) const
      {
        double v = 0;
        for (unsigned int a = 0; a < n_basis; ++a)
          v += theta[a] * basis.shape_value(a, unit_point);
        return v;
      }

      /** theta_bar at point @p q of the rule, from its coefficients. */
      double
      value_at(const unsigned int q, const Vector<double> &theta) const
      {
        double v = 0;
        for (unsigned int a = 0; a < n_basis; ++a)
          v += theta[a] * phi(a, q);
        return v;
      }

      /** d theta_bar / d u_i at point @p q of the rule (the B-bar
       * operator's volumetric row), for every DoF i of the cell. */
      void
      derivatives_at(const unsigned int q, std::vector<double> &d) const
      {
        d.assign(fe.n_dofs_per_cell(), 0.);
        for (unsigned int a = 0; a < n_basis; ++a)
          for (unsigned int i = 0; i < d.size(); ++i)
            d[i] += phi(a, q) * M_inv_G(a, i);
      }

      /** Coefficients of the projection of a field given by its
       * @p values at the points of the rule (after finish_cell()). */
      void
      coefficients_of(const std::vector<double> &values,
                      Vector<double>            &theta) const
      {
        Vector<double> moments(n_basis);
        for (unsigned int a = 0; a < n_basis; ++a)
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            moments[a] += phi(a, q) * values[q] * dV[q];
        theta.reinit(n_basis);
        M_inv.vmult(theta, moments);
      }

      /** The projection as a matrix on the point values: P[f](q) =
       * sum_q' Pi(q, q') f(q') (after finish_cell()). */
      void
      projection_matrix(FullMatrix<double> &Pi) const
      {
        const unsigned int nq = quadrature.size();
        Pi.reinit(nq, nq);
        for (unsigned int q = 0; q < nq; ++q)
          for (unsigned int p = 0; p < nq; ++p)
            {
              double v = 0;
              for (unsigned int a = 0; a < n_basis; ++a)
                for (unsigned int b = 0; b < n_basis; ++b)
                  v += phi(a, q) * M_inv(a, b) * phi(b, p);
              Pi(q, p) = v * dV[p];
            }
      }

    private:
      const FiniteElement<dim> &fe;
      const Quadrature<dim>     quadrature;
      const FE_DGQ<dim>         basis; // polynomials of one degree less
      const bool                axisymmetric;
      const unsigned int        n_basis;
      FullMatrix<double>        phi; // basis at the points of the rule
      FullMatrix<double>        M, M_inv, G, M_inv_G;
      std::vector<double>       dV; // the weights of the last cell
    };

    /**
     * Finite strain: the coefficients @p theta of theta_bar = P[ln J] in the
     * cell of @p fe_values (reinit on it, with values, gradients,
     * quadrature points and JxW, on the rule of @p projection: the bulk
     * rule, as in the assembly) for the displacement @p solution.
     */
    template <int dim, typename VectorType>
    void
    projected_log_J(ProjectedVolumetricStrain<dim> &projection,
                    const FEValues<dim>            &fe_values,
                    const VectorType               &solution,
                    const bool                      axisymmetric,
                    Vector<double>                 &theta)
    {
      const FEValuesExtractors::Vector displacement(0);
      const unsigned int               nq = fe_values.n_quadrature_points;
      std::vector<Tensor<2, dim>>      grad(nq);
      std::vector<Tensor<1, dim>>      u(nq);
      std::vector<double>              log_J(nq);
      fe_values[displacement].get_function_gradients(solution, grad);
      fe_values[displacement].get_function_values(solution, u);
      for (unsigned int q = 0; q < nq; ++q)
        log_J[q] = std::log(determinant(
          unit_symmetric_tensor<3>() +
          to_3d<dim>(grad[q],
                     axisymmetric ? u[q][0] / fe_values.quadrature_point(q)[0] :
                                    0.)));
      projection.reinit(fe_values);
      projection.coefficients_of(log_J, theta);
    }
  } // namespace Material
} // namespace Signorini

#endif
