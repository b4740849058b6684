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

      unsigned int
      n_history_values() const override
      {
        return 13;
      }

      void
      update_history(const SymmetricTensor<2, 3> &strain,
                     const ArrayView<double>     &history) const override;

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
        return {history[12]};
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

    private:
      double yield_stress = 0, isotropic_hardening = 0, kinematic_hardening = 0;
    };
  } // namespace Material
} // namespace Signorini

#endif
