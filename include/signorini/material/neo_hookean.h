#ifndef signorini_material_neo_hookean_h
#define signorini_material_neo_hookean_h

#include <signorini/material/interface.h>

namespace Signorini
{
  namespace Material
  {
    /**
     * Compressible neo-Hookean hyperelasticity with the isochoric /
     * volumetric split, model 'neo-Hookean' (finite strain only; doc/
     * theory.md, "Materials"). With J = det F, the isochoric left
     * Cauchy-Green tensor b_bar = J^(-2/3) F F^T, mu the shear modulus and
     * kappa = E / (3 (1 - 2 nu)) the bulk modulus of 'Material k', the
     * stored energy per reference volume is
     *
     *   W = mu / 2 (tr b_bar - 3) + kappa U(J),
     *   U(J) = (J^2 - 1 - 2 ln J) / 4,
     *
     * (U as in step-44: U(1) = U'(1) = 0, U''(1) = 1, U -> infinity as
     * J -> 0 or infinity). The Kirchhoff stress is
     *
     *   tau = mu dev(b_bar) + kappa / 2 (J^2 - 1) I,
     *
     * and the spatial tangent (d tau = c : d + l tau + tau l^T)
     *
     *   c = 2/3 mu tr(b_bar) P - 2/3 (tau_iso x I + I x tau_iso)
     *       + kappa J^2 I x I - kappa (J^2 - 1) I_s,
     *
     * with P = I_s - 1/3 I x I and tau_iso = mu dev(b_bar). At F = I the
     * tangent is lambda I x I + 2 mu I_s: for small strains the model is
     * linear elasticity with the same E and nu. No parameters of its own,
     * no history.
     */
    template <int dim>
    class NeoHookean : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        (void)prm;
      }

      bool
      supports(const Kinematics kinematics) const override
      {
        return kinematics == Kinematics::finite_strain;
      }

      void
      evaluate_finite_strain(const Tensor<2, 3>            &F,
                             const ArrayView<const double> &history,
                             SymmetricTensor<2, 3>         &tau,
                             SymmetricTensor<4, 3> *tangent) const override;

      bool
      is_linear() const override
      {
        return false;
      }

      /** The bulk modulus kappa = E / (3 (1 - 2 nu)) [Pa]. */
      double
      bulk_modulus() const
      {
        return this->E / (3 * (1 - 2 * this->nu));
      }
    };
  } // namespace Material
} // namespace Signorini

#endif
