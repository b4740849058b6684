#ifndef signorini_bulk_assembler_h
#define signorini_bulk_assembler_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/boundary_conditions.h>
#include <signorini/material/history.h>
#include <signorini/material/interface.h>
#include <signorini/material/projected_volumetric_strain.h>

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <vector>

/**
 * The bulk part of the residual and its Jacobian: internal force from the
 * stress of each cell's constitutive model (Material::Interface), external
 * force from the body force and the Neumann conditions, for plane strain,
 * axisymmetric (x = r: the hoop strain u_r / r and the weight 2 pi r) and 3D
 * models.
 *
 * Kinematics (small strain): eps = sym grad u, as a 3D tensor whose
 * component (2, 2) is the strain normal to the plane in 2D (0 in plane
 * strain, u_r / r axisymmetric). With 'Finite element/Volumetric strain =
 * projected' (B-bar) the volumetric part of eps is replaced by the cell's
 * projected volumetric strain theta_bar (Material::ProjectedVolumetricStrain):
 *   eps_bar = eps + (theta_bar - tr eps) / 3 I,
 * for every model alike; the Jacobian uses the matching B-bar operator.
 *
 * Kinematics (finite strain, per material: Material::Interface::
 * kinematics()), total Lagrangian as in step-44: F = I + H with H the 3D
 * displacement gradient (H_33 = u_r / R axisymmetric), the model gives the
 * Kirchhoff stress tau and its spatial tangent c; with g_i = Grad N_i F^-1
 * the spatial gradient of shape function i and d_i = sym g_i,
 *   F_int,i = int tau : d_i dV,
 *   K_ij    = int d_i : c : d_j + g_i : (g_j tau) dV
 * (material and geometric stiffness), over the reference volume dV. A
 * Neumann pressure p then follows the deformed surface: the traction is
 * -p cof(F) N per reference area, with its derivative in K (the load
 * stiffness). A traction stays a dead load per reference area, the body
 * force one per reference volume.
 *
 * With 'Volumetric strain = projected' a finite-strain cell uses F_bar =
 * exp((theta_bar - ln J) / 3) F, theta_bar the cell's projection of ln J
 * (add_projected_finite_strain_cell()).
 *
 * Models with history (Material::History) see the values committed at the
 * end of the last converged step; update_history() commits new ones from a
 * converged solution.
 */
namespace Signorini
{
  namespace Bulk
  {
    using namespace dealii;

    template <int dim>
    using Materials =
      std::map<types::material_id, std::unique_ptr<Material::Interface<dim>>>;

    /** The 3D strain of a point from the in-plane strain @p strain and the
     * strain normal to the plane @p strain_33 (2D), with its volumetric part
     * replaced by @p theta_bar if given (B-bar). */
    template <int dim>
    SymmetricTensor<2, 3>
    point_strain(const SymmetricTensor<2, dim> &strain,
                 const double                   strain_33,
                 const double                  *theta_bar = nullptr)
    {
      const SymmetricTensor<2, 3> e = Material::to_3d<dim>(strain, strain_33);
      return theta_bar ? Material::with_volumetric(e, *theta_bar) : e;
    }

    /** An empty, closed AffineConstraints: as the row constraints of
     * AffineConstraints::distribute_local_to_global() or
     * add_entries_local_to_global() with other column constraints, it keeps
     * constrained rows as they are (the pinned rows, theory.md F8). */
    const AffineConstraints<double> &
    rows_as_they_are();


    template <int dim>
    class Assembler
    {
    public:
      /** @p neumann: one function per Neumann condition of @p parameters;
       * @p body_forces: that of each material, dim components. Functions
       * are evaluated at the time they are set to. */
      Assembler(
        const Parameters                                        &parameters,
        const Mapping<dim>                                      &mapping,
        const FESystem<dim>                                     &fe,
        const Materials<dim>                                    &materials,
        const std::vector<std::unique_ptr<FunctionParser<dim>>> &neumann,
        const BodyForces<dim>                                   &body_forces);

      /** The right-hand side of the linear system of a Jacobian whose
       * constraints differ from those of the residual (a first update
       * that moves prescribed values: -K_fd delta in @p rhs). */
      struct LinearSystemRhs
      {
        const AffineConstraints<double> &constraints;
        TrilinosWrappers::MPI::Vector   &rhs;
      };

      /** The Jacobian rows of pinned DoFs, kept for the rows of their
       * contact nodes (theory.md F8, pins): the rows of the DoFs in
       * @p dofs into @p matrix, columns condensed by the assembly's
       * constraints; with a first update, sum_c K_dc g_c of its prescribed
       * increments into @p shift (ghost-writable). */
      struct PinRows
      {
        const std::set<types::global_dof_index> &dofs;
        TrilinosWrappers::SparseMatrix          &matrix;
        TrilinosWrappers::MPI::Vector           &shift;
      };

      /**
       * Adds F_ext - F_int of @p solution (ghosted) into @p rhs and the
       * Jacobian into @p matrix (if not null), through @p constraints; adds
       * F_int and F_ext into @p internal_force and @p external_force (no
       * constraints: the reactions are their sums at the Dirichlet DoFs).
       * With @p linear_system, the Jacobian and F_ext - F_int once more go
       * through its constraints, into @p matrix and its rhs: the residual
       * and the linear system of a Newton iterate in one pass over the
       * cells. The models read their committed @p history. With a
       * @p matrix and @p pin_rows, the rows of its DoFs go there too.
       */
      void
      assemble(const DoFHandler<dim>               &dof_handler,
               const TrilinosWrappers::MPI::Vector &solution,
               const Material::History<dim>        &history,
               const AffineConstraints<double>     &constraints,
               TrilinosWrappers::SparseMatrix      *matrix,
               TrilinosWrappers::MPI::Vector       &rhs,
               TrilinosWrappers::MPI::Vector       &internal_force,
               TrilinosWrappers::MPI::Vector       &external_force,
               const LinearSystemRhs               *linear_system = nullptr,
               const PinRows                       *pin_rows = nullptr) const;

      /** F_ext alone (the Neumann loads and, @p with_body_force, the body
       * force, at the time of the functions) into @p external_force (owned;
       * overwritten), in the configuration of @p solution (ghosted).
       * Without the body force only the cells at the boundary are visited.
       */
      void
      assemble_external_force(
        const DoFHandler<dim>               &dof_handler,
        const TrilinosWrappers::MPI::Vector &solution,
        const bool                           with_body_force,
        TrilinosWrappers::MPI::Vector       &external_force) const;

      /** Commits the history of every quadrature point from the converged
       * @p solution (ghosted); nothing without a model with history. */
      void
      update_history(const DoFHandler<dim>               &dof_handler,
                     const TrilinosWrappers::MPI::Vector &solution,
                     Material::History<dim>              &history) const;

      /** The finite-strain cells of this rank that the last assemble()
       * found inverted: det F <= 0 at a bulk quadrature point or at one of
       * the points where the output evaluates the stress (the vertices, and
       * for degree 2 the points DataOut adds). Their internal force is NaN,
       * so the residual is not finite and Newton rejects the iterate. */
      struct Inversion
      {
        unsigned int n_cells = 0;
        /** The smallest det F of those cells and the centre of its cell. */
        double     smallest_J = 1.;
        Point<dim> where;

        /** Whether (J, centre) is to be named instead: a smaller det F, or
         * one within 1e-10 of it (a tie of symmetric cells, equal up to
         * round-off) at a lexicographically smaller centre, so that 1 and
         * N ranks name the same cell. */
        bool
        named_instead_by(const double J, const Point<dim> &centre) const
        {
          if (!(std::abs(J - smallest_J) <= 1e-10)) // also a NaN J
            return !(J >= smallest_J);
          for (unsigned int d = 0; d < dim; ++d)
            if (centre[d] != where[d])
              return centre[d] < where[d];
          return false;
        }

        /** For Utilities::MPI::all_gather(). */
        template <class Archive>
        void
        serialize(Archive &archive, const unsigned int)
        {
          archive &n_cells &smallest_J &where;
        }
      };

      const Inversion &
      inversion() const
      {
        return inverted;
      }

      /** The bulk quadrature rule (that of the history). */
      const Quadrature<dim> &
      quadrature() const
      {
        return cell_quadrature;
      }

    private:
      /** The rows of @p cell_matrix of the DoFs of @p pin_rows
       * (PinRows), columns through @p constraints, and the shift of a
       * @p first_update. */
      void
      add_pin_rows(const FullMatrix<double>                   &cell_matrix,
                   const std::vector<types::global_dof_index> &dofs,
                   const AffineConstraints<double>            &constraints,
                   const AffineConstraints<double>            *first_update,
                   const PinRows                              &pin_rows) const;

      /** The kinematics of one cell: FEValues, the 3D strain of each shape
       * function at each point (B, B-bar with the projection), the volume
       * element dV (2 pi r dA axisymmetric) and the 3D strain of the
       * solution at each point. */
      struct CellKinematics
      {
        CellKinematics(const Mapping<dim>    &mapping,
                       const FESystem<dim>   &fe,
                       const Quadrature<dim> &quadrature,
                       const bool             axisymmetric);

        FEValues<dim>                                   fe_values;
        Material::ProjectedVolumetricStrain<dim>        projection;
        std::vector<std::vector<SymmetricTensor<2, 3>>> B;
        std::vector<double>                             dV;
        std::vector<SymmetricTensor<2, 3>>              strain;
        std::vector<SymmetricTensor<2, dim>>            gradients;
        std::vector<Tensor<1, dim>>                     u_values;
        std::vector<double>                             theta_i, dtheta_bar;
        Vector<double>                                  local_u, theta_bar;
        // Finite strain: the 3D displacement gradient H of the solution and
        // the 3D gradient Grad N_i of each shape function at each point.
        std::vector<Tensor<2, dim>>            full_gradients;
        std::vector<Tensor<2, 3>>              H;
        std::vector<std::vector<Tensor<2, 3>>> grad_N;
        std::vector<Tensor<2, 3>>              g, g_tau;
        std::vector<SymmetricTensor<2, 3>>     d, c_d;
        // F, and F_bar with the projection (F-bar; else F); ln J.
        std::vector<Tensor<2, 3>>              F, F_bar;
        std::vector<double>                    log_J;
        bool                                   inverted = false;
        FullMatrix<double>                     Pi; // projection on points
        std::vector<std::vector<Tensor<2, 3>>> g_q, g_bar;
        std::vector<SymmetricTensor<2, 3>>     tau_q;
        std::vector<SymmetricTensor<4, 3>>     c_q;
        // The smallest det F at the bulk quadrature points; the output
        // points (QIterated trapezoid of the degree) and the solution there.
        double                      smallest_J = 1.;
        FEValues<dim>               output_points;
        std::vector<Tensor<2, dim>> output_gradients;
        std::vector<Tensor<1, dim>> output_u;
      };

      /** The finite-strain part of cell_kinematics(): H, Grad N_i, F, ln J
       * and F_bar. */
      void
      finite_strain_kinematics(CellKinematics &k) const;

      /** Finite strain: whether @p cell keeps det F > 0 at its quadrature
       * points (finite_strain_kinematics() before) and at its output
       * points; if not, counts it in #inverted. A bilinear element can
       * invert at a corner while its Gauss points stay positive; its
       * stress written there would be NaN. */
      bool
      deformation_valid(
        const typename DoFHandler<dim>::active_cell_iterator &cell,
        const TrilinosWrappers::MPI::Vector                  &solution,
        CellKinematics                                       &k) const;

      /** Finite strain with 'Volumetric strain = projected' (F-bar):
       * internal force and tangent of the whole cell of @p k. */
      void
      add_projected_finite_strain_cell(
        const Material::Interface<dim>             &material,
        const std::vector<ArrayView<const double>> &history,
        CellKinematics                             &k,
        Vector<double>                             &f_int,
        FullMatrix<double>                         *matrix) const;

      /** Fills @p k for @p cell and @p solution with the @p kinematics of
       * the cell's material. */
      void
      cell_kinematics(
        const typename DoFHandler<dim>::active_cell_iterator &cell,
        const TrilinosWrappers::MPI::Vector                  &solution,
        const Material::Kinematics                            kinematics,
        CellKinematics                                       &k) const;

      /** Small strain: internal force and (if @p matrix) tangent of point
       * @p q of the cell of @p k into @p f_int and @p matrix. */
      void
      add_small_strain_point(const Material::Interface<dim> &material,
                             const ArrayView<const double>  &history,
                             const unsigned int              q,
                             CellKinematics                 &k,
                             Vector<double>                 &f_int,
                             FullMatrix<double>             *matrix) const;

      /** Finite strain: the same, total Lagrangian (class documentation). */
      void
      add_finite_strain_point(const Material::Interface<dim> &material,
                              const ArrayView<const double>  &history,
                              const unsigned int              q,
                              CellKinematics                 &k,
                              Vector<double>                 &f_int,
                              FullMatrix<double>             *matrix) const;

      /** The body force of the cell of @p k into @p cell_fext. */
      void
      add_body_force(const types::material_id material_id,
                     const CellKinematics    &k,
                     Vector<double>          &cell_fext) const;

      /** The face values of the Neumann loads (add_neumann()). */
      std::unique_ptr<FEFaceValues<dim>>
      neumann_face_values() const;

      /** Neumann tractions of the boundary faces of @p cell into
       * @p cell_fext; at finite strain a pressure follows the deformed
       * face of @p solution, and its load stiffness goes into
       * @p cell_matrix if given. */
      void
      add_neumann(const typename DoFHandler<dim>::active_cell_iterator &cell,
                  const TrilinosWrappers::MPI::Vector &solution,
                  FEFaceValues<dim>                   &fe_face_values,
                  Vector<double>                      &cell_fext,
                  FullMatrix<double>                  *cell_matrix) const;

      /** The follower pressure @p p at face point @p q of a finite-strain
       * cell: its traction into @p cell_fext and, if given, minus its
       * derivative into @p cell_matrix. */
      void
      add_follower_pressure(const FEFaceValues<dim> &fe_face_values,
                            const unsigned int       q,
                            const double             p,
                            const Tensor<2, 3>      &H,
                            const double             ring,
                            Vector<double>          &cell_fext,
                            FullMatrix<double>      *cell_matrix) const;

      const Parameters                                        &parameters;
      const Mapping<dim>                                      &mapping;
      const FESystem<dim>                                     &fe;
      const Materials<dim>                                    &materials;
      const std::vector<std::unique_ptr<FunctionParser<dim>>> &neumann;
      const BodyForces<dim>                                   &body_forces;
      const QGauss<dim>                                        cell_quadrature;
      mutable Inversion                                        inverted;
    };
  } // namespace Bulk
} // namespace Signorini

#endif
