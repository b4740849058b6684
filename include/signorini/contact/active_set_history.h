#ifndef signorini_contact_active_set_history_h
#define signorini_contact_active_set_history_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <signorini/base/parameters.h>
#include <signorini/contact/contact_point.h>
#include <signorini/contact/contact_statistics.h>
#include <signorini/contact/surface_data.h>
#include <signorini/contact/surfaces.h>

#include <map>
#include <set>
#include <vector>

/**
 * The history of the active set across Newton iterates and geometric
 * iterations (theory.md F8, doc/robustness.md): anti-cycling (status
 * cycles, freezes and their release at convergence), the freezes of the
 * geometric loop, and the release extrapolation near a shrinking contact
 * edge. It keeps the history of the multiplier nodes (statuses per node)
 * and writes the history groups of the contact points (ContactPoint::newton
 * and ContactPoint::geometric), which the pairing creates and owns.
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    template <int dim>
    class ActiveSetHistory
    {
    public:
      using Points        = std::vector<ContactPoint<dim>>;
      using NodeStatusMap = std::map<types::global_dof_index, bool>;
      using NodeFrictionMap =
        std::map<types::global_dof_index, NodeFriction<dim>>;

      /** @p node_status_pair: the pairs whose normal statuses are decided
       * per multiplier node. */
      ActiveSetHistory(const ContactParameters &parameters,
                       const Surfaces<dim>     &surfaces,
                       const std::vector<bool> &node_status_pair,
                       const MPI_Comm           comm);

      /**
       * Anti-cycling within a Newton solve. Each evaluation of a new
       * iterate compares every point's status with its status two
       * iterates back; a point that returns to it (A -> B -> A,
       * stick/slip, contact/free or a slip reversal) has cycled. After
       * ContactParameters::freeze_after_cycles cycles in one Newton solve
       * its status is frozen: a contact/free cycle keeps the point in
       * contact, a stick/slip cycle keeps it slipping in its last slip
       * direction, a slip reversal cycle (neither direction is consistent)
       * keeps it sticking. start_newton_solve() clears the history of the
       * solve (a freeze of the geometric loop stays for the step).
       */
      void
      start_newton_solve(Points &points, NodeFrictionMap &node_friction);

      /** Counts an evaluation; a new iterate moves the cycle window. */
      void
      end_evaluation(const bool new_iterate)
      {
        if (new_iterate)
          ++iterates_recorded;
      }

      /** The cycle count of @p point at a new iterate, which takes
       * @p status (slip direction @p direction), @p changed from its last
       * status: a return to its status of two iterates back (or more than
       * 2 N changes) is a cycle, and the point is frozen after N cycles.
       * Counts into @p stats. */
      void
      count_point_cycle(ContactPoint<dim>    &point,
                        const PointStatus     status,
                        const Tensor<1, dim> &direction,
                        const bool            changed,
                        const bool            friction,
                        ContactStatistics    &stats) const;

      /** Anti-cycling of one node's friction status @p nf (decided by the
       * plain law) at an evaluation: applies the node's freeze, records
       * what the plain law says under it, and at a new iterate counts a
       * return to the status of two iterates back against @p previous
       * (the status of the last solve) and freezes after N of them.
       * Counts into @p stats when @p owned. */
      NodeFriction<dim>
      node_anti_cycling(const types::global_dof_index dof,
                        const NodeFriction<dim>      &nf,
                        const NodeFriction<dim>      *previous,
                        const bool                    new_iterate,
                        const bool                    owned,
                        ContactStatistics            &stats);

      /** Stick/slip status (or a slip direction turned by more than 90
       * degrees) of a node differs from @p previous (none: inactive). */
      static bool
      friction_status_differs(const NodeFriction<dim> *previous,
                              const NodeFriction<dim> &now);

      /**
       * At a converged iterate: lets every frozen point and node whose
       * plain law disagrees follow the plain law again (a point is frozen
       * by a cycle at most once per Newton solve), except that one with
       * active friction contradicted for the first time is frozen again in
       * the stick or slip status the plain law asks for (counted in
       * @p refrozen). Returns the number released, over all ranks.
       */
      unsigned int
      release_frozen(Points &points, unsigned int &refrozen);

      /**
       * Anti-cycling across pairings (theory.md F7 and 8). A point
       * whose converged status at the end of geometric iteration g equals
       * its status at the end of g-2 and differs from g-1 makes the fixed
       * point on the geometry 2-cycle: its status is frozen as in a Newton
       * cycle for the rest of the load step. start_geometric_loop() clears
       * the history at the start of a step; end_geometric_iteration()
       * records the statuses after the Newton solve of iteration @p g and
       * returns the number of points newly frozen (over all ranks).
       */
      void
      start_geometric_loop(Points &points) const;
      unsigned int
      end_geometric_iteration(Points &points, const unsigned int g) const;

      /**
       * Release extrapolation (doc/robustness.md), after the residual
       * evaluation of an iterate that follows a solve, before the matrix
       * assembly. Per frictionless pair whose contact zone only shrank at
       * this iterate (points or nodes closed in the last solve and open
       * now: the tension band T; none entered), every carrier still closed
       * whose mirror image across its nearest point of T lies in T is
       * released for the next solve: near a smooth contact edge a too wide
       * zone gives tension only in its outer half, so the band halves per
       * plain solve and the mirror jumps to the edge. Frozen carriers are
       * left alone, and so is, for the rest of the Newton solve, one that
       * closed again after such a release. At most as many as the band
       * holds and half of those in compression are released, the nearest
       * to the band first. @p node_active: the node statuses now. Returns
       * the number released (over all ranks); clear_releases() ends their
       * release after the matrix assembly.
       */
      unsigned int
      extrapolate_releases(Points &points, const NodeStatusMap &node_active);
      void
      clear_releases(Points &points);
      /** The node statuses of the solve that follows (the 'before' of the
       * next release extrapolation). */
      void
      set_solved_node_statuses(const NodeStatusMap &node_active)
      {
        node_active_solved = node_active;
      }
      /** The multiplier node @p dof is released for this solve. */
      bool
      node_released(const types::global_dof_index dof) const
      {
        return node_release.count(dof) > 0;
      }

      /** What a line search trial restores (the node cycles; the points
       * are restored by their owner). */
      struct Snapshot
      {
        std::map<types::global_dof_index, NodeCycle<dim>> node_cycle;
        unsigned int                                      iterates_recorded;
      };
      Snapshot
      save() const
      {
        return {node_cycle, iterates_recorded};
      }
      void
      restore(const Snapshot &saved)
      {
        node_cycle        = saved.node_cycle;
        iterates_recorded = saved.iterates_recorded;
      }

    private:
      /** Back to the plain contact law at @p point. */
      static void
      clear_freeze(ContactPoint<dim> &point);
      /** Freezes @p point after a cycle between @p status (slip direction
       * @p direction) and @p other (@p other_direction); see the class
       * documentation. False if nothing is frozen (a frictionless cycle
       * that never went through 'free'). */
      static bool
      freeze_for_cycle(ContactPoint<dim>    &point,
                       const PointStatus     status,
                       const Tensor<1, dim> &direction,
                       const PointStatus     other,
                       const Tensor<1, dim> &other_direction,
                       const bool            friction);

      // The status carriers of the release extrapolation (points, and
      // multiplier nodes of node-status pairs) per pair, and one pair's
      // releases.
      struct Carrier;
      std::vector<std::vector<Carrier>>
      release_carriers(Points &points, const NodeStatusMap &node_active);
      unsigned int
      release_mirrored(Points &points, const std::vector<Carrier> &carriers);

      const ContactParameters &parameters;
      const Surfaces<dim>     &surfaces;
      const std::vector<bool> &node_status_pair;
      MPI_Comm                 comm;

      // Evaluations of new iterates in this Newton solve.
      unsigned int iterates_recorded = 0;
      // Anti-cycling of the friction status per node (key: lambda DoF).
      std::map<types::global_dof_index, NodeCycle<dim>> node_cycle;
      // Release extrapolation on node-status pairs: the node statuses of
      // the last solve, the nodes open for the next solve, those opened
      // that way for the last, and those that closed again after such a
      // release (not released early again in this Newton solve).
      NodeStatusMap                     node_active_solved;
      std::set<types::global_dof_index> node_release, node_extrapolated,
        node_kept;
    };
  } // namespace Contact
} // namespace Signorini

#endif
