#ifndef signorini_bulk_boundary_conditions_h
#define signorini_bulk_boundary_conditions_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>

#include <array>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

/**
 * The data of subsection 'Boundary conditions' as functions of (x, t):
 * Dirichlet values (as constraint lines), Neumann tractions and the body
 * force (evaluated by Bulk::Assembler), and what the supports carry (the
 * reaction and mean displacement of each Dirichlet condition).
 */
namespace Signorini
{
  namespace Bulk
  {
    using namespace dealii;

    /** The body force per unit volume of each material (by material id),
     * dim components of x, y, z and the time set. */
    template <int dim>
    using BodyForces =
      std::map<types::material_id, std::unique_ptr<FunctionParser<dim>>>;

    /** Per Dirichlet condition: the force of the supports on the body [N],
     * the mean displacement of the DoFs it constrains, and which components
     * it constrains (statistics.csv: force-displacement curves). */
    template <int dim>
    struct Supports
    {
      std::vector<Tensor<1, dim>>        reactions;
      std::vector<Tensor<1, dim>>        displacement;
      std::vector<std::array<bool, dim>> components;
      /** The support force at each locally owned held node, the sum of
       * what reactions charges to each of its conditions, keyed by the
       * node's x DoF (the force balance of each body sums them). */
      std::vector<std::pair<types::global_dof_index, Tensor<1, dim>>>
        node_forces;
    };

    template <int dim>
    class BoundaryConditions
    {
    public:
      /** Parses the expressions of @p parameters (an InputError names the
       * subsection of an expression that does not parse). */
      /** The conditions of @p parameters and the body force of each of
       * @p materials. */
      BoundaryConditions(const BoundaryConditionParameters     &parameters,
                         const std::vector<MaterialParameters> &materials);

      /** InputError if a condition names a boundary id that is not in
       * @p ids (the ids of the mesh). */
      void
      check_boundary_ids(const std::set<types::boundary_id> &ids) const;

      /** A body force other than 0 (on some material). */
      bool
      has_body_force() const;

      /** Some Neumann condition, or a body force: the run has loads besides
       * its prescribed values. */
      bool
      has_loads() const
      {
        return !neumann_functions.empty() || has_body_force();
      }

      /** Sets the time of the Neumann tractions and the body force. */
      void
      set_load_time(const double time);

      const std::vector<std::unique_ptr<FunctionParser<dim>>> &
      neumann() const
      {
        return neumann_functions;
      }

      /** The body force of each material, by material id. */
      const BodyForces<dim> &
      body_forces() const
      {
        return body_force_functions;
      }

      /**
       * Adds the Dirichlet lines at @p time: the values into @p values, the
       * same lines with zero values into @p update. A DoF constrained
       * already (a hanging node, an earlier condition) is left as it is.
       * An 'At point' condition takes the boundary vertices within
       * @p tolerance of its point. Remembers the locally owned DoFs each
       * condition constrains (supports()).
       */
      void
      add_dirichlet_constraints(const double               time,
                                const Mapping<dim>        &mapping,
                                const DoFHandler<dim>     &dof_handler,
                                const double               tolerance,
                                AffineConstraints<double> &values,
                                AffineConstraints<double> &update);

      /** The DoFs whose line an 'At point' condition added (locally
       * relevant): a pin at a point, where a contact node's support force
       * and its friction share one DoF (theory.md F8, pins). */
      const std::set<types::global_dof_index> &
      point_lines() const
      {
        return point_line_dofs;
      }

      /** Collective: the reactions (the sums of @p support_force, owned,
       * over the DoFs of each condition; below 1e-12 @p force_scale
       * printed as zero) and the mean of @p solution there. */
      Supports<dim>
      supports(const TrilinosWrappers::MPI::Vector &support_force,
               const TrilinosWrappers::MPI::Vector &solution,
               const double                         force_scale,
               const MPI_Comm                       mpi_communicator) const;

      /** Collective: for each Dirichlet or Neumann expression that is not
       * finite at time @p t at a vertex of a locally owned cell of
       * @p triangulation, "; subsection ... is not finite at t = ..., x =
       * (...)"; "" if all are finite. */
      std::string
      non_finite(const double              t,
                 const Triangulation<dim> &triangulation,
                 const MPI_Comm            mpi_communicator) const;

    private:
      /** The lines of Dirichlet condition @p k with Components = normal or
       * tangential (deal.II's normal-flux constraints). */
      void
      add_flux_constraint(const unsigned int         k,
                          const Mapping<dim>        &mapping,
                          const DoFHandler<dim>     &dof_handler,
                          AffineConstraints<double> &values,
                          AffineConstraints<double> &update);

      /** The lines of Dirichlet condition @p k with Components = direction:
       * u.d = value at each node of its boundaries. */
      void
      add_direction_constraint(const unsigned int         k,
                               const Mapping<dim>        &mapping,
                               const DoFHandler<dim>     &dof_handler,
                               AffineConstraints<double> &values,
                               AffineConstraints<double> &update);

      /** The DoFs of the vertices of boundary faces of Dirichlet condition
       * @p k at its 'At point' (within @p tolerance). */
      void
      add_point_constraint(const unsigned int         k,
                           const DoFHandler<dim>     &dof_handler,
                           const double               tolerance,
                           AffineConstraints<double> &values,
                           AffineConstraints<double> &update);

      /** Every component of the locally owned DoFs of @p nodes: the DoFs
       * whose support force is the reaction of condition @p k. */
      void
      record_node_dofs(const unsigned int          k,
                       const std::map<std::array<types::global_dof_index, dim>,
                                      Point<dim>> &nodes,
                       const IndexSet             &owned);

      const BoundaryConditionParameters                &parameters;
      std::vector<std::unique_ptr<FunctionParser<dim>>> dirichlet_functions;
      std::vector<std::unique_ptr<FunctionParser<dim>>> neumann_functions;
      BodyForces<dim>                                   body_force_functions;
      bool                                              any_body_force = false;
      /** Records that condition @p k holds @p node (its DoFs, one per
       * component) by a line with coefficients @p a (a . u = g), if this
       * rank owns the node. */
      void
      hold(const unsigned int                              k,
           const std::array<types::global_dof_index, dim> &node,
           const Tensor<1, dim>                           &a);

      // A node held by Dirichlet lines, and the (condition, coefficient
      // vector) of each line added there (a node that an earlier condition
      // holds already gets no line of a later one along the same
      // direction): supports() shares its support force among them.
      struct HeldNode
      {
        std::array<types::global_dof_index, dim>             dofs;
        std::vector<std::pair<unsigned int, Tensor<1, dim>>> relations;
      };
      // The locally owned held nodes, and their index by DoFs; written by
      // add_dirichlet_constraints() only.
      std::vector<HeldNode> held_nodes;
      std::map<std::array<types::global_dof_index, dim>, std::size_t>
               held_index;
      IndexSet locally_owned;
      // Per Dirichlet condition: the locally owned (DoF, component) pairs
      // of its boundaries (the mean displacement), sorted.
      std::vector<std::vector<std::pair<types::global_dof_index, unsigned int>>>
        dirichlet_dofs;
      // The DoFs of the lines 'At point' conditions added; written by
      // add_dirichlet_constraints() only.
      std::set<types::global_dof_index> point_line_dofs;
    };
  } // namespace Bulk
} // namespace Signorini

#endif
