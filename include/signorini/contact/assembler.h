#ifndef signorini_contact_assembler_h
#define signorini_contact_assembler_h

#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <signorini/base/parameters.h>
#include <signorini/contact/active_set_history.h>
#include <signorini/contact/coefficients.h>
#include <signorini/contact/contact_point.h>
#include <signorini/contact/contact_statistics.h>
#include <signorini/contact/node_statuses.h>
#include <signorini/contact/pairing.h>
#include <signorini/contact/surfaces.h>

#include <map>
#include <set>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    /** System indices of the local unknowns of @p point in the order
     * e | m | lambda | Lambda (slave face displacements, master face
     * displacements, multipliers), used by assembly and sparsity;
     * @p cell_dofs are the DoFs of the slave face's cell. */
    template <int dim>
    void
    point_dofs(const Surfaces<dim>                        &surfaces,
               const ContactPoint<dim>                    &point,
               const std::vector<types::global_dof_index> &cell_dofs,
               std::vector<types::global_dof_index>       &dofs)
    {
      const auto &face = surfaces.slave_faces()[point.face];
      dofs.clear();
      for (const auto i : face.u_local)
        dofs.push_back(cell_dofs[i]);
      if (point.master_face >= 0)
        for (const auto d : surfaces.master_faces()[point.master_face].dofs)
          dofs.push_back(d);
      dofs.insert(dofs.end(), face.lambda_dofs.begin(), face.lambda_dofs.end());
      dofs.insert(dofs.end(),
                  face.friction_dofs.begin(),
                  face.friction_dofs.end());
    }


    /**
     * The contact residual and its exact Jacobian (the "assembly" step of
     * the data path for contact; theory.md F2 to 5): the loop over the
     * contact points of the current pairing. Each point goes state ->
     * law -> local rows: evaluate_point() (kinematics, gap, slip,
     * multipliers, the law's response or the node path's),
     * record_point_status() (counts, anti-cycling, output values),
     * local_residual() and local_jacobian() (source/contact/local_rows.cc),
     * summed per (slave face, master face) and distributed with the
     * constraints. The parts it works on (surfaces, pairing, coefficients,
     * node statuses, active-set history) belong to the ContactProblem.
     */
    template <int dim>
    class Assembler
    {
      using SlaveFace    = Contact::SlaveFace<dim>;
      using MasterFace   = Contact::MasterFace<dim>;
      using ContactPoint = Contact::ContactPoint<dim>;
      using NodeFriction = Contact::NodeFriction<dim>;

    public:
      /** @p newton_geometry_pair: per pair, Newton on the geometry
       * (frictionless rigid obstacles), set by the ContactProblem's
       * set-up. */
      Assembler(const Parameters        &parameters,
                const FESystem<dim>     &fe,
                const Surfaces<dim>     &surfaces,
                Pairing<dim>            &pairing,
                const Coefficients      &coefficients,
                NodeStatuses<dim>       &node_statuses,
                ActiveSetHistory<dim>   &history,
                const std::vector<bool> &newton_geometry_pair,
                const MPI_Comm           comm);

      /** ContactProblem::assemble(). */
      ContactStatistics
      assemble(const TrilinosWrappers::MPI::Vector &state,
               const TrilinosWrappers::MPI::Vector &start,
               const AffineConstraints<double>     &constraints,
               TrilinosWrappers::SparseMatrix      *matrix,
               TrilinosWrappers::MPI::Vector       &rhs,
               TrilinosWrappers::MPI::Vector       &contact_force,
               const bool                           new_iterate,
               const TrilinosWrappers::MPI::Vector &weight_state);

      /** The pinned DoFs (Surfaces::pins()) whose node sticks at the last
       * assemble(), over all ranks: their node's rows along the held
       * tangent are the pin's support force R_d = 0 (theory.md F8, pins;
       * the bulk's part is added by EquilibriumProblem). */
      const std::set<types::global_dof_index> &
      sticking_pins() const
      {
        return stick_pins;
      }

    private:
      // What one point computes on the way to its rows (helpers.h).
      struct PointEvaluation;

      /** Point state and law response of @p point at @p state (from
       * @p start): kinematics, gap, slip, multipliers (the friction rows'
       * weight from @p weight_state), the law (or the node path's), the
       * node friction force and, on a rigid obstacle with Newton on the
       * geometry, its derivatives. */
      void
      evaluate_point(ContactPoint                               &point,
                     const std::vector<types::global_dof_index> &cell_dofs,
                     const TrilinosWrappers::MPI::Vector        &state,
                     const TrilinosWrappers::MPI::Vector        &start,
                     const TrilinosWrappers::MPI::Vector        &weight_state,
                     PointEvaluation                            &e);

      /** The kinematics of evaluate_point(): position and increment of the
       * point, its multipliers, the projection and normal of an obstacle
       * with Newton on the geometry (written into @p point), gap and
       * slip. */
      void
      point_kinematics(ContactPoint                               &point,
                       const std::vector<types::global_dof_index> &cell_dofs,
                       const TrilinosWrappers::MPI::Vector        &state,
                       const TrilinosWrappers::MPI::Vector        &start,
                       const TrilinosWrappers::MPI::Vector        &weight_state,
                       PointEvaluation                            &e);

      /** The law's flags for @p point (anti-cycling freezes, release,
       * held tangents, all tangents held at a pinned node); true if the
       * point is at a pinned node. */
      bool
      law_input(const ContactPoint &point, PointEvaluation &e) const;

      /** The face's node statuses and multipliers for the node rows, the
       * label of a pinned point, and the friction force of the nodes with
       * statuses per node. */
      void
      node_friction(const ContactPoint                  &point,
                    const bool                           pinned,
                    const TrilinosWrappers::MPI::Vector &state,
                    const TrilinosWrappers::MPI::Vector &weight_state,
                    PointEvaluation                     &e);

      /** Counts the status of an evaluated point into @p stats, runs its
       * anti-cycling at a new iterate, and stores its status and output
       * values. */
      void
      record_point_status(ContactPoint          &point,
                          const PointEvaluation &e,
                          const bool             new_iterate,
                          ContactStatistics     &stats);

      /** Layout of the local unknowns and the local residual rows -R of an
       * evaluated point (point path; node friction rows per node). */
      void
      local_residual(const ContactPoint                  &point,
                     const TrilinosWrappers::MPI::Vector &state,
                     PointEvaluation                     &e,
                     Vector<double>                      &F) const;

      /** The local Jacobian of an evaluated point: the law's derivatives,
       * then those of the node friction rows. */
      void
      local_jacobian(const ContactPoint    &point,
                     const PointEvaluation &e,
                     FullMatrix<double>    &K) const;

      /** stick_pins from the node statuses (collective). */
      void
      find_sticking_pins();

      /** Adds row @p a of a group's local rows (@p K, @p F on @p dofs),
       * the contact's part of the support force R_d of a sticking pin, to
       * the held-tangent rows of its node: a_k (-R_d) into @p rhs (with
       * -K g of the inhomogeneous columns of @p constraints when there is
       * a @p matrix), a_k dR_d into @p matrix (columns condensed). */
      void
      add_pin_rows(const unsigned int                          a,
                   const FullMatrix<double>                   &K,
                   const Vector<double>                       &F,
                   const std::vector<types::global_dof_index> &dofs,
                   const AffineConstraints<double>            &constraints,
                   TrilinosWrappers::SparseMatrix             *matrix,
                   TrilinosWrappers::MPI::Vector              &rhs) const;

      /** The friction rows of the nodes of a node-status pair (and the
       * held nodes of the others), each point adding its share. */
      void
      add_node_friction_rows(const ContactPoint    &point,
                             const PointEvaluation &e,
                             Vector<double>        &F) const;

      /** The derivatives of the friction rows of a node-status pair, the
       * status of each node fixed. */
      void
      add_node_friction_jacobian(const ContactPoint    &point,
                                 const PointEvaluation &e,
                                 FullMatrix<double>    &K) const;

      const Parameters        &parameters;
      const FESystem<dim>     &fe;
      const Surfaces<dim>     &surfaces;
      Pairing<dim>            &pairing;
      const Coefficients      &coefficients;
      NodeStatuses<dim>       &node_statuses;
      ActiveSetHistory<dim>   &history;
      const std::vector<bool> &newton_geometry_pair;
      MPI_Comm                 comm;
      // Written by assemble() (find_sticking_pins) only.
      std::set<types::global_dof_index> stick_pins;
    };
  } // namespace Contact
} // namespace Signorini

#endif
