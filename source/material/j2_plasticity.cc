#include <signorini/core/errors.h>
#include <signorini/material/j2_plasticity.h>

#include <cmath>

namespace Signorini
{
  namespace Material
  {
    template <int dim>
    void
    J2Plasticity<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("J2 plasticity");
      prm.declare_entry("Yield stress",
                        "0",
                        Patterns::Double(0),
                        "Initial yield stress sigma_y in uniaxial tension "
                        "[Pa]; must be > 0 with this model.");
      prm.declare_entry("Isotropic hardening modulus",
                        "0",
                        Patterns::Double(0),
                        "H_iso [Pa]: the yield stress grows by H_iso times "
                        "the equivalent plastic strain (0: no isotropic "
                        "hardening).");
      prm.declare_entry("Kinematic hardening modulus",
                        "0",
                        Patterns::Double(0),
                        "H_kin [Pa]: the back stress moves by 2/3 H_kin "
                        "times the plastic strain (Prager; 0: none). In "
                        "uniaxial tension the hardening slope d sigma / d "
                        "eps_p is H_iso + H_kin.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    J2Plasticity<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("J2 plasticity");
      yield_stress        = prm.get_double("Yield stress");
      isotropic_hardening = prm.get_double("Isotropic hardening modulus");
      kinematic_hardening = prm.get_double("Kinematic hardening modulus");
      prm.leave_subsection();
      if (!(yield_stress > 0))
        throw InputError("subsection 'J2 plasticity', parameter 'Yield "
                         "stress': it is 0; give the "
                         "initial yield stress in uniaxial tension [Pa] "
                         "(> 0), or use 'Model = linear elastic'.");
    }


    template <int dim>
    typename J2Plasticity<dim>::State
    J2Plasticity<dim>::return_mapping(const SymmetricTensor<2, 3> &strain,
                                      const State                 &old,
                                      SymmetricTensor<2, 3>       &stress,
                                      SymmetricTensor<4, 3> *tangent) const
    {
      const double                mu = this->mu;
      const double                K  = this->lambda + 2. / 3. * mu;
      const double                H = isotropic_hardening + kinematic_hardening;
      const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();
      const SymmetricTensor<2, 3> xi =
        2 * mu * (deviator(strain) - old.plastic_strain) - old.back_stress;
      const double norm_xi = xi.norm();
      const double f =
        norm_xi -
        std::sqrt(2. / 3.) * (yield_stress + isotropic_hardening * old.alpha);
      State state = old;
      if (f <= 0)
        {
          stress = K * trace(strain) * I +
                   2 * mu * (deviator(strain) - old.plastic_strain);
          if (tangent)
            *tangent = K * outer_product(I, I) + 2 * mu * deviator_tensor<3>();
          return state;
        }
      const double                dgamma = f / (2 * mu + 2. / 3. * H);
      const SymmetricTensor<2, 3> n      = xi / norm_xi;
      state.plastic_strain += dgamma * n;
      state.back_stress += 2. / 3. * kinematic_hardening * dgamma * n;
      state.alpha += std::sqrt(2. / 3.) * dgamma;
      stress = K * trace(strain) * I +
               2 * mu * (deviator(strain) - state.plastic_strain);
      if (tangent)
        {
          const double theta     = 1 - 2 * mu * dgamma / norm_xi;
          const double theta_bar = 1 / (1 + H / (3 * mu)) - (1 - theta);
          *tangent               = K * outer_product(I, I) +
                     2 * mu * theta * deviator_tensor<3>() -
                     2 * mu * theta_bar * outer_product(n, n);
        }
      return state;
    }


    template <int dim>
    typename J2Plasticity<dim>::State
    J2Plasticity<dim>::unpack(const ArrayView<const double> &history)
    {
      AssertDimension(history.size(), 13);
      State state;
      for (unsigned int k = 0; k < 6; ++k)
        {
          const auto ij =
            SymmetricTensor<2, 3>::unrolled_to_component_indices(k);
          state.plastic_strain[ij] = history[k];
          state.back_stress[ij]    = history[6 + k];
        }
      state.alpha = history[12];
      return state;
    }


    template <int dim>
    void
    J2Plasticity<dim>::pack(const State             &state,
                            const ArrayView<double> &history)
    {
      AssertDimension(history.size(), 13);
      for (unsigned int k = 0; k < 6; ++k)
        {
          const auto ij =
            SymmetricTensor<2, 3>::unrolled_to_component_indices(k);
          history[k]     = state.plastic_strain[ij];
          history[6 + k] = state.back_stress[ij];
        }
      history[12] = state.alpha;
    }


    template <int dim>
    void
    J2Plasticity<dim>::evaluate(const SymmetricTensor<2, 3>   &strain,
                                const ArrayView<const double> &history,
                                SymmetricTensor<2, 3>         &stress,
                                SymmetricTensor<4, 3>         *tangent) const
    {
      return_mapping(strain, unpack(history), stress, tangent);
    }


    template <int dim>
    void
    J2Plasticity<dim>::update_history(const SymmetricTensor<2, 3> &strain,
                                      const ArrayView<double> &history) const
    {
      SymmetricTensor<2, 3> stress;
      pack(return_mapping(strain,
                          unpack(ArrayView<const double>(history.data(),
                                                         history.size())),
                          stress,
                          nullptr),
           history);
    }


    template class J2Plasticity<2>;
    template class J2Plasticity<3>;
  } // namespace Material
} // namespace Signorini

SIGNORINI_REGISTER_MATERIAL(Signorini::Material::J2Plasticity,
                            "J2 plasticity",
                            "small-strain von Mises plasticity with linear "
                            "isotropic and kinematic hardening, radial return "
                            "and consistent tangent")
