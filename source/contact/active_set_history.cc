// Active-set history across Newton and geometric iterations: anti-cycling
// freezes and their release, the freezes of the geometric loop, release
// extrapolation.
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/contact/active_set_history.h>

#include <boost/serialization/utility.hpp>

#include <algorithm>
#include <set>

namespace Signorini
{
  namespace Contact
  {
    template <int dim>
    ActiveSetHistory<dim>::ActiveSetHistory(
      const ContactParameters &parameters,
      const Surfaces<dim>     &surfaces,
      const std::vector<bool> &node_status_pair,
      const MPI_Comm           comm)
        : parameters(parameters)
        , surfaces(surfaces)
        , node_status_pair(node_status_pair)
        , comm(comm)
    {
    }


    template <int dim>
    void
    ActiveSetHistory<dim>::start_newton_solve(Points          &points,
                                              NodeFrictionMap &node_friction)
    {
      iterates_recorded = 0;
      node_cycle.clear();
      for (auto &[dof, nf] : node_friction)
        nf.frozen = false;
      node_release.clear();
      node_extrapolated.clear();
      node_kept.clear();
      for (auto &point : points)
        {
          point.newton.release          = false;
          point.newton.extrapolated     = false;
          point.newton.keep_closed      = false;
          point.newton.status_before    = point.status;
          point.newton.direction_before = point.slip_direction;
          point.newton.cycles           = 0;
          point.newton.changes          = 0;
          point.newton.refrozen         = false;
          // A status frozen by the geometric loop stays for the step.
          point.newton.was_frozen = point.geometric.frozen;
          if (!point.geometric.frozen)
            clear_freeze(point);
        }
    }


    template <int dim>
    void
    ActiveSetHistory<dim>::start_geometric_loop(Points &points) const
    {
      for (auto &point : points)
        {
          point.geometric.status_1    = point.status;
          point.geometric.status_2    = point.status;
          point.geometric.direction_1 = point.slip_direction;
          point.geometric.direction_2 = point.slip_direction;
          point.geometric.frozen      = false;
          point.geometric.face_1      = -1;
          point.geometric.face_2      = -1;
          point.geometric.pinned_face = -1;
          clear_freeze(point);
        }
    }


    template <int dim>
    unsigned int
    ActiveSetHistory<dim>::end_geometric_iteration(Points            &points,
                                                   const unsigned int g) const
    {
      unsigned int n = 0;
      for (auto &point : points)
        {
          const PointStatus status = point.status;
          const auto       &dir    = point.slip_direction;
          // Same status as two pairings before (a slip in a direction not
          // turned against it), different from the last one (or reversed).
          const bool same_as_2 = status == point.geometric.status_2 &&
                                 (status != PointStatus::slip ||
                                  dir * point.geometric.direction_2 >= 0);
          const bool differs_from_1 = status != point.geometric.status_1 ||
                                      (status == PointStatus::slip &&
                                       dir * point.geometric.direction_1 < 0);
          if (g >= 3 && !point.geometric.frozen && same_as_2 && differs_from_1)
            {
              ++n;
              point.geometric.frozen  = true;
              point.newton.was_frozen = true;
              freeze_for_cycle(point,
                               status,
                               dir,
                               point.geometric.status_1,
                               point.geometric.direction_1,
                               true);
            }
          point.geometric.status_2    = point.geometric.status_1;
          point.geometric.direction_2 = point.geometric.direction_1;
          point.geometric.status_1    = status;
          point.geometric.direction_1 = dir;
        }
      return Utilities::MPI::sum(n, comm);
    }


    template <int dim>
    unsigned int
    ActiveSetHistory<dim>::release_frozen(Points       &points,
                                          unsigned int &refrozen)
    {
      unsigned int n = 0, again = 0;
      for (auto &point : points)
        if (point.newton.freeze_contact && !point.geometric.frozen)
          {
            // The first contradiction of a frozen point whose friction is
            // active: frozen once more, in the stick or slip status the
            // plain law asks for (released, it would enter its stick/slip
            // or reversal cycle again). Otherwise released.
            if (!point.newton.refrozen && point.newton.plain_violated &&
                point.newton.plain_status != PointStatus::free &&
                point.friction_active)
              {
                ++again;
                point.newton.refrozen = true;
                point.newton.freeze_stick =
                  point.newton.plain_status == PointStatus::stick;
                point.newton.frozen_slip_direction =
                  point.newton.plain_status == PointStatus::slip ?
                    point.newton.plain_direction :
                    Tensor<1, dim>();
              }
            else
              {
                ++n;
                clear_freeze(point);
              }
          }
      // Nodes (friction status per node): the same rule.
      for (auto &[dof, c] : node_cycle)
        if (c.freeze && c.plain_violated)
          {
            const bool owned = surfaces.owned_multipliers().is_element(dof);
            if (!c.refrozen && c.plain.active)
              {
                again += owned;
                c.refrozen     = true;
                c.freeze_stick = c.plain.stick;
                if (!c.plain.stick && c.plain.H.norm() > 0)
                  c.q = c.plain.H / c.plain.H.norm();
              }
            else
              {
                n += owned;
                c.freeze = false;
              }
          }
      refrozen = Utilities::MPI::sum(again, comm);
      return Utilities::MPI::sum(n, comm);
    }


    // A status carrier of the release extrapolation: a point, or a
    // multiplier node of a node-status pair, with its class at this
    // iterate.
    template <int dim>
    struct ActiveSetHistory<dim>::Carrier
    {
      // tension: closed in the last solve, open now; compression: closed
      // both; open: both; entered: open in the last solve, closed now.
      enum Kind : int
      {
        tension = 0,
        compression,
        open,
        entered
      };
      static int
      class_of(const bool before, const bool now)
      {
        return before ? (now ? compression : tension) : (now ? entered : open);
      }
      Point<dim>              x;
      int                     kind;
      int                     point; // index into points, or -1 (node)
      types::global_dof_index dof;
      bool                    kept; // closed again after such a release
    };


    template <int dim>
    unsigned int
    ActiveSetHistory<dim>::extrapolate_releases(
      Points              &points,
      const NodeStatusMap &node_active)
    {
      const auto   carriers   = release_carriers(points, node_active);
      unsigned int n_released = 0;
      for (unsigned int p = 0; p < carriers.size(); ++p)
        // Frictionless pairs only: with friction the tension band does not
        // follow the halving (SSNV128 in one step: 9 -> 11 Newton).
        if (parameters.pairs[p].friction == 0)
          n_released += release_mirrored(points, carriers[p]);
      return Utilities::MPI::sum(n_released, comm);
    }


    // The carriers of every pair by class (points; multiplier nodes on
    // node-status pairs); a carrier released early and closed again is
    // kept closed for the rest of the Newton solve.
    template <int dim>
    std::vector<std::vector<typename ActiveSetHistory<dim>::Carrier>>
    ActiveSetHistory<dim>::release_carriers(Points              &points,
                                            const NodeStatusMap &node_active)
    {
      std::vector<std::vector<Carrier>> carriers(parameters.pairs.size());
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          auto              &point = points[i];
          const unsigned int p     = surfaces.slave_faces()[point.face].pair;
          const bool         now   = point.status != PointStatus::free;
          if (point.newton.extrapolated && now)
            point.newton.keep_closed = true;
          point.newton.extrapolated = false;
          if (!node_status_pair[p])
            carriers[p].push_back(
              {point.x_ref,
               Carrier::class_of(
                 point.newton.status_before != PointStatus::free, now),
               static_cast<int>(i),
               0,
               point.newton.keep_closed || point.newton.freeze_contact});
        }
      std::set<types::global_dof_index> seen;
      for (const auto &face : surfaces.slave_faces())
        if (node_status_pair[face.pair])
          for (unsigned int k = 0; k < face.X.size(); ++k)
            {
              const auto dof = face.lambda_dofs[face.k_node[k]];
              if (!seen.insert(dof).second)
                continue;
              const bool now = node_active.at(dof);
              if (node_extrapolated.count(dof) && now)
                node_kept.insert(dof);
              const auto before = node_active_solved.find(dof);
              carriers[face.pair].push_back(
                {face.X[k],
                 Carrier::class_of(
                   before != node_active_solved.end() && before->second, now),
                 -1,
                 dof,
                 node_kept.count(dof) > 0});
            }
      node_extrapolated.clear();
      return carriers;
    }


    // One pair's release extrapolation (collective): while its zone
    // shrinks (none entered, some in tension), the carriers in compression
    // whose mirror image across their nearest tension carrier lies in the
    // band are opened for this solve. Returns those released here.
    template <int dim>
    unsigned int
    ActiveSetHistory<dim>::release_mirrored(
      Points                     &points,
      const std::vector<Carrier> &carriers)
    {
      // All carriers of the pair, from all ranks (position and class).
      std::vector<std::pair<Point<dim>, int>> mine;
      for (const auto &c : carriers)
        mine.emplace_back(c.x, c.kind);
      std::vector<std::pair<Point<dim>, unsigned int>> all, band;
      std::vector<int>                                 kind;
      for (const auto &part : Utilities::MPI::all_gather(comm, mine))
        for (const auto &[x, k] : part)
          {
            if (k == Carrier::tension)
              band.emplace_back(x, band.size());
            all.emplace_back(x, all.size());
            kind.push_back(k);
          }
      if (band.empty() ||
          std::find(kind.begin(), kind.end(), int(Carrier::entered)) !=
            kind.end())
        return 0;
      const auto band_tree = pack_rtree(band);
      const auto all_tree  = pack_rtree(all);
      // Candidates: carriers in compression whose mirror image across their
      // nearest tension carrier lies in the band (the carrier nearest to
      // the image is in tension), with their distance to it.
      std::vector<std::pair<const Carrier *, double>> candidates;
      for (const auto &c : carriers)
        {
          if (c.kind != Carrier::compression || c.kept)
            continue;
          std::vector<std::pair<Point<dim>, unsigned int>> hit;
          band_tree.query(boost::geometry::index::nearest(c.x, 1),
                          std::back_inserter(hit));
          const Point<dim> image    = c.x + 2. * (hit[0].first - c.x);
          const double     distance = c.x.distance(hit[0].first);
          hit.clear();
          all_tree.query(boost::geometry::index::nearest(image, 1),
                         std::back_inserter(hit));
          if (kind[hit[0].second] == Carrier::tension)
            candidates.emplace_back(&c, distance);
        }
      // At most as many as the band holds, and at most half of those in
      // compression, the nearest to the band first: on a graded mesh a band
      // of a few long elements mirrors onto the whole zone, and a pair left
      // without contact would float.
      const std::size_t n_compression =
        std::count(kind.begin(), kind.end(), int(Carrier::compression));
      const std::size_t   cap = std::min(band.size(), n_compression / 2);
      std::vector<double> mine_d;
      for (const auto &c : candidates)
        mine_d.push_back(c.second);
      std::vector<double> distances;
      for (const auto &part : Utilities::MPI::all_gather(comm, mine_d))
        distances.insert(distances.end(), part.begin(), part.end());
      if (cap == 0 || distances.empty())
        return 0;
      std::sort(distances.begin(), distances.end());
      const double limit      = distances[std::min(cap, distances.size()) - 1];
      unsigned int n_released = 0;
      for (const auto &candidate : candidates)
        {
          if (candidate.second > limit)
            continue;
          const Carrier &c = *candidate.first;
          if (c.point >= 0)
            {
              points[c.point].newton.release      = true;
              points[c.point].newton.extrapolated = true;
              ++n_released;
            }
          else
            {
              node_release.insert(c.dof);
              node_extrapolated.insert(c.dof);
              n_released += surfaces.owned_multipliers().is_element(c.dof);
            }
        }
      return n_released;
    }


    template <int dim>
    void
    ActiveSetHistory<dim>::clear_releases(Points &points)
    {
      for (auto &point : points)
        point.newton.release = false;
      node_release.clear();
    }



    template <int dim>
    void
    ActiveSetHistory<dim>::count_point_cycle(ContactPoint<dim>    &point,
                                             const PointStatus     status,
                                             const Tensor<1, dim> &direction,
                                             const bool            changed,
                                             const bool            friction,
                                             ContactStatistics    &stats) const
    {
      const unsigned int freeze_after = parameters.freeze_after_cycles;
      // Back to the status of two iterates before (a 2-cycle), or
      // changed more than 2 N times (longer cycles).
      point.newton.changes += changed;
      const bool back = changed && iterates_recorded >= 2 &&
                        ((status == point.newton.status_before &&
                          (status != PointStatus::slip ||
                           direction * point.newton.direction_before >= 0)) ||
                         (point.newton.changes > 2 * freeze_after));
      if (back)
        {
          ++point.newton.cycles;
          ++stats.n_cycling;
        }
      if (back && point.newton.cycles >= freeze_after &&
          !point.newton.was_frozen)
        {
          // Freeze from the next evaluation on: in contact if the cycle
          // went through 'free', slipping in the last slip direction if
          // it went through stick or reversed.
          point.newton.was_frozen = true;
          ++stats.n_newly_frozen;
          freeze_for_cycle(point,
                           status,
                           direction,
                           point.status,
                           point.slip_direction,
                           friction);
        }
    }


    template <int dim>
    bool
    ActiveSetHistory<dim>::friction_status_differs(
      const NodeFriction<dim> *previous,
      const NodeFriction<dim> &now)
    {
      if (!previous)
        return now.active;
      return previous->active != now.active || previous->stick != now.stick ||
             previous->saturated != now.saturated ||
             (now.active && !now.stick && !previous->stick &&
              previous->H * now.H < 0);
    }


    template <int dim>
    NodeFriction<dim>
    ActiveSetHistory<dim>::node_anti_cycling(const types::global_dof_index dof,
                                             const NodeFriction<dim>      &nf,
                                             const NodeFriction<dim> *previous,
                                             const bool         new_iterate,
                                             const bool         owned,
                                             ContactStatistics &stats)
    {
      const unsigned int freeze_after = parameters.freeze_after_cycles;
      auto               found        = node_cycle.find(dof);
      if (found == node_cycle.end())
        {
          NodeCycle<dim> c;
          c.before = previous ? *previous : NodeFriction<dim>();
          found    = node_cycle.emplace(dof, c).first;
        }
      NodeCycle<dim>   &c    = found->second;
      NodeFriction<dim> used = nf;
      // Frozen (only while the node is in contact with a threshold): the
      // status of the freeze; the plain law's status is kept for the
      // check at convergence (release_frozen()).
      c.plain_violated = false;
      if (c.freeze && nf.active)
        {
          used.frozen    = true;
          used.stick     = c.freeze_stick;
          used.saturated = false;
          if (!c.freeze_stick)
            used.H = c.q;
          c.plain = nf;
          c.plain_violated =
            c.freeze_stick ? !nf.stick : (nf.stick || nf.H * c.q < 0);
          if (owned)
            {
              ++stats.n_frozen;
              stats.n_violated += c.plain_violated;
            }
        }
      if (!new_iterate)
        return used;
      // A return to the status of two iterates back (a 2-cycle), or more
      // than 2 N changes (longer cycles), as for points.
      const bool changed =
        friction_status_differs(previous, used) && !used.frozen;
      c.changes += changed;
      const bool back = changed && iterates_recorded >= 2 &&
                        (!friction_status_differs(&c.before, used) ||
                         (c.changes > 2 * freeze_after));
      if (back)
        {
          ++c.cycles;
          stats.n_cycling += owned;
        }
      // Frozen from the next evaluation on, as a point is
      // (freeze_for_cycle()): a cycle through stick slips along its slip
      // direction; a slip direction that reverses sticks (the slip changes
      // sign from iterate to iterate: the node is at zero slip).
      if (back && c.cycles >= freeze_after && !c.was_frozen && used.active)
        {
          const bool reversed =
            !used.stick && previous && previous->active && !previous->stick;
          const Tensor<1, dim - 1> h =
            !used.stick ? used.H :
                          (previous && previous->active && !previous->stick ?
                             previous->H :
                             Tensor<1, dim - 1>());
          if (reversed || h.norm() > 0)
            {
              c.was_frozen   = true;
              c.freeze       = true;
              c.freeze_stick = reversed;
              if (!reversed)
                c.q = h / h.norm();
              stats.n_newly_frozen += owned;
            }
        }
      c.before = previous ? *previous : NodeFriction<dim>();
      return used;
    }


    template <int dim>
    void
    ActiveSetHistory<dim>::clear_freeze(ContactPoint<dim> &point)
    {
      point.newton.freeze_contact        = false;
      point.newton.frozen_slip_direction = Tensor<1, dim>();
      point.newton.freeze_stick          = false;
    }


    template <int dim>
    bool
    ActiveSetHistory<dim>::freeze_for_cycle(
      ContactPoint<dim>    &point,
      const PointStatus     status,
      const Tensor<1, dim> &direction,
      const PointStatus     other,
      const Tensor<1, dim> &other_direction,
      const bool            friction)
    {
      if (status == PointStatus::free || other == PointStatus::free)
        {
          point.newton.freeze_contact = true;
          return true;
        }
      if (!friction)
        return false;
      point.newton.freeze_contact = true;
      if (status == PointStatus::slip && other == PointStatus::slip)
        point.newton.freeze_stick = true;
      else
        point.newton.frozen_slip_direction =
          status == PointStatus::slip ? direction : other_direction;
      return true;
    }


    template class ActiveSetHistory<2>;
    template class ActiveSetHistory<3>;
  } // namespace Contact
} // namespace Signorini
