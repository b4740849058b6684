// Unit test of the constitutive model 'neo-Hookean' (finite strain,
// material/neo_hookean.h), E = 10 MPa, nu = 0.45:
// * the spatial tangent c equals central finite differences of the
//   Kirchhoff stress, d tau = c : sym(l) + l tau + tau l^T with
//   l = dF F^-1 (relative error below 1e-6), at random deformation
//   gradients with stretches up to about 1.5 and rotations;
// * objectivity: tau(Q) = 0 for a rotation Q of 90 degrees, and
//   tau(Q F) = Q tau(F) Q^T; the small-strain model does not have it
//   (linear elasticity gives a stress of order E at the same rotation);
// * small-load limit: at F = I + H with |H| ~ 1e-7 the stress equals linear
//   elasticity with the same E and nu to 1e-6 relative, and c(I) equals
//   lambda I x I + 2 mu I_s;
// * closed forms at 50 %: simple shear (gamma = 0.5, J = 1) sigma_xy =
//   mu gamma, sigma_xx = 2/3 mu gamma^2, sigma_yy = sigma_zz = -mu gamma^2
//   / 3; uniaxial stress (stretch 1.5, lateral stretch l from sigma_22 =
//   0, solved here by bisection) sigma_11 = mu J^(-5/3) (1.5^2 - l^2),
//   J = 1.5 l^2. The lateral stretch is printed to 12 digits: tests/
//   neo_hookean_uniaxial_3d.prm uses it as its reference.
// The compared output (file "output") holds verdicts and rounded numbers.
#include <deal.II/base/parameter_handler.h>

#include <signorini/material/linear_elastic.h>
#include <signorini/material/neo_hookean.h>

#include "tensor_helpers.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>

using namespace dealii;
using namespace test_helpers;
using Model = Signorini::Material::NeoHookean<3>;

namespace
{
  const double E = 10e6, nu = 0.45;

  Model
  make_model()
  {
    Model model;
    model.set_elastic_constants(E, nu);
    model.set_kinematics(Signorini::Material::Kinematics::finite_strain);
    return model;
  }

  SymmetricTensor<2, 3>
  tau_of(const Model &model, const Tensor<2, 3> &F, SymmetricTensor<4, 3> *c)
  {
    SymmetricTensor<2, 3> tau;
    model.evaluate_finite_strain(F, ArrayView<const double>(), tau, c);
    return tau;
  }

  // Largest relative FD error of the spatial tangent over random F.
  double
  tangent_error(const Model &model, std::mt19937 &rng)
  {
    double worst = 0;
    for (unsigned int trial = 0; trial < 50; ++trial)
      {
        Tensor<1, 3> axis;
        axis[0] = 1;
        axis[1] = 0.3 * trial;
        axis[2] = -0.2;
        axis /= axis.norm();
        const Tensor<2, 3> F =
          rotation(axis, 0.1 * trial) *
          (Tensor<2, 3>(unit_symmetric_tensor<3>()) + random_tensor(rng, 0.3));
        if (determinant(F) < 0.3)
          continue;
        SymmetricTensor<4, 3>       c;
        const SymmetricTensor<2, 3> tau   = tau_of(model, F, &c);
        const Tensor<2, 3>          F_inv = invert(F);
        double                      err2 = 0, norm2 = 0;
        const double                h = 1e-6;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            {
              Tensor<2, 3> A;
              A[a][b] = 1;
              const SymmetricTensor<2, 3> fd =
                (tau_of(model, F + h * A, nullptr) -
                 tau_of(model, F - h * A, nullptr)) /
                (2 * h);
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

  SymmetricTensor<2, 3>
  cauchy(const Model &model, const Tensor<2, 3> &F)
  {
    return tau_of(model, F, nullptr) / determinant(F);
  }

} // namespace


int
main()
{
  std::ofstream out("output");
  out << std::setprecision(4);
  const Model  model = make_model();
  const double mu    = model.shear_modulus();
  std::mt19937 rng(2026);

  const double tangent = tangent_error(model, rng);
  std::cout << "tangent error " << tangent << std::endl; // not compared
  out << "Tangent against central differences over 50 random F (tolerance "
         "1e-6): "
      << verdict(tangent < 1e-6) << std::endl;

  // Objectivity.
  Tensor<1, 3> e3;
  e3[2]                 = 1;
  const Tensor<2, 3> Q  = rotation(e3, numbers::PI / 2);
  const double       t0 = tau_of(model, Q, nullptr).norm();
  const Tensor<2, 3> F =
    Tensor<2, 3>(unit_symmetric_tensor<3>()) + random_tensor(rng, 0.3);
  const Tensor<2, 3> rotated =
    Q * Tensor<2, 3>(tau_of(model, F, nullptr)) * transpose(Q);
  const double objectivity =
    (Tensor<2, 3>(tau_of(model, Q * F, nullptr)) - rotated).norm() /
    rotated.norm();
  Signorini::Material::LinearElastic<3> linear;
  linear.set_elastic_constants(E, nu);
  SymmetricTensor<2, 3> sigma_linear;
  linear.evaluate(symmetrize(Q - Tensor<2, 3>(unit_symmetric_tensor<3>())),
                  ArrayView<const double>(),
                  sigma_linear,
                  nullptr);
  out << "Rotation by 90 degrees: |tau| / E below 1e-14: "
      << verdict(t0 / E < 1e-14)
      << "; linear elasticity at the same displacement: |sigma| / E = "
      << sigma_linear.norm() / E << std::endl;
  out << "tau(Q F) = Q tau(F) Q^T to 1e-13: " << verdict(objectivity < 1e-13)
      << std::endl;

  // Small-load limit.
  const Tensor<2, 3>          H = random_tensor(rng, 1e-7);
  const SymmetricTensor<2, 3> small =
    cauchy(model, Tensor<2, 3>(unit_symmetric_tensor<3>()) + H);
  linear.evaluate(symmetrize(H),
                  ArrayView<const double>(),
                  sigma_linear,
                  nullptr);
  SymmetricTensor<4, 3> c0, C_linear;
  tau_of(model, unit_symmetric_tensor<3>(), &c0);
  linear.evaluate(SymmetricTensor<2, 3>(),
                  ArrayView<const double>(),
                  sigma_linear,
                  &C_linear);
  linear.evaluate(symmetrize(H),
                  ArrayView<const double>(),
                  sigma_linear,
                  nullptr);
  out << "Small load (|H| ~ 1e-7): stress equal to linear elasticity to "
         "1e-6: "
      << verdict((small - sigma_linear).norm() < 1e-6 * sigma_linear.norm())
      << "; c(I) = lambda I x I + 2 mu I_s to 1e-14: "
      << verdict((c0 - C_linear).norm() < 1e-14 * C_linear.norm()) << std::endl;

  // Simple shear, gamma = 0.5.
  const double gamma                = 0.5;
  Tensor<2, 3> S                    = unit_symmetric_tensor<3>();
  S[0][1]                           = gamma;
  const SymmetricTensor<2, 3> shear = cauchy(model, S);
  SymmetricTensor<2, 3>       shear_exact;
  shear_exact[0][1] = mu * gamma;
  shear_exact[0][0] = 2. / 3. * mu * gamma * gamma;
  shear_exact[1][1] = shear_exact[2][2] = -mu * gamma * gamma / 3;
  out << "Simple shear gamma = 0.5: sigma_xy / mu = " << shear[0][1] / mu
      << ", sigma_xx / mu = " << shear[0][0] / mu
      << ", sigma_yy / mu = " << shear[1][1] / mu << "; closed form to 1e-13: "
      << verdict((shear - shear_exact).norm() < 1e-13 * shear_exact.norm())
      << std::endl;

  // Uniaxial stress, stretch 1.5: bisection on the lateral stretch.
  const double lambda1 = 1.5;
  const auto   stretch = [&](const double l) {
    Tensor<2, 3> G;
    G[0][0] = lambda1;
    G[1][1] = G[2][2] = l;
    return G;
  };
  double lo = 0.5, hi = 1.0;
  for (unsigned int it = 0; it < 200 && hi - lo > 1e-15; ++it)
    {
      const double mid                                  = 0.5 * (lo + hi);
      (cauchy(model, stretch(mid))[1][1] > 0 ? hi : lo) = mid;
    }
  const double l   = 0.5 * (lo + hi);
  const double J   = lambda1 * l * l;
  const double s11 = cauchy(model, stretch(l))[0][0];
  const double s11_closed =
    mu * std::pow(J, -5. / 3.) * (lambda1 * lambda1 - l * l);
  out << "Uniaxial stress, stretch 1.5: lateral stretch "
      << std::setprecision(12) << l << std::setprecision(4)
      << ", sigma_11 = " << s11 << " Pa (closed form " << s11_closed
      << "), equal to 1e-12: "
      << verdict(std::abs(s11 - s11_closed) < 1e-12 * s11_closed) << std::endl;
  return 0;
}
