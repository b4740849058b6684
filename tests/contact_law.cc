// Unit test of the per-point contact law (doc/theory.md sections 3-5):
// * every derivative block returned by evaluate_contact_law() equals central
//   finite differences of the returned densities (n, T frozen; g = g0 + n.d,
//   v = v0 + P d), for dim = 2, 3, states well inside free / stick / slip,
//   mu = 0, 0.3, 1, Newton on the threshold (with K_fc);
// * physical facts: free-point residual, converged slip and stick points
//   have r_f = 0, hand-picked status classification, the zero-threshold rule
//   of section 3.3, mu = 0, tangent basis properties.
// The compared output (file "output") holds verdicts only; the raw FD errors
// go to stdout.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/logstream.h>

#include <signorini/contact/contact_law.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace Signorini::Contact;

namespace
{
  const double fd_tolerance = 1e-6;

  // Point variables x = (d, lambda, Lambda) and densities
  // y = (force, r_c, r_f) packed in flat vectors of size 2 dim.
  template <int dim>
  struct Probe
  {
    PointState<dim> base; // state at d = 0

    PointState<dim>
    state_at(const std::vector<double> &x) const
    {
      PointState<dim> s = base;
      Tensor<1, dim>  d;
      for (unsigned int j = 0; j < dim; ++j)
        d[j] = x[j];
      const Tensor<1, dim> &n = base.normal;
      s.gap                   = base.gap + n * d;
      s.slip                  = base.slip + (d - (n * d) * n);
      s.lambda                = x[dim];
      for (unsigned int k = 0; k < dim - 1; ++k)
        s.Lambda[k] = x[dim + 1 + k];
      return s;
    }

    std::vector<double>
    base_variables() const
    {
      std::vector<double> x(2 * dim, 0.);
      x[dim] = base.lambda;
      for (unsigned int k = 0; k < dim - 1; ++k)
        x[dim + 1 + k] = base.Lambda[k];
      return x;
    }
  };

  template <int dim>
  std::vector<double>
  densities(const PointResponse<dim> &r)
  {
    std::vector<double> y(2 * dim);
    for (unsigned int i = 0; i < dim; ++i)
      y[i] = r.force[i];
    y[dim] = r.r_c;
    for (unsigned int k = 0; k < dim - 1; ++k)
      y[dim + 1 + k] = r.r_f[k];
    return y;
  }

  // J[row][col], rows = densities, cols = variables.
  template <int dim>
  std::vector<std::vector<double>>
  jacobian(const PointResponse<dim> &r)
  {
    std::vector<std::vector<double>> J(2 * dim,
                                       std::vector<double>(2 * dim, 0.));
    for (unsigned int i = 0; i < dim; ++i)
      {
        for (unsigned int j = 0; j < dim; ++j)
          J[i][j] = r.dforce_dd[i][j];
        J[i][dim] = r.dforce_dlambda[i];
        for (unsigned int l = 0; l < dim - 1; ++l)
          J[i][dim + 1 + l] = r.dforce_dLambda[l][i];
      }
    for (unsigned int j = 0; j < dim; ++j)
      J[dim][j] = r.drc_dd[j];
    J[dim][dim] = r.drc_dlambda;
    for (unsigned int k = 0; k < dim - 1; ++k)
      {
        for (unsigned int j = 0; j < dim; ++j)
          J[dim + 1 + k][j] = r.drf_dd[k][j];
        for (unsigned int l = 0; l < dim - 1; ++l)
          J[dim + 1 + k][dim + 1 + l] = r.drf_dLambda[k][l];
      }
    return J;
  }

  std::string
  yes_no(const bool b)
  {
    return b ? "yes" : "no";
  }

  template <int dim>
  Tensor<1, dim>
  tangent_combination(const std::array<Tensor<1, dim>, dim - 1> &T,
                      const double                               a,
                      const double                               b)
  {
    Tensor<1, dim> t = a * T[0];
    if constexpr (dim == 3)
      t += b * T[1];
    (void)b;
    return t;
  }

  template <int dim>
  Tensor<1, dim>
  generic_normal()
  {
    Tensor<1, dim> n;
    if constexpr (dim == 2)
      {
        n[0] = 0.6;
        n[1] = -0.8;
      }
    else
      {
        n[0] = 0.36;
        n[1] = -0.48;
        n[2] = 0.8;
      }
    return n / n.norm();
  }

  enum class Which
  {
    free,
    stick,
    slip
  };

  // States well inside each status for rho_n = 50, rho_t = 20:
  //  free : lambda_aug = 0.4 + 1.5 = 1.9 > 0
  //  stick: lambda_aug = -1.5 - 1 = -2.5 < 0, |h| ~ 0.5
  //  slip : lambda_aug = -2.5, |h| ~ 2.2
  template <int dim>
  PointState<dim>
  make_state(const Which which)
  {
    PointState<dim> s;
    s.normal    = generic_normal<dim>();
    s.tangents  = tangent_basis(s.normal);
    s.Lambda[0] = 0.3;
    if constexpr (dim == 3)
      s.Lambda[1] = -0.2;
    switch (which)
      {
        case Which::free:
          s.gap    = -0.03;
          s.lambda = 0.4;
          s.slip   = tangent_combination<dim>(s.tangents, 0.01, -0.02);
          break;
        case Which::stick:
          s.gap    = 0.02;
          s.lambda = -1.5;
          s.slip   = tangent_combination<dim>(s.tangents, 0.01, 0.005);
          break;
        case Which::slip:
          s.gap       = 0.02;
          s.lambda    = -1.5;
          s.Lambda[0] = 0.5;
          if constexpr (dim == 3)
            s.Lambda[1] = 0.4;
          s.slip = tangent_combination<dim>(s.tangents, 0.08, -0.05);
          break;
      }
    // The friction rows' weight: lambda at the iterate, held while the
    // finite differences move lambda (no K_fc).
    s.row_lambda = s.lambda;
    return s;
  }

  const char *
  to_string(const Which w)
  {
    return w == Which::free ? "free" : (w == Which::stick ? "stick" : "slip");
  }

  // Compares the analytic Jacobian against central differences. Entry error
  // = |fd - exact| / max(|exact|, |fd|, floor): relative for entries of
  // order one and more (all data are O(1)-scaled), absolute below the floor,
  // so that exactly-zero blocks are checked too.
  template <int dim>
  double
  fd_error(const PointState<dim> &state, const LawParameters &parameters)
  {
    Probe<dim> probe;
    probe.base = state;

    const std::vector<double> x0 = probe.base_variables();
    const PointResponse<dim>  r0 =
      evaluate_contact_law(probe.state_at(x0), parameters);
    const auto J = jacobian(r0);

    const double rel_step = 1e-6;
    const double floor    = 1e-3;
    double       max_err  = 0.;
    for (unsigned int j = 0; j < 2 * dim; ++j)
      {
        const double h  = rel_step * std::max(std::abs(x0[j]), 1.);
        auto         xp = x0, xm = x0;
        xp[j] += h;
        xm[j] -= h;
        const auto rp = evaluate_contact_law(probe.state_at(xp), parameters);
        const auto rm = evaluate_contact_law(probe.state_at(xm), parameters);
        // The stencil must not cross a kink.
        AssertThrow(rp.status == r0.status && rm.status == r0.status &&
                      rp.in_contact == r0.in_contact &&
                      rm.in_contact == r0.in_contact &&
                      rp.friction_active == r0.friction_active &&
                      rm.friction_active == r0.friction_active,
                    ExcMessage("FD stencil crosses a status change."));
        const auto yp = densities(rp);
        const auto ym = densities(rm);
        for (unsigned int i = 0; i < 2 * dim; ++i)
          {
            const double fd  = (yp[i] - ym[i]) / (2. * h);
            const double ex  = J[i][j];
            const double den = std::max({std::abs(ex), std::abs(fd), floor});
            max_err          = std::max(max_err, std::abs(fd - ex) / den);
          }
      }
    return max_err;
  }

  template <int dim>
  void
  check_jacobians()
  {
    for (const double mu : {0., 0.3, 1.0})
      for (const Which which : {Which::free, Which::stick, Which::slip})
        {
          LawParameters p;
          p.rho_n = 50.;
          p.rho_t = 20.;
          p.mu    = mu;

          const PointState<dim>    s = make_state<dim>(which);
          const PointResponse<dim> r = evaluate_contact_law(s, p);

          const PointStatus expected =
            (which == Which::free ?
               PointStatus::free :
               (which == Which::stick && mu > 0. ? PointStatus::stick :
                                                   PointStatus::slip));
          AssertThrow(r.status == expected,
                      ExcMessage("Wrong status classification."));

          const double err = fd_error(s, p);

          std::ostringstream name;
          name << dim << "d " << to_string(which) << " mu=" << mu
               << " lagrange";
          if (mu > 0.)
            name << " lambda_f=lambda, row weight held";

          std::cout << std::left << std::setw(52) << name.str()
                    << " status=" << std::setw(5) << to_string(r.status)
                    << " max rel FD error = " << std::scientific
                    << std::setprecision(2) << err << std::defaultfloat
                    << std::endl;

          deallog << "case " << name.str()
                  << ": status = " << to_string(r.status)
                  << ", max rel FD error < 1e-6: " << yes_no(err < fd_tolerance)
                  << std::endl;
          AssertThrow(err < fd_tolerance,
                      ExcMessage("FD check failed for " + name.str()));
        }
  }


  template <int dim>
  void
  check_physics()
  {
    LawParameters p;
    p.rho_n = 50.;
    p.rho_t = 20.;
    p.mu    = 0.3;

    const Tensor<1, dim> n = generic_normal<dim>();
    const auto           T = tangent_basis(n);

    // Tangent basis: orthonormal, orthogonal to n, right-handed; 2D formula.
    {
      bool                        ok      = true;
      std::vector<Tensor<1, dim>> normals = {n};
      for (unsigned int i = 0; i < dim; ++i)
        {
          Tensor<1, dim> e;
          e[i] = (i % 2 == 0 ? 1. : -1.);
          normals.push_back(e);
        }
      for (const auto &m : normals)
        {
          const auto t = tangent_basis(m);
          for (unsigned int k = 0; k < dim - 1; ++k)
            {
              ok = ok && std::abs(t[k].norm() - 1.) < 1e-14;
              ok = ok && std::abs(t[k] * m) < 1e-14;
              for (unsigned int l = 0; l < k; ++l)
                ok = ok && std::abs(t[k] * t[l]) < 1e-14;
            }
          if constexpr (dim == 2)
            ok = ok && t[0][0] == m[1] && t[0][1] == -m[0];
          else
            ok = ok && (cross_product_3d(t[0], t[1]) - m).norm() < 1e-14;
        }
      deallog << dim
              << "d tangent basis orthonormal, right-handed: " << yes_no(ok)
              << std::endl;
      AssertThrow(ok, ExcInternalError());
    }

    // Free point: r_c = -lambda / rho_n, no force, Lambda driven to 0.
    {
      const auto s  = make_state<dim>(Which::free);
      const auto r  = evaluate_contact_law(s, p);
      const bool ok = r.status == PointStatus::free && !r.in_contact &&
                      r.r_c == -s.lambda / p.rho_n && r.force.norm() == 0. &&
                      r.r_f == s.Lambda && r.drc_dlambda == -1. / p.rho_n;
      deallog << dim << "d free point"
              << ": r_c = -lambda/rho_n, force = 0, r_f = Lambda: "
              << yes_no(ok) << std::endl;
      AssertThrow(ok, ExcInternalError());
    }

    // Converged slip point: g = 0, T Lambda = v / |v| -> r_c = 0, r_f = 0,
    // force = p n + mu p v/|v| with p = -lambda.
    {
      PointState<dim> s;
      s.normal               = n;
      s.tangents             = T;
      s.gap                  = 0.;
      s.lambda               = -1.5;
      s.row_lambda           = s.lambda;
      s.slip                 = tangent_combination<dim>(T, 0.03, -0.04);
      const Tensor<1, dim> t = s.slip / s.slip.norm();
      for (unsigned int k = 0; k < dim - 1; ++k)
        s.Lambda[k] = T[k] * t;
      {
        const auto           r = evaluate_contact_law(s, p);
        const Tensor<1, dim> expected_force =
          -s.lambda * n - p.mu * s.lambda * t;
        const bool ok = r.status == PointStatus::slip && r.in_contact &&
                        r.friction_active && r.r_c == 0. &&
                        r.r_f.norm() < 1e-14 &&
                        (r.force - expected_force).norm() < 1e-14;
        deallog << dim << "d converged slip point"
                << ": r_c = 0, r_f = 0, force = p (n + mu v/|v|): "
                << yes_no(ok) << std::endl;
        AssertThrow(ok, ExcInternalError());
      }
    }

    // Stick with v = 0: r_f = 0 exactly, force = p n - mu lambda T Lambda.
    {
      PointState<dim> s = make_state<dim>(Which::stick);
      s.slip            = Tensor<1, dim>();
      const auto r      = evaluate_contact_law(s, p);
      const bool ok     = r.status == PointStatus::stick && r.r_f.norm() == 0.;
      deallog << dim << "d stick point with v = 0: r_f = 0: " << yes_no(ok)
              << std::endl;
      AssertThrow(ok, ExcInternalError());
    }

    // The rows' weight: a stick and a slip point evaluated with the weight
    // lambda and 3 lambda. The rows and their derivatives scale by 3; the
    // status, the traction and its derivatives (lambda itself) do not move.
    for (const Which which : {Which::stick, Which::slip})
      {
        PointState<dim> s = make_state<dim>(which);
        const auto      r = evaluate_contact_law(s, p);
        s.row_lambda      = 3. * s.lambda;
        const auto r3     = evaluate_contact_law(s, p);
        bool       ok     = r3.status == r.status &&
                  (r3.r_f - 3. * r.r_f).norm() < 1e-14 * r.r_f.norm() &&
                  (r3.drf_dLambda - 3. * r.drf_dLambda).norm() <=
                    1e-14 * r.drf_dLambda.norm() &&
                  r3.force == r.force && r3.dforce_dd == r.dforce_dd &&
                  r3.dforce_dlambda == r.dforce_dlambda;
        for (unsigned int k = 0; k < dim - 1; ++k)
          ok = ok &&
               (r3.drf_dd[k] - 3. * r.drf_dd[k]).norm() <=
                 1e-14 * r.drf_dd[k].norm() &&
               r3.dforce_dLambda[k] == r.dforce_dLambda[k];
        deallog << dim << "d " << to_string(which)
                << " point, friction rows weighted by 3 lambda: rows x 3, "
                   "traction unchanged: "
                << yes_no(ok) << std::endl;
        AssertThrow(ok, ExcInternalError());
      }

    // Hand-picked classification, on an axis-aligned normal so that the
    // kinks are hit exactly in floating point.
    {
      Tensor<1, dim> e;
      e[dim - 1] = 1.;
      PointState<dim> s;
      s.normal   = e;
      s.tangents = tangent_basis(e);

      struct Pick
      {
        const char *what;
        double      gap, lambda, Lambda0, slip0;
        PointStatus expected;
        bool        contact;
      };
      const std::vector<Pick> picks = {
        {"lambda_aug = 0 (kink) -> free",
         0.,
         0.,
         0.,
         0.,
         PointStatus::free,
         false},
        {"lambda = -1e-3, g = 0 -> contact",
         0.,
         -1e-3,
         0.2,
         0.,
         PointStatus::stick,
         true},
        {"lambda = 0.5 > 0 but g = 0.02 -> contact",
         0.02,
         0.5,
         0.2,
         0.,
         PointStatus::stick,
         true},
        {"g < 0, lambda = -0.5 -> contact",
         -0.005,
         -0.5,
         0.2,
         0.,
         PointStatus::stick,
         true},
        {"g < 0, lambda = -0.1 -> free",
         -0.005,
         -0.1,
         0.2,
         0.,
         PointStatus::free,
         false},
        {"|h| = 1 exactly -> stick",
         0.01,
         -1.,
         1.,
         0.,
         PointStatus::stick,
         true},
        {"|h| = 0.5 + 20*0.03 = 1.1 -> slip",
         0.01,
         -1.,
         0.5,
         0.03,
         PointStatus::slip,
         true},
        {"|h| = 0.5 - 20*0.03 -> stick",
         0.01,
         -1.,
         0.5,
         -0.03,
         PointStatus::stick,
         true}};
      for (const auto &pick : picks)
        {
          s.gap        = pick.gap;
          s.lambda     = pick.lambda;
          s.Lambda     = Tensor<1, dim - 1>();
          s.Lambda[0]  = pick.Lambda0;
          s.slip       = pick.slip0 * s.tangents[0];
          const auto r = evaluate_contact_law(s, p);
          const bool ok =
            r.status == pick.expected && r.in_contact == pick.contact;
          deallog << dim << "d status " << pick.what << ": "
                  << to_string(r.status) << ", correct: " << yes_no(ok)
                  << std::endl;
          AssertThrow(ok, ExcInternalError());
        }
    }

    // Zero-threshold rule (section 3.3): in contact but lambda_f == 0
    // exactly -> friction rows as at a free point, no friction force, no
    // threshold coupling; the contact part is untouched.
    {
      PointState<dim> s      = make_state<dim>(Which::slip);
      s.lambda               = 0.; // lambda_aug = -rho_n g < 0: in contact
      const auto           r = evaluate_contact_law(s, p);
      const Tensor<1, dim> contact_force = -(s.lambda - p.rho_n * s.gap) * n;
      Tensor<2, dim - 1>   identity;
      for (unsigned int k = 0; k < dim - 1; ++k)
        identity[k][k] = 1.;
      bool ok = r.in_contact && !r.friction_active && r.lambda_f == 0. &&
                r.status == PointStatus::slip && r.r_f == s.Lambda &&
                r.drf_dLambda == identity &&
                (r.force - contact_force).norm() < 1e-13 &&
                (r.dforce_dlambda + n).norm() == 0. &&
                (r.dforce_dd - p.rho_n * outer_product(n, n)).norm() == 0.;
      for (unsigned int k = 0; k < dim - 1; ++k)
        ok = ok && r.dforce_dLambda[k].norm() == 0. && r.drf_dd[k].norm() == 0.;
      deallog << dim << "d zero threshold"
              << " (lambda = 0)"
              << ": friction treated as free: " << yes_no(ok) << std::endl;
      AssertThrow(ok, ExcInternalError());
    }

    // mu = 0: in contact -> slip, no friction contributions at all.
    {
      LawParameters q = p;
      q.mu            = 0.;
      for (const Which which : {Which::free, Which::stick, Which::slip})
        {
          const auto s  = make_state<dim>(which);
          const auto r  = evaluate_contact_law(s, q);
          bool       ok = !r.friction_active && r.r_f.norm() == 0. &&
                    r.drf_dLambda.norm() == 0.;
          for (unsigned int k = 0; k < dim - 1; ++k)
            ok = ok && r.dforce_dLambda[k].norm() == 0. &&
                 r.drf_dd[k].norm() == 0.;
          if (r.in_contact)
            ok = ok &&
                 (r.force - (-(s.lambda - p.rho_n * s.gap)) * n).norm() < 1e-13;
          deallog << dim << "d mu = 0, " << to_string(which)
                  << " state: status = " << to_string(r.status)
                  << ", no friction terms: " << yes_no(ok) << std::endl;
          AssertThrow(ok, ExcInternalError());
        }
    }
  }
} // namespace


// A point whose nodes hold tangents (PointState::held = Q, theory.md F8):
// the Jacobian is the derivative at stick and slip, and sticking, the rows
// along Q are s Q Lambda and the traction has no rho_t v along Q.
template <int dim>
void
check_held_law()
{
  Tensor<2, dim - 1> Q;
  if constexpr (dim == 2)
    Q[0][0] = 1;
  else
    {
      const Tensor<1, 2> a({0.6, 0.8});
      Q = outer_product(a, a);
    }
  for (const Which which : {Which::stick, Which::slip})
    {
      LawParameters p;
      p.rho_n               = 50.;
      p.rho_t               = 20.;
      p.mu                  = 0.3;
      p.free_friction_scale = 0.7;
      PointState<dim> s     = make_state<dim>(which);
      s.held                = Q;
      const auto   r        = evaluate_contact_law(s, p);
      const double err      = fd_error(s, p);
      bool         ok       = err < fd_tolerance;
      if (which == Which::stick)
        {
          // Rows along Q: s Q Lambda; traction along Q: -mu lambda T Q Lambda.
          Tensor<1, dim - 1> QL = Q * s.Lambda, r_held = Q * r.r_f;
          Tensor<1, dim - 1> f_t;
          for (unsigned int k = 0; k < dim - 1; ++k)
            f_t[k] = r.force * s.tangents[k];
          ok = ok && r.status == PointStatus::stick &&
               (r_held - p.free_friction_scale * QL).norm() < 1e-14 &&
               (Q * f_t + p.mu * s.lambda * QL).norm() < 1e-13;
        }
      deallog << dim << "d " << to_string(which)
              << " point with held tangents: FD error < 1e-6"
              << (which == Which::stick ? ", rows s Q Lambda, no rho_t v" : "")
              << ": " << yes_no(ok) << std::endl;
      AssertThrow(ok, ExcMessage("held law check failed"));
    }
}


// held_tangent(): a node held along tangential directions (a symmetry
// plane) keeps the friction component the conditions leave free.
void
check_held_tangent()
{
  // 2D: the one tangent held, no friction; nothing held, a = 0.
  {
    const Tensor<1, 2> n({0.6, 0.8});
    const bool         ok = !held_tangent<2>(n, {Tensor<1, 2>({0.8, -0.6})}) &&
                    held_tangent<2>(n, {})->norm() == 0;
    deallog << "2d held tangent: no friction: " << yes_no(ok) << std::endl;
    AssertThrow(ok, ExcInternalError());
  }
  // 3D: a . T is the held direction's tangential part (unit), for a
  // normal in a coordinate plane (a symmetry plane: a is a frame axis) and
  // a generic one; the largest component of a positive.
  bool ok = true;
  for (const auto &[n, h] : std::vector<std::pair<Tensor<1, 3>, Tensor<1, 3>>>{
         {Tensor<1, 3>({0, 0.6, -0.8}), Tensor<1, 3>({2, 0, 0})},
         {Tensor<1, 3>({0.6, 0, 0.8}), Tensor<1, 3>({0, -1, 0})},
         {Tensor<1, 3>({0.8, 0.6, 0.0}), Tensor<1, 3>({0, 0, 1})},
         {generic_normal<3>(), Tensor<1, 3>({0, 1, 0})}})
    {
      const auto a = held_tangent<3>(n, {h});
      const auto T = tangent_basis(n);
      ok           = ok && a && std::abs(a->norm() - 1) < 1e-14;
      if (!ok)
        break;
      const Tensor<1, 3> t   = (*a)[0] * T[0] + (*a)[1] * T[1];
      Tensor<1, 3>       h_t = h - (h * n) * n;
      h_t /= h_t.norm();
      ok = ok && std::abs(std::abs(t * h_t) - 1) < 1e-14 &&
           std::max((*a)[0], (*a)[1]) >= std::abs(std::min((*a)[0], (*a)[1]));
      // On a symmetry plane (n . h = 0) the frame axis is exact.
      if (n * h == 0)
        ok = ok && std::min(std::abs((*a)[0]), std::abs((*a)[1])) < 1e-15;
    }
  deallog << "3d held tangent: a . T along the held direction: " << yes_no(ok)
          << std::endl;
  AssertThrow(ok, ExcInternalError());
  // Two independent tangents held: no slip, no friction; two parallel
  // ones: one condition.
  const Tensor<1, 3> n({0, 0, 1});
  ok =
    !held_tangent<3>(n, {Tensor<1, 3>({1, 0, 0}), Tensor<1, 3>({1, 1, 0})}) &&
    held_tangent<3>(n, {Tensor<1, 3>({1, 0, 0}), Tensor<1, 3>({-2, 0, 0})})
        ->norm() > 0;
  deallog << "3d two tangents held: no friction; parallel: one condition: "
          << yes_no(ok) << std::endl;
  AssertThrow(ok, ExcInternalError());
}


int
main()
{
  try
    {
      std::ofstream logfile("output");
      deallog.attach(logfile, /*print_job_id=*/false);
      deallog.depth_console(0);

      check_jacobians<2>();
      check_jacobians<3>();
      check_physics<2>();
      check_physics<3>();
      check_held_tangent();
      check_held_law<2>();
      check_held_law<3>();

      deallog << "OK" << std::endl;
    }
  catch (std::exception &exc)
    {
      std::cerr << "Exception: " << exc.what() << std::endl;
      return 1;
    }
  return 0;
}
