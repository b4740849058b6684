// Unit test of the constitutive model 'J2 plasticity' (small-strain von
// Mises plasticity with linear isotropic and kinematic hardening,
// material/j2_plasticity.h):
// * the consistent tangent equals central finite differences of the stress
//   (relative error below 1e-6) at random strains and random committed
//   histories, in the elastic and in the plastic regime, with isotropic,
//   kinematic, combined and no hardening;
// * a uniaxial-stress cycle (load to 3 eps_y, reverse to -3 eps_y, reload
//   to 3 eps_y, lateral stresses zero by a local Newton solve on the lateral
//   strain, history committed after each increment) against the closed
//   form: first yield at sigma_y, plastic slope E H / (E + H) with
//   H = H_iso + H_kin, unloading slope E, reverse yield at
//   H_kin eps_p - (sigma_y + H_iso alpha), and every point of the cycle;
// * evaluate() leaves the history alone, update_history() stores the
//   return mapping's state, and the stress of the committed state at the
//   converged strain is the converged stress.
// The compared output (file "output") holds verdicts and rounded numbers.
#include <deal.II/base/parameter_handler.h>

#include <signorini/material/j2_plasticity.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <vector>

using namespace dealii;
using Model = Signorini::Material::J2Plasticity<3>;

namespace
{
  const double E = 200e9, nu = 0.3, sigma_y = 200e6;

  Model
  make_model(const double H_iso, const double H_kin)
  {
    ParameterHandler prm;
    Model::declare_parameters(prm);
    prm.enter_subsection("J2 plasticity");
    prm.set("Yield stress", sigma_y);
    prm.set("Isotropic hardening modulus", H_iso);
    prm.set("Kinematic hardening modulus", H_kin);
    prm.leave_subsection();
    Model model;
    model.set_elastic_constants(E, nu);
    model.parse_parameters(prm);
    return model;
  }

  SymmetricTensor<2, 3>
  random_tensor(std::mt19937 &rng, const double scale)
  {
    std::uniform_real_distribution<double> u(-1, 1);
    SymmetricTensor<2, 3>                  t;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        t[i][j] = scale * u(rng);
    return t;
  }

  // Largest relative FD error of the tangent over @p n random points in
  // the regime asked for; counts the points found plastic.
  double
  tangent_error(const Model  &model,
                const bool    plastic,
                unsigned int &n_plastic,
                std::mt19937 &rng)
  {
    const double eps_y = sigma_y / E;
    double       worst = 0;
    for (unsigned int trial = 0; trial < 20; ++trial)
      {
        Model::State old;
        old.plastic_strain = deviator(random_tensor(rng, eps_y));
        old.back_stress    = deviator(random_tensor(rng, 0.2 * sigma_y));
        old.alpha          = 2 * eps_y * (trial + 1) / 20.;
        // Elastic: the strain of the committed state plus a small
        // perturbation; plastic: far beyond the yield surface.
        const SymmetricTensor<2, 3> strain =
          old.plastic_strain + old.back_stress / (2 * model.shear_modulus()) +
          random_tensor(rng, plastic ? 5 * eps_y : 0.05 * eps_y);
        std::vector<double> h(13);
        Model::pack(old, make_array_view(h));
        SymmetricTensor<2, 3> stress;
        SymmetricTensor<4, 3> C;
        const auto            view = ArrayView<const double>(h.data(), 13);
        model.evaluate(strain, view, stress, &C);
        const Model::State now =
          model.return_mapping(strain, old, stress, nullptr);
        const bool yielded = now.alpha > old.alpha;
        if (yielded != plastic)
          continue;
        n_plastic += yielded ? 1 : 0;
        const double dh   = 1e-7 * eps_y;
        double       err2 = 0, norm2 = 0;
        for (unsigned int k = 0; k < 6; ++k)
          {
            const auto ij =
              SymmetricTensor<2, 3>::unrolled_to_component_indices(k);
            SymmetricTensor<2, 3> d;
            d[ij] = dh; // a shear component perturbs eps_ij and eps_ji
            SymmetricTensor<2, 3> s_plus, s_minus;
            model.evaluate(strain + d, view, s_plus, nullptr);
            model.evaluate(strain - d, view, s_minus, nullptr);
            const SymmetricTensor<2, 3> fd = (s_plus - s_minus) / (2 * dh);
            const SymmetricTensor<2, 3> an = C * d / dh;
            err2 += std::pow((fd - an).norm(), 2);
            norm2 += std::pow(an.norm(), 2);
          }
        worst = std::max(worst, std::sqrt(err2 / norm2));
      }
    return worst;
  }

  // Uniaxial stress: the stress and new state for the axial strain @p e
  // from @p old, the lateral strain found by Newton (sigma_22 = sigma_33
  // = 0).
  double
  uniaxial(const Model  &model,
           const double  e,
           Model::State &state,
           double       &lateral)
  {
    SymmetricTensor<2, 3> stress, strain;
    SymmetricTensor<4, 3> C;
    for (unsigned int it = 0; it < 50; ++it)
      {
        strain       = SymmetricTensor<2, 3>();
        strain[0][0] = e;
        strain[1][1] = strain[2][2] = lateral;
        model.return_mapping(strain, state, stress, &C);
        if (std::abs(stress[1][1]) < 1e-10 * sigma_y)
          break;
        lateral -= stress[1][1] / (C[1][1][1][1] + C[1][1][2][2]);
      }
    state = model.return_mapping(strain, state, stress, nullptr);
    return stress[0][0];
  }

  // The closed form of the uniaxial cycle, a branch at a time.
  struct Cycle
  {
    double H_iso, H_kin;

    double
    tangent_modulus() const
    {
      const double H = H_iso + H_kin;
      return E * H / (E + H);
    }
    // Axial stress at axial strain e on the branch that starts at stress
    // s0, strain e0, elastic until the yield stress s_yield of that branch.
    double
    branch(const double e,
           const double e0,
           const double s0,
           const double s_yield) const
    {
      const double s_elastic = s0 + E * (e - e0);
      const bool   forward   = e > e0;
      if (forward ? s_elastic <= s_yield : s_elastic >= s_yield)
        return s_elastic;
      const double e_yield = e0 + (s_yield - s0) / E;
      return s_yield + tangent_modulus() * (e - e_yield);
    }
  };
} // namespace

int
main()
{
  std::ofstream out("output");
  out << std::setprecision(4);
  std::mt19937 rng(4);
  const double eps_y = sigma_y / E;

  out << "Tangent against central differences (tolerance 1e-6):\n";
  for (const auto &[H_iso, H_kin] : std::vector<std::pair<double, double>>{
         {0., 0.}, {10e9, 0.}, {0., 10e9}, {5e9, 15e9}})
    {
      const Model model = make_model(H_iso, H_kin);
      for (const bool plastic : {false, true})
        {
          unsigned int n_plastic = 0;
          const double err = tangent_error(model, plastic, n_plastic, rng);
          std::cout << "H_iso " << H_iso << " H_kin " << H_kin
                    << (plastic ? " plastic" : " elastic") << ": " << err
                    << std::endl;
          out << "  H_iso = " << H_iso << ", H_kin = " << H_kin << ", "
              << (plastic ? "plastic" : "elastic")
              << " points: " << (err < 1e-6 ? "PASS" : "FAIL")
              << (plastic == (n_plastic > 0) ? "" : " (no point in regime)")
              << "\n";
        }
    }

  // The cycle 0 -> 3 eps_y -> -3 eps_y -> 3 eps_y in steps of eps_y / 8.
  const double H_iso = 5e9, H_kin = 15e9;
  const Model  model = make_model(H_iso, H_kin);
  const Cycle  cycle{H_iso, H_kin};
  Model::State state;
  double       lateral = 0, worst = 0, e_prev = 0, s_prev = 0;
  const double ea = 3 * eps_y;
  // Branch starts (strain, stress, yield stress of the branch).
  double e0 = 0, s0 = 0, s_yield = sigma_y;
  double first_yield = 0, slope_plastic = 0, slope_unload = 0,
         reverse_yield_expected = 0;
  std::vector<double> path;
  for (int k = 0; k <= 24; ++k)
    path.push_back(k * eps_y / 8);
  for (int k = 23; k >= -24; --k)
    path.push_back(k * eps_y / 8);
  for (int k = -23; k <= 24; ++k)
    path.push_back(k * eps_y / 8);
  for (unsigned int k = 1; k < path.size(); ++k)
    {
      const double e = path[k];
      // A reversal starts a new branch from the last converged point.
      if (k > 1 && (e - path[k - 1]) * (path[k - 1] - path[k - 2]) < 0)
        {
          e0              = path[k - 1];
          s0              = s_prev;
          const double ep = e0 - s0 / E;
          // Yield of the new branch: |sigma - H_kin eps_p| = sigma_y +
          // H_iso alpha.
          const double radius = sigma_y + H_iso * state.alpha;
          s_yield = e > e0 ? H_kin * ep + radius : H_kin * ep - radius;
          if (reverse_yield_expected == 0)
            reverse_yield_expected = s_yield;
        }
      const double s     = uniaxial(model, e, state, lateral);
      const double exact = cycle.branch(e, e0, s0, s_yield);
      worst              = std::max(worst, std::abs(s - exact) / sigma_y);
      if (first_yield == 0 && std::abs(s - E * e) > 1e-9 * sigma_y)
        first_yield = s_prev; // last point of the elastic line (eps_y)
      if (k == 24)
        slope_plastic = (s - s_prev) / (e - e_prev);
      if (k == 25)
        slope_unload = (s - s_prev) / (e - e_prev);
      e_prev = e;
      s_prev = s;
    }
  out << "Uniaxial cycle 0 -> 3 eps_y -> -3 eps_y -> 3 eps_y (H_iso = 5e9, "
         "H_kin = 15e9 Pa):\n"
      << "  first yield " << first_yield << " Pa (sigma_y " << sigma_y
      << ")\n  plastic slope " << slope_plastic << " Pa (E H / (E + H) "
      << cycle.tangent_modulus() << ")\n  unloading slope " << slope_unload
      << " Pa (E " << E << ")\n  reverse yield stress "
      << reverse_yield_expected << " Pa (closed form H_kin eps_p - (sigma_y "
      << "+ H_iso alpha))\n  largest error over " << path.size() - 1
      << " points / sigma_y: " << (worst < 1e-9 ? "below 1e-9" : "FAIL")
      << "\n";
  std::cout << "cycle error " << worst << std::endl;
  (void)ea;

  // The history: evaluate() keeps it, update_history() stores the return
  // mapping's state, and the converged stress is that of the new state.
  {
    Model::State old;
    old.alpha = 1e-3;
    std::vector<double> h(13);
    Model::pack(old, make_array_view(h));
    const std::vector<double> before = h;
    SymmetricTensor<2, 3>     strain = random_tensor(rng, 5 * eps_y), s1, s2;
    model.evaluate(strain, ArrayView<const double>(h.data(), 13), s1, nullptr);
    const bool kept = h == before;
    model.update_history(strain, make_array_view(h));
    const Model::State now =
      Model::unpack(ArrayView<const double>(h.data(), 13));
    model.evaluate(strain, ArrayView<const double>(h.data(), 13), s2, nullptr);
    out << "History: evaluate() keeps it: " << (kept ? "yes" : "NO")
        << "; update_history() advanced alpha: "
        << (now.alpha > old.alpha ? "yes" : "NO")
        << "; stress of the committed state at the same strain equal to 1e-12: "
        << ((s1 - s2).norm() < 1e-12 * s1.norm() ? "yes" : "NO") << "\n";
  }
  return 0;
}
