#ifndef signorini_contact_pairing_h
#define signorini_contact_pairing_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/base/parameters.h>
#include <signorini/contact/contact_point.h>
#include <signorini/contact/integration_rule.h>
#include <signorini/contact/obstacles/interface.h>
#include <signorini/contact/projection.h>
#include <signorini/contact/surfaces.h>

#include <array>
#include <memory>
#include <vector>

/**
 * The contact points and their pairing with the master (theory.md F6
 * and 7): the points of the integration rule on the owned slave faces (the
 * mortar rule cuts the faces of meshed pairs by the master faces at every
 * pairing), the search of a master face through a bounding-box tree, the
 * closest-point projection onto it or onto a rigid obstacle at time t, and
 * the pairing 2-cycles at kinks of the master surface.
 *
 * It owns the point store: the statuses, the assembly and the active-set
 * history read and update the points through points().
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    template <int dim>
    class Pairing
    {
    public:
      using Points = std::vector<ContactPoint<dim>>;

      /** @p obstacles: the rigid obstacle of every pair (nullptr for a
       * meshed master). */
      Pairing(
        const Parameters                                         &parameters,
        const Surfaces<dim>                                      &surfaces,
        std::vector<std::unique_ptr<Obstacles::Interface<dim>>> &&obstacles,
        const MPI_Comm                                            comm);

      /** After Surfaces::setup(): the rule's points on every owned slave
       * face; the obstacles take the pairs' face sizes as length scale. */
      void
      setup();

      /**
       * Pairs every contact point at @p state (ghosted system vector), the
       * rigid obstacles moved to time @p time; @p step_start_time is the
       * start of the load step (increments of the obstacles' material
       * points).
       */
      void
      pair(const TrilinosWrappers::MPI::Vector &state,
           const double                         time,
           const double                         step_start_time);

      /** The load time and the step start of the last pair() call. */
      std::array<double, 2>
      paired_times() const
      {
        return {{time_paired, start_paired}};
      }

      /** The prescribed rigid motion at time @p t of the obstacle of pair
       * @p p (a rigid master). */
      Obstacles::RigidMotion<dim>
      obstacle_motion(const unsigned int p, const double t) const
      {
        return motions[p]->at(t);
      }

      /** A new load step: the pairing 2-cycles start again. */
      void
      start_step()
      {
        pairings_in_step = 0;
        n_newly_pinned   = 0;
      }

      Points &
      points()
      {
        return point_store;
      }

      const Points &
      points() const
      {
        return point_store;
      }

      /** The rigid obstacle of pair @p p (nullptr: meshed master). */
      const Obstacles::Interface<dim> *
      obstacle(const unsigned int p) const
      {
        return obstacles[p].get();
      }

      /** Points the last pairing found deep inside the master body and
       * paired from the penetrated side (all ranks). */
      unsigned int
      deep_points() const
      {
        return n_deep;
      }

      /**
       * Pairing 2-cycles (meshed masters, non-mortar rules): a point whose
       * new master face is the one of two pairings before and not the one
       * of the last pairing sits at a kink of the master surface, where
       * each pairing's normal moves it onto the other face. It is pinned to
       * that face for the rest of the step (projected onto it, also just
       * outside it, while the projection tolerance allows). The number of
       * points pinned by the last pair() call, over all ranks.
       */
      unsigned int
      newly_pinned() const
      {
        return n_newly_pinned;
      }

      /**
       * The prescribed motion of the rigid obstacles as predictor data:
       * this rank's parts of d_new . d_old and d_old . d_old, with d the
       * displacement of the obstacle's material point at each paired point
       * between @p start and @p time (new) and between @p previous and
       * @p start (old) (LoadStep::predictor_factor).
       */
      std::array<double, 2>
      obstacle_increment_products(const double time,
                                  const double start,
                                  const double previous) const;

      /** "; subsection 'Contact/Pair k', parameter 'Obstacle motion' is not
       * finite at t = ..." for the first obstacle whose motion at @p time
       * is not finite (translation, rotation), empty if all are. */
      std::string
      non_finite_motion(const double time) const;

      /** "mortar (...)" or the fixed rule's name and the number of
       * points (collective). */
      std::string
      rule_description() const;

      /** g of theory.md F2 at @p point (-max if unpaired). */
      double
      gap(const ContactPoint<dim>             &point,
          const TrilinosWrappers::MPI::Vector &state) const;

      /** Tangent coordinates T^T v of the slip increment v of
       * theory.md F2 at a paired @p point (from @p start). */
      Tensor<1, dim - 1>
      slip(const ContactPoint<dim>             &point,
           const TrilinosWrappers::MPI::Vector &state,
           const TrilinosWrappers::MPI::Vector &start) const;

    private:
      using Tree  = RTree<std::pair<BoundingBox<dim>, unsigned int>>;
      using Nodes = std::vector<std::vector<Point<dim>>>;

      /** A contact point of slave face @p f at @p xi with rule weight
       * @p w on the unit face (shape values, position, weight, normal). */
      ContactPoint<dim>
      make_point(const unsigned int    f,
                 const unsigned int    q,
                 const Point<dim - 1> &xi,
                 const double          w) const;

      /** Pairs one contact point at @p state with the master faces at
       * @p x_master (rigid obstacle, pinned face, the mortar piece's face,
       * else the search), records its pairing history and sets its normal
       * and tangents; true if a pairing 2-cycle pinned it now. */
      bool
      pair_point(ContactPoint<dim>                   &point,
                 const TrilinosWrappers::MPI::Vector &state,
                 const Nodes                         &x_master,
                 const std::vector<Point<dim>>       &inside,
                 const Tree                          &tree);

      /** The search: the closest master face onto which @p point at @p x_e
       * projects inside, else the smallest violation within the projection
       * tolerance, else pair_deep(). */
      void
      search_master(ContactPoint<dim>             &point,
                    const Point<dim>              &x_e,
                    const Nodes                   &x_master,
                    const std::vector<Point<dim>> &inside,
                    const Tree                    &tree);

      /** Pairs an unpaired @p point deep inside the master body with the
       * nearest master face it lies behind (see the definition). */
      void
      pair_deep(ContactPoint<dim>             &point,
                const Point<dim>              &x_e,
                const Nodes                   &x_master,
                const std::vector<Point<dim>> &inside,
                const Tree                    &tree);

      /** psi_lambda of every point: the dual basis on the faces of
       * node-status pairs whose points are all paired, else psi. */
      void
      set_multiplier_basis();

      /**
       * Mortar rule: cuts every slave face of a meshed pair by the master
       * faces at their current positions @p x_master (theory.md F6)
       * and rebuilds the contact points; a new point takes the last status
       * of the nearest old point of its face.
       */
      void
      segment(const TrilinosWrappers::MPI::Vector &state,
              const Nodes                         &x_master,
              const Tree                          &tree);

      /** Takes the projection @p proj onto a master face as the point's:
       * xi_m, N_m(xi_m) and the normal. */
      void
      take_projection(ContactPoint<dim>         &point,
                      const FaceProjection<dim> &proj) const;

      const Parameters                                       &parameters;
      const Surfaces<dim>                                    &surfaces;
      const MPI_Comm                                          comm;
      std::vector<std::unique_ptr<Obstacles::Interface<dim>>> obstacles;
      // Prescribed motion of each rigid obstacle (nullptr for a meshed
      // master) and its value at the start of the current step.
      std::vector<std::unique_ptr<Obstacles::Motion<dim>>> motions;
      std::vector<Obstacles::RigidMotion<dim>>             motion_at_start;
      // The fixed rule; with the mortar rule, the nodal rule for the faces
      // of rigid pairs (an analytic master has nothing to cut).
      std::unique_ptr<SlaveRule<dim>> rule;
      bool                            mortar         = false;
      unsigned int                    segment_order  = 0;
      unsigned int                    n_newly_pinned = 0, pairings_in_step = 0;
      double                          time_paired = 0, start_paired = 0;
      unsigned int n_deep = 0; // points paired by pair_deep(), last pairing
      Points       point_store;
    };
  } // namespace Contact
} // namespace Signorini

#endif
