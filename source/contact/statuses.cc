// Contact statuses per multiplier node and the initial multipliers.
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


    template <int dim>
    void
    ContactProblem<dim>::set_initial_multipliers(
      const TrilinosWrappers::MPI::Vector &state,
      TrilinosWrappers::MPI::Vector       &state_owned) const
    {
      const auto status = parameters.contact.initial_status;
      // lambda_aug = lambda - rho_n g = -/+ delta at every point, as the
      // psi-weighted average over the node's points. 'penetrating': the
      // points that touch (g >= 0 up to the round-off of mesh coordinates,
      // 1e-8 of the face size) start closed, as where they penetrate; the
      // others keep lambda = 0 (lambda_aug = -rho_n g: open).
      const double touch_tolerance = 1e-8;
      auto         num             = surfaces.writable_multipliers();
      auto         den             = surfaces.writable_multipliers();
      for (const auto &point : pairing.points())
        {
          const auto        &face = surfaces.slave_faces()[point.face];
          const unsigned int p    = face.pair;
          const double       g    = point_gap(point, state);
          // delta: half the zero friction threshold of the law (see
          // law_parameters), so that lambda_aug = -/+ delta sets the normal
          // status strictly while the friction of a point closed this way
          // starts inactive, as for a point that has just closed
          // (formulation.md 3.3). A larger delta would be a tiny nonzero
          // threshold: Lambda = F_t / (mu delta) of order 1e8 at the first
          // iterate.
          const double delta = 0.5 * coefficients.law(p).zero_threshold;
          if (status != InitialStatus::open && !point.paired)
            continue;
          double target;
          if (status == InitialStatus::closed)
            target = std::min(0.,
                              coefficients.normal(p) *
                                std::max(g, -1e300 / coefficients.normal(p))) -
                     delta;
          else if (status == InitialStatus::penetrating)
            target =
              g >= -touch_tolerance * surfaces.pair_scales().face_size[p] ?
                -delta :
                0.;
          else
            target = std::max(0., coefficients.normal(p) * g) + delta;
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              const double w = point.weight * point.psi[l];
              add_entry(num, face.lambda_dofs[l], w * target);
              add_entry(den, face.lambda_dofs[l], w);
            }
        }
      num.compress(VectorOperation::add);
      den.compress(VectorOperation::add);
      for (const auto i : surfaces.owned_multipliers())
        if (i < surfaces.n_u() + surfaces.n_lambda() && den[i] != 0)
          state_owned[i] = num[i] / den[i];
      state_owned.compress(VectorOperation::insert);
    }


    template <int dim>
    PointResponse<dim>
    ContactProblem<dim>::node_status_response(const ContactPoint    &point,
                                              const PointState<dim> &s) const
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
          // Labelled with the friction status of the same node; the
          // friction force and rows are the assembly's (per node).
          const auto &nf    = node_friction.at(face.lambda_dofs[nearest]);
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
    unsigned int
    ContactProblem<dim>::decide_node_statuses(
      const TrilinosWrappers::MPI::Vector &state,
      const TrilinosWrappers::MPI::Vector &start,
      const bool                           new_iterate,
      ContactStatistics                   &stats)
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
      if (any_friction_node)
        for (unsigned int k = 0; k < dim - 1; ++k)
          W.push_back(surfaces.writable_multipliers());
      for (const auto &point : pairing.points())
        {
          const auto &face = surfaces.slave_faces()[point.face];
          if (!node_status_pair[face.pair])
            continue;
          const double g    = point.paired ? point_gap(point, state) : 0.;
          const bool   slip = point.paired && friction_node_pair[face.pair];
          const auto   v =
            slip ? point_slip(point, state, start) : Tensor<1, dim - 1>();
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
            }
        }
      G.compress(VectorOperation::add);
      D.compress(VectorOperation::add);
      P.compress(VectorOperation::add);
      TrilinosWrappers::MPI::Vector G_read = surfaces.ghosted_multipliers();
      TrilinosWrappers::MPI::Vector D_read = surfaces.ghosted_multipliers();
      TrilinosWrappers::MPI::Vector P_read = surfaces.ghosted_multipliers();
      G_read = G;
      D_read = D;
      P_read = P;
      std::vector<TrilinosWrappers::MPI::Vector> W_read(W.size());
      for (unsigned int k = 0; k < W.size(); ++k)
        {
          W[k].compress(VectorOperation::add);
          W_read[k] = surfaces.ghosted_multipliers();
          W_read[k] = W[k];
        }
      unsigned int changed = 0;
      for (const auto &face : surfaces.slave_faces())
        if (node_status_pair[face.pair])
          for (const auto dof : face.lambda_dofs)
            {
              const bool active =
                P_read[dof] > 0 &&
                node_in_contact(state[dof],
                                G_read[dof],
                                D_read[dof],
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
      // Friction status per node (theory.md, "Friction status per node"):
      // active if in contact with a threshold above zero (formulation.md
      // 3.3); H_l = Lambda_l + rho_t W_l / D_l; stick iff |H_l| <= 1 (the
      // round-off tie as in the point law). Each node once (it is on
      // several faces), then its anti-cycling.
      std::set<types::global_dof_index> seen;
      if (any_friction_node)
        for (unsigned int f = 0; f < surfaces.slave_faces().size(); ++f)
          {
            const auto &face = surfaces.slave_faces()[f];
            if (!friction_node_pair[face.pair])
              continue;
            const auto law = coefficients.law(face.pair);
            for (unsigned int l = 0; l < face.lambda_dofs.size(); ++l)
              {
                const auto dof = face.lambda_dofs[l];
                if (!seen.insert(dof).second)
                  continue;
                NodeFriction nf;
                nf.active = node_active.at(dof) &&
                            std::abs(state[dof]) > law.zero_threshold &&
                            D_read[dof] > 0;
                if (nf.active)
                  {
                    for (unsigned int k = 0; k < dim - 1; ++k)
                      nf.H[k] = state[face.friction_dofs[l * (dim - 1) + k]] +
                                law.rho_t * W_read[k][dof] / D_read[dof];
                    nf.stick = nf.H.norm() <= 1. + stick_tie;
                  }
                const auto  it    = node_friction.find(dof);
                const bool owned = surfaces.owned_multipliers().is_element(dof);
                const auto *previous =
                  it == node_friction.end() ? nullptr : &it->second;
                const auto used = history.node_anti_cycling(
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


    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace Contact
} // namespace Signorini
