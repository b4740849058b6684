#ifndef signorini_contact_output_h
#define signorini_contact_output_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>
#include <signorini/contact/contact_law.h>
#include <signorini/contact/node_statuses.h>
#include <signorini/contact/pairing.h>
#include <signorini/contact/surfaces.h>

#include <limits>
#include <string>
#include <utility>
#include <vector>

/**
 * What the contact points hold after an evaluation, for the user: the
 * per-pair summary (forces, counts, largest pressure and gap), the point
 * records gathered on every rank, the slave-surface CSV, the nodal fields
 * of the VTU, and the cells of the active contact zone (adaptive
 * refinement). It reads the points; it changes nothing.
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    template <int dim>
    class Output
    {
    public:
      Output(const Parameters        &parameters,
             const FESystem<dim>     &fe,
             const DoFHandler<dim>   &dof_handler,
             const Surfaces<dim>     &surfaces,
             const Pairing<dim>      &pairing,
             const NodeStatuses<dim> &node_statuses,
             const MPI_Comm           comm);

      /** Per-pair results of the last evaluation, summed over ranks. */
      struct PairSummary
      {
        // Contact force the slave exerts on the master [N] (the force on
        // the slave is its opposite).
        Tensor<1, dim> force;
        double         p_max = 0; // largest p = -lambda at a point [Pa]
        // Sum of the weights of the closed points: the contact area [m^2]
        // (plane strain: the contact length [m] per unit thickness).
        double area = 0;
        // Sums of w |f . n| and w |P f| over the points, each in its own
        // contact frame [N].
        double       normal_force_local = 0, tangential_force_local = 0;
        unsigned int n_contact = 0, n_stick = 0, n_slip = 0, n_points = 0;
        // Points that found the master, and their largest gap (g > 0:
        // interpenetration; -infinity when none is paired) [m].
        unsigned int   n_paired  = 0;
        double         max_gap   = -std::numeric_limits<double>::infinity();
        double         face_size = 0;         // mean slave face size [m]
        bool           rigid     = false;     // master is a rigid obstacle
        Tensor<1, dim> obstacle_displacement; // its prescribed motion [m]
      };
      std::vector<PairSummary>
      summary() const;

      /** Values at the contact points, gathered on every rank, sorted by
       * (pair, reference coordinates). */
      struct PointRecord
      {
        unsigned int       pair;
        Point<dim>         x;        // reference position
        double             weight;   // quadrature weight x reference Jacobian
        double             p;        // -lambda
        Tensor<1, dim - 1> traction; // mu lambda Lambda (tangent coordinates)
        double             gap;
        Tensor<1, dim - 1> slip; // v in tangent coordinates
        PointStatus        status;
        bool               paired;

        // Utilities::MPI::all_gather() sends records through this.
        template <class Archive>
        void
        serialize(Archive &archive, const unsigned int)
        {
          archive &pair &x &weight &p &traction &gap &slip &status &paired;
        }
      };
      std::vector<PointRecord>
      gather_points() const;

      /** One slave node: its reference and deformed position, the nodal
       * values of nodal_fields() (the surface VTU's), and its status (its
       * own for a pair with statuses per node, else that of its nearest
       * contact point); paired: that point found a master face. */
      struct NodeRecord
      {
        unsigned int       pair;
        Point<dim>         x;          // reference position
        Point<dim>         x_deformed; // x + u
        double             p;          // pressure that carries force
        Tensor<1, dim - 1> traction;   // mu lambda Lambda (tangent basis)
        double             gap;        // > 0: interpenetration
        Tensor<1, dim - 1> slip;       // v in the tangent basis
        PointStatus        status;
        bool               paired;

        template <class Archive>
        void
        serialize(Archive &archive, const unsigned int)
        {
          archive &pair &x &x_deformed &p &traction &gap &slip &status &paired;
        }
      };

      /** The slave nodes, each once, gathered on rank 0 (empty elsewhere),
       * sorted by (pair, reference position); @p u: the ghosted
       * displacement (collective). */
      std::vector<NodeRecord>
      gather_nodes(const TrilinosWrappers::MPI::Vector &u) const;

      /** Writes the per-step slave-surface CSV, one row per slave node
       * (collective; rank 0 writes, under a temporary name renamed into
       * place); @p u: the ghosted displacement. Returns "" or why the write
       * failed (rank 0). */
      std::string
      write_csv(const std::string                   &filename,
                const TrilinosWrappers::MPI::Vector &u) const;

      /**
       * Nodal fields on the displacement mesh for the VTU (zero away from
       * the slave surface): p, gap, status (0 free, 1 stick, 2 slip or
       * closed without friction), tangential traction and slip (dim-1
       * each), as weighted averages of the point values; the status of a
       * pair with statuses per node is the node's own. Returns (name,
       * vector on @p scalar_dofs) pairs.
       */
      std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector>>
      nodal_fields(const DoFHandler<dim> &scalar_dofs) const;

      /** Locally owned cells with a face in the active contact zone: slave
       * faces with a point in contact at the last evaluation, and master
       * faces such a point is paired with (adaptive refinement). */
      std::vector<typename DoFHandler<dim>::active_cell_iterator>
      contact_zone_cells() const;

    private:
      /** The normal and tangential forces of the node-status pairs from
       * the per-node sums @p nodal (force, then normal; compressed here),
       * each owned node once, into @p result. */
      void
      add_node_forces(std::vector<TrilinosWrappers::MPI::Vector> &nodal,
                      std::vector<PairSummary>                   &result) const;

      /** The status of a multiplier node of a pair with statuses per node,
       * as a PointStatus value. */
      double
      node_status(const types::global_dof_index lambda_dof) const;

      const Parameters        &parameters;
      const FESystem<dim>     &fe;
      const DoFHandler<dim>   &dof_handler;
      const Surfaces<dim>     &surfaces;
      const Pairing<dim>      &pairing;
      const NodeStatuses<dim> &node_statuses;
      const MPI_Comm           comm;
    };
  } // namespace Contact
} // namespace Signorini

#endif
