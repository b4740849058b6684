#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include <signorini/contact/contact_law.h>

#include <cmath>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    namespace
    {
      template <int dim>
      Tensor<2, dim>
      identity_tensor()
      {
        Tensor<2, dim> identity;
        for (unsigned int i = 0; i < dim; ++i)
          identity[i][i] = 1.;
        return identity;
      }
    } // namespace

    const char *
    to_string(const PointStatus status)
    {
      switch (status)
        {
          case PointStatus::free:
            return "free";
          case PointStatus::stick:
            return "stick";
          case PointStatus::slip:
            return "slip";
        }
      Assert(false, ExcInternalError());
      return "unknown";
    }



    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &n)
    {
      static_assert(dim == 2 || dim == 3, "Only dim = 2 and 3 are supported.");
      Assert(std::abs(n.norm() - 1.) < 1e-10,
             ExcMessage("The normal passed to tangent_basis() must be a unit "
                        "vector."));

      return tangent_basis(n, tangent_axis(n));
    }


    template <int dim>
    unsigned int
    tangent_axis(const Tensor<1, dim> &n)
    {
      // The x axis unless n is within 37 degrees of it (the cross
      // product's norm stays >= 0.6, no cancellation); then the one of y, z
      // least aligned with n. One axis for every point of a surface that
      // does not face x: the tangent frames of neighbouring points agree,
      // so that a multiplier node's Lambda means one direction over its
      // faces (the least aligned axis of each point flipped between x and
      // y on a slightly uneven surface facing z, turning T by 90 degrees).
      unsigned int axis = 0;
      if constexpr (dim == 3)
        if (std::abs(n[0]) > 0.8)
          axis = std::abs(n[1]) <= std::abs(n[2]) ? 1 : 2;
      return axis;
    }


    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &n, const unsigned int axis)
    {
      std::array<Tensor<1, dim>, dim - 1> tangents;
      if constexpr (dim == 2)
        {
          (void)axis;
          // Section 2 fixes this choice, so that Lambda has the same meaning
          // for every code that rebuilds T from n.
          tangents[0][0] = n[1];
          tangents[0][1] = -n[0];
        }
      else
        {
          Tensor<1, dim> e;
          e[axis]     = 1.;
          tangents[0] = cross_product_3d(n, e);
          tangents[0] /= tangents[0].norm();
          // (tau_1, tau_2, n) right-handed, like (tau_1, n) in 2D.
          tangents[1] = cross_product_3d(n, tangents[0]);
        }
      return tangents;
    }



    template <int dim>
    std::optional<Tensor<1, dim - 1>>
    held_tangent(const Tensor<1, dim>              &n,
                 const std::vector<Tensor<1, dim>> &held)
    {
      Tensor<1, dim - 1> a;
      if (held.empty())
        return a;
      if (dim == 2)
        return std::nullopt;
      const auto tau = tangent_basis(n);
      for (const auto &h : held)
        {
          Tensor<1, dim - 1> t;
          for (unsigned int k = 0; k < dim - 1; ++k)
            t[k] = tau[k] * h;
          if (t.norm() == 0)
            continue;
          t /= t.norm();
          if (a.norm() == 0)
            a = t;
          else if (std::abs(a[0] * t[dim - 2] - a[dim - 2] * t[0]) > 1e-6)
            return std::nullopt; // two tangents held: no slip at all
        }
      if (a.norm() == 0)
        return std::nullopt;
      const unsigned int largest =
        std::abs(a[0]) >= std::abs(a[dim - 2]) ? 0 : dim - 2;
      return a[largest] > 0 ? a : -a;
    }


    namespace
    {
      // Normal part: sections 3.1, 4 (L_c rows), 5 ("Contact").
      template <int dim>
      void
      add_normal_response(const PointState<dim> &state,
                          const double           rho_n,
                          PointResponse<dim>    &response)
      {
        const Tensor<1, dim> &n = state.normal;
        // Section 3.1: contact iff lambda_aug < 0 (strict: lambda_aug == 0
        // is the kink, assigned to the free side).
        const double lambda_aug = state.lambda - rho_n * state.gap;
        response.in_contact =
          ((lambda_aug < 0.) || state.freeze_contact) && !state.release;
        if (response.in_contact)
          {
            // L_c^e = -w N^e lambda_aug n, L_c^c = -w psi g.
            response.force          = -lambda_aug * n;
            response.dforce_dd      = rho_n * outer_product(n, n);
            response.dforce_dlambda = -n;
            response.r_c            = -state.gap;
            response.drc_dd         = -n;
            response.drc_dlambda    = 0.;
          }
        else
          {
            // L_c^c = -w psi lambda / rho_n drives lambda to 0 (K_cc).
            response.r_c         = -state.lambda / rho_n;
            response.drc_dlambda = -1. / rho_n;
          }
        response.status =
          (response.in_contact ? PointStatus::slip : PointStatus::free);
      }


      // What the stick and slip branches share: the state, the law's
      // coefficients, P = I - n (x) n, the tangential slip v = P slip,
      // mu lambda_f (s = -mu lambda_f of section 5) and the rows' weight
      // mu lambda_f held at the iterate (mu_lw).
      template <int dim>
      struct FrictionTerms
      {
        const PointState<dim> &state;
        double                 mu, rho_t, mu_lf, mu_lw;
        Tensor<2, dim>         P;
        Tensor<1, dim>         v;
      };


      // Stick: P_B(h) = h. Along held tangents (Q, theory.md F8) the rows
      // are s Q Lambda and the traction takes Lambda alone.
      template <int dim>
      void
      add_stick_response(const FrictionTerms<dim> &f,
                         const Tensor<1, dim>     &h,
                         const double              s,
                         PointResponse<dim>       &response)
      {
        const auto &T   = f.state.tangents;
        const auto &Q   = f.state.held;
        response.status = PointStatus::stick;
        // The free part of v, T (I - Q) T^T v, and its derivative
        // T (I - Q) T^T P = P_f P.
        Tensor<2, dim> P_f = f.P;
        for (unsigned int k = 0; k < dim - 1; ++k)
          for (unsigned int l = 0; l < dim - 1; ++l)
            P_f -= Q[k][l] * outer_product(T[k], T[l]);
        const Tensor<1, dim> h_f = h - f.rho_t * (f.v - P_f * f.v);
        // L_f^e = -w mu lambda_f N^e h_f.
        response.force += -f.mu_lf * h_f;
        response.dforce_dd += -f.mu_lf * f.rho_t * P_f * f.P;
        for (unsigned int k = 0; k < dim - 1; ++k)
          response.dforce_dLambda[k] = -f.mu_lf * T[k];
        // K_ec threshold coupling: -mu P_B(h).
        response.dforce_dlambda += -f.mu * h_f;
        // L_f^f = -w psi mu lambda_f T^T v (weight held), K_ff = 0, along
        // the free tangents; s Q Lambda along the held ones.
        for (unsigned int k = 0; k < dim - 1; ++k)
          {
            // T^T P = T^T since T is tangent.
            response.r_f[k]    = -f.mu_lw * (T[k] * (P_f * f.v));
            response.drf_dd[k] = -f.mu_lw * (T[k] * P_f);
            for (unsigned int l = 0; l < dim - 1; ++l)
              {
                response.r_f[k] += s * Q[k][l] * f.state.Lambda[l];
                response.drf_dLambda[k][l] = s * Q[k][l];
              }
          }
      }


      // Slip: P_B(h) = q = h / |h|, K_B = (I - q (x) q) / |h|; with a
      // frozen slip direction q does not depend on h, so K_B = 0.
      template <int dim>
      void
      add_slip_response(const FrictionTerms<dim> &f,
                        const Tensor<1, dim>     &q,
                        const Tensor<2, dim>     &K_B,
                        PointResponse<dim>       &response)
      {
        const auto  &T          = f.state.tangents;
        const auto  &Lambda     = f.state.Lambda;
        const double mu_lf      = f.mu_lf;
        response.status         = PointStatus::slip;
        response.slip_direction = q;
        // K_B maps tangent vectors to tangent vectors, so K_B P = P K_B P.
        const Tensor<2, dim> K_B_P = K_B * f.P;
        // L_f^e = -w mu lambda_f N^e h / |h|.
        response.force += -mu_lf * q;
        response.dforce_dd += -mu_lf * f.rho_t * K_B_P;
        for (unsigned int k = 0; k < dim - 1; ++k)
          response.dforce_dLambda[k] = -mu_lf * (K_B * T[k]);
        response.dforce_dlambda += -f.mu * q;
        // L_f^f = +w psi (mu lambda_f / rho_t) T^T (T Lambda - h / |h|),
        // the weight mu lambda_f held (mu_lw).
        const double mu_lw = f.mu_lw;
        for (unsigned int k = 0; k < dim - 1; ++k)
          {
            response.r_f[k] = mu_lw / f.rho_t * (Lambda[k] - T[k] * q);
            // K_fe = -mu lambda_f T^T K_B P (row k: (K_B P)^T tau_k).
            response.drf_dd[k] = -mu_lw * (T[k] * K_B_P);
            // K_ff = (mu lambda_f / rho_t) T^T (I - K_B) T.
            for (unsigned int l = 0; l < dim - 1; ++l)
              response.drf_dLambda[k][l] =
                mu_lw / f.rho_t * ((k == l ? 1. : 0.) - T[k] * (K_B * T[l]));
          }
      }
    } // namespace


    template <int dim>
    PointResponse<dim>
    evaluate_contact_law(const PointState<dim> &state,
                         const LawParameters   &parameters)
    {
      Assert(parameters.rho_n > 0., ExcMessage("rho_n must be positive."));
      Assert(parameters.mu >= 0., ExcMessage("mu must be non-negative."));
      Assert(parameters.mu == 0. || parameters.rho_t > 0.,
             ExcMessage("rho_t must be positive when mu > 0."));
      Assert(std::abs(state.normal.norm() - 1.) < 1e-10,
             ExcMessage("The normal must be a unit vector."));
      AssertIsFinite(state.gap);
      AssertIsFinite(state.lambda);

      // Everything starts at zero: deal.II tensors are zero-initialised, so
      // only nonzero contributions are written below.
      PointResponse<dim> response;
      response.status          = PointStatus::free;
      response.in_contact      = false;
      response.friction_active = false;
      response.lambda_f        = 0.;
      response.r_c             = 0.;
      response.drc_dlambda     = 0.;
      add_normal_response(state, parameters.rho_n, response);

      // Friction: sections 3.2, 3.3, 4 (L_f rows), 5 ("Friction").
      // mu == 0: no friction unknowns at all (section 4), everything stays 0.
      if (parameters.mu == 0.)
        return response;

      // Section 3.3: Newton on the threshold, lambda_f = lambda. No clamping
      // of the sign of lambda_f: the formulas of sections 4-5 are applied
      // as written, which keeps the Jacobian the exact derivative also at
      // iterates where an in-contact point has lambda > 0.
      const double lambda_f = state.lambda;
      response.lambda_f     = lambda_f;

      // Section 3.3: in contact with lambda_f == 0 is treated as a free
      // point for friction, otherwise K_ff = 0 (stick) or
      // (mu lambda_f / rho_t)(...) = 0 (slip) would make the f block
      // singular. This is the value a point carries right after it closes
      // (lambda still 0); "zero" means at most
      // zero_threshold, the round-off level of the solve that closed it.
      response.friction_active =
        response.in_contact && (std::abs(lambda_f) > parameters.zero_threshold);
      if (!response.friction_active)
        {
          // L_f^f = +w psi Lambda, K_ff = I: drives Lambda to 0; weighted
          // by free_friction_scale so that all Lambda rows share one unit.
          const double s = parameters.free_friction_scale;
          response.r_f   = s * state.Lambda;
          for (unsigned int k = 0; k < dim - 1; ++k)
            response.drf_dLambda[k][k] = s;
          return response;
        }

      // P = I - n (x) n (section 2); dv/dd = P. h = T Lambda + rho_t v
      // (section 3.2). v is projected once more so that a slightly
      // non-tangent input cannot leak into the normal direction; this is
      // consistent with dv/dd = P since P P = P.
      const Tensor<2, dim> P =
        identity_tensor<dim>() - outer_product(state.normal, state.normal);
      const FrictionTerms<dim> f{state,
                                 parameters.mu,
                                 parameters.rho_t,
                                 parameters.mu * lambda_f,
                                 parameters.mu * state.row_lambda,
                                 P,
                                 P * state.slip};
      Tensor<1, dim>           T_Lambda;
      for (unsigned int k = 0; k < dim - 1; ++k)
        T_Lambda += state.Lambda[k] * state.tangents[k];
      const Tensor<1, dim> h      = T_Lambda + f.rho_t * f.v;
      const double         norm_h = h.norm();

      // A frozen slip direction (anti-cycling), carried into the current
      // tangent plane; ignored if the plane turned away from it.
      Tensor<1, dim> q_frozen    = P * state.frozen_slip_direction;
      const bool     frozen_slip = q_frozen.norm() > 0.5;
      if (frozen_slip)
        q_frozen /= q_frozen.norm();

      // |h| <= 1 up to round-off: at the first iterate of a step a point
      // that slipped in the last one has T Lambda on the unit circle and
      // v = 0, so |h| = 1 +/- 1e-16 and the decision would be round-off
      // (different in SI and in mm-N-MPa). Such a tie is stick: the point
      // has not slipped in this step yet.
      if ((norm_h <= 1. + stick_tie || state.freeze_stick) && !frozen_slip)
        add_stick_response(f, h, parameters.free_friction_scale, response);
      else if (frozen_slip)
        add_slip_response(f, q_frozen, Tensor<2, dim>(), response);
      else
        {
          const Tensor<1, dim> q = h / norm_h;
          add_slip_response(f,
                            q,
                            (identity_tensor<dim>() - outer_product(q, q)) /
                              norm_h,
                            response);
        }
      return response;
    }


    // Explicit instantiations.
    template std::array<Tensor<1, 2>, 1>
    tangent_basis<2>(const Tensor<1, 2> &);
    template unsigned int
    tangent_axis<2>(const Tensor<1, 2> &);
    template unsigned int
    tangent_axis<3>(const Tensor<1, 3> &);
    template std::array<Tensor<1, 2>, 1>
    tangent_basis<2>(const Tensor<1, 2> &, const unsigned int);
    template std::array<Tensor<1, 3>, 2>
    tangent_basis<3>(const Tensor<1, 3> &, const unsigned int);

    template std::array<Tensor<1, 3>, 2>
    tangent_basis<3>(const Tensor<1, 3> &);
    template std::optional<Tensor<1, 1>>
    held_tangent<2>(const Tensor<1, 2> &, const std::vector<Tensor<1, 2>> &);
    template std::optional<Tensor<1, 2>>
    held_tangent<3>(const Tensor<1, 3> &, const std::vector<Tensor<1, 3>> &);

    template PointResponse<2>
    evaluate_contact_law<2>(const PointState<2> &, const LawParameters &);
    template PointResponse<3>
    evaluate_contact_law<3>(const PointState<3> &, const LawParameters &);

  } // namespace Contact
} // namespace Signorini
