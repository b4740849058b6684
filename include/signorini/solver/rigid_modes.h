#ifndef signorini_solver_rigid_modes_h
#define signorini_solver_rigid_modes_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <string>
#include <vector>

/**
 * Rigid-body motions of the bodies of a mesh, and the test whether the
 * Jacobian of an iterate holds each of them.
 *
 * A body is a connected part of the coarse mesh (bodies never share
 * vertices). Its rigid motions are the dim translations and the rotations
 * about its centroid (one in 2D, three in 3D; in an axisymmetric model only
 * the axial translation is rigid). Linear elasticity gives no stiffness to
 * them; a Dirichlet condition, a closed contact point (its normal, or its
 * friction once the point has a friction threshold) does. A motion that
 * nothing holds at an iterate makes the Jacobian singular: K t = 0 for its
 * nodal vector t. The commonest case is a body pushed along a contact
 * surface by a force, held tangentially by friction alone: at the first
 * iterate of a step the friction threshold of a point that has just closed
 * is zero (theory.md F3.3), and so is its tangential stiffness.
 *
 * find() evaluates K t per motion (one matrix-vector product each) and
 * compares the displacement rows and the multiplier rows with their own
 * scales; hold() adds, for this solve only, a spring of the stiffness of
 * the stiffest diagonal entry at one node of the body along the motion
 * (the node where the motion is largest, ties broken by position, so that
 * the choice does not depend on the MPI partition): the motion's share of
 * the update is then zero instead of whatever the factorisation makes of a
 * zero pivot.
 */
namespace Signorini
{
  namespace Solver
  {
    using namespace dealii;

    /** Number of rigid motions of a body in dim dimensions. */
    template <int dim>
    constexpr unsigned int n_rigid_modes = dim == 2 ? 3 : 6;

    /**
     * Component @p c at @p x of rigid motion @p m about @p centre: m < dim
     * the translation along e_m, then the rotations (2D: about z; 3D:
     * about x, y, z) with unit angular velocity.
     */
    template <int dim>
    double
    rigid_mode_value(const unsigned int m,
                     const unsigned int c,
                     const Point<dim>  &x,
                     const Point<dim>  &centre);

    /** "translation along x", "rotation about z", ... */
    template <int dim>
    std::string
    rigid_mode_name(const unsigned int m);

    template <int dim>
    class RigidModes
    {
    public:
      /** Mode @p mode of body @p body; with @p weights, the combination
       * sum_k weights[k] t_k of the body's modes (largest |weight| 1, at
       * @p mode): a motion that no single mode is, e.g. a translation
       * along an inclined roller. */
      struct Motion
      {
        unsigned int        body;
        unsigned int        mode;
        std::vector<double> weights;
      };

      /**
       * The motions of every body for the DoFs of @p dof_handler (its
       * first dim components), as vectors over @p owned_system (u DoFs
       * first, multipliers after: their entries are zero). DoFs with a
       * constraint that has entries (hanging nodes) are zero: they follow
       * their parents in the condensed system.
       */
      void
      setup(const Mapping<dim>              &mapping,
            const DoFHandler<dim>           &dof_handler,
            const AffineConstraints<double> &constraints,
            const IndexSet                  &owned_system,
            const bool                       axisymmetric,
            const MPI_Comm                   comm);

      /** The motions that @p K (u DoFs in [0, n_u)) does not hold: single
       * modes, or, for a body none of whose modes is free, combinations
       * of them (the smallest eigenvectors of the body's modes' Gram
       * matrix of K t against that of t). */
      std::vector<Motion>
      find(const TrilinosWrappers::SparseMatrix &K,
           const types::global_dof_index         n_u) const;

      /** Springs at one node per motion, for this solve (see above). */
      void
      hold(TrilinosWrappers::SparseMatrix &K,
           const types::global_dof_index   n_u,
           const std::vector<Motion>      &motions) const;

      /** "the body of material 1 (around (0.02, 0.005)): rigid
       * translation along x" */
      std::string
      describe(const Motion &motion) const;

    private:
      /** bodies (material, centroid) from the parts of @p tria; the part
       * of each coarse cell. */
      std::vector<unsigned int>
      find_bodies(const Triangulation<dim> &tria);

      /** The combinations of body @p b's modes that @p K does not hold,
       * from the scaled K t_k (@p Kt) of each mode. */
      std::vector<Motion>
      find_combinations(const unsigned int                                b,
                        const std::vector<TrilinosWrappers::MPI::Vector> &Kt,
                        const types::global_dof_index                     n_u,
                        const double scale_u,
                        const double scale_m) const;

      /** Largest diagonal entry of the u rows, largest u coupling of the
       * multiplier rows. */
      std::pair<double, double>
      scales(const TrilinosWrappers::SparseMatrix &K,
             const types::global_dof_index         n_u) const;

      struct Body
      {
        types::material_id                         material = 0;
        Point<dim>                                 centroid;
        std::vector<TrilinosWrappers::MPI::Vector> modes;
        std::vector<types::global_dof_index>       pins; // one per mode
      };
      std::vector<Body>         bodies;
      IndexSet                  owned;
      MPI_Comm                  comm    = MPI_COMM_SELF;
      unsigned int              n_modes = 0;
      std::vector<unsigned int> mode_ids; // rigid_mode_value numbers
    };
  } // namespace Solver
} // namespace Signorini

#endif
