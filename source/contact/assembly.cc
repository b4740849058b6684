// Assembly of the contact residual and Jacobian: point state, contact law,
// local rows.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/contact/distributed_vectors.h>
#include <signorini/contact/segmentation.h>
#include <signorini/postprocess/output_files.h>

#include "helpers.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <set>

namespace Signorini
{
  namespace Contact
  {
    using internal::add_entry;
    using internal::faces_meeting;
    using internal::offset_of;
    using internal::pair_name;
    using internal::writable_vector;


    template <int dim>
    ContactStatistics
    ContactProblem<dim>::assemble(const TrilinosWrappers::MPI::Vector &state,
                                  const TrilinosWrappers::MPI::Vector &start,
                                  const AffineConstraints<double> &constraints,
                                  TrilinosWrappers::SparseMatrix  *matrix,
                                  TrilinosWrappers::MPI::Vector   &rhs,
                                  TrilinosWrappers::MPI::Vector &contact_force,
                                  const bool                     new_iterate)
    {
      ContactStatistics  stats;
      const unsigned int freeze_after = parameters.contact.freeze_after_cycles;
      // Normal status per node (decided before the point loop: a node's
      // status needs the points of all its faces).
      update_projections(state);
      if (any_node_status)
        {
          stats.n_changed +=
            decide_node_statuses(state, start, new_iterate, stats);
          // The statuses of the next solve (release extrapolation).
          if (matrix)
            node_active_solved = node_active;
        }
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs;
      FullMatrix<double>                   K, K_group;
      Vector<double>                       F, F_group;
      std::vector<types::global_dof_index> group_dofs;
      int                                  group_face = -1, group_master = -1;
      // Per-point work arrays, sized per point but allocated once.
      std::vector<double>             N_e, Nd;
      std::vector<unsigned int>       comp;
      std::vector<NodeStatusRow<dim>> node_rows;
      struct NodeData
      {
        const NodeFriction *status;
        double              lambda;
        Tensor<1, dim - 1>  Lambda;
      };
      std::vector<NodeData>   node_data; // friction status per node
      std::vector<Point<dim>> x_face;
      const auto              flush = [&]() {
        if (group_dofs.empty())
          return;
        if (matrix)
          constraints.distribute_local_to_global(
            K_group, F_group, group_dofs, *matrix, rhs);
        else
          constraints.distribute_local_to_global(F_group, group_dofs, rhs);
        group_dofs.clear();
      };

      for (auto &point : points)
        {
          const auto &face = slave_faces[point.face];
          if (point.q == 0)
            face.cell->get_dof_indices(cell_dofs);
          const unsigned int p    = face.pair;
          const auto         law  = law_parameters(p);
          const bool         fric = law.mu > 0;

          // Point state (formulation.md 2).
          const unsigned int         n_e = face.u_local.size();
          const unsigned int         n_l = face.node_local.size();
          const std::vector<double> &psi = point.psi;
          // Multiplier basis: psi, or the dual psi~ (node-status pairs).
          const std::vector<double> &psi_c = point.psi_lambda;
          N_e.resize(n_e);
          Point<dim>     x_e = point.x_ref;
          Tensor<1, dim> du_e;
          for (unsigned int a = 0; a < n_e; ++a)
            {
              const unsigned int i = face.u_local[a];
              const unsigned int c = face.u_comp[a];
              N_e[a]               = psi[face.u_node[a]];
              x_e[c] += N_e[a] * state[cell_dofs[i]];
              du_e[c] += N_e[a] * (state[cell_dofs[i]] - start[cell_dofs[i]]);
            }
          PointState<dim> s;
          s.lambda            = 0;
          double lambda_shown = 0; // with psi (output)
          for (unsigned int l = 0; l < n_l; ++l)
            {
              s.lambda += psi_c[l] * state[face.lambda_dofs[l]];
              lambda_shown += psi[l] * state[face.lambda_dofs[l]];
              if (fric)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  s.Lambda[k] +=
                    psi[l] * state[face.friction_dofs[l * (dim - 1) + k]];
            }
          // Newton on the geometry of a rigid obstacle: projection, normal
          // and tangents of the current iterate, and dn/du for the
          // Jacobian (added after the law below).
          const bool geometry_newton = newton_geometry_pair[p] && point.paired;
          Tensor<2, dim> dn_du, dslip_du;
          Tensor<1, dim> surface_slip;
          if (geometry_newton)
            {
              const auto proj = obstacles[p]->project(x_e);
              point.normal    = proj.normal;
              point.x_m_rigid = proj.x_m;
              point.tangents =
                tangent_basis<dim>(point.normal, point.tangent_axis);
              dn_du    = proj.dnormal;
              dslip_du = proj.dclosest;
              // Slip on the obstacle's surface: the closest point now
              // against that of the step-start position carried with the
              // obstacle (a normal approach is no slip, whatever n does).
              surface_slip =
                proj.x_m -
                obstacles[p]
                  ->project(obstacles[p]->get_motion().apply(
                    motion_at_start[p].inverse(x_e - du_e)))
                  .x_m;
            }
          s.normal          = point.normal;
          s.tangents        = point.tangents;
          s.lambda_f_frozen = point.lambda_frozen;

          const MasterFace *master =
            point.master_face >= 0 ? &master_faces[point.master_face] : nullptr;
          const unsigned int n_m  = master ? master->dofs.size() : 0;
          Point<dim>         x_m  = point.x_m_rigid;
          Tensor<1, dim>     du_m = point.rigid_increment;
          if (master)
            {
              x_m  = Point<dim>();
              du_m = Tensor<1, dim>();
              for (unsigned int k = 0; k < master->X.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const auto d = master->dofs[k * dim + c];
                    x_m[c] += point.N_m[k] * (master->X[k][c] + state[d]);
                    du_m[c] += point.N_m[k] * (state[d] - start[d]);
                  }
            }
          if (point.paired)
            s.gap =
              (x_e - x_m) * s.normal + parameters.contact.pairs[p].gap_offset;
          else
            s.gap = -1e30; // no master in reach: free
          s.slip = geometry_newton ? surface_slip : du_e - du_m;
          s.slip -= (s.slip * s.normal) * s.normal;

          s.freeze_contact        = point.freeze_contact;
          s.frozen_slip_direction = point.frozen_slip_direction;
          s.freeze_stick          = point.freeze_stick;
          s.release               = point.release;
          const bool by_node      = node_status_pair[p];
          // A point whose multiplier nodes are all excluded from contact
          // (friction) by a Dirichlet condition (formulation.md 8) carries
          // no contact (friction) force: its multipliers are held at zero,
          // and the plain law would act there as a penalty of stiffness
          // rho_n (rho_t) on the master. The nodal rule's points are nodes.
          LawParameters point_law = law;
          if (!by_node)
            {
              bool contact_out = true, friction_out = true;
              for (unsigned int l = 0; l < n_l; ++l)
                if (psi[l] > 1e-12)
                  {
                    contact_out &= face.excluded_contact[l];
                    friction_out &= face.excluded_friction[l];
                  }
              s.release |= contact_out;
              if (friction_out)
                point_law.mu = 0;
            }
          auto r = by_node ? node_status_response(point, s) :
                             evaluate_contact_law(s, point_law);
          // Friction status per node: the friction force of the multipliers,
          // -mu lambda_l T Lambda_l of each node with active friction
          // interpolated like lambda (theory.md, "Friction status per
          // node").
          const bool         node_friction_rows = by_node && fric;
          Tensor<1, dim - 1> slip_t; // T^T v (s.slip is tangential)
          for (unsigned int k = 0; k < dim - 1; ++k)
            slip_t[k] = point.paired ? s.slip * s.tangents[k] : 0.;
          // Status, lambda_l and Lambda_l of the face's nodes, looked up
          // once per point (force, rows and derivatives below).
          node_data.resize(node_friction_rows ? n_l : 0);
          for (unsigned int l = 0; l < node_data.size(); ++l)
            {
              auto &d  = node_data[l];
              d.status = &node_friction.at(face.lambda_dofs[l]);
              d.lambda = state[face.lambda_dofs[l]];
              for (unsigned int k = 0; k < dim - 1; ++k)
                d.Lambda[k] = state[face.friction_dofs[l * (dim - 1) + k]];
            }
          if (point.paired)
            for (unsigned int l = 0; l < node_data.size(); ++l)
              if (node_data[l].status->active)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  r.force += -law.mu * psi_c[l] * node_data[l].lambda *
                             node_data[l].Lambda[k] * s.tangents[k];
          if (geometry_newton)
            add_geometric_derivatives(
              r, s, surface_slip, dslip_du, dn_du, point.tangent_axis);

          // Statistics and the values for output.
          ++stats.n_points;
          stats.n_unpaired += !point.paired;
          if (r.in_contact)
            {
              ++stats.n_contact;
              if (fric && r.friction_active)
                (r.status == PointStatus::stick ? stats.n_stick :
                                                  stats.n_slip)++;
            }
          // The status label of a law response ('slip' also for a closed
          // point without friction).
          const auto label = [fric](const PointResponse<dim> &response) {
            return !response.in_contact ?
                     PointStatus::free :
                     (fric && response.friction_active ? response.status :
                                                         PointStatus::slip);
          };
          const PointStatus status = label(r);
          // A point that closed with a zero threshold (friction inactive,
          // formulation.md 3.3) and one with friction on are different
          // branches of the law even when both are labelled 'slip'.
          // A slip direction that turned by more than 90 degrees (in 2D:
          // reversed) is another branch of the slip law too.
          const bool reversed = status == PointStatus::slip &&
                                point.status == PointStatus::slip &&
                                r.slip_direction * point.slip_direction < 0;
          // (Node-status points: the node changes are counted instead.)
          const bool changed =
            !by_node &&
            ((status != point.status) ||
             (r.friction_active != point.friction_active) || reversed);
          stats.n_reversed += reversed;
          stats.n_changed += changed;

          // Anti-cycling (formulation.md 8), see start_newton_solve().
          const bool frozen = point.freeze_contact && !by_node;
          if (frozen)
            {
              // What the plain law says at this iterate.
              PointState<dim> plain       = s;
              plain.freeze_contact        = false;
              plain.frozen_slip_direction = Tensor<1, dim>();
              plain.freeze_stick          = false;
              const auto        rp = evaluate_contact_law(plain, point_law);
              const PointStatus plain_status = label(rp);
              ++stats.n_frozen;
              const bool violated = plain_status != status ||
                                    (status == PointStatus::slip &&
                                     rp.slip_direction * r.slip_direction < 0);
              point.plain_status    = plain_status;
              point.plain_direction = rp.slip_direction;
              point.plain_violated  = violated;
              if (point.geometric_freeze)
                {
                  ++stats.n_geometric_frozen;
                  stats.n_geometric_violated += violated;
                }
              else
                stats.n_violated += violated;
            }
          if (new_iterate && !frozen && !by_node)
            {
              // Back to the status of two iterates before (a 2-cycle), or
              // changed more than 2 N times (longer cycles).
              point.changes += changed;
              const bool back =
                changed && iterates_recorded >= 2 &&
                ((status == point.status_before &&
                  (status != PointStatus::slip ||
                   r.slip_direction * point.direction_before >= 0)) ||
                 (freeze_after > 0 && point.changes > 2 * freeze_after));
              if (back)
                {
                  ++point.cycles;
                  ++stats.n_cycling;
                }
              if (back && freeze_after > 0 && point.cycles >= freeze_after &&
                  !point.was_frozen)
                {
                  // Freeze from the next evaluation on: in contact if the
                  // cycle went through 'free', slipping in the last slip
                  // direction if it went through stick or reversed.
                  point.was_frozen = true;
                  ++stats.n_newly_frozen;
                  freeze_for_cycle(point,
                                   status,
                                   r.slip_direction,
                                   point.status,
                                   point.slip_direction,
                                   fric);
                }
            }
          if (new_iterate)
            {
              point.status_before    = point.status;
              point.direction_before = point.slip_direction;
            }
          point.status          = status;
          point.friction_active = r.friction_active;
          point.slip_direction  = r.slip_direction;
          point.gap             = s.gap;
          point.lambda          = lambda_shown;
          point.Lambda          = s.Lambda;
          point.force           = r.force;
          for (unsigned int k = 0; k < dim - 1; ++k)
            point.slip[k] = s.slip * s.tangents[k];

          // Local dofs: e | m | lambda | Lambda.
          const unsigned int n_f = fric ? n_l * (dim - 1) : 0;
          const unsigned int o_c = n_e + n_m, o_f = o_c + n_l;
          const unsigned int n = o_f + n_f;
          point_dofs(point, cell_dofs, dofs);
          AssertDimension(dofs.size(), n);

          // Shape value and component of each displacement column, with the
          // sign of d = u^e - u^m.
          Nd.resize(n_e + n_m);
          comp.resize(n_e + n_m);
          for (unsigned int a = 0; a < n_e; ++a)
            {
              Nd[a]   = N_e[a];
              comp[a] = face.u_comp[a];
            }
          for (unsigned int b = 0; b < n_m; ++b)
            {
              Nd[n_e + b]   = -point.N_m[b / dim];
              comp[n_e + b] = b % dim;
            }

          const double w  = point.weight;
          const double sc = rho_n[p]; // row scaling of lambda rows
          const double sf = rho_t[p]; // row scaling of Lambda rows
          F.reinit(n);
          for (unsigned int a = 0; a < n_e + n_m; ++a)
            F[a] = -w * Nd[a] * r.force[comp[a]];
          // The Signorini row of each node: the point's law, or the
          // node's status (node_status_row).
          auto &rows = node_rows;
          rows.resize(n_l);
          for (unsigned int l = 0; l < n_l; ++l)
            rows[l] = by_node ?
                        node_status_row(node_active.at(face.lambda_dofs[l]) &&
                                          point.paired,
                                        point.paired ? s.gap : 0.,
                                        state[face.lambda_dofs[l]],
                                        s.normal,
                                        rho_n[p]) :
                        NodeStatusRow<dim>{r.r_c, r.drc_dd, 0.};
          for (unsigned int l = 0; l < n_l; ++l)
            {
              F[o_c + l] = -sc * w * psi_c[l] * rows[l].r_c;
              for (unsigned int k = 0; k < (fric ? dim - 1 : 0); ++k)
                F[o_f + l * (dim - 1) + k] = -sf * w * psi[l] * r.r_f[k];
            }
          // Friction rows of a node-status pair, per node: free (or zero
          // threshold) s Lambda_l; stick -mu lambda_l W_l (its weighted
          // slip closed); slip (mu lambda_l / rho_t) D_l (Lambda_l - q_l),
          // q_l = H_l / |H_l|; each point adds its share w psi_l.
          for (unsigned int l = 0; l < node_data.size(); ++l)
            {
              const auto  &nf  = *node_data[l].status;
              const double lam = node_data[l].lambda;
              const auto  &L   = node_data[l].Lambda;
              for (unsigned int k = 0; k < dim - 1; ++k)
                {
                  const double r_f =
                    !nf.active ?
                      law.free_friction_scale * L[k] :
                    nf.stick ?
                      -law.mu * lam * slip_t[k] :
                      law.mu * lam / law.rho_t * (L[k] - nf.H[k] / nf.H.norm());
                  F[o_f + l * (dim - 1) + k] += -sf * w * psi_c[l] * r_f;
                }
            }
          for (unsigned int a = 0; a < n_e + n_m; ++a)
            add_entry(contact_force, dofs[a], -F[a]);

          if (matrix)
            {
              K.reinit(n, n);
              for (unsigned int a = 0; a < n_e + n_m; ++a)
                {
                  for (unsigned int b = 0; b < n_e + n_m; ++b)
                    K(a, b) = w * Nd[a] * Nd[b] * r.dforce_dd[comp[a]][comp[b]];
                  for (unsigned int l = 0; l < n_l; ++l)
                    {
                      K(a, o_c + l) =
                        w * Nd[a] * psi_c[l] * r.dforce_dlambda[comp[a]];
                      K(o_c + l, a) =
                        sc * w * psi_c[l] * Nd[a] * rows[l].drc_dd[comp[a]];
                      for (unsigned int k = 0; k < (fric ? dim - 1 : 0); ++k)
                        {
                          K(a, o_f + l * (dim - 1) + k) =
                            w * Nd[a] * psi[l] * r.dforce_dLambda[k][comp[a]];
                          K(o_f + l * (dim - 1) + k, a) =
                            sf * w * psi[l] * Nd[a] * r.drf_dd[k][comp[a]];
                        }
                    }
                }
              // Newton on the pairing of a meshed master: the force
              // f = (f . n) n turns with n, and the master rows follow
              // N_m(xi_m); the gap needs nothing more (at the closest
              // point, dg = n . (du^e - N_m du^m) exactly).
              if (point.reprojected)
                {
                  Point<dim> inside;
                  master_face_position(point.master_face,
                                       state,
                                       x_face,
                                       inside);
                  const auto   D   = face_projection_derivatives<dim>(x_e,
                                                                  x_face,
                                                                  point.xi_m,
                                                                  s.normal);
                  const double phi = r.force * s.normal;
                  for (unsigned int j = 0; j < n_e + n_m; ++j)
                    {
                      // Column j: slave DoF j (moves x_e by N_e e_c) or
                      // component c of master support point k.
                      const unsigned int c = comp[j];
                      Tensor<1, dim>     dn;
                      Tensor<1, dim - 1> dxi;
                      const unsigned int k = j < n_e ? 0 : (j - n_e) / dim;
                      for (unsigned int i = 0; i < dim; ++i)
                        dn[i] =
                          j < n_e ? N_e[j] * D.dn_dp[i][c] : D.dn_dX[k][i][c];
                      for (unsigned int a = 0; a < dim - 1; ++a)
                        dxi[a] =
                          j < n_e ? N_e[j] * D.dxi_dp[a][c] : D.dxi_dX[k][a][c];
                      for (unsigned int a = 0; a < n_e + n_m; ++a)
                        {
                          const double dNd =
                            a < n_e ? 0. : -(D.dN[(a - n_e) / dim] * dxi);
                          K(a, j) += w * (dNd * r.force[comp[a]] +
                                          Nd[a] * phi * dn[comp[a]]);
                        }
                    }
                }
              for (unsigned int l = 0; l < n_l; ++l)
                for (unsigned int m = 0; m < n_l; ++m)
                  {
                    K(o_c + l, o_c + m) =
                      by_node ?
                        (l == m ? sc * w * psi_c[l] * rows[l].drc_dlambda_own :
                                  0.) :
                        sc * w * psi[l] * psi[m] * r.drc_dlambda;
                    for (unsigned int k = 0; k < (fric ? dim - 1 : 0); ++k)
                      {
                        K(o_f + l * (dim - 1) + k, o_c + m) =
                          sf * w * psi[l] * psi[m] * r.drf_dlambda[k];
                        for (unsigned int kk = 0; kk < dim - 1; ++kk)
                          K(o_f + l * (dim - 1) + k, o_f + m * (dim - 1) + kk) =
                            sf * w * psi[l] * psi[m] * r.drf_dLambda[k][kk];
                      }
                  }
            }

          // Their derivatives (the status of each node fixed).
          if (matrix)
            for (unsigned int l = 0; l < node_data.size(); ++l)
              {
                const auto        &nf  = *node_data[l].status;
                const double       lam = node_data[l].lambda;
                const auto        &L   = node_data[l].Lambda;
                const double       wl  = sf * w * psi_c[l];
                const unsigned int of  = o_f + l * (dim - 1);
                if (!nf.active)
                  {
                    for (unsigned int k = 0; k < dim - 1; ++k)
                      K(of + k, of + k) += wl * law.free_friction_scale;
                    continue;
                  }
                if (point.paired)
                  {
                    // Displacement rows: d/dlambda_l, d/dLambda_l.
                    Tensor<1, dim> TL;
                    for (unsigned int k = 0; k < dim - 1; ++k)
                      TL += L[k] * s.tangents[k];
                    for (unsigned int a = 0; a < n_e + n_m; ++a)
                      {
                        K(a, o_c + l) +=
                          w * Nd[a] * (-law.mu * psi_c[l] * TL[comp[a]]);
                        for (unsigned int k = 0; k < dim - 1; ++k)
                          K(a, of + k) +=
                            w * Nd[a] *
                            (-law.mu * psi_c[l] * lam * s.tangents[k][comp[a]]);
                      }
                  }
                if (nf.stick)
                  {
                    if (point.paired)
                      for (unsigned int k = 0; k < dim - 1; ++k)
                        {
                          for (unsigned int a = 0; a < n_e + n_m; ++a)
                            K(of + k, a) += wl * (-law.mu * lam) *
                                            s.tangents[k][comp[a]] * Nd[a];
                          K(of + k, o_c + l) += wl * (-law.mu * slip_t[k]);
                        }
                    continue;
                  }
                // Slip: K_B = (I - q q) / |H|, dH/dLambda_l = I,
                // dH/du = rho_t / D_l dW/du.
                // Frozen in slip: q fixed, K_B = 0.
                const double       nH = nf.H.norm();
                Tensor<2, dim - 1> KB;
                if (!nf.frozen)
                  for (unsigned int k = 0; k < dim - 1; ++k)
                    for (unsigned int kk = 0; kk < dim - 1; ++kk)
                      KB[k][kk] =
                        ((k == kk) - nf.H[k] * nf.H[kk] / (nH * nH)) / nH;
                for (unsigned int k = 0; k < dim - 1; ++k)
                  {
                    for (unsigned int kk = 0; kk < dim - 1; ++kk)
                      K(of + k, of + kk) +=
                        wl * law.mu * lam / law.rho_t * ((k == kk) - KB[k][kk]);
                    K(of + k, o_c + l) +=
                      wl * law.mu / law.rho_t * (L[k] - nf.H[k] / nH);
                    if (point.paired)
                      for (unsigned int a = 0; a < n_e + n_m; ++a)
                        {
                          double KBT = 0;
                          for (unsigned int kk = 0; kk < dim - 1; ++kk)
                            KBT += KB[k][kk] * s.tangents[kk][comp[a]];
                          K(of + k, a) += wl * (-law.mu * lam) * KBT * Nd[a];
                        }
                  }
              }

          // Points of one slave face paired with one master face share
          // their unknowns: sum them and distribute once per group (a
          // mortar face has tens of points per master face).
          if (static_cast<int>(point.face) != group_face ||
              point.master_face != group_master)
            {
              flush();
              group_face   = point.face;
              group_master = point.master_face;
              group_dofs   = dofs;
              F_group.reinit(n);
              if (matrix)
                K_group.reinit(n, n);
            }
          F_group += F;
          if (matrix)
            K_group.add(1., K);
        }
      flush();

      stats.n_points   = Utilities::MPI::sum(stats.n_points, comm);
      stats.n_unpaired = Utilities::MPI::sum(stats.n_unpaired, comm);
      stats.n_contact  = Utilities::MPI::sum(stats.n_contact, comm);
      stats.n_stick    = Utilities::MPI::sum(stats.n_stick, comm);
      stats.n_slip     = Utilities::MPI::sum(stats.n_slip, comm);
      stats.n_changed  = Utilities::MPI::sum(stats.n_changed, comm);
      stats.n_reversed = Utilities::MPI::sum(stats.n_reversed, comm);
      if (new_iterate)
        ++iterates_recorded;
      stats.n_cycling      = Utilities::MPI::sum(stats.n_cycling, comm);
      stats.n_frozen       = Utilities::MPI::sum(stats.n_frozen, comm);
      stats.n_newly_frozen = Utilities::MPI::sum(stats.n_newly_frozen, comm);
      stats.n_violated     = Utilities::MPI::sum(stats.n_violated, comm);
      stats.n_geometric_frozen =
        Utilities::MPI::sum(stats.n_geometric_frozen, comm);
      stats.n_geometric_violated =
        Utilities::MPI::sum(stats.n_geometric_violated, comm);
      return stats;
    }


    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace Contact
} // namespace Signorini
