#include <signorini/base/errors.h>
#include <signorini/material/j2_plasticity.h>

#include <array>
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
      if (finite() && kinematic_hardening > 0)
        throw InputError("subsection 'J2 plasticity', parameter 'Kinematic "
                         "hardening modulus': with 'Kinematics = finite "
                         "strain' only isotropic hardening is available "
                         "(a back stress would need a transport between "
                         "configurations); set it to 0 or use 'Kinematics "
                         "= small strain'.");
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


    namespace
    {
      // Symmetric function of a symmetric tensor through its eigenbasis.
      template <typename Function>
      SymmetricTensor<2, 3>
      spectral(const SymmetricTensor<2, 3> &A, const Function &f)
      {
        const auto            eig = eigenvectors(A);
        SymmetricTensor<2, 3> r;
        for (const auto &[x, n] : eig)
          r += f(x) * symmetrize(outer_product(n, n));
        return r;
      }

      // The derivative of ln(b) in the direction db (Daleckii-Krein): in
      // the eigenbasis of b, theta_AB (n_A . db n_B) with theta_AB the
      // divided difference of ln at the eigenvalues x_A, x_B (1 / x_A when
      // they coincide; the geometric mean keeps the limit to second order).
      SymmetricTensor<2, 3>
      log_derivative(const std::array<std::pair<double, Tensor<1, 3>>, 3> &eig,
                     const SymmetricTensor<2, 3>                          &db)
      {
        SymmetricTensor<2, 3> r;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            {
              const double xa = eig[a].first, xb = eig[b].first;
              const double theta = std::abs(xa - xb) > 1e-8 * std::max(xa, xb) ?
                                     (std::log(xa) - std::log(xb)) / (xa - xb) :
                                     1 / std::sqrt(xa * xb);
              const double component = eig[a].second * (db * eig[b].second);
              r += theta * component *
                   symmetrize(outer_product(eig[a].second, eig[b].second));
            }
        return r;
      }
    } // namespace


    template <int dim>
    typename J2Plasticity<dim>::State
    J2Plasticity<dim>::finite_return(const Tensor<2, 3>            &F,
                                     const ArrayView<const double> &history,
                                     SymmetricTensor<2, 3>         &eps_tr,
                                     SymmetricTensor<2, 3>         &b_tr,
                                     SymmetricTensor<2, 3>         &tau,
                                     SymmetricTensor<4, 3>         *D) const
    {
      AssertDimension(history.size(), 7);
      SymmetricTensor<2, 3> Cp_inv = unit_symmetric_tensor<3>();
      for (unsigned int k = 0; k < 6; ++k)
        Cp_inv[SymmetricTensor<2, 3>::unrolled_to_component_indices(k)] +=
          history[k];
      b_tr   = symmetrize(F * Tensor<2, 3>(Cp_inv) * transpose(F));
      eps_tr = spectral(b_tr, [](const double x) { return 0.5 * std::log(x); });
      State old;
      old.alpha = history[6];
      return return_mapping(eps_tr, old, tau, D);
    }


    template <int dim>
    void
    J2Plasticity<dim>::evaluate_finite_strain(
      const Tensor<2, 3>            &F,
      const ArrayView<const double> &history,
      SymmetricTensor<2, 3>         &tau,
      SymmetricTensor<4, 3>         *tangent) const
    {
      SymmetricTensor<2, 3> eps_tr, b;
      SymmetricTensor<4, 3> D;
      finite_return(F, history, eps_tr, b, tau, tangent ? &D : nullptr);
      if (!tangent)
        return;
      // c : d for the 6 symmetric unit directions d (both shear entries 1:
      // c : d = 2 c_ijkl).
      const auto eig = eigenvectors(b);
      for (unsigned int k = 0; k < 6; ++k)
        {
          const auto kl =
            SymmetricTensor<2, 3>::unrolled_to_component_indices(k);
          SymmetricTensor<2, 3> d;
          d[kl] = 1;
          const SymmetricTensor<2, 3> db =
            symmetrize(Tensor<2, 3>(d) * Tensor<2, 3>(b) +
                       Tensor<2, 3>(b) * Tensor<2, 3>(d));
          const SymmetricTensor<2, 3> column =
            D * (0.5 * log_derivative(eig, db)) -
            symmetrize(Tensor<2, 3>(d) * Tensor<2, 3>(tau) +
                       Tensor<2, 3>(tau) * Tensor<2, 3>(d));
          const double scale = kl[0] == kl[1] ? 1. : 0.5;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              (*tangent)[i][j][kl[0]][kl[1]] = scale * column[i][j];
        }
    }


    template <int dim>
    void
    J2Plasticity<dim>::update_history_finite_strain(
      const Tensor<2, 3>      &F,
      const ArrayView<double> &history) const
    {
      SymmetricTensor<2, 3> eps_tr, b, tau;
      const State           state =
        finite_return(F,
                      ArrayView<const double>(history.data(), history.size()),
                      eps_tr,
                      b,
                      tau,
                      nullptr);
      const SymmetricTensor<2, 3> b_e =
        spectral(eps_tr - state.plastic_strain,
                 [](const double e) { return std::exp(2 * e); });
      const Tensor<2, 3>          F_inv = invert(F);
      const SymmetricTensor<2, 3> Cp_inv =
        symmetrize(F_inv * Tensor<2, 3>(b_e) * transpose(F_inv));
      for (unsigned int k = 0; k < 6; ++k)
        {
          const auto ij =
            SymmetricTensor<2, 3>::unrolled_to_component_indices(k);
          history[k] = Cp_inv[ij] - (ij[0] == ij[1] ? 1. : 0.);
        }
      history[6] = state.alpha;
    }


    template class J2Plasticity<2>;
    template class J2Plasticity<3>;
  } // namespace Material
} // namespace Signorini

SIGNORINI_REGISTER_MATERIAL(Signorini::Material::J2Plasticity,
                            "J2 plasticity",
                            "von Mises plasticity with linear isotropic and "
                            "kinematic hardening, radial return and "
                            "consistent tangent; at finite strain Hencky "
                            "elasticity with Simo's exponential-map return "
                            "(isotropic hardening)")
