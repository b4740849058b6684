#ifndef signorini_contact_node_statuses_h
#define signorini_contact_node_statuses_h

#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>
#include <signorini/contact/active_set_history.h>
#include <signorini/contact/coefficients.h>
#include <signorini/contact/contact_law.h>
#include <signorini/contact/contact_statistics.h>
#include <signorini/contact/pairing.h>
#include <signorini/contact/surfaces.h>

#include <map>
#include <vector>

/**
 * Contact statuses per multiplier node (theory.md, "Statuses per node"):
 * with an integration-point rule on a meshed master, one normal status per
 * slave node from its weighted gap, and on frictional pairs one friction
 * status per node from its weighted slip, so that every multiplier has one
 * law however many points its faces carry. The other pairs (nodal rule,
 * rigid obstacles) decide their statuses per point, in the law, except
 * the friction status of a slave node with a tangent held by a Dirichlet
 * condition, which every frictional pair decides here, per node
 * (theory.md F8): its rows are the node's.
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    template <int dim>
    class NodeStatuses
    {
    public:
      using NodeStatusMap   = typename ActiveSetHistory<dim>::NodeStatusMap;
      using NodeFrictionMap = typename ActiveSetHistory<dim>::NodeFrictionMap;

      NodeStatuses(const ContactParameters &parameters,
                   const Surfaces<dim>     &surfaces,
                   const Pairing<dim>      &pairing,
                   const Coefficients      &coefficients);

      /** True if pair @p p decides its normal statuses per node. */
      bool
      by_node(const unsigned int p) const
      {
        return node_status_pair[p];
      }

      /** True if pair @p p also decides its friction statuses per node. */
      bool
      friction_by_node(const unsigned int p) const
      {
        return friction_node_pair[p];
      }

      /** The pairs that decide their normal statuses per node. */
      const std::vector<bool> &
      pairs_by_node() const
      {
        return node_status_pair;
      }

      /** True if some pair decides its statuses per node. */
      bool
      any() const
      {
        return any_node_status;
      }

      /** True if pair @p p decides its statuses per point but the
       * friction of its held nodes per node. */
      bool
      held_by_node(const unsigned int p) const
      {
        return held_node_pair[p];
      }

      /** True if decide() has anything to decide (the same on all ranks). */
      bool
      decides() const
      {
        return any_node_status || any_held_node;
      }

      /** True if some pair decides its friction statuses per node. */
      bool
      any_friction() const
      {
        return any_friction_node;
      }

      /**
       * Decides the statuses of the nodes of the node-status pairs at
       * @p state (slips from @p start): the weighted gaps and slips, summed
       * over all ranks, give node_active and node_friction; @p history
       * releases nodes and runs the friction anti-cycling of a
       * @p new_iterate. Returns the number of owned nodes whose status
       * changed.
       */
      unsigned int
      decide(const TrilinosWrappers::MPI::Vector &state,
             const TrilinosWrappers::MPI::Vector &start,
             const bool                           new_iterate,
             ActiveSetHistory<dim>               &history,
             ContactStatistics                   &stats);

      /** The normal status of the node of multiplier @p lambda_dof. */
      bool
      active(const types::global_dof_index lambda_dof) const
      {
        return node_active.at(lambda_dof);
      }

      /** The friction status of the node of multiplier @p lambda_dof. */
      const NodeFriction<dim> &
      friction(const types::global_dof_index lambda_dof) const
      {
        return node_friction.at(lambda_dof);
      }

      /** The friction status of the node, or nullptr if it has none yet. */
      const NodeFriction<dim> *
      find_friction(const types::global_dof_index lambda_dof) const
      {
        const auto it = node_friction.find(lambda_dof);
        return it == node_friction.end() ? nullptr : &it->second;
      }

      /** The statuses, for the active-set history and the snapshots. */
      const NodeStatusMap &
      normal_statuses() const
      {
        return node_active;
      }
      NodeStatusMap &
      normal_statuses()
      {
        return node_active;
      }
      const NodeFrictionMap &
      friction_statuses() const
      {
        return node_friction;
      }
      NodeFrictionMap &
      friction_statuses()
      {
        return node_friction;
      }

      /** The law response of @p point of a node-status pair at its state
       * @p s: the multiplier force, labelled with the statuses of its
       * nearest node. */
      PointResponse<dim>
      response(const ContactPoint<dim> &point, const PointState<dim> &s) const;

      /** The bulk's force F_int - F_ext at each pinned DoF at the state
       * of the next decide() (theory.md F8, pins). */
      void
      set_pin_loads(std::map<types::global_dof_index, double> loads)
      {
        pin_loads = std::move(loads);
      }

      /** True if a node of @p face has a held tangent. */
      static bool
      has_held_node(const SlaveFace<dim> &face);

    private:
      /** The gathered weighted sums of every node: gap G, weight D, paired
       * share P and (frictional pairs) slip W per tangent direction. */
      struct NodeSums;
      NodeSums
      gather_sums(const TrilinosWrappers::MPI::Vector &state,
                  const TrilinosWrappers::MPI::Vector &start) const;

      /** The friction statuses of the nodes of frictional node-status
       * pairs, each node once, then its anti-cycling. */
      unsigned int
      decide_friction(const TrilinosWrappers::MPI::Vector &state,
                      const NodeSums                      &sums,
                      const bool                           new_iterate,
                      ActiveSetHistory<dim>               &history,
                      ContactStatistics                   &stats);

      /** Node @p l of @p face is pinned: its H takes Lambda*, the Lambda
       * along the held tangent at which the pin carries nothing, and its
       * status is one of the three of a pinned node (NodeFriction). */
      void
      decide_pinned(const SlaveFace<dim>                &face,
                    const unsigned int                   l,
                    const TrilinosWrappers::MPI::Vector &state,
                    const double                         mu,
                    const NodeSums                      &sums,
                    NodeFriction<dim>                   &nf) const;

      const Surfaces<dim> &surfaces;
      const Pairing<dim>  &pairing;
      const Coefficients  &coefficients;
      std::vector<bool>    node_status_pair;   // per pair
      std::vector<bool>    friction_node_pair; // per pair
      std::vector<bool>    held_node_pair;     // per pair
      bool                 any_node_status   = false;
      bool                 any_friction_node = false;
      bool                 any_held_node     = false;
      // Normal status of the multiplier nodes of node-status pairs (key:
      // lambda DoF; the nodes of this rank's slave faces).
      NodeStatusMap node_active;
      // Friction status of the multiplier nodes of frictional node-status
      // pairs and of the held nodes of the other frictional pairs (key:
      // lambda DoF): active (in contact, nonzero threshold),
      // stick, and H_l = Lambda_l + rho_t W_l / D_l with the weighted slip
      // W_l (theory.md).
      NodeFrictionMap node_friction;
      // F_int - F_ext at the pinned DoFs (key: the DoF, every rank's);
      // written by set_pin_loads() (EquilibriumProblem, after each bulk
      // assembly, through ContactProblem).
      std::map<types::global_dof_index, double> pin_loads;
    };
  } // namespace Contact
} // namespace Signorini

#endif
