// The contact problem's construction, set-up, coefficients, DoF couplings,
// initial multipliers and snapshots (its parts: surfaces.cc, pairing.cc,
// node_statuses.cc, active_set_history.cc, output.cc; its point loop:
// assembler.cc, local_rows.cc).
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/base/output_files.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/contact/distributed_vectors.h>
#include <signorini/contact/segmentation.h>

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
    ContactProblem<dim>::ContactProblem(
      const Parameters                                         &parameters,
      const Mapping<dim>                                       &mapping,
      const FESystem<dim>                                      &fe,
      const DoFHandler<dim>                                    &dof_handler,
      const Bulk::Materials<dim>                               &materials,
      std::vector<std::unique_ptr<Obstacles::Interface<dim>>> &&obstacles_in,
      const MPI_Comm                                            comm)
        : parameters(parameters)
        , fe(fe)
        , comm(comm)
        , surfaces(parameters, mapping, fe, dof_handler, materials, comm)
        , pairing(parameters, surfaces, std::move(obstacles_in), comm)
        , coefficients(parameters.contact)
        , node_statuses(parameters.contact, surfaces, pairing, coefficients)
        , output(parameters,
                 fe,
                 dof_handler,
                 surfaces,
                 pairing,
                 node_statuses,
                 comm)
        , history(parameters.contact,
                  surfaces,
                  node_statuses.pairs_by_node(),
                  comm)
        , assembler(parameters,
                    fe,
                    surfaces,
                    pairing,
                    coefficients,
                    node_statuses,
                    history,
                    newton_geometry_pair,
                    comm)
    {
      const auto &contact = parameters.contact;
      for (unsigned int p = 0; p < contact.pairs.size(); ++p)
        {
          const auto &pair = contact.pairs[p];
          // Newton on the geometry (projection, normal and curvature at
          // every iterate) for frictionless rigid obstacles; the geometric
          // loop for the others (doc/robustness.md, "Geometry in Newton").
          newton_geometry_pair.push_back(pair.friction == 0 &&
                                         !pair.master_is_body());
          pairing_exact =
            (p == 0 || pairing_exact) && newton_geometry_pair.back();
          // A frictionless meshed master paired at fixed points and
          // normals within each Newton solve.
          const bool frictionless_fixed_body =
            pair.friction == 0 && pair.master_is_body();
          linear_statuses = (p == 0 || linear_statuses) &&
                            (frictionless_fixed_body ||
                             (pair.friction == 0 && pairing.obstacle(p) &&
                              pairing.obstacle(p)->flat()));
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::setup(const AffineConstraints<double> &u_constraints,
                               const IndexSet                  &owned_u,
                               const std::set<types::global_dof_index> &pins,
                               ConditionalOStream                      &pcout)
    {
      const auto counts = surfaces.setup(u_constraints,
                                         owned_u,
                                         node_statuses.pairs_by_node(),
                                         pins);
      set_coefficients();
      pairing.setup();
      print_setup(pcout, counts);
    }


    template <int dim>
    void
    ContactProblem<dim>::set_coefficients()
    {
      const auto &scales = surfaces.pair_scales();
      coefficients.set(scales.face_size,
                       scales.slave_modulus,
                       scales.master_modulus);
    }


    template <int dim>
    void
    ContactProblem<dim>::print_setup(
      ConditionalOStream                   &pcout,
      const typename Surfaces<dim>::Counts &counts) const
    {
      const auto        &pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
      pcout << "Contact: " << n_pairs << " pair(s), rule "
            << pairing.rule_description();
      pcout << " on "
            << Utilities::MPI::sum(
                 static_cast<unsigned int>(surfaces.slave_faces().size()), comm)
            << " slave faces, " << surfaces.n_lambda() << " slave nodes"
            << std::endl;
      for (unsigned int p = 0; p < n_pairs; ++p)
        pcout << "  pair " << p + 1 << ": mu = " << pairs[p].friction
              << ", h = " << std::setprecision(4)
              << surfaces.pair_scales().face_size[p]
              << ", rho_n = " << coefficients.normal(p)
              << ", rho_t = " << coefficients.tangential(p)
              << std::setprecision(6) << std::endl;
      for (unsigned int p = 0; p < n_pairs; ++p)
        if (pairing.obstacle(p) &&
            !pairing.obstacle(p)->approximate_derivatives().empty())
          pcout << "  pair " << p + 1 << ": "
                << pairing.obstacle(p)->approximate_derivatives()
                << ": the contact Jacobian is not exact" << std::endl;
      if (counts.n_excluded_contact > 0)
        pcout << "  over-constraint: " << counts.n_excluded_contact
              << " slave node(s) with a Dirichlet condition along the normal "
                 "excluded from contact"
              << std::endl;
      const unsigned int n_pinned = surfaces.pins().size();
      if (counts.n_excluded_friction + counts.n_held_tangent > n_pinned)
        pcout << "  "
              << counts.n_excluded_friction + counts.n_held_tangent - n_pinned
              << " slave node(s) with a tangent held by a Dirichlet "
                 "condition: friction decided per node, the support "
                 "carries it while they stick"
              << std::endl;
      if (n_pinned > 0)
        pcout << "  " << n_pinned
              << " slave node(s) pinned at a point ('At point') against a "
                 "rigid master: the pin carries only what friction cannot"
              << std::endl;
      if (counts.n_hanging > 0)
        pcout << "  " << counts.n_hanging
              << " hanging slave node(s): multipliers interpolated"
              << std::endl;
      if (counts.n_axis > 0)
        pcout << "  " << counts.n_axis
              << " slave node(s) on the axis of quadratic faces (weight "
                 "int psi 2 pi r zero or nearly): multipliers from the next "
                 "two nodes by symmetry, no friction"
              << std::endl;
    }


    template <int dim>
    void
    ContactProblem<dim>::update_coefficients(
      const TrilinosWrappers::MPI::Vector &state)
    {
      const auto         &pairs = parameters.contact.pairs;
      std::vector<double> sum2(pairs.size(), 0.), count(pairs.size(), 0.);
      // Pressures at or below the zero threshold (e.g. the 'closed'
      // initial multipliers, see set_initial_multipliers) are not a
      // pressure level: they would make rho_t enormous.
      for (const auto &[dof0, node] : surfaces.nodes())
        if (surfaces.owned_multipliers().is_element(node.lambda) &&
            state[node.lambda] < -coefficients.law(node.pair).zero_threshold)
          {
            sum2[node.pair] += state[node.lambda] * state[node.lambda];
            count[node.pair] += 1;
          }
      for (unsigned int p = 0; p < pairs.size(); ++p)
        {
          const double s = Utilities::MPI::sum(sum2[p], comm);
          const double n = Utilities::MPI::sum(count[p], comm);
          if (n > 0 && s > 0)
            coefficients.set_pressure_level(p, std::sqrt(s / n));
        }
    }


    template <int dim>
    std::vector<types::global_dof_index>
    ContactProblem<dim>::coupled_dofs() const
    {
      std::vector<types::global_dof_index> mine, dofs,
        cell_dofs(fe.n_dofs_per_cell());
      for (const auto &point : pairing.points())
        {
          surfaces.slave_faces()[point.face].cell->get_dof_indices(cell_dofs);
          point_dofs(surfaces, point, cell_dofs, dofs);
          mine.insert(mine.end(), dofs.begin(), dofs.end());
        }
      std::vector<types::global_dof_index> all;
      for (const auto &part : Utilities::MPI::all_gather(comm, mine))
        all.insert(all.end(), part.begin(), part.end());
      std::sort(all.begin(), all.end());
      all.erase(std::unique(all.begin(), all.end()), all.end());
      return all;
    }


    template <int dim>
    void
    ContactProblem<dim>::add_sparsity(
      TrilinosWrappers::SparsityPattern &sparsity,
      const AffineConstraints<double>   &constraints) const
    {
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs;
      int                                  last_face = -1;
      // Points of one slave face paired with one master face couple the
      // same unknowns: one entry block per (slave face, master face).
      std::set<int> masters_of_face;
      for (const auto &point : pairing.points())
        {
          const auto &face = surfaces.slave_faces()[point.face];
          if (static_cast<int>(point.face) != last_face)
            {
              face.cell->get_dof_indices(cell_dofs);
              last_face = point.face;
              masters_of_face.clear();
            }
          if (!masters_of_face.insert(point.master_face).second)
            continue;
          point_dofs(surfaces, point, cell_dofs, dofs);
          constraints.add_entries_local_to_global(dofs, sparsity, false);
        }
    }


    template <int dim>
    struct ContactProblem<dim>::PointsState
    {
      std::vector<ContactPoint>                       points;
      std::map<types::global_dof_index, bool>         node_active;
      std::map<types::global_dof_index, NodeFriction> node_friction;
      typename ActiveSetHistory<dim>::Snapshot        history;
    };


    template <int dim>
    std::shared_ptr<const typename ContactProblem<dim>::PointsState>
    ContactProblem<dim>::save_points() const
    {
      return std::make_shared<const PointsState>(
        PointsState{pairing.points(),
                    node_statuses.normal_statuses(),
                    node_statuses.friction_statuses(),
                    history.save()});
    }


    template <int dim>
    void
    ContactProblem<dim>::restore_points(const PointsState &saved)
    {
      pairing.points()                  = saved.points;
      node_statuses.normal_statuses()   = saved.node_active;
      node_statuses.friction_statuses() = saved.node_friction;
      history.restore(saved.history);
    }


    template <int dim>
    double
    ContactProblem<dim>::roundoff_scale() const
    {
      double sum = 0;
      for (const auto &point : pairing.points())
        if (point.paired)
          sum += std::pow(2 * point.weight *
                            coefficients.normal(
                              surfaces.slave_faces()[point.face].pair) *
                            point.x_ref.norm(),
                          2);
      return std::sqrt(Utilities::MPI::sum(sum, comm));
    }


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
      // others keep lambda = 0 (lambda_aug = -rho_n g: open). Pairs with
      // statuses per node decide it per node, on the weighted gap G_l / D_l
      // their statuses use: a node that touches starts closed even where
      // no integration point of its faces does (a curved face touching a
      // flat one at the node).
      const double touch_tolerance = 1e-8;
      auto         num             = surfaces.writable_multipliers();
      auto         den             = surfaces.writable_multipliers();
      auto         G               = surfaces.writable_multipliers();
      auto         D               = surfaces.writable_multipliers();
      const bool   per_node        = status == InitialStatus::penetrating;
      for (const auto &point : pairing.points())
        {
          const auto        &face = surfaces.slave_faces()[point.face];
          const unsigned int p    = face.pair;
          const double       g    = pairing.gap(point, state);
          // delta: half the zero friction threshold of the law (see
          // law_parameters), so that lambda_aug = -/+ delta sets the normal
          // status strictly while the friction of a point closed this way
          // starts inactive, as for a point that has just closed
          // (theory.md F3.3). A larger delta would be a tiny nonzero
          // threshold: Lambda = F_t / (mu delta) of order 1e8 at the first
          // iterate.
          const double delta = 0.5 * coefficients.law(p).zero_threshold;
          if (status != InitialStatus::open && !point.paired)
            continue;
          if (per_node && node_statuses.by_node(p))
            {
              for (unsigned int l = 0; l < face.node_local.size(); ++l)
                {
                  const double w = point.weight * point.psi_lambda[l];
                  add_entry(G, face.lambda_dofs[l], w * g);
                  add_entry(D, face.lambda_dofs[l], w);
                }
              continue;
            }
          double target;
          if (status == InitialStatus::closed)
            target = std::min(0.,
                              coefficients.normal(p) *
                                std::max(g, -1e300 / coefficients.normal(p))) -
                     delta;
          else if (status == InitialStatus::penetrating)
            target =
              g >= -touch_tolerance * surfaces.pair_scales().face_size[p] ?
                coefficients.normal(p) * std::min(g, 0.) - delta :
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
      G.compress(VectorOperation::add);
      D.compress(VectorOperation::add);
      for (const auto i : surfaces.owned_multipliers())
        if (i < surfaces.n_u() + surfaces.n_lambda() && den[i] != 0)
          state_owned[i] = num[i] / den[i];
      if (per_node)
        for (const auto &face : surfaces.slave_faces())
          if (node_statuses.by_node(face.pair))
            for (const auto i : face.lambda_dofs)
              if (surfaces.owned_multipliers().is_element(i) && D[i] > 0)
                {
                  const unsigned int p = face.pair;
                  const double       g = G[i] / D[i];
                  const double delta = 0.5 * coefficients.law(p).zero_threshold;
                  state_owned[i] =
                    g >=
                        -touch_tolerance * surfaces.pair_scales().face_size[p] ?
                      coefficients.normal(p) * std::min(g, 0.) - delta :
                      0.;
                }
      state_owned.compress(VectorOperation::insert);
    }


    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace Contact
} // namespace Signorini
