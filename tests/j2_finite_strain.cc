// Unit test of 'J2 plasticity' at finite strain (material/j2_plasticity.h:
// Hencky elasticity, Simo's exponential-map return, isotropic hardening;
// E = 200 GPa, nu = 0.3, sigma_y = 200 MPa, H_iso = 10 GPa):
// * the spatial tangent c against central differences of the Kirchhoff
//   stress, d tau = c : sym(l) + l tau + tau l^T with l = dF F^-1
//   (relative error below 1e-6), at random deformation gradients
//   (stretches to about 1.3, rotations) and random committed histories
//   (C_p^-1 = exp(2 A) with A deviatoric, alpha > 0), elastic and plastic;
// * objectivity: tau(Q F) = Q tau(F) Q^T for a committed history;
// * small-strain limit: at F = I + H, abs(H) ~ 1e-7, the stress and the
//   tangent equal those of the small-strain model to 1e-6;
// * uniaxial tension to a stretch of 1.5 in 100 increments (lateral
//   Kirchhoff stress zero by a local Newton solve, history committed after
//   each increment): tau_11 against ln(stretch) is the small-strain curve,
//   E eps up to sigma_y / E, then sigma_y + E H / (E + H) (eps - sigma_y /
//   E); the plastic volume is conserved (det C_p^-1 = 1).
// The compared output (file "output") holds verdicts and rounded numbers.
#include <deal.II/base/parameter_handler.h>

#include <signorini/material/j2_plasticity.h>

#include "tensor_helpers.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <vector>

using namespace dealii;
using namespace test_helpers;
using Model = Signorini::Material::J2Plasticity<3>;

namespace
{
  const double E = 200e9, nu = 0.3, sigma_y = 200e6, H = 10e9;

  Model
  make_model(const Signorini::Material::Kinematics kinematics,
             const double                          yield)
  {
    ParameterHandler prm;
    Model::declare_parameters(prm);
    prm.enter_subsection("J2 plasticity");
    prm.set("Yield stress", yield);
    prm.set("Isotropic hardening modulus", H);
    prm.leave_subsection();
    Model model;
    model.set_elastic_constants(E, nu);
    model.set_kinematics(kinematics);
    model.parse_parameters(prm);
    return model;
  }

  // A random committed history: C_p^-1 = exp(2 A), A deviatoric, alpha.
  std::vector<double>
  random_history(std::mt19937 &rng, const double scale)
  {
    const SymmetricTensor<2, 3> A =
      deviator(symmetrize(random_tensor(rng, scale)));
    const auto            eig = eigenvectors(A);
    SymmetricTensor<2, 3> Cp_inv;
    for (const auto &[x, n] : eig)
      Cp_inv += std::exp(2 * x) * symmetrize(outer_product(n, n));
    std::vector<double> h(7);
    for (unsigned int k = 0; k < 6; ++k)
      {
        const auto ij = SymmetricTensor<2, 3>::unrolled_to_component_indices(k);
        h[k]          = Cp_inv[ij] - (ij[0] == ij[1] ? 1. : 0.);
      }
    h[6] = 4 * scale;
    return h;
  }

  SymmetricTensor<2, 3>
  tau_of(const Model               &model,
         const Tensor<2, 3>        &F,
         const std::vector<double> &h,
         SymmetricTensor<4, 3>     *c)
  {
    SymmetricTensor<2, 3> tau;
    model.evaluate_finite_strain(F,
                                 ArrayView<const double>(h.data(), h.size()),
                                 tau,
                                 c);
    return tau;
  }

  // Largest relative FD error of c over random F and histories; counts the
  // points that yielded.
  double
  tangent_error(const Model &model, std::mt19937 &rng, unsigned int &n_plastic)
  {
    double worst = 0;
    for (unsigned int trial = 0; trial < 40; ++trial)
      {
        const std::vector<double> h = random_history(rng, 0.05);
        const Tensor<2, 3>        F =
          rotation_z(0.2 * trial) *
          (Tensor<2, 3>(unit_symmetric_tensor<3>()) + random_tensor(rng, 0.2));
        SymmetricTensor<4, 3>       c;
        const SymmetricTensor<2, 3> tau   = tau_of(model, F, h, &c);
        std::vector<double>         h_new = h;
        model.update_history_finite_strain(F,
                                           ArrayView<double>(h_new.data(),
                                                             h_new.size()));
        n_plastic += h_new[6] > h[6] ? 1 : 0;
        const Tensor<2, 3> F_inv = invert(F);
        const double       step  = 1e-7;
        double             err2 = 0, norm2 = 0;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            {
              Tensor<2, 3> A;
              A[a][b] = 1;
              const SymmetricTensor<2, 3> fd =
                (tau_of(model, F + step * A, h, nullptr) -
                 tau_of(model, F - step * A, h, nullptr)) /
                (2 * step);
              const Tensor<2, 3>          l = A * F_inv;
              const SymmetricTensor<2, 3> an =
                c * symmetrize(l) + symmetrize(l * tau + tau * transpose(l));
              err2 += std::pow((fd - an).norm(), 2);
              norm2 += std::pow(an.norm(), 2);
            }
        worst = std::max(worst, std::sqrt(err2 / norm2));
      }
    return worst;
  }

} // namespace


int
main()
{
  using Signorini::Material::Kinematics;
  std::ofstream out("output");
  out << std::setprecision(4);
  std::mt19937 rng(31);

  const Model  plastic   = make_model(Kinematics::finite_strain, sigma_y);
  const Model  elastic   = make_model(Kinematics::finite_strain, 1e300);
  unsigned int n_plastic = 0, n_elastic = 0;
  const double e_plastic = tangent_error(plastic, rng, n_plastic);
  const double e_elastic = tangent_error(elastic, rng, n_elastic);
  std::cout << "tangent errors " << e_elastic << " " << e_plastic
            << std::endl; // not compared
  out << "Tangent against central differences (tolerance 1e-6): elastic "
         "(Hencky): "
      << verdict(e_elastic < 1e-6 && n_elastic == 0)
      << "; plastic: " << verdict(e_plastic < 1e-6)
      << " (points that yielded: " << n_plastic << " of 40)" << std::endl;

  // Objectivity.
  const std::vector<double> h = random_history(rng, 0.05);
  const Tensor<2, 3>        F =
    Tensor<2, 3>(unit_symmetric_tensor<3>()) + random_tensor(rng, 0.2);
  const Tensor<2, 3> Q = rotation_z(1.0);
  const Tensor<2, 3> rotated =
    Q * Tensor<2, 3>(tau_of(plastic, F, h, nullptr)) * transpose(Q);
  out << "tau(Q F) = Q tau(F) Q^T to 1e-12: "
      << verdict(
           (Tensor<2, 3>(tau_of(plastic, Q * F, h, nullptr)) - rotated).norm() <
           1e-12 * rotated.norm())
      << std::endl;

  // Small-strain limit.
  const Model           small   = make_model(Kinematics::small_strain, sigma_y);
  const Tensor<2, 3>    H_small = random_tensor(rng, 1e-7);
  std::vector<double>   zero7(7, 0.), zero13(13, 0.);
  SymmetricTensor<4, 3> c, C;
  const SymmetricTensor<2, 3> tau = tau_of(
    plastic, Tensor<2, 3>(unit_symmetric_tensor<3>()) + H_small, zero7, &c);
  SymmetricTensor<2, 3> sigma;
  small.evaluate(symmetrize(H_small),
                 ArrayView<const double>(zero13.data(), 13),
                 sigma,
                 &C);
  out << "Small strain (abs(H) ~ 1e-7): stress and tangent equal to the "
         "small-strain model to 1e-6: "
      << verdict((tau - sigma).norm() < 1e-6 * sigma.norm() &&
                 (c - C).norm() < 1e-6 * C.norm())
      << std::endl;

  // Uniaxial tension to a stretch of 1.5.
  std::vector<double> history(7, 0.);
  double              lateral = 1, worst = 0, det_error = 0;
  const unsigned int  n = 100;
  for (unsigned int k = 1; k <= n; ++k)
    {
      const double lambda = 1 + 0.5 * k / n;
      Tensor<2, 3> G;
      for (unsigned int it = 0; it < 50; ++it)
        {
          G       = Tensor<2, 3>();
          G[0][0] = lambda;
          G[1][1] = G[2][2] = lateral;
          SymmetricTensor<4, 3>       ct;
          const SymmetricTensor<2, 3> t = tau_of(plastic, G, history, &ct);
          if (std::abs(t[1][1]) < 1e-6)
            break;
          // d tau_22 / d lateral: l = e2 x e2 / lateral + e3 x e3 / lateral.
          SymmetricTensor<2, 3> d;
          d[1][1] = d[2][2]  = 1 / lateral;
          const double slope = (ct * d)[1][1] + 2 * t[1][1] / lateral;
          lateral -= t[1][1] / slope;
        }
      const double tau_11 = tau_of(plastic, G, history, nullptr)[0][0];
      plastic.update_history_finite_strain(G,
                                           ArrayView<double>(history.data(),
                                                             history.size()));
      const double eps   = std::log(lambda);
      const double exact = eps <= sigma_y / E ?
                             E * eps :
                             sigma_y + E * H / (E + H) * (eps - sigma_y / E);
      worst              = std::max(worst, std::abs(tau_11 - exact) / sigma_y);
      SymmetricTensor<2, 3> Cp_inv = unit_symmetric_tensor<3>();
      for (unsigned int m = 0; m < 6; ++m)
        Cp_inv[SymmetricTensor<2, 3>::unrolled_to_component_indices(m)] +=
          history[m];
      det_error = std::max(det_error, std::abs(determinant(Cp_inv) - 1));
    }
  out << "Uniaxial tension to stretch 1.5 in " << n
      << " increments: tau_11 against the small-strain curve in ln(stretch), "
         "largest error / sigma_y below 1e-9: "
      << verdict(worst < 1e-9)
      << "; det C_p^-1 = 1 to 1e-12: " << verdict(det_error < 1e-12)
      << "; final alpha = " << history[6] << std::endl;
  return 0;
}
