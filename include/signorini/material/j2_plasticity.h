#ifndef signorini_material_j2_plasticity_h
#define signorini_material_j2_plasticity_h

#include <signorini/material/interface.h>

namespace Signorini
{
  namespace Material
  {
    /**
     * Small-strain J2 (von Mises) plasticity with linear isotropic and
     * linear kinematic (Prager) hardening, model 'J2 plasticity' (doc/
     * theory.md, "Materials"). With K = E / (3 (1 - 2 nu)), mu the shear
     * modulus, eps_p the plastic strain, beta the back stress and alpha the
     * equivalent plastic strain:
     *
     *   sigma = K tr(eps) I + 2 mu dev(eps - eps_p),
     *   f = |dev sigma - beta| - sqrt(2/3) (sigma_y + H_iso alpha) <= 0,
     *
     * and on yielding the associated flow eps_p' = gamma' n,
     * beta' = 2/3 H_kin gamma' n, alpha' = sqrt(2/3) gamma', with
     * n = (dev sigma - beta) / |dev sigma - beta|. Backward Euler gives the
     * radial return: from the trial xi = 2 mu dev(eps - eps_p,n) - beta_n,
     *   Delta gamma = f(xi) / (2 mu + 2/3 (H_iso + H_kin)),
     * and the consistent tangent
     *   C = K I x I + 2 mu theta I_dev - 2 mu theta_bar n x n,
     *   theta = 1 - 2 mu Delta gamma / |xi|,
     *   theta_bar = 1 / (1 + (H_iso + H_kin) / (3 mu)) - (1 - theta).
     * In uniaxial stress the model yields at sigma_y and hardens with the
     * slope d sigma / d eps_p = H_iso + H_kin.
     *
     * History per point (13 values): eps_p (6), beta (6), alpha.
     * Parameters: subsection 'J2 plasticity' of 'Material k'.
     *
     * Finite strain ('Kinematics = finite strain'; isotropic hardening
     * only): multiplicative split F = F_e F_p with the exponential-map
     * return of Simo (1992) and Hencky (logarithmic) elasticity. With the
     * committed C_p^-1, the trial b_e = F C_p^-1 F^T and its logarithmic
     * strain eps_tr = 1/2 ln b_e, the radial return above, applied to
     * eps_tr with eps_p = 0, gives the Kirchhoff stress tau and the return
     * D = d tau / d eps_tr; the spatial tangent is
     *   c : d = D : (1/2 L : (d b_e + b_e d)) - (d tau + tau d),
     * with L the derivative of the tensor logarithm (Daleckii-Krein in the
     * eigenbasis of b_e). The converged elastic strain eps_e = eps_tr -
     * Delta gamma n gives b_e = exp(2 eps_e) and C_p^-1 = F^-1 b_e F^-T.
     * In uniaxial stress tau against ln(stretch) is the small-strain curve.
     * History (7 values): C_p^-1 - I (6), alpha.
     */
    template <int dim>
    class J2Plasticity : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      evaluate(const SymmetricTensor<2, 3>   &strain,
               const ArrayView<const double> &history,
               SymmetricTensor<2, 3>         &stress,
               SymmetricTensor<4, 3>         *tangent) const override;

      bool
      supports(const Kinematics) const override
      {
        return true;
      }

      unsigned int
      n_history_values() const override
      {
        return finite() ? 7 : 13;
      }

      void
      update_history(const SymmetricTensor<2, 3> &strain,
                     const ArrayView<double>     &history) const override;

      void
      evaluate_finite_strain(const Tensor<2, 3>            &F,
                             const ArrayView<const double> &history,
                             SymmetricTensor<2, 3>         &tau,
                             SymmetricTensor<4, 3> *tangent) const override;

      void
      update_history_finite_strain(
        const Tensor<2, 3>      &F,
        const ArrayView<double> &history) const override;

      /** The equivalent plastic strain alpha (accumulated
       * sqrt(2/3) |d eps_p|); positive where the material has yielded. */
      std::vector<std::string>
      history_output_names() const override
      {
        return {"equivalent_plastic_strain"};
      }

      std::vector<double>
      history_output(const ArrayView<const double> &history) const override
      {
        return {history[finite() ? 6 : 12]};
      }

      bool
      is_linear() const override
      {
        return false;
      }

      /** The state of a point after the return mapping. */
      struct State
      {
        SymmetricTensor<2, 3> plastic_strain, back_stress;
        double                alpha = 0;
      };

      /** The radial return from the committed @p old state for the strain
       * @p strain: the new state, the stress, and if @p tangent is given
       * the consistent tangent. */
      State
      return_mapping(const SymmetricTensor<2, 3> &strain,
                     const State                 &old,
                     SymmetricTensor<2, 3>       &stress,
                     SymmetricTensor<4, 3>       *tangent) const;

      /** The state in the layout of the history values, and back. */
      static State
      unpack(const ArrayView<const double> &history);
      static void
      pack(const State &state, const ArrayView<double> &history);

      /** Finite strain: the trial logarithmic elastic strain eps_tr =
       * 1/2 ln(F C_p^-1 F^T) of the committed @p history, the return from
       * it (stress tau, tangent D if asked), and the state. */
      State
      finite_return(const Tensor<2, 3>            &F,
                    const ArrayView<const double> &history,
                    SymmetricTensor<2, 3>         &eps_tr,
                    SymmetricTensor<2, 3>         &b_tr,
                    SymmetricTensor<2, 3>         &tau,
                    SymmetricTensor<4, 3>         *D) const;

    private:
      bool
      finite() const
      {
        return this->kinematics() == Kinematics::finite_strain;
      }

      double yield_stress = 0, isotropic_hardening = 0, kinematic_hardening = 0;
    };
  } // namespace Material
} // namespace Signorini

#endif
