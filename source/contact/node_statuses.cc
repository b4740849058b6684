// Contact statuses per multiplier node.
#include <deal.II/base/mpi.h>

#include <signorini/contact/distributed_vectors.h>
#include <signorini/contact/node_statuses.h>

#include "helpers.h"

#include <algorithm>
#include <set>

namespace Signorini
{
  namespace Contact
  {
    using internal::add_entry;


    template <int dim>
    struct NodeStatuses<dim>::NodeSums
    {
      TrilinosWrappers::MPI::Vector              G, D, P;
      std::vector<TrilinosWrappers::MPI::Vector> W;
      // Pinned nodes (Surfaces::pins()): A_l = sum w psi_l n_c and
      // B_l = sum w psi_l (T a)_c over their points, c the pinned
      // component, a the held tangent (empty without pins).
      TrilinosWrappers::MPI::Vector A, B;
    };


    template <int dim>
    NodeStatuses<dim>::NodeStatuses(const ContactParameters &parameters,
                                    const Surfaces<dim>     &surfaces,
                                    const Pairing<dim>      &pairing,
                                    const Coefficients      &coefficients)
        : surfaces(surfaces)
        , pairing(pairing)
        , coefficients(coefficients)
    {
      for (const auto &pair : parameters.pairs)
        {
          // Statuses per multiplier node: integration-point rules, meshed
          // master (the others have one law per node).
          node_status_pair.push_back(
            parameters.rule != IntegrationRule::nodal && pair.master_is_body());
          friction_node_pair.push_back(node_status_pair.back() &&
                                       pair.friction > 0);
          // The other frictional pairs: the friction of held nodes.
          held_node_pair.push_back(!node_status_pair.back() &&
                                   pair.friction > 0);
          any_friction_node = any_friction_node || friction_node_pair.back();
          any_node_status   = any_node_status || node_status_pair.back();
          any_held_node     = any_held_node || held_node_pair.back();
        }
    }


    template <int dim>
    bool
    NodeStatuses<dim>::has_held_node(const SlaveFace<dim> &face)
    {
      return std::any_of(face.held.begin(), face.held.end(), [](const auto &Q) {
        return Q.norm() > 0;
      });
    }


    template <int dim>
    PointResponse<dim>
    NodeStatuses<dim>::response(const ContactPoint<dim> &point,
                                const PointState<dim>   &s) const
    {
      // The multiplier force -lambda n (the law's -lambda_aug n without
      // the augmentation; lambda = 0 at free nodes); the point is labelled
      // with the status of its nearest node (statistics and output).
      PointResponse<dim> r{};
      const auto        &face = surfaces.slave_faces()[point.face];
      const auto         nearest =
        std::max_element(point.psi.begin(), point.psi.end()) -
        point.psi.begin();
      r.in_contact = point.paired && node_active.at(face.lambda_dofs[nearest]);
      r.status     = r.in_contact ? PointStatus::slip : PointStatus::free;
      r.friction_active = false;
      if (r.in_contact && friction_node_pair[face.pair])
        {
          // Labelled with the friction status of the nearest node with
          // friction (a node excluded from friction has none: a point
          // between it and another node takes the other's, whatever the
          // round-off of psi); the friction force and rows are the
          // assembly's (per node).
          auto labelled = nearest;
          for (unsigned int l = 0; l < point.psi.size(); ++l)
            if (!face.excluded_friction[l] && point.psi[l] > 0 &&
                (face.excluded_friction[labelled] ||
                 point.psi[l] > point.psi[labelled]))
              labelled = l;
          const auto &nf    = node_friction.at(face.lambda_dofs[labelled]);
          r.friction_active = nf.active;
          if (nf.active && nf.stick)
            r.status = PointStatus::stick;
          else if (nf.active)
            for (unsigned int k = 0; k < dim - 1; ++k)
              r.slip_direction += nf.H[k] / nf.H.norm() * s.tangents[k];
        }
      if (point.paired)
        {
          r.force          = -s.lambda * s.normal;
          r.dforce_dlambda = -s.normal;
        }
      return r;
    }


    template <int dim>
    typename NodeStatuses<dim>::NodeSums
    NodeStatuses<dim>::gather_sums(
      const TrilinosWrappers::MPI::Vector &state,
      const TrilinosWrappers::MPI::Vector &start) const
    {
      // Weighted gap G_l and weight D_l of every node (faces of all ranks).
      // P_l: the paired share of the node (psi >= 0); a node without
      // paired points has no gap and stays free.
      auto G = surfaces.writable_multipliers();
      auto D = surfaces.writable_multipliers();
      auto P = surfaces.writable_multipliers();
      // Frictional pairs: the weighted slip W_l = sum_k w_k psi_l T^T v_k,
      // component k in the vector of index k (by the node's lambda DoF).
      std::vector<TrilinosWrappers::MPI::Vector> W;
      if (any_friction_node || any_held_node)
        for (unsigned int k = 0; k < dim - 1; ++k)
          W.push_back(surfaces.writable_multipliers());
      const bool                    any_pin = !surfaces.pins().empty();
      TrilinosWrappers::MPI::Vector A, B;
      if (any_pin)
        {
          A = surfaces.writable_multipliers();
          B = surfaces.writable_multipliers();
        }
      for (const auto &point : pairing.points())
        {
          const auto &face = surfaces.slave_faces()[point.face];
          if (!node_status_pair[face.pair] &&
              !(held_node_pair[face.pair] && has_held_node(face)))
            continue;
          const double g    = point.paired ? pairing.gap(point, state) : 0.;
          const bool   slip = point.paired && (friction_node_pair[face.pair] ||
                                             held_node_pair[face.pair]);
          const auto   v =
            slip ? pairing.slip(point, state, start) : Tensor<1, dim - 1>();
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              const double w = point.weight * point.psi_lambda[l];
              add_entry(G, face.lambda_dofs[l], w * g);
              add_entry(D, face.lambda_dofs[l], w);
              if (point.paired)
                add_entry(P, face.lambda_dofs[l], point.weight * point.psi[l]);
              if (slip)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  add_entry(W[k], face.lambda_dofs[l], w * v[k]);
              if (any_pin && point.paired &&
                  face.pin[l] != numbers::invalid_dof_index)
                {
                  const unsigned int c =
                    std::find(face.node_dofs.begin() + l * dim,
                              face.node_dofs.begin() + (l + 1) * dim,
                              face.pin[l]) -
                    (face.node_dofs.begin() + l * dim);
                  const double wd = point.weight * point.psi[l];
                  const auto  &a  = surfaces.pins().at(face.pin[l]).a;
                  double       Ta = 0; // (T a) . e_c
                  for (unsigned int k = 0; k < dim - 1; ++k)
                    Ta += a[k] * point.tangents[k][c];
                  add_entry(A, face.lambda_dofs[l], wd * point.normal[c]);
                  add_entry(B, face.lambda_dofs[l], wd * Ta);
                }
            }
        }
      NodeSums sums{surfaces.ghosted_multipliers(),
                    surfaces.ghosted_multipliers(),
                    surfaces.ghosted_multipliers(),
                    {},
                    {},
                    {}};
      G.compress(VectorOperation::add);
      D.compress(VectorOperation::add);
      P.compress(VectorOperation::add);
      sums.G = G;
      sums.D = D;
      sums.P = P;
      for (unsigned int k = 0; k < W.size(); ++k)
        {
          W[k].compress(VectorOperation::add);
          sums.W.push_back(surfaces.ghosted_multipliers());
          sums.W[k] = W[k];
        }
      if (any_pin)
        {
          A.compress(VectorOperation::add);
          B.compress(VectorOperation::add);
          sums.A = surfaces.ghosted_multipliers();
          sums.B = surfaces.ghosted_multipliers();
          sums.A = A;
          sums.B = B;
        }
      return sums;
    }


    template <int dim>
    unsigned int
    NodeStatuses<dim>::decide(const TrilinosWrappers::MPI::Vector &state,
                              const TrilinosWrappers::MPI::Vector &start,
                              const bool                           new_iterate,
                              ActiveSetHistory<dim>               &history,
                              ContactStatistics                   &stats)
    {
      const NodeSums                    sums    = gather_sums(state, start);
      unsigned int                      changed = 0;
      std::set<types::global_dof_index> extrapolated; // decided below
      for (const auto &[x_dof, info] : surfaces.nodes())
        if (!info.closure.empty())
          extrapolated.insert(info.lambda);
      for (const auto &face : surfaces.slave_faces())
        if (node_status_pair[face.pair])
          for (const auto dof : face.lambda_dofs)
            {
              if (extrapolated.count(dof) > 0)
                continue;
              const bool active =
                sums.P[dof] > 0 &&
                node_in_contact(state[dof],
                                sums.G[dof],
                                sums.D[dof],
                                coefficients.normal(face.pair)) &&
                !history.node_released(dof);
              const auto it = node_active.find(dof);
              if (it != node_active.end() && it->second == active)
                continue;
              // Counted once, by the owner (a node is on several faces).
              if (surfaces.owned_multipliers().is_element(dof) &&
                  (it != node_active.end() || active))
                ++changed;
              node_active[dof] = active;
            }
      // A node whose multiplier is extrapolated from its two neighbours (on
      // the axis of quadratic axisymmetric faces: its weight D is zero, or
      // round-off, so that lambda - rho_n G / D above was a sign of
      // round-off and differed between unit systems) takes the status of
      // the nearer of them.
      for (const auto &[x_dof, info] : surfaces.nodes())
        if (!info.closure.empty())
          {
            const auto it_from = node_active.find(
              surfaces.nodes().at(info.closure.front().first).lambda);
            if (it_from == node_active.end())
              continue; // not a pair with statuses per node
            const bool active = it_from->second;
            const auto it     = node_active.find(info.lambda);
            if (it != node_active.end() && it->second == active)
              continue;
            if (surfaces.owned_multipliers().is_element(info.lambda) &&
                (it != node_active.end() || active))
              ++changed;
            node_active[info.lambda] = active;
          }
      if (any_friction_node || any_held_node)
        changed += decide_friction(state, sums, new_iterate, history, stats);
      return changed;
    }


    template <int dim>
    unsigned int
    NodeStatuses<dim>::decide_friction(
      const TrilinosWrappers::MPI::Vector &state,
      const NodeSums                      &sums,
      const bool                           new_iterate,
      ActiveSetHistory<dim>               &history,
      ContactStatistics                   &stats)
    {
      // Friction status per node (theory.md, "Friction status per node"):
      // active if in contact with a threshold above zero (doc/theory.md
      // 3.3); H_l = Lambda_l + rho_t W_l / D_l; stick iff |H_l| <= 1 (the
      // round-off tie as in the point law). Each node once (it is on
      // several faces), then its anti-cycling. The held nodes of pairs
      // with statuses per point: in contact by their weighted gap, as a
      // node-status node would be (theory.md F8).
      unsigned int                      changed = 0;
      std::set<types::global_dof_index> seen;
      for (unsigned int f = 0; f < surfaces.slave_faces().size(); ++f)
        {
          const auto &face = surfaces.slave_faces()[f];
          const bool  held = held_node_pair[face.pair];
          if (!friction_node_pair[face.pair] && !held)
            continue;
          const auto law = coefficients.law(face.pair);
          for (unsigned int l = 0; l < face.lambda_dofs.size(); ++l)
            {
              const auto dof = face.lambda_dofs[l];
              if ((held && face.held[l].norm() == 0) ||
                  !seen.insert(dof).second)
                continue;
              const bool in_contact =
                held ? sums.P[dof] > 0 &&
                         node_in_contact(state[dof],
                                         sums.G[dof],
                                         sums.D[dof],
                                         coefficients.normal(face.pair)) :
                       node_active.at(dof);
              NodeFriction<dim> nf;
              nf.active = in_contact && !face.excluded_friction[l] &&
                          std::abs(state[dof]) > law.zero_threshold &&
                          sums.D[dof] > 0;
              if (nf.active)
                {
                  for (unsigned int k = 0; k < dim - 1; ++k)
                    nf.H[k] = state[face.friction_dofs[l * (dim - 1) + k]] +
                              law.rho_t * sums.W[k][dof] / sums.D[dof];
                  if (face.pin[l] != numbers::invalid_dof_index)
                    decide_pinned(face, l, state, law.mu, sums, nf);
                  else
                    nf.stick = nf.H.norm() <= 1. + stick_tie;
                }
              const bool  owned = surfaces.owned_multipliers().is_element(dof);
              const auto *previous = find_friction(dof);
              const auto  used     = history.node_anti_cycling(
                dof, nf, previous, new_iterate, owned, stats);
              if (owned &&
                  ActiveSetHistory<dim>::friction_status_differs(previous,
                                                                 used))
                ++changed;
              node_friction[dof] = used;
            }
        }
      return changed;
    }


    // A pinned node (theory.md F8, pins): Lambda*, the Lambda along its
    // held tangent a for which its pin carries nothing, from the pinned
    // DoF's balance R_d = 0 with the bulk's force r_d = F_int - F_ext there
    // and the node's contact force -lambda A - mu lambda B (a . Lambda)
    // (the nodal rule: the node's own multipliers; exact at convergence,
    // where the gap is closed): Lambda* = (r_d - lambda A) / (mu lambda B).
    // It takes the place of a . Lambda in H: the node sticks while friction
    // can carry that (|H| <= 1). Otherwise Coulomb's law decides along the
    // free tangent b alone, the only way the node can move (3D): it slides
    // along b if |b . H| > 1, and its friction then opposes that slip,
    // H = (b . H) b; else b sticks and its friction is saturated along a
    // (NodeFriction). With a . Lambda itself in H a saturated node sits on
    // |H| = 1 and flips.
    template <int dim>
    void
    NodeStatuses<dim>::decide_pinned(const SlaveFace<dim>                &face,
                                     const unsigned int                   l,
                                     const TrilinosWrappers::MPI::Vector &state,
                                     const double                         mu,
                                     const NodeSums                      &sums,
                                     NodeFriction<dim> &nf) const
    {
      const auto  &pin    = surfaces.pins().at(face.pin[l]);
      const double lambda = state[pin.lambda];
      const double B      = sums.B[pin.lambda];
      const double r_d    = pin_loads.at(face.pin[l]);
      if (std::abs(B) > 1e-12 * sums.D[pin.lambda])
        {
          const double demand =
            (r_d - lambda * sums.A[pin.lambda]) / (mu * lambda * B);
          double aL = 0;
          for (unsigned int k = 0; k < dim - 1; ++k)
            aL += pin.a[k] * state[face.friction_dofs[l * (dim - 1) + k]];
          for (unsigned int k = 0; k < dim - 1; ++k)
            nf.H[k] += pin.a[k] * (demand - aL);
        }
      nf.stick = nf.H.norm() <= 1. + stick_tie;
      if (nf.stick)
        return;
      if (dim == 3)
        {
          const auto   b  = free_tangent<dim>(pin.a);
          const double bH = b * nf.H;
          if (std::abs(bH) > 1. + stick_tie)
            {
              nf.H = bH * b;
              return;
            }
        }
      nf.saturated = true;
    }


    template class NodeStatuses<2>;
    template class NodeStatuses<3>;
  } // namespace Contact
} // namespace Signorini
