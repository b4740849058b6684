#ifndef signorini_contact_surfaces_h
#define signorini_contact_surfaces_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/assembler.h>
#include <signorini/contact/surface_data.h>

#include <map>
#include <set>
#include <vector>

/**
 * The contact surfaces (theory.md F1 and 8): the slave faces of this
 * rank with their multiplier unknowns, the master faces of every rank, the
 * slave nodes with their exclusions at Dirichlet conditions and their
 * hanging-node weights, and the constraint lines this adds. setup() builds
 * them from the mesh; afterwards they are read only, by pairing, statuses,
 * assembly and output (ContactProblem).
 *
 * The multipliers are numbered after the displacements, in one system index
 * space:
 *   [0, n_u)                       displacement u (the DoFHandler's numbers)
 *   [n_u, n_u + n_l)               lambda, one per slave node
 *   [n_u + n_l, n_system)          Lambda, dim-1 per node of a frictional pair
 * A slave node is owned by the rank that owns its x-displacement DoF.
 *
 * Every rank keeps the master faces of all ranks (positions of their nodes
 * and DoF numbers: surface data only), the multiplier numbers of all slave
 * nodes, and the constraint lines of the master DoFs.
 *
 * The current position x = X + u of a point of a slave or master face is
 * interpolated here and nowhere else (slave_position(), master_position(),
 * master_increment(), master_nodes()).
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    template <int dim>
    class Surfaces
    {
    public:
      Surfaces(const Parameters           &parameters,
               const Mapping<dim>         &mapping,
               const FESystem<dim>        &fe,
               const DoFHandler<dim>      &dof_handler,
               const Bulk::Materials<dim> &materials,
               const MPI_Comm              comm);

      /** Per pair, over all ranks: the mean slave face size h [m] and the
       * largest representative moduli of the slave body and of a meshed
       * master (0 for a rigid obstacle) [Pa]. */
      struct PairScales
      {
        std::vector<double> face_size, slave_modulus, master_modulus;
      };

      /** What setup() reports (summed over all ranks). */
      struct Counts
      {
        unsigned int n_excluded_contact = 0, n_excluded_friction = 0,
                     n_held_tangent = 0, n_hanging = 0, n_axis = 0;
      };

      /**
       * Finds the slave and master faces of every pair, numbers the
       * multipliers and decides the exclusions from the displacement
       * constraints (hanging nodes and Dirichlet) of the locally relevant
       * DoFs @p u_constraints. The faces of the pairs marked in
       * @p dual_pair get the dual multiplier basis. @p pins: the DoFs
       * whose line pins a point ('At point' conditions; theory.md F8). An
       * input error if a pair's boundary ids name no face of the mesh.
       */
      Counts
      setup(const AffineConstraints<double>         &u_constraints,
            const IndexSet                          &owned_u,
            const std::vector<bool>                 &dual_pair,
            const std::set<types::global_dof_index> &pins);

      const PairScales &
      pair_scales() const
      {
        return scales;
      }

      types::global_dof_index
      n_u() const
      {
        return n_displacements;
      }
      types::global_dof_index
      n_lambda() const
      {
        return n_lambdas;
      }
      types::global_dof_index
      n_friction() const
      {
        return n_frictions;
      }
      types::global_dof_index
      n_system() const
      {
        return n_displacements + n_lambdas + n_frictions;
      }

      /** Owned multiplier indices (system numbering). */
      const IndexSet &
      owned_multipliers() const
      {
        return owned;
      }
      /** Indices this rank reads or writes besides its locally relevant
       * displacement DoFs: master face DoFs, multipliers of its slave faces
       * and constraint parents. */
      const IndexSet &
      extra_relevant() const
      {
        return extra;
      }
      /** The multiplier part of extra_relevant(): the ghosts of vectors
       * over the multipliers alone. */
      const IndexSet &
      multiplier_ghosts() const
      {
        return ghost_multipliers;
      }

      /** A vector of the system's layout that takes additions to the
       * multipliers of this rank's slave faces (compress(add) sums them
       * on their owners); only its multiplier entries are used. (Over the
       * multipliers alone its indices would not start at 0, which
       * deal.II's Trilinos vectors require: size() is the span of the
       * indices.) */
      TrilinosWrappers::MPI::Vector
      writable_multipliers() const
      {
        TrilinosWrappers::MPI::Vector v;
        v.reinit(owned_system, ghost_multipliers, comm, true);
        return v;
      }
      /** A ghosted vector of the system's layout that reads the
       * multipliers of this rank's slave faces (see above). */
      TrilinosWrappers::MPI::Vector
      ghosted_multipliers() const
      {
        return TrilinosWrappers::MPI::Vector(owned_system,
                                             ghost_multipliers,
                                             comm);
      }

      /** This rank's slave faces (locally owned cells). */
      const std::vector<SlaveFace<dim>> &
      slave_faces() const
      {
        return slaves;
      }
      /** The master faces of all ranks, sorted by their key. */
      const std::vector<MasterFace<dim>> &
      master_faces() const
      {
        return masters;
      }
      /** Every slave node, keyed by its x-displacement DoF. */
      const std::map<types::global_dof_index, NodeInfo> &
      nodes() const
      {
        return node_info;
      }

      /** A slave node whose one held tangent a pin holds (NodeInfo::pin):
       * the pinned DoF, the node's multipliers, and a, the held tangent
       * in the node's frame (1 in 2D). */
      struct Pin
      {
        types::global_dof_index lambda, friction;
        Tensor<1, dim - 1>      a;
      };
      /** Every pinned slave node of any rank, keyed by the pinned DoF. */
      const std::map<types::global_dof_index, Pin> &
      pins() const
      {
        return pin_nodes;
      }
      /** The cell of a master face this rank owns (own_cell >= 0). */
      const typename DoFHandler<dim>::active_cell_iterator &
      master_cell(const MasterFace<dim> &face) const
      {
        return own_master_cells[face.own_cell];
      }
      /** Nodes of a face (FE_Q<dim-1> of the element degree). */
      unsigned int
      n_face_nodes() const
      {
        return face_fe.n_dofs_per_cell();
      }

      /** Adds the multiplier lines (hanging slave nodes, excluded nodes)
       * and the master DoF lines known to other ranks to @p constraints. */
      void
      add_constraint_lines(AffineConstraints<double> &constraints) const;

      /** x = X + sum_l psi_l u_l on slave face @p f at the point of
       * reference position @p x_ref and node shape values @p psi. */
      Point<dim>
      slave_position(const unsigned int                   f,
                     const std::vector<double>           &psi,
                     const Point<dim>                    &x_ref,
                     const TrilinosWrappers::MPI::Vector &state) const;
      /** x = sum_k N_k (X_k + u_k) on master face @p m. */
      Point<dim>
      master_position(const unsigned int                   m,
                      const std::vector<double>           &N,
                      const TrilinosWrappers::MPI::Vector &state) const;
      /** sum_k N_k (u_k - u0_k) on master face @p m: its displacement
       * increment from @p start. */
      Tensor<1, dim>
      master_increment(const unsigned int                   m,
                       const std::vector<double>           &N,
                       const TrilinosWrappers::MPI::Vector &state,
                       const TrilinosWrappers::MPI::Vector &start) const;
      /** Current positions of the nodes of master face @p m and a point
       * inside its cell (orientation of the normal). */
      void
      master_nodes(const unsigned int                   m,
                   const TrilinosWrappers::MPI::Vector &state,
                   std::vector<Point<dim>>             &x,
                   Point<dim>                          &inside) const;

      /**
       * The multipliers of @p state as a field on the displacement DoFs,
       * for solution transfer across refinement: at a slave node,
       * component 0 holds lambda and components 1..dim-1 hold Lambda; zero
       * elsewhere. Writes the owned entries of @p field (displacement
       * layout, no ghosts).
       */
      void
      multipliers_to_field(const TrilinosWrappers::MPI::Vector &state,
                           TrilinosWrappers::MPI::Vector       &field) const;

      /** The inverse of multipliers_to_field(): the owned multipliers of
       * @p state_owned from the ghosted @p field (after setup() on the new
       * mesh). */
      void
      multipliers_from_field(const TrilinosWrappers::MPI::Vector &field,
                             TrilinosWrappers::MPI::Vector &state_owned) const;

    private:
      // What setup() collects from this rank's boundary (surfaces.cc).
      struct Scan;
      Scan
      scan_boundary(const AffineConstraints<double> &u_constraints);
      void
      add_slave_face(const typename DoFHandler<dim>::active_cell_iterator &cell,
                     const unsigned int                                    f,
                     const unsigned int                                    p,
                     const std::vector<types::global_dof_index> &cell_dofs,
                     Scan                                       &scan);
      void
      add_master_face(
        const typename DoFHandler<dim>::active_cell_iterator &cell,
        const unsigned int                                    f,
        const unsigned int                                    p,
        const std::vector<types::global_dof_index>           &cell_dofs,
        const AffineConstraints<double>                      &u_constraints,
        Scan                                                 &scan);
      /** Face size and moduli per pair, over all ranks. */
      void
      sum_pair_scales(const Scan &scan);
      /** Every rank's slave nodes (@p own: this rank's) into node_info
       * and pin_nodes, counted. */
      Counts
      gather_node_info(
        const std::vector<std::pair<types::global_dof_index, NodeInfo>> &own);
      /** Numbers the multipliers of the owned slave nodes after the
       * displacements, decides their exclusions and hanging weights, and
       * gathers every node's from all ranks. */
      Counts
      number_multipliers(const Scan                              &scan,
                         const IndexSet                          &owned_u,
                         const AffineConstraints<double>         &u_constraints,
                         const std::set<types::global_dof_index> &pins);
      /** Master faces and the constraint lines of their DoFs from all
       * ranks; the ghost index sets. */
      void
      gather_master_faces(Scan &scan);
      /** Multiplier DoFs, exclusions and dual basis of each slave face. */
      void
      finish_slave_faces(const std::vector<bool> &dual_pair);
      /** Axisymmetric: the closure of the multipliers of slave nodes on
       * the axis of quadratic faces, whose weight is zero or nearly
       * (NodeInfo::closure); returns their number over all ranks. */
      unsigned int
      close_axis_multipliers();
      /** The dual multiplier basis of @p face (SlaveFace::dual). */
      std::vector<double>
      dual_basis(const SlaveFace<dim> &face) const;

      const Parameters           &parameters;
      const Mapping<dim>         &mapping;
      const FESystem<dim>        &fe;
      const DoFHandler<dim>      &dof_handler;
      const Bulk::Materials<dim> &materials;
      MPI_Comm                    comm;
      FE_Q<dim - 1>               face_fe; // face parametrisation

      PairScales              scales;
      types::global_dof_index n_displacements = 0, n_lambdas = 0,
                              n_frictions = 0;
      // owned: this rank's multipliers; owned_system: its displacements
      // and multipliers.
      IndexSet owned, owned_system, extra, ghost_multipliers;
      std::map<types::global_dof_index, NodeInfo> node_info; // key: x-dof
      // Written with node_info (gather_node_info).
      std::map<types::global_dof_index, Pin> pin_nodes;
      std::vector<SlaveFace<dim>>            slaves;
      std::vector<MasterFace<dim>>           masters;
      // The cells of the master faces this rank owns (MasterFace::own_cell).
      std::vector<typename DoFHandler<dim>::active_cell_iterator>
        own_master_cells;
      // Constraint lines of master DoFs, from their owners.
      std::vector<MasterLine> master_lines;
    };
  } // namespace Contact
} // namespace Signorini

#endif
