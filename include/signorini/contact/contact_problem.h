#ifndef signorini_contact_contact_problem_h
#define signorini_contact_contact_problem_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/assembler.h>
#include <signorini/contact/active_set_history.h>
#include <signorini/contact/assembler.h>
#include <signorini/contact/coefficients.h>
#include <signorini/contact/contact_law.h>
#include <signorini/contact/contact_point.h>
#include <signorini/contact/contact_statistics.h>
#include <signorini/contact/node_statuses.h>
#include <signorini/contact/obstacles/interface.h>
#include <signorini/contact/output.h>
#include <signorini/contact/pairing.h>
#include <signorini/contact/projection.h>
#include <signorini/contact/surface_data.h>
#include <signorini/contact/surfaces.h>

#include <limits>
#include <map>
#include <memory>
#include <set>
#include <vector>

/**
 * The contact part of the system (doc/theory.md sections 1-7): the slave
 * surfaces with their multiplier unknowns, the master surfaces (meshed faces
 * or rigid analytic obstacles), the pairing of contact points, and the
 * assembly of the contact residual and its exact Jacobian.
 *
 * The surfaces, their slave nodes and the numbering of the multipliers
 * after the displacements are a Surfaces object (surfaces.h); slave contact
 * points are treated by the rank that owns the slave cell.
 *
 * Rows of the multiplier equations are scaled by rho_n (lambda rows) and
 * rho_t (Lambda rows) of their pair, so that the residual of the active rows
 * is a force like the displacement residual; Newton's iterates do not depend
 * on this scaling.
 *
 * The members are defined by concern in source/contact/:
 *   contact_problem.cc      construction, set-up, couplings, initial
 *                           multipliers, snapshots (coefficients: class
 *                           Coefficients)
 *   surfaces.cc             class Surfaces: faces, multiplier numbering,
 *                           exclusions, constraint lines
 *   surfaces_fields.cc      positions X + u, master increments, the
 *                           multipliers to and from fields
 *   pairing.cc              class Pairing: the contact points, search,
 *                           projection, mortar segmentation
 *   node_statuses.cc        class NodeStatuses: statuses per node
 *   active_set_history.cc   class ActiveSetHistory: anti-cycling, freezes,
 *                           releases, extrapolation
 *   pin_rows.cc             the contact's part of a sticking pinned node's
 *                           rows (the pin's support force)
 *   assembler.cc            class Assembler: the point loop, point state
 *                           and law response
 *   local_rows.cc           its local residual and Jacobian of a point
 *                           (point path, node friction rows)
 *   output.cc               class Output: summaries, point records, CSV,
 *                           fields, contact-zone cells
 * and its data in surface_data.h (faces, nodes) and contact_point.h.
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;


    template <int dim>
    class ContactProblem
    {
      // The data of surfaces and points (surface_data.h, contact_point.h).
      using SlaveFace    = Contact::SlaveFace<dim>;
      using MasterFace   = Contact::MasterFace<dim>;
      using ContactPoint = Contact::ContactPoint<dim>;
      using NodeFriction = Contact::NodeFriction<dim>;

    public:
      ContactProblem(
        const Parameters                                         &parameters,
        const Mapping<dim>                                       &mapping,
        const FESystem<dim>                                      &fe,
        const DoFHandler<dim>                                    &dof_handler,
        const Bulk::Materials<dim>                               &materials,
        std::vector<std::unique_ptr<Obstacles::Interface<dim>>> &&obstacles,
        const MPI_Comm                                            comm);

      bool
      active() const
      {
        return !parameters.contact.pairs.empty();
      }

      /**
       * True if a new pairing cannot change the equations: every pair is a
       * rigid obstacle projected at every Newton iterate, and no friction
       * threshold is frozen at the pairing. The geometric loop then has
       * nothing to hand over to.
       */
      bool
      pairing_is_exact() const
      {
        return pairing_exact;
      }

      /**
       * True if the residual is linear in the unknowns once the statuses
       * are fixed: every pair frictionless (no slip norm), on a meshed
       * master paired at fixed points and normals, or on a rigid plane.
       * A Newton step solved exactly (direct solver, full step) whose
       * statuses the next iterate keeps then lands on the solution up to
       * round-off.
       */
      bool
      linear_at_fixed_statuses() const
      {
        return linear_statuses;
      }

      /**
       * Finds the slave and master surfaces, numbers the multipliers and
       * computes the coefficients. Needs the displacement constraints
       * (hanging nodes and Dirichlet) of the locally relevant DoFs to decide
       * which slave nodes are excluded (theory.md F8, over-constraint),
       * and @p pins, the DoFs of the lines that pin a point.
       */
      void
      setup(const AffineConstraints<double>         &u_constraints,
            const IndexSet                          &locally_owned_u,
            const std::set<types::global_dof_index> &pins,
            ConditionalOStream                      &pcout);

      /** The contact points and their pairing (pairing.h). */
      const Pairing<dim> &
      contact_pairing() const
      {
        return pairing;
      }

      /** The contact surfaces: faces, slave nodes, multiplier numbering
       * (surfaces.h). */
      const Surfaces<dim> &
      contact_surfaces() const
      {
        return surfaces;
      }


      /**
       * Pairs every contact point (geometric iteration, theory.md F7):
       * closest-point projection on the master faces proposed by a
       * bounding-box tree, or on the rigid obstacle at time @p time.
       * @p state is the ghosted system vector. @p step_start_time is the
       * start of the load step (rigid obstacle increments).
       */
      void
      pair(const TrilinosWrappers::MPI::Vector &state,
           const double                         time,
           const double                         step_start_time)
      {
        pairing.pair(state, time, step_start_time);
      }

      /**
       * Friction augmentation rho_t = c_t rho_n / (mu p_ref) per pair, with
       * p_ref the RMS of the nodal pressures -lambda above the zero threshold
       * nodes in @p state (kept from the last call while no node is
       * closed). Called once per Newton solve (its first residual), so
       * that all iterates of one solve work on the same equations.
       */
      void
      update_coefficients(const TrilinosWrappers::MPI::Vector &state);

      /** Every system index the contact terms touch with the current
       * pairing (slave-face displacements, master-face displacements,
       * multipliers), sorted, the same list on every rank. */
      std::vector<types::global_dof_index>
      coupled_dofs() const;

      /** Entries of the contact blocks for the current pairing. */
      void
      add_sparsity(TrilinosWrappers::SparsityPattern &sparsity,
                   const AffineConstraints<double>   &constraints) const;

      /**
       * Multipliers realising 'Initial status' = open / closed: written
       * into the owned entries of @p state_owned after the first pairing.
       */
      void
      set_initial_multipliers(const TrilinosWrappers::MPI::Vector &state,
                              TrilinosWrappers::MPI::Vector &state_owned) const;

      /**
       * Adds -R_contact into @p rhs (and K into @p matrix if not null),
       * evaluating the law of every contact point at @p state; @p
       * step_start is the state at the start of the load step (slip
       * increments). The physical contact force on the displacement DoFs is
       * added into @p contact_force (for reactions). The friction rows
       * are weighted by the multipliers of @p weight_state (nullptr:
       * @p state), which the matrix does not differentiate (doc/theory.md
       * section 3.2, "Row weight of the friction law"); the Jacobian check
       * holds them at its base state.
       */
      ContactStatistics
      assemble(const TrilinosWrappers::MPI::Vector &state,
               const TrilinosWrappers::MPI::Vector &step_start,
               const AffineConstraints<double>     &constraints,
               TrilinosWrappers::SparseMatrix      *matrix,
               TrilinosWrappers::MPI::Vector       &rhs,
               TrilinosWrappers::MPI::Vector       &contact_force,
               const bool                           new_iterate  = false,
               const TrilinosWrappers::MPI::Vector *weight_state = nullptr)
      {
        return assembler.assemble(state,
                                  step_start,
                                  constraints,
                                  matrix,
                                  rhs,
                                  contact_force,
                                  new_iterate,
                                  weight_state ? *weight_state : state);
      }

      /** Anti-cycling within a Newton solve and at its convergence
       * (ActiveSetHistory::start_newton_solve(), release_frozen()). */
      void
      start_newton_solve()
      {
        history.start_newton_solve(pairing.points(),
                                   node_statuses.friction_statuses());
      }
      unsigned int
      release_frozen(unsigned int &refrozen)
      {
        return history.release_frozen(pairing.points(), refrozen);
      }

      /** Release extrapolation after the residual of an iterate that
       * follows a solve, ended by clear_releases() after the matrix
       * assembly (ActiveSetHistory::extrapolate_releases()). */
      unsigned int
      extrapolate_releases()
      {
        return history.extrapolate_releases(pairing.points(),
                                            node_statuses.normal_statuses());
      }
      void
      clear_releases()
      {
        history.clear_releases(pairing.points());
      }

      /** Anti-cycling across pairings, and the pairing 2-cycles of
       * newly_pinned(), at the start of a load step; the statuses after
       * the Newton solve of geometric iteration @p g, returning the number
       * of points newly frozen (ActiveSetHistory). */
      void
      start_geometric_loop()
      {
        history.start_geometric_loop(pairing.points());
        pairing.start_step();
      }
      unsigned int
      end_geometric_iteration(const unsigned int g)
      {
        return history.end_geometric_iteration(pairing.points(), g);
      }

      /** Pairing::non_finite_motion(). */
      std::string
      non_finite_motion(const double time) const
      {
        return pairing.non_finite_motion(time);
      }

      /** Pairing::obstacle_increment_products(). */
      std::array<double, 2>
      obstacle_increment_products(const double time,
                                  const double start,
                                  const double previous) const
      {
        return pairing.obstacle_increment_products(time, start, previous);
      }

      /** Pairing::deep_points(). */
      unsigned int
      deep_points() const
      {
        return pairing.deep_points();
      }

      /** Pairing::newly_pinned(). */
      unsigned int
      newly_pinned() const
      {
        return pairing.newly_pinned();
      }

      /** NodeStatuses::set_pin_loads(). */
      void
      set_pin_loads(std::map<types::global_dof_index, double> loads)
      {
        node_statuses.set_pin_loads(std::move(loads));
      }

      /** Assembler::sticking_pins(). */
      const std::set<types::global_dof_index> &
      sticking_pins() const
      {
        return assembler.sticking_pins();
      }

      /** Opaque copy of the per-point state (statuses, values, anti-cycling
       * history): trial evaluations (line search) restore it so that the
       * status history sees accepted iterates only. */
      struct PointsState;
      std::shared_ptr<const PointsState>
      save_points() const;
      void
      restore_points(const PointsState &saved);

      /**
       * Round-off scale of the contact residual [N], over all ranks:
       * sqrt(sum_k (2 w_k rho_n |x_k|)^2) over the paired points. The gap
       * g = (x^e - x^m) . n is a difference of positions, so its round-off
       * is about eps |x|, and rho_n carries it into the lambda rows and
       * (through lambda_aug) into the displacement rows: eps times this
       * scale is the size of the residual's round-off (Newton's round-off
       * floor; large coefficients c_n put it above 'Relative tolerance').
       */
      double
      roundoff_scale() const;

      /** Per-pair results and point records (output.h). */
      using PairSummary = typename Output<dim>::PairSummary;
      using PointRecord = typename Output<dim>::PointRecord;

      /** The summaries, records, CSV, nodal fields and contact-zone cells
       * of the last evaluation (output.h). */
      const Output<dim> &
      contact_output() const
      {
        return output;
      }

      /** Per-pair results of the last evaluation, summed over ranks
       * (Output::summary()). */
      std::vector<PairSummary>
      summary() const
      {
        return output.summary();
      }

      /** Values at the contact points, gathered on every rank, sorted by
       * (pair, reference coordinates) (Output::gather_points()). */
      std::vector<PointRecord>
      gather_points() const
      {
        return output.gather_points();
      }

      /**
       * Two facts of a converged contact state that the residual does not
       * restate, per pair (reference checks, doc/verification.md;
       * source/contact/contact_checks.cc):
       * - action = reaction: the force that the displacement rows of the
       *   pair carry (sum of w f over its points: what the master receives,
       *   by the same shape functions that sum to one) against the force
       *   that the multiplier unknowns stand for, recomputed from them
       *   alone: the traction lambda n + mu lambda T Lambda (doc/theory.md
       *   1 and 4; per node with statuses per node). They differ by the
       *   augmentation terms (rho_n g, rho_t v), which vanish at a
       *   converged state, and by any error of the law in the rows.
       * - Coulomb's law where the contact slips: at every slipping point
       *   (statuses per point) or slipping multiplier node (statuses per
       *   node), the tangential force that the slave receives opposes the
       *   slip increment v of the bodies (@p slips below, measured from
       *   the displacement field, not the slip the law was given;
       *   theory.md F3.2: h / |h| along v at convergence) and
       *   |f_t| = mu |f_n|; and the law's slip is the bodies' (the
       *   largest difference, max_slip_difference); for a node, its force
       *   F_l = sum_k w psi_l f, split by its mean normal, against its
       *   weighted slip sum_k w psi~_l v (exact on flat masters; on curved
       *   ones the normal turns under a node).
       * @p state: the converged (ghosted) system vector of the last
       * assemble().
       */
      struct LawCheck
      {
        Tensor<1, dim> force_rows;        // on the master [N]
        Tensor<1, dim> force_multipliers; // on the master [N]
        // Slipping points or nodes whose slip and friction force are
        // measurable (above 1e-9 of the pair's largest), and among them
        // those whose friction opposes the slip.
        unsigned int n_slipping = 0, n_opposed = 0;
        // Smallest cosine of the angle between the friction force on the
        // slave and -v over them (1: exactly opposed), and the largest
        // relative deviation from |f_t| = mu |f_n|.
        double min_cosine    = 1;
        double max_deviation = 0;
        // The largest difference between the slip the law was given and
        // @p slips over the closed points, relative to the largest of
        // @p slips (0 without slip).
        double max_slip_difference = 0;
        bool   by_node             = false; // statuses per node
      };
      /** @p slips: the slip of every point of the pairing (in its order)
       * as the bodies moved, from the displacement field and the
       * obstacles' motion (Postprocess::field_slips()): the friction force
       * is checked against it, not against the slip the law was given. */
      std::vector<LawCheck>
      law_checks(const TrilinosWrappers::MPI::Vector &state,
                 const std::vector<Tensor<1, dim>>   &slips) const;


    private:
      /** rho_n, rho_t and p_ref per pair (setup()). */
      void
      set_coefficients();
      void
      print_setup(ConditionalOStream                   &pcout,
                  const typename Surfaces<dim>::Counts &counts) const;



      /** The force on the master at @p point from the multipliers
       * (law_checks()). */
      Tensor<1, dim>
      multiplier_force(const ContactPoint                  &point,
                       const TrilinosWrappers::MPI::Vector &state) const;
      /** The largest slip and friction force of each pair: the scale below
       * which a slip direction is round-off (law_checks()). */
      struct SlipScales
      {
        std::vector<double> v_max, f_max;
        bool
        measurable(const unsigned int    p,
                   const Tensor<1, dim> &f,
                   const Tensor<1, dim> &v) const
        {
          return v.norm() > 1e-9 * v_max[p] && f.norm() > 1e-9 * f_max[p];
        }
      };
      void
      add_node_slip_samples(std::vector<TrilinosWrappers::MPI::Vector> &nodal,
                            const SlipScales                           &scales,
                            std::vector<LawCheck> &result) const;
      const Parameters    &parameters;
      const FESystem<dim> &fe;
      MPI_Comm             comm;
      Surfaces<dim>        surfaces;
      // The contact points and their masters (pairing.h).
      Pairing<dim> pairing;
      Coefficients coefficients; // rho_n, rho_t, law parameters per pair
      // Statuses per multiplier node (node_statuses.h).
      NodeStatuses<dim> node_statuses;
      // What the points hold, for the user (output.h).
      Output<dim> output;
      // Newton on the geometry, per pair: frictionless rigid obstacles.
      std::vector<bool> newton_geometry_pair;
      bool              pairing_exact = false; // see pairing_is_exact()
      bool linear_statuses            = false; // see linear_at_fixed_statuses()
      ActiveSetHistory<dim> history;
      // The point loop of the residual and Jacobian (assembler.h).
      Assembler<dim> assembler;
    };
  } // namespace Contact
} // namespace Signorini

#endif
