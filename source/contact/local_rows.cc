// Local rows of one evaluated contact point (theory.md F4 and 5): the
// residual -R and the Jacobian K on its unknowns e | m | lambda | Lambda.
// The point path takes the law's response; the node path (statuses per
// multiplier node) adds the friction rows of each node.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <signorini/contact/assembler.h>

#include "helpers.h"

namespace Signorini
{
  namespace Contact
  {
    namespace
    {
      // The row of a saturated pinned node (NodeFriction) along its held
      // tangent a: a . Lambda - s (1 - (b . Lambda)^2)^(1/2), s = sign(a .
      // H), and its gradient in Lambda (the root kept off zero, where the
      // node is about to slide along b).
      template <int dim>
      std::pair<double, Tensor<1, dim - 1>>
      saturated_row(const Tensor<1, dim - 1> &a,
                    const NodeFriction<dim>  &nf,
                    const Tensor<1, dim - 1> &L)
      {
        const auto       b     = free_tangent<dim>(a);
        const double     s     = a * nf.H < 0 ? -1. : 1.;
        const double     beta  = b * L;
        constexpr double floor = 1e-8;
        const double     c2    = 1. - beta * beta;
        const double     c     = std::sqrt(std::max(c2, floor));
        return {a * L - s * c, a + (c2 > floor ? s * beta / c : 0.) * b};
      }
    } // namespace


    template <int dim>
    void
    Assembler<dim>::local_residual(const ContactPoint                  &point,
                                   const TrilinosWrappers::MPI::Vector &state,
                                   PointEvaluation                     &e,
                                   Vector<double>                      &F) const
    {
      const auto        &face  = surfaces.slave_faces()[point.face];
      const unsigned int p     = face.pair;
      const auto        &r     = e.r;
      const auto        &psi   = point.psi;
      const auto        &psi_c = point.psi_lambda;
      const unsigned int n_e = e.n_e, n_m = e.n_m, n_l = e.n_l;

      // Local dofs: e | m | lambda | Lambda.
      e.n_f                  = e.fric ? n_l * (dim - 1) : 0;
      e.o_c                  = n_e + n_m;
      e.o_f                  = e.o_c + n_l;
      e.n                    = e.o_f + e.n_f;
      const unsigned int o_c = e.o_c, o_f = e.o_f;

      // Shape value and component of each displacement column, with the
      // sign of d = u^e - u^m.
      e.Nd.resize(n_e + n_m);
      e.comp.resize(n_e + n_m);
      for (unsigned int a = 0; a < n_e; ++a)
        {
          e.Nd[a]   = e.N_e[a];
          e.comp[a] = face.u_comp[a];
        }
      for (unsigned int b = 0; b < n_m; ++b)
        {
          e.Nd[n_e + b]   = -point.N_m[b / dim];
          e.comp[n_e + b] = b % dim;
        }

      const double w  = point.weight;
      const double sc = coefficients.normal(p); // row scaling of lambda rows
      const double sf =
        coefficients.tangential(p); // row scaling of Lambda rows
      F.reinit(e.n);
      for (unsigned int a = 0; a < n_e + n_m; ++a)
        F[a] = -w * e.Nd[a] * r.force[e.comp[a]];
      // The Signorini row of each node: the point's law, or the node's
      // status (node_status_row).
      e.rows.resize(n_l);
      for (unsigned int l = 0; l < n_l; ++l)
        e.rows[l] =
          e.by_node ?
            node_status_row(node_statuses.active(face.lambda_dofs[l]) &&
                              point.paired,
                            point.paired ? e.s.gap : 0.,
                            state[face.lambda_dofs[l]],
                            e.s.normal,
                            coefficients.normal(p)) :
            NodeStatusRow<dim>{r.r_c, r.drc_dd, 0.};
      for (unsigned int l = 0; l < n_l; ++l)
        {
          F[o_c + l] = -sc * w * psi_c[l] * e.rows[l].r_c;
          for (unsigned int k = 0; k < (e.fric ? dim - 1 : 0); ++k)
            F[o_f + l * (dim - 1) + k] = -sf * w * psi[l] * r.r_f[k];
        }
      add_node_friction_rows(point, e, F);
    }


    template <int dim>
    void
    Assembler<dim>::add_node_friction_rows(const ContactPoint    &point,
                                           const PointEvaluation &e,
                                           Vector<double>        &F) const
    {
      const auto        &face  = surfaces.slave_faces()[point.face];
      const auto        &law   = e.law;
      const auto        &psi_c = point.psi_lambda;
      const double       w     = point.weight;
      const double       sf    = coefficients.tangential(face.pair);
      const unsigned int o_f   = e.o_f;
      // Friction rows per node (node-status pairs; the held nodes of the
      // others, in place of the point's rows): free (or zero threshold)
      // s Lambda_l; stick -mu lambda_l W_l (its weighted slip closed),
      // along a held tangent s Q Lambda_l instead; slip
      // (mu lambda_l / rho_t) D_l (Lambda_l - q_l), q_l = H_l / |H_l|; a
      // saturated pinned node its stick rows along the free tangent, and
      // (mu lambda_l / rho_t) D_l times its saturated row along the held
      // one; each point adds its share w psi_l. The weight mu lambda_l is held
      // at the iterate (NodeData::row_lambda).
      for (unsigned int l = 0; l < e.node_data.size(); ++l)
        {
          if (!e.node_data[l].status)
            continue;
          const auto  &nf = *e.node_data[l].status;
          const double lw = e.node_data[l].row_lambda;
          const auto  &L  = e.node_data[l].Lambda;
          const auto  &Q  = face.held[l];
          // A pinned node's rows along Q are its pin's support force
          // (Assembler::add_pin_rows, PinRows), not s Q Lambda, or,
          // saturated, its saturated row.
          const bool         pinned = face.pin[l] != numbers::invalid_dof_index;
          const double       sQ     = pinned ? 0. : law.free_friction_scale;
          Tensor<1, dim - 1> a;
          double             saturated = 0;
          if (nf.active && nf.saturated)
            {
              a         = surfaces.pins().at(face.pin[l]).a;
              saturated = saturated_row(a, nf, L).first;
            }
          for (unsigned int k = 0; k < dim - 1; ++k)
            {
              double r_f = 0;
              if (!nf.active)
                r_f = law.free_friction_scale * L[k];
              else if (nf.stick || nf.saturated)
                for (unsigned int j = 0; j < dim - 1; ++j)
                  r_f += ((k == j) - Q[k][j]) * -law.mu * lw * e.slip_t[j] +
                         sQ * Q[k][j] * L[j];
              else
                r_f = law.mu * lw / law.rho_t * (L[k] - nf.H[k] / nf.H.norm());
              r_f += law.mu * lw / law.rho_t * a[k] * saturated;
              if (!e.by_node)
                F[o_f + l * (dim - 1) + k] = 0; // the node's row instead
              F[o_f + l * (dim - 1) + k] += -sf * w * psi_c[l] * r_f;
            }
        }
    }


    template <int dim>
    void
    Assembler<dim>::local_jacobian(const ContactPoint    &point,
                                   const PointEvaluation &e,
                                   FullMatrix<double>    &K) const
    {
      const unsigned int p     = surfaces.slave_faces()[point.face].pair;
      const auto        &r     = e.r;
      const auto        &psi   = point.psi;
      const auto        &psi_c = point.psi_lambda;
      const auto        &Nd    = e.Nd;
      const auto        &comp  = e.comp;
      const unsigned int n_u = e.n_e + e.n_m, n_l = e.n_l;
      const unsigned int o_c = e.o_c, o_f = e.o_f;
      const unsigned int n_t = e.fric ? dim - 1 : 0;
      const double       w   = point.weight;
      const double sc = coefficients.normal(p); // row scaling of lambda rows
      const double sf =
        coefficients.tangential(p); // row scaling of Lambda rows

      K.reinit(e.n, e.n);
      for (unsigned int a = 0; a < n_u; ++a)
        {
          for (unsigned int b = 0; b < n_u; ++b)
            K(a, b) = w * Nd[a] * Nd[b] * r.dforce_dd[comp[a]][comp[b]];
          for (unsigned int l = 0; l < n_l; ++l)
            {
              K(a, o_c + l) = w * Nd[a] * psi_c[l] * r.dforce_dlambda[comp[a]];
              K(o_c + l, a) =
                sc * w * psi_c[l] * Nd[a] * e.rows[l].drc_dd[comp[a]];
              for (unsigned int k = 0; k < n_t; ++k)
                {
                  K(a, o_f + l * (dim - 1) + k) =
                    w * Nd[a] * psi[l] * r.dforce_dLambda[k][comp[a]];
                  K(o_f + l * (dim - 1) + k, a) =
                    sf * w * psi[l] * Nd[a] * r.drf_dd[k][comp[a]];
                }
            }
        }
      for (unsigned int l = 0; l < n_l; ++l)
        for (unsigned int m = 0; m < n_l; ++m)
          {
            K(o_c + l, o_c + m) =
              e.by_node ?
                (l == m ? sc * w * psi_c[l] * e.rows[l].drc_dlambda_own : 0.) :
                sc * w * psi[l] * psi[m] * r.drc_dlambda;
            for (unsigned int k = 0; k < n_t; ++k)
              {
                for (unsigned int kk = 0; kk < dim - 1; ++kk)
                  K(o_f + l * (dim - 1) + k, o_f + m * (dim - 1) + kk) =
                    sf * w * psi[l] * psi[m] * r.drf_dLambda[k][kk];
              }
          }
      // Pairs with statuses per point: a held node's rows are the node's.
      if (!e.by_node)
        for (unsigned int l = 0; l < e.node_data.size(); ++l)
          if (e.node_data[l].status)
            for (unsigned int k = 0; k < n_t; ++k)
              for (unsigned int j = 0; j < e.n; ++j)
                K(o_f + l * (dim - 1) + k, j) = 0;
      add_node_friction_jacobian(point, e, K);
    }


    template <int dim>
    void
    Assembler<dim>::add_node_friction_jacobian(const ContactPoint    &point,
                                               const PointEvaluation &e,
                                               FullMatrix<double>    &K) const
    {
      const auto        &face  = surfaces.slave_faces()[point.face];
      const auto        &law   = e.law;
      const auto        &s     = e.s;
      const auto        &psi_c = point.psi_lambda;
      const auto        &Nd    = e.Nd;
      const auto        &comp  = e.comp;
      const unsigned int n_u   = e.n_e + e.n_m;
      const double       w     = point.weight;
      const double       sf    = coefficients.tangential(face.pair);
      for (unsigned int l = 0; l < e.node_data.size(); ++l)
        {
          if (!e.node_data[l].status)
            continue;
          const auto        &nf  = *e.node_data[l].status;
          const auto        &Q   = face.held[l];
          const double       lam = e.node_data[l].lambda;
          const double       lw  = e.node_data[l].row_lambda;
          const auto        &L   = e.node_data[l].Lambda;
          const double       wl  = sf * w * psi_c[l];
          const unsigned int of  = e.o_f + l * (dim - 1);
          if (!nf.active)
            {
              for (unsigned int k = 0; k < dim - 1; ++k)
                K(of + k, of + k) += wl * law.free_friction_scale;
              continue;
            }
          if (point.paired && e.by_node)
            {
              // Displacement rows: d/dlambda_l, d/dLambda_l (the point
              // law's at the other pairs).
              Tensor<1, dim> TL;
              for (unsigned int k = 0; k < dim - 1; ++k)
                TL += L[k] * s.tangents[k];
              for (unsigned int a = 0; a < n_u; ++a)
                {
                  K(a, e.o_c + l) +=
                    w * Nd[a] * (-law.mu * psi_c[l] * TL[comp[a]]);
                  for (unsigned int k = 0; k < dim - 1; ++k)
                    K(a, of + k) +=
                      w * Nd[a] *
                      (-law.mu * psi_c[l] * lam * s.tangents[k][comp[a]]);
                }
            }
          // The friction rows: their weight mu lambda_l is held, so they
          // have no lambda_l column.
          if (nf.stick || nf.saturated)
            {
              // Along a held tangent: s Q Lambda_l (a pin's: its support
              // force, Assembler::add_pin_rows, or its saturated row).
              const bool   pinned = face.pin[l] != numbers::invalid_dof_index;
              const double sQ     = pinned ? 0. : law.free_friction_scale;
              for (unsigned int k = 0; k < dim - 1; ++k)
                for (unsigned int j = 0; j < dim - 1; ++j)
                  {
                    K(of + k, of + j) += wl * sQ * Q[k][j];
                    if (point.paired)
                      for (unsigned int a = 0; a < n_u; ++a)
                        K(of + k, a) += wl * ((k == j) - Q[k][j]) *
                                        (-law.mu * lw) *
                                        s.tangents[j][comp[a]] * Nd[a];
                  }
              if (nf.saturated)
                {
                  const auto &a = surfaces.pins().at(face.pin[l]).a;
                  const auto  g = saturated_row(a, nf, L).second;
                  for (unsigned int k = 0; k < dim - 1; ++k)
                    for (unsigned int j = 0; j < dim - 1; ++j)
                      K(of + k, of + j) +=
                        wl * law.mu * lw / law.rho_t * a[k] * g[j];
                }
              continue;
            }
          // Slip: K_B = (I - q q) / |H|, dH/dLambda_l = I,
          // dH/du = rho_t / D_l dW/du. Frozen in slip: q fixed, K_B = 0; a
          // pinned node slides along its free tangent b, q = +-b whatever
          // H: K_B = 0 too.
          const double       nH = nf.H.norm();
          Tensor<2, dim - 1> KB;
          if (!nf.frozen && face.pin[l] == numbers::invalid_dof_index)
            for (unsigned int k = 0; k < dim - 1; ++k)
              for (unsigned int kk = 0; kk < dim - 1; ++kk)
                KB[k][kk] = ((k == kk) - nf.H[k] * nf.H[kk] / (nH * nH)) / nH;
          for (unsigned int k = 0; k < dim - 1; ++k)
            {
              for (unsigned int kk = 0; kk < dim - 1; ++kk)
                K(of + k, of + kk) +=
                  wl * law.mu * lw / law.rho_t * ((k == kk) - KB[k][kk]);
              if (point.paired)
                for (unsigned int a = 0; a < n_u; ++a)
                  {
                    double KBT = 0;
                    for (unsigned int kk = 0; kk < dim - 1; ++kk)
                      KBT += KB[k][kk] * s.tangents[kk][comp[a]];
                    K(of + k, a) += wl * (-law.mu * lw) * KBT * Nd[a];
                  }
            }
        }
    }


    template class Assembler<2>;
    template class Assembler<3>;
  } // namespace Contact
} // namespace Signorini
