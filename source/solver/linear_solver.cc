#include <deal.II/base/exceptions.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <signorini/solver/linear_solver.h>

namespace Signorini
{
  namespace Solver
  {
    template <int dim>
    LinearSolver<dim>::LinearSolver(const LinearSolverParameters &parameters)
      : parameters(parameters)
    {}

    template <int dim>
    LinearSolver<dim>::~LinearSolver() = default;


    template <int dim>
    void
    LinearSolver<dim>::set_null_space(const DoFHandler<dim> &dof_handler,
                                      const IndexSet &       locally_owned)
    {
      owned = locally_owned;
      if (parameters.type == LinearSolverType::direct)
        return;
      const unsigned int n_modes =
        parameters.rigid_body_modes ? (dim == 2 ? 3 : 6) : dim;
      modes.assign(n_modes, std::vector<double>(owned.n_elements(), 0.));

      // Support points and component of every locally owned displacement
      // DoF: the rigid-body motions evaluated there.
      const auto &fe = dof_handler.get_fe();
      const std::vector<Point<dim>> &unit_points = fe.get_unit_support_points();
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      MappingQ1<dim>                       mapping;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
              {
                const unsigned int c = fe.system_to_component_index(i).first;
                if (c >= dim || !owned.is_element(dofs[i]))
                  continue;
                const Point<dim> x =
                  mapping.transform_unit_to_real_cell(cell, unit_points[i]);
                const unsigned int k = owned.index_within_set(dofs[i]);
                modes[c][k]          = 1.;
                if (!parameters.rigid_body_modes)
                  continue;
                if (dim == 2)
                  modes[2][k] = (c == 0 ? -x[1] : x[0]);
                else
                  {
                    // rotations about z, x, y: omega x x
                    const double z = x[dim - 1];
                    modes[3][k]    = c == 0 ? -x[1] : c == 1 ? x[0] : 0.;
                    modes[4][k]    = c == 0 ? 0. : c == 1 ? -z : x[1];
                    modes[5][k]    = c == 0 ? z : c == 1 ? 0. : -x[0];
                  }
              }
          }
    }


    template <int dim>
    unsigned int
    LinearSolver<dim>::solve(const TrilinosWrappers::SparseMatrix &A,
                             TrilinosWrappers::MPI::Vector &       x,
                             const TrilinosWrappers::MPI::Vector & b)
    {
      if (parameters.type == LinearSolverType::direct)
        {
          SolverControl                               control(1, 0);
          TrilinosWrappers::SolverDirect::AdditionalData data(
            false, parameters.direct_package);
          TrilinosWrappers::SolverDirect solver(control, data);
          solver.solve(A, x, b);
          return 0;
        }

      TrilinosWrappers::PreconditionAMG                 amg;
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = true;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      Teuchos::ParameterList              ml_list;
      std::unique_ptr<Epetra_MultiVector> translations;
      data.set_parameters(ml_list, translations, A);

      const Epetra_Map &map = A.trilinos_matrix().DomainMap();
      null_space = std::make_unique<Epetra_MultiVector>(map, modes.size());
      AssertThrow(static_cast<unsigned int>(map.NumMyElements()) ==
                    owned.n_elements(),
                  ExcMessage("AMG null space: the matrix rows do not match "
                             "the locally owned DoFs; call set_null_space() "
                             "after setting up the system."));
      for (unsigned int m = 0; m < modes.size(); ++m)
        for (unsigned int k = 0; k < owned.n_elements(); ++k)
          (*null_space)[m][map.LID(static_cast<int>(
            owned.nth_index_in_set(k)))] = modes[m][k];
      ml_list.set("null space: type", "pre-computed");
      ml_list.set("null space: dimension", null_space->NumVectors());
      ml_list.set("null space: vectors", null_space->Values());
      amg.initialize(A, ml_list);

      SolverControl control(parameters.max_iterations,
                            parameters.relative_tolerance * b.l2_norm());
      if (parameters.type == LinearSolverType::cg)
        {
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          cg.solve(A, x, b, amg);
        }
      else
        {
          SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
            control,
            SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(100));
          gmres.solve(A, x, b, amg);
        }
      return control.last_step();
    }

    template class LinearSolver<2>;
    template class LinearSolver<3>;
  } // namespace Solver
} // namespace Signorini
