#include <deal.II/base/exceptions.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <signorini/base/errors.h>
#include <signorini/solver/linear_solver.h>

#include <algorithm>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>

namespace Signorini
{
  namespace Solver
  {
    template <int dim>
    LinearSolver<dim>::LinearSolver(const LinearSolverParameters &parameters)
        : parameters(parameters)
    {
    }

    template <int dim>
    LinearSolver<dim>::~LinearSolver() = default;


    template <int dim>
    void
    LinearSolver<dim>::set_null_space(const Mapping<dim>    &mapping,
                                      const DoFHandler<dim> &dof_handler,
                                      const IndexSet        &locally_owned)
    {
      // New DoFs: a kept hierarchy is of the old ones.
      kept_amg.reset();
      kept_A.reset();
      owned = locally_owned;
      if (parameters.type == LinearSolverType::direct)
        return;
      const unsigned int n_modes =
        parameters.rigid_body_modes ? (dim == 2 ? 3 : 6) : dim;
      modes.assign(n_modes, std::vector<double>(owned.n_elements(), 0.));

      // Support points and component of every locally owned displacement
      // DoF: the rigid-body motions evaluated there.
      const auto                    &fe          = dof_handler.get_fe();
      const std::vector<Point<dim>> &unit_points = fe.get_unit_support_points();
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
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
    void
    LinearSolver<dim>::set_bulk_linear(const bool linear)
    {
      bulk_linear = linear;
    }


    template <int dim>
    void
    LinearSolver<dim>::initialize_amg(TrilinosWrappers::PreconditionAMG    &amg,
                                      const TrilinosWrappers::SparseMatrix &A)
    {
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = true;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.003;
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
          (*null_space)[m]
                       [map.LID(static_cast<int>(owned.nth_index_in_set(k)))] =
                         modes[m][k];
      ml_list.set("null space: type", "pre-computed");
      ml_list.set("null space: dimension", null_space->NumVectors());
      ml_list.set("null space: vectors", null_space->Values());
      amg.initialize(A, ml_list);
    }


    template <int dim>
    void
    LinearSolver<dim>::set_multipliers(const types::global_dof_index n_u_,
                                       const IndexSet &owned_multipliers)
    {
      n_u     = n_u_;
      owned_m = IndexSet(owned_multipliers.size() - n_u);
      for (const auto i : owned_multipliers)
        owned_m.add_index(i - n_u);
      owned_m.compress();
    }


    namespace
    {
      // Copies the entries of the locally owned rows of @p M whose row and
      // column lie in the given ranges ([begin, end) in the system
      // numbering) into a new matrix with rows @p rows and columns @p cols
      // numbered from the range starts.
      void
      extract_block(const TrilinosWrappers::SparseMatrix &M,
                    const types::global_dof_index         row_begin,
                    const types::global_dof_index         row_end,
                    const types::global_dof_index         col_begin,
                    const types::global_dof_index         col_end,
                    const IndexSet                       &rows,
                    const IndexSet                       &cols,
                    TrilinosWrappers::SparseMatrix       &block,
                    const MPI_Comm                        comm)
      {
        // Raw Epetra row views: local rows, local column ids.
        const Epetra_CrsMatrix &E = M.trilinos_matrix();
        std::vector<std::vector<types::global_dof_index>> columns;
        std::vector<std::vector<double>>                  values;
        std::vector<types::global_dof_index>              row_ids;
        for (int lr = 0; lr < E.NumMyRows(); ++lr)
          {
            const auto r =
              static_cast<types::global_dof_index>(E.RowMap().GID64(lr));
            if (r < row_begin || r >= row_end)
              continue;
            int     n;
            double *v;
            int    *c;
            E.ExtractMyRowView(lr, n, v, c);
            row_ids.push_back(r - row_begin);
            columns.emplace_back();
            values.emplace_back();
            for (int k = 0; k < n; ++k)
              {
                const auto g =
                  static_cast<types::global_dof_index>(E.ColMap().GID64(c[k]));
                if (g >= col_begin && g < col_end)
                  {
                    columns.back().push_back(g - col_begin);
                    values.back().push_back(v[k]);
                  }
              }
          }
        TrilinosWrappers::SparsityPattern sp(rows, cols, comm);
        for (unsigned int k = 0; k < row_ids.size(); ++k)
          sp.add_entries(row_ids[k], columns[k].begin(), columns[k].end());
        sp.compress();
        block.reinit(sp);
        for (unsigned int k = 0; k < row_ids.size(); ++k)
          block.set(row_ids[k], columns[k], values[k]);
        block.compress(VectorOperation::insert);
      }

      // f(row, column, value) for every stored entry of the locally owned
      // rows of @p M (global indices).
      template <class F>
      void
      for_each_entry(const TrilinosWrappers::SparseMatrix &M, const F &f)
      {
        const Epetra_CrsMatrix &E = M.trilinos_matrix();
        for (int lr = 0; lr < E.NumMyRows(); ++lr)
          {
            int     n;
            double *v;
            int    *c;
            E.ExtractMyRowView(lr, n, v, c);
            const auto r =
              static_cast<types::global_dof_index>(E.RowMap().GID64(lr));
            for (int k = 0; k < n; ++k)
              f(r,
                static_cast<types::global_dof_index>(E.ColMap().GID64(c[k])),
                v[k]);
          }
      }

      // P^-1 of the block lower-triangular preconditioner [A 0; C S].
      class BlockPreconditioner
      {
      public:
        BlockPreconditioner(const TrilinosWrappers::PreconditionAMG &amg,
                            const TrilinosWrappers::SparseMatrix    &C,
                            TrilinosWrappers::SolverDirect          &schur,
                            const IndexSet                          &owned_u,
                            const IndexSet                          &owned_m,
                            const MPI_Comm                           comm)
            : amg(amg)
            , C(C)
            , schur(schur)
            , owned_u(owned_u)
            , owned_m(owned_m)
            , f(owned_u, comm)
            , y(owned_u, comm)
            , g(owned_m, comm)
            , z(owned_m, comm)
        {
        }

        // A system vector holds this rank's u entries first and its
        // multipliers after them (the owned system indices are sorted and
        // the u indices come first), so the blocks are copied as the two
        // contiguous parts of the local array, without global lookups.
        void
        vmult(TrilinosWrappers::MPI::Vector       &dst,
              const TrilinosWrappers::MPI::Vector &src) const
        {
          const auto n_owned_u = owned_u.n_elements();
          AssertDimension(src.locally_owned_size(),
                          n_owned_u + owned_m.n_elements());
          std::copy(src.begin(), src.begin() + n_owned_u, f.begin());
          amg.vmult(y, f);
          C.vmult(g, y); // g = C y
          std::transform(src.begin() + n_owned_u,
                         src.end(),
                         g.begin(),
                         g.begin(),
                         std::minus<double>());
          schur.solve(z, g);
          std::copy(y.begin(), y.end(), dst.begin());
          std::copy(z.begin(), z.end(), dst.begin() + n_owned_u);
        }

      private:
        const TrilinosWrappers::PreconditionAMG &amg;
        const TrilinosWrappers::SparseMatrix    &C;
        TrilinosWrappers::SolverDirect          &schur;
        const IndexSet                          &owned_u, &owned_m;
        mutable TrilinosWrappers::MPI::Vector    f, y, g, z;
      };
    } // namespace


    template <int dim>
    unsigned int
    LinearSolver<dim>::solve_blocks(const TrilinosWrappers::SparseMatrix &M,
                                    TrilinosWrappers::MPI::Vector        &x,
                                    const TrilinosWrappers::MPI::Vector  &b)
    {
      const MPI_Comm comm = M.get_mpi_communicator();
      const auto     n    = M.m();

      TrilinosWrappers::SparseMatrix Bt, C, D;
      // The AMG hierarchy of the u block is kept for the solves on the same
      // pattern: it is built on the first matrix of the pattern, and later
      // matrices differ from that one only in the contact terms.
      if (!kept_amg)
        {
          kept_A = std::make_unique<TrilinosWrappers::SparseMatrix>();
          extract_block(M, 0, n_u, 0, n_u, owned, owned, *kept_A, comm);
          kept_amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
          initialize_amg(*kept_amg, *kept_A);
        }
      extract_block(M, 0, n_u, n_u, n, owned, owned_m, Bt, comm);
      extract_block(M, n_u, n, 0, n_u, owned_m, owned, C, comm);
      extract_block(M, n_u, n, n_u, n, owned_m, owned_m, D, comm);

      // S = D - C diag(A)^-1 B^T on the union of the two patterns.
      TrilinosWrappers::MPI::Vector inverse_diagonal(owned, comm);
      for (const auto i : owned)
        inverse_diagonal[i] = 1. / M.diag_element(i);
      inverse_diagonal.compress(VectorOperation::insert);
      TrilinosWrappers::SparseMatrix CB;
      C.mmult(CB, Bt, inverse_diagonal);
      // The entries through Epetra's local row views: deal.II's row
      // iterators take the owned rows for one contiguous range, and the
      // multipliers a rank owns are two (its lambda and its Lambda).
      TrilinosWrappers::SparsityPattern sp(owned_m, owned_m, comm);
      for_each_entry(D,
                     [&](const auto r, const auto c, double) { sp.add(r, c); });
      for_each_entry(CB,
                     [&](const auto r, const auto c, double) { sp.add(r, c); });
      sp.compress();
      TrilinosWrappers::SparseMatrix S;
      S.reinit(sp);
      for_each_entry(D, [&](const auto r, const auto c, const double v) {
        S.add(r, c, v);
      });
      for_each_entry(CB, [&](const auto r, const auto c, const double v) {
        S.add(r, c, -v);
      });
      S.compress(VectorOperation::add);

      SolverControl                                  schur_control(1, 0);
      TrilinosWrappers::SolverDirect::AdditionalData schur_data(
        false, parameters.direct_package);
      TrilinosWrappers::SolverDirect schur(schur_control, schur_data);
      schur.initialize(S);
      const BlockPreconditioner preconditioner(
        *kept_amg, C, schur, owned, owned_m, comm);

      SolverControl control(parameters.max_iterations,
                            parameters.relative_tolerance * b.l2_norm());
      SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
        control,
        SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(200, true));
      gmres.solve(M, x, b, preconditioner);
      return control.last_step();
    }


    template <int dim>
    void
    LinearSolver<dim>::pattern_changed()
    {
      if (!bulk_linear)
        {
          kept_amg.reset();
          kept_A.reset();
        }
      direct_solver.reset();
      direct_problem.reset();
      analysed_matrix = nullptr;
    }


    // Amesos directly (TrilinosWrappers::SolverDirect analyses the matrix at
    // every solve): the analysis once per pattern, the numeric
    // factorisation of the current values at every solve.
    template <int dim>
    void
    LinearSolver<dim>::solve_direct(const TrilinosWrappers::SparseMatrix &A,
                                    TrilinosWrappers::MPI::Vector        &x,
                                    const TrilinosWrappers::MPI::Vector  &b)
    {
      const auto analyse = [&]() {
        pattern_changed();
        direct_problem = std::make_unique<Epetra_LinearProblem>();
        direct_problem->SetOperator(
          const_cast<Epetra_CrsMatrix *>(&A.trilinos_matrix()));
        Amesos factory;
        AssertThrow(factory.Query(parameters.direct_package.c_str()),
                    ExcMessage("subsection 'Linear solver', parameter "
                               "'Direct solver': " +
                               parameters.direct_package +
                               " is not in this Trilinos build; choose "
                               "the other package (MUMPS or KLU)."));
        direct_solver.reset(
          factory.Create(parameters.direct_package.c_str(), *direct_problem));
        // MUMPS counts the null pivots: pivots below 1e-12 of the norm of
        // the scaled matrix, where a tangent singular to round-off (a
        // mechanism) has them near 1e-16 and a regular one, even a stiff
        // contrast of 1e6, far above.
        if (auto *mumps = dynamic_cast<Amesos_Mumps *>(direct_solver.get()))
          {
            mumps->SetICNTL(24, 1);
            mumps->SetCNTL(3, 1e-12);
          }
        AssertThrow(direct_solver->SymbolicFactorization() == 0,
                    ExcMessage("The direct solver's analysis failed."));
        analysed_matrix = &A.trilinos_matrix();
      };
      const auto factorise = [&]() {
        direct_problem->SetLHS(&x.trilinos_vector());
        direct_problem->SetRHS(
          const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
        return direct_solver->NumericFactorization();
      };
      const bool fresh =
        !direct_solver || analysed_matrix != &A.trilinos_matrix();
      if (fresh)
        analyse();
      int status = factorise();
      // The analysis chose its pivot order on the values of an earlier
      // matrix; should the factorisation of the current values fail with it
      // (e.g. more delayed pivots than the workspace it reserved), the
      // current matrix is analysed again.
      if (status != 0 && !fresh)
        {
          analyse();
          status = factorise();
        }
      // INFOG(28) (0-based 27): the number of null pivots found.
      auto *mumps = dynamic_cast<Amesos_Mumps *>(direct_solver.get());
      if (status == 0 && mumps != nullptr && mumps->GetINFOG()[27] > 0)
        throw LinearSolveError("the tangent is singular: MUMPS found " +
                               std::to_string(mumps->GetINFOG()[27]) +
                               " null pivot(s) in its factorisation");
      if (status != 0)
        throw LinearSolveError("the " + parameters.direct_package +
                               " factorisation of the tangent failed (status " +
                               std::to_string(status) +
                               "): the tangent is singular or nearly so");
      if (direct_solver->Solve() != 0)
        throw LinearSolveError("the " + parameters.direct_package +
                               " solve with the factorised tangent failed");
    }


    template <int dim>
    unsigned int
    LinearSolver<dim>::solve(const TrilinosWrappers::SparseMatrix &A,
                             TrilinosWrappers::MPI::Vector        &x,
                             const TrilinosWrappers::MPI::Vector  &b)
    {
      if (parameters.type == LinearSolverType::direct)
        {
          solve_direct(A, x, b);
          return 0;
        }

      try
        {
          return solve_iterative(A, x, b);
        }
      catch (const SolverControl::NoConvergence &e)
        {
          std::ostringstream s;
          s << "the Krylov solve of the tangent stopped at " << e.last_step
            << " iterations ('Linear solver/Maximum iterations' = "
            << parameters.max_iterations << ") with residual "
            << std::scientific << std::setprecision(2) << e.last_residual
            << " above 'Linear solver/Relative tolerance' = "
            << parameters.relative_tolerance << " times |b|";
          throw LinearSolveError(s.str());
        }
    }


    template <int dim>
    unsigned int
    LinearSolver<dim>::solve_iterative(const TrilinosWrappers::SparseMatrix &A,
                                       TrilinosWrappers::MPI::Vector        &x,
                                       const TrilinosWrappers::MPI::Vector  &b)
    {
      if (owned_m.size() > 0)
        return solve_blocks(A, x, b);
      TrilinosWrappers::PreconditionAMG amg;
      initialize_amg(amg, A);

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
