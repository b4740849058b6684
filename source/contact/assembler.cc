// The contact assembler: the point loop, the point state and law response
// of each point (its local rows are in local_rows.cc), and the status
// record of each evaluated point.
#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>

#include <signorini/contact/assembler.h>
#include <signorini/contact/distributed_vectors.h>

#include "helpers.h"

namespace Signorini
{
  namespace Contact
  {
    using internal::add_entry;


    template <int dim>
    Assembler<dim>::Assembler(const Parameters        &parameters,
                              const FESystem<dim>     &fe,
                              const Surfaces<dim>     &surfaces,
                              Pairing<dim>            &pairing,
                              const Coefficients      &coefficients,
                              NodeStatuses<dim>       &node_statuses,
                              ActiveSetHistory<dim>   &history,
                              const std::vector<bool> &newton_geometry_pair,
                              const MPI_Comm           comm)
        : parameters(parameters)
        , fe(fe)
        , surfaces(surfaces)
        , pairing(pairing)
        , coefficients(coefficients)
        , node_statuses(node_statuses)
        , history(history)
        , newton_geometry_pair(newton_geometry_pair)
        , comm(comm)
    {
    }


    template <int dim>
    ContactStatistics
    Assembler<dim>::assemble(const TrilinosWrappers::MPI::Vector &state,
                             const TrilinosWrappers::MPI::Vector &start,
                             const AffineConstraints<double>     &constraints,
                             TrilinosWrappers::SparseMatrix      *matrix,
                             TrilinosWrappers::MPI::Vector       &rhs,
                             TrilinosWrappers::MPI::Vector       &contact_force,
                             const bool                           new_iterate,
                             const TrilinosWrappers::MPI::Vector &weight_state)
    {
      ContactStatistics stats;
      // Normal status per node (decided before the point loop: a node's
      // status needs the points of all its faces).
      if (node_statuses.decides())
        {
          stats.n_changed +=
            node_statuses.decide(state, start, new_iterate, history, stats);
          // The statuses of the next solve (release extrapolation).
          if (matrix)
            history.set_solved_node_statuses(node_statuses.normal_statuses());
        }
      find_sticking_pins();
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs;
      FullMatrix<double>                   K, K_group;
      Vector<double>                       F, F_group;
      PointEvaluation                      e;
      // Points of one slave face paired with one master face share their
      // unknowns: they are summed and distributed once per group (a mortar
      // face has tens of points per master face).
      std::vector<types::global_dof_index> group_dofs;
      int                                  group_face = -1, group_master = -1;
      const auto                           flush = [&]() {
        if (group_dofs.empty())
          return;
        if (matrix)
          constraints.distribute_local_to_global(
            K_group, F_group, group_dofs, *matrix, rhs);
        else
          constraints.distribute_local_to_global(F_group, group_dofs, rhs);
        if (!stick_pins.empty())
          for (unsigned int a = 0; a < group_dofs.size(); ++a)
            if (stick_pins.count(group_dofs[a]) > 0)
              add_pin_rows(
                a, K_group, F_group, group_dofs, constraints, matrix, rhs);
        group_dofs.clear();
      };

      for (auto &point : pairing.points())
        {
          if (point.q == 0)
            surfaces.slave_faces()[point.face].cell->get_dof_indices(cell_dofs);
          evaluate_point(point, cell_dofs, state, start, weight_state, e);
          record_point_status(point, e, new_iterate, stats);

          local_residual(point, state, e, F);
          point_dofs(surfaces, point, cell_dofs, dofs);
          AssertDimension(dofs.size(), e.n);
          for (unsigned int a = 0; a < e.n_e + e.n_m; ++a)
            add_entry(contact_force, dofs[a], -F[a]);
          if (matrix)
            local_jacobian(point, e, K);

          if (static_cast<int>(point.face) != group_face ||
              point.master_face != group_master)
            {
              flush();
              group_face   = point.face;
              group_master = point.master_face;
              group_dofs   = dofs;
              F_group.reinit(e.n);
              if (matrix)
                K_group.reinit(e.n, e.n);
            }
          F_group += F;
          if (matrix)
            K_group.add(1., K);
        }
      flush();

      history.end_evaluation(new_iterate);
      for (unsigned int *count : {&stats.n_points,
                                  &stats.n_unpaired,
                                  &stats.n_contact,
                                  &stats.n_stick,
                                  &stats.n_slip,
                                  &stats.n_changed,
                                  &stats.n_reversed,
                                  &stats.n_cycling,
                                  &stats.n_frozen,
                                  &stats.n_newly_frozen,
                                  &stats.n_violated,
                                  &stats.n_geometric_frozen,
                                  &stats.n_geometric_violated})
        *count = Utilities::MPI::sum(*count, comm);
      return stats;
    }


    template <int dim>
    void
    Assembler<dim>::evaluate_point(
      ContactPoint                               &point,
      const std::vector<types::global_dof_index> &cell_dofs,
      const TrilinosWrappers::MPI::Vector        &state,
      const TrilinosWrappers::MPI::Vector        &start,
      const TrilinosWrappers::MPI::Vector        &weight_state,
      PointEvaluation                            &e)
    {
      const unsigned int p = surfaces.slave_faces()[point.face].pair;
      e.law                = coefficients.law(p);
      e.fric               = e.law.mu > 0;
      e.by_node            = node_statuses.by_node(p);
      point_kinematics(point, cell_dofs, state, start, weight_state, e);
      const bool pinned = law_input(point, e);
      e.r               = e.by_node ? node_statuses.response(point, e.s) :
                                      evaluate_contact_law(e.s, e.law);
      node_friction(point, pinned, state, weight_state, e);
      // The force f = (f . n) n turns with the normal (curvature); the
      // gap needs nothing more: at the closest point dg/du = n exactly.
      if (e.geometry_newton)
        e.r.dforce_dd += (e.r.force * e.s.normal) * e.dn_du;
    }


    template <int dim>
    void
    Assembler<dim>::point_kinematics(
      ContactPoint                               &point,
      const std::vector<types::global_dof_index> &cell_dofs,
      const TrilinosWrappers::MPI::Vector        &state,
      const TrilinosWrappers::MPI::Vector        &start,
      const TrilinosWrappers::MPI::Vector        &weight_state,
      PointEvaluation                            &e)
    {
      const auto        &face = surfaces.slave_faces()[point.face];
      const unsigned int p    = face.pair;
      // Point state (theory.md F2).
      e.n_e                          = face.u_local.size();
      e.n_l                          = face.node_local.size();
      const std::vector<double> &psi = point.psi;
      // Multiplier basis: psi, or the dual psi~ (node-status pairs).
      const std::vector<double> &psi_c = point.psi_lambda;
      e.N_e.resize(e.n_e);
      e.x_e  = point.x_ref;
      e.du_e = Tensor<1, dim>();
      for (unsigned int a = 0; a < e.n_e; ++a)
        {
          const unsigned int i = face.u_local[a];
          const unsigned int c = face.u_comp[a];
          e.N_e[a]             = psi[face.u_node[a]];
          e.x_e[c] += e.N_e[a] * state[cell_dofs[i]];
          e.du_e[c] += e.N_e[a] * (state[cell_dofs[i]] - start[cell_dofs[i]]);
        }
      auto &s        = e.s;
      s              = PointState<dim>();
      s.lambda       = 0;
      e.lambda_shown = 0;
      for (unsigned int l = 0; l < e.n_l; ++l)
        {
          s.lambda += psi_c[l] * state[face.lambda_dofs[l]];
          s.row_lambda += psi_c[l] * weight_state[face.lambda_dofs[l]];
          e.lambda_shown += psi[l] * state[face.lambda_dofs[l]];
          if (e.fric)
            for (unsigned int k = 0; k < dim - 1; ++k)
              s.Lambda[k] +=
                psi[l] * state[face.friction_dofs[l * (dim - 1) + k]];
        }
      // Newton on the geometry of a frictionless rigid obstacle: the
      // projection and normal of the current iterate, and dn/du for the
      // Jacobian (added after the law below).
      e.geometry_newton = newton_geometry_pair[p] && point.paired;
      if (e.geometry_newton)
        {
          const auto proj = pairing.obstacle(p)->project(e.x_e);
          point.normal    = proj.normal;
          point.x_m_rigid = proj.x_m;
          point.tangents = tangent_basis<dim>(point.normal, point.tangent_axis);
          e.dn_du        = proj.dnormal;
        }
      s.normal   = point.normal;
      s.tangents = point.tangents;

      e.master                 = point.master_face >= 0 ?
                                   &surfaces.master_faces()[point.master_face] :
                                   nullptr;
      e.n_m                    = e.master ? e.master->dofs.size() : 0;
      const int            m   = point.master_face;
      const Point<dim>     x_m = e.master ?
                                   surfaces.master_position(m, point.N_m, state) :
                                   point.x_m_rigid;
      const Tensor<1, dim> du_m =
        e.master ? surfaces.master_increment(m, point.N_m, state, start) :
                   point.rigid_increment;
      if (point.paired)
        s.gap =
          (e.x_e - x_m) * s.normal + parameters.contact.pairs[p].gap_offset;
      else
        s.gap = -1e30; // no master in reach: free
      s.slip = e.du_e - du_m;
      s.slip -= (s.slip * s.normal) * s.normal;
    }


    template <int dim>
    bool
    Assembler<dim>::law_input(const ContactPoint &point,
                              PointEvaluation    &e) const
    {
      const auto                &face = surfaces.slave_faces()[point.face];
      const std::vector<double> &psi  = point.psi;
      auto                      &s    = e.s;
      s.freeze_contact                = point.newton.freeze_contact;
      s.frozen_slip_direction         = point.newton.frozen_slip_direction;
      s.freeze_stick                  = point.newton.freeze_stick;
      s.release                       = point.newton.release;
      // A point whose multiplier nodes are all excluded from contact by a
      // Dirichlet condition (theory.md F8) carries no contact force: their
      // multipliers are held at zero, and the plain law would act there as
      // a penalty of stiffness rho_n on the master. One whose nodes all
      // hold the same tangents (Q) takes them into its law: sticking, no
      // rho_t v along them (the nodal rule's points are nodes).
      {
        bool contact_out = !e.by_node, first = true, same_held = true;
        for (unsigned int l = 0; l < e.n_l; ++l)
          if (psi[l] > 1e-12)
            {
              contact_out &= face.excluded_contact[l];
              same_held &= first || face.held[l] == s.held;
              s.held = face.held[l];
              first  = false;
            }
        s.release |= contact_out;
        if (!same_held)
          s.held = Tensor<2, dim - 1>();
      }
      // A point at a pinned node (theory.md F8, pins): its traction takes
      // Lambda as it is (the stick branch, all tangents held), whatever
      // the node's status, which the node's rows carry; so the pin's
      // balance R_d has its derivative in Lambda at every iterate.
      bool pinned = false;
      for (unsigned int l = 0; l < e.n_l; ++l)
        if (psi[l] > 1e-12 && face.pin[l] != numbers::invalid_dof_index)
          pinned = true;
      if (pinned)
        {
          // All tangents as held: the traction is mu lambda T Lambda, with
          // no rho_t v along the free one (3D) either; at convergence that
          // is the node's traction in both statuses.
          s.freeze_stick          = true;
          s.frozen_slip_direction = Tensor<1, dim>();
          s.held                  = Tensor<2, dim - 1>();
          for (unsigned int k = 0; k < dim - 1; ++k)
            s.held[k][k] = 1;
        }
      return pinned;
    }


    template <int dim>
    void
    Assembler<dim>::node_friction(
      const ContactPoint                  &point,
      const bool                           pinned,
      const TrilinosWrappers::MPI::Vector &state,
      const TrilinosWrappers::MPI::Vector &weight_state,
      PointEvaluation                     &e)
    {
      const auto                &face  = surfaces.slave_faces()[point.face];
      const unsigned int         p     = face.pair;
      const std::vector<double> &psi   = point.psi;
      const std::vector<double> &psi_c = point.psi_lambda;
      const auto                &s     = e.s;
      // Friction status per node: the friction force of the multipliers,
      // -mu lambda_l T Lambda_l of each node with active friction
      // interpolated like lambda (theory.md, "Friction status per node").
      for (unsigned int k = 0; k < dim - 1; ++k)
        e.slip_t[k] = point.paired ? s.slip * s.tangents[k] : 0.;
      // Status, lambda_l and Lambda_l of the face's nodes, looked up once
      // per point (force, rows and derivatives). Pairs with statuses per
      // point: the held nodes only, whose rows are the node's (status
      // nullptr at the others).
      const bool held_rows = e.fric && node_statuses.held_by_node(p) &&
                             NodeStatuses<dim>::has_held_node(face);
      e.node_data.resize((e.by_node && e.fric) || held_rows ? e.n_l : 0);
      for (unsigned int l = 0; l < e.node_data.size(); ++l)
        {
          auto &d      = e.node_data[l];
          d.status     = e.by_node || face.held[l].norm() > 0 ?
                           &node_statuses.friction(face.lambda_dofs[l]) :
                           nullptr;
          d.lambda     = state[face.lambda_dofs[l]];
          d.row_lambda = weight_state[face.lambda_dofs[l]];
          for (unsigned int k = 0; k < dim - 1; ++k)
            d.Lambda[k] = state[face.friction_dofs[l * (dim - 1) + k]];
        }
      // The pinned point is labelled with its node's status.
      if (pinned && e.r.friction_active)
        for (unsigned int l = 0; l < e.node_data.size(); ++l)
          if (psi[l] > 1e-12 && e.node_data[l].status &&
              e.node_data[l].status->active && !e.node_data[l].status->stick)
            {
              const auto &H      = e.node_data[l].status->H;
              e.r.status         = PointStatus::slip;
              e.r.slip_direction = Tensor<1, dim>();
              for (unsigned int k = 0; k < dim - 1; ++k)
                e.r.slip_direction += H[k] / H.norm() * s.tangents[k];
            }
      if (point.paired && e.by_node)
        for (unsigned int l = 0; l < e.node_data.size(); ++l)
          if (e.node_data[l].status->active)
            for (unsigned int k = 0; k < dim - 1; ++k)
              e.r.force += -e.law.mu * psi_c[l] * e.node_data[l].lambda *
                           e.node_data[l].Lambda[k] * s.tangents[k];
    }


    template <int dim>
    void
    Assembler<dim>::record_point_status(ContactPoint          &point,
                                        const PointEvaluation &e,
                                        const bool             new_iterate,
                                        ContactStatistics     &stats)
    {
      const auto &r    = e.r;
      const bool  fric = e.fric;
      ++stats.n_points;
      stats.n_unpaired += !point.paired;
      if (r.in_contact)
        {
          ++stats.n_contact;
          if (fric && r.friction_active)
            (r.status == PointStatus::stick ? stats.n_stick : stats.n_slip)++;
        }
      // The status label of a law response ('slip' also for a closed point
      // without friction).
      const auto label = [fric](const PointResponse<dim> &response) {
        return !response.in_contact ?
                 PointStatus::free :
                 (fric && response.friction_active ? response.status :
                                                     PointStatus::slip);
      };
      const PointStatus status = label(r);
      // A point that closed with a zero threshold (friction inactive,
      // theory.md F3.3) and one with friction on are different branches
      // of the law even when both are labelled 'slip'. A slip direction that
      // turned by more than 90 degrees (in 2D: reversed) is another branch
      // of the slip law too.
      const bool reversed = status == PointStatus::slip &&
                            point.status == PointStatus::slip &&
                            r.slip_direction * point.slip_direction < 0;
      // (Node-status points: the node changes are counted instead.)
      const bool changed =
        !e.by_node &&
        ((status != point.status) ||
         (r.friction_active != point.friction_active) || reversed);
      stats.n_reversed += reversed;
      stats.n_changed += changed;

      // Anti-cycling (theory.md F8), see start_newton_solve().
      const bool frozen = point.newton.freeze_contact && !e.by_node;
      if (frozen)
        {
          // What the plain law says at this iterate.
          PointState<dim> plain          = e.s;
          plain.freeze_contact           = false;
          plain.frozen_slip_direction    = Tensor<1, dim>();
          plain.freeze_stick             = false;
          const auto        rp           = evaluate_contact_law(plain, e.law);
          const PointStatus plain_status = label(rp);
          ++stats.n_frozen;
          const bool violated = plain_status != status ||
                                (status == PointStatus::slip &&
                                 rp.slip_direction * r.slip_direction < 0);
          point.newton.plain_status    = plain_status;
          point.newton.plain_direction = rp.slip_direction;
          point.newton.plain_violated  = violated;
          if (point.geometric.frozen)
            {
              ++stats.n_geometric_frozen;
              stats.n_geometric_violated += violated;
            }
          else
            stats.n_violated += violated;
        }
      if (new_iterate && !frozen && !e.by_node)
        history.count_point_cycle(
          point, status, r.slip_direction, changed, fric, stats);
      if (new_iterate)
        {
          point.newton.status_before    = point.status;
          point.newton.direction_before = point.slip_direction;
        }
      point.status          = status;
      point.friction_active = r.friction_active;
      point.slip_direction  = r.slip_direction;
      point.gap             = e.s.gap;
      point.lambda          = e.lambda_shown;
      point.Lambda          = e.s.Lambda;
      point.force           = r.force;
      for (unsigned int k = 0; k < dim - 1; ++k)
        point.slip[k] = e.s.slip * e.s.tangents[k];
    }


    template class Assembler<2>;
    template class Assembler<3>;
  } // namespace Contact
} // namespace Signorini
