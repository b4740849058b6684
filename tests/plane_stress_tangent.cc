// Unit test of plane stress (Material::Interface::completed_strain() and
// evaluate_completed(), 'Plane stress = true'):
// * linear elastic: sigma_zz = 0, eps_zz = -nu/(1-nu) (eps_xx + eps_yy),
//   and the condensed tangent equals the closed-form plane-stress
//   constants (lambda* = 2 lambda mu / (lambda + 2 mu), mu) on the in-plane
//   strains, at random strains;
// * J2 plasticity with hardening, from random committed histories (built
//   by plane-stress increments): sigma_zz = 0 to round-off and the
//   condensed tangent equals central finite differences of the
//   plane-stress stress (eps_zz solved again at each perturbed strain)
//   along the in-plane strains, in the elastic and in the plastic regime.
// The compared output (file "output") holds verdicts only.
#include <deal.II/base/parameter_handler.h>

#include <signorini/material/j2_plasticity.h>
#include <signorini/material/linear_elastic.h>

#include <cmath>
#include <fstream>
#include <random>
#include <vector>

using namespace dealii;

namespace
{
  const double E = 200e9, nu = 0.3, sigma_y = 200e6;

  SymmetricTensor<2, 3>
  in_plane(std::mt19937 &rng, const double scale)
  {
    std::uniform_real_distribution<double> u(-1, 1);
    SymmetricTensor<2, 3>                  t;
    t[0][0] = scale * u(rng);
    t[1][1] = scale * u(rng);
    t[0][1] = scale * u(rng);
    return t;
  }

  // Largest relative FD error of the condensed tangent along the in-plane
  // strains, and largest |sigma_zz| / |sigma|, at @p strain.
  void
  check_point(const Signorini::Material::Interface<2> &model,
              const SymmetricTensor<2, 3>             &strain,
              const ArrayView<const double>           &history,
              double                                  &worst_tangent,
              double                                  &worst_szz)
  {
    SymmetricTensor<2, 3> stress;
    SymmetricTensor<4, 3> C;
    model.evaluate_completed(strain, history, stress, &C);
    // The stress without the clean-up of evaluate_completed().
    SymmetricTensor<2, 3> raw;
    model.evaluate(model.completed_strain(strain, history),
                   history,
                   raw,
                   nullptr);
    worst_szz         = std::max(worst_szz, std::abs(raw[2][2]) / raw.norm());
    const double dh   = 1e-7 * sigma_y / E;
    double       err2 = 0, norm2 = 0;
    for (const auto &ij :
         {TableIndices<2>(0, 0), TableIndices<2>(1, 1), TableIndices<2>(0, 1)})
      {
        SymmetricTensor<2, 3> d;
        d[ij] = dh;
        SymmetricTensor<2, 3> s_plus, s_minus;
        model.evaluate_completed(strain + d, history, s_plus, nullptr);
        model.evaluate_completed(strain - d, history, s_minus, nullptr);
        const SymmetricTensor<2, 3> fd = (s_plus - s_minus) / (2 * dh);
        const SymmetricTensor<2, 3> an = C * d / dh;
        err2 += std::pow((fd - an).norm(), 2);
        norm2 += std::pow(an.norm(), 2);
      }
    worst_tangent = std::max(worst_tangent, std::sqrt(err2 / norm2));
  }
} // namespace


int
main()
{
  std::ofstream out("output");
  std::mt19937  rng(7);

  // Linear elastic against the closed form.
  {
    Signorini::Material::LinearElastic<2> model;
    model.set_elastic_constants(E, nu);
    model.set_plane_stress(true);
    const double lambda = model.lame_lambda(), mu = model.shear_modulus();
    const double lambda_star = 2 * lambda * mu / (lambda + 2 * mu);
    double       worst_C = 0, worst_szz = 0, worst_ezz = 0;
    for (unsigned int trial = 0; trial < 20; ++trial)
      {
        const SymmetricTensor<2, 3> strain = in_plane(rng, 1e-3);
        SymmetricTensor<2, 3>       stress;
        SymmetricTensor<4, 3>       C;
        model.evaluate_completed(strain, {}, stress, &C);
        const SymmetricTensor<2, 3> e = model.completed_strain(strain, {});
        worst_ezz =
          std::max(worst_ezz,
                   std::abs(e[2][2] +
                            nu / (1 - nu) * (strain[0][0] + strain[1][1])) /
                     strain.norm());
        SymmetricTensor<2, 3> raw;
        model.evaluate(e, {}, raw, nullptr);
        worst_szz = std::max(worst_szz, std::abs(raw[2][2]) / raw.norm());
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            for (unsigned int k = 0; k < 2; ++k)
              for (unsigned int l = 0; l < 2; ++l)
                {
                  const double exact =
                    lambda_star * (i == j) * (k == l) +
                    mu * ((i == k) * (j == l) + (i == l) * (j == k));
                  worst_C =
                    std::max(worst_C, std::abs(C[i][j][k][l] - exact) / E);
                }
      }
    out << "linear elastic: eps_zz = -nu/(1-nu) tr: "
        << (worst_ezz < 1e-12 ? "PASS" : "FAIL")
        << ", sigma_zz = 0: " << (worst_szz < 1e-12 ? "PASS" : "FAIL")
        << ", tangent = plane-stress constants: "
        << (worst_C < 1e-12 ? "PASS" : "FAIL") << std::endl;
  }

  // J2 with hardening: tangent against differences, from random histories.
  for (const bool plastic : {false, true})
    {
      ParameterHandler prm;
      Signorini::Material::J2Plasticity<2>::declare_parameters(prm);
      prm.enter_subsection("J2 plasticity");
      prm.set("Yield stress", sigma_y);
      prm.set("Isotropic hardening modulus", 0.05 * E);
      prm.set("Kinematic hardening modulus", 0.02 * E);
      prm.leave_subsection();
      Signorini::Material::J2Plasticity<2> model;
      model.set_elastic_constants(E, nu);
      model.parse_parameters(prm);
      model.set_plane_stress(true);
      const double eps_y         = sigma_y / E;
      double       worst_tangent = 0, worst_szz = 0;
      unsigned int n_points = 0;
      for (unsigned int trial = 0; trial < 20; ++trial)
        {
          // A committed history: one plane-stress increment to a random
          // plastic strain.
          std::vector<double>         h(model.n_history_values(), 0.);
          const SymmetricTensor<2, 3> before = in_plane(rng, 4 * eps_y);
          model.update_history(
            model.completed_strain(before,
                                   ArrayView<const double>(h.data(), h.size())),
            make_array_view(h));
          const auto view = ArrayView<const double>(h.data(), h.size());
          const SymmetricTensor<2, 3> strain =
            before + in_plane(rng, plastic ? 4 * eps_y : 0.01 * eps_y);
          // Elastic or plastic: whether the history moves from here.
          std::vector<double> after = h;
          model.update_history(model.completed_strain(strain, view),
                               make_array_view(after));
          if ((after != h) != plastic)
            continue;
          ++n_points;
          check_point(model, strain, view, worst_tangent, worst_szz);
        }
      out << "J2 plasticity, " << (plastic ? "plastic" : "elastic")
          << " points (" << (n_points >= 5 ? "at least 5" : "too few")
          << "): sigma_zz = 0: " << (worst_szz < 1e-12 ? "PASS" : "FAIL")
          << ", condensed tangent against differences: "
          << (worst_tangent < 1e-6 ? "PASS" : "FAIL") << std::endl;
    }
}
