#include <deal.II/lac/trilinos_index_access.h>

#include <signorini/solver/roundoff.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_FEVector.h>

#include <cmath>

namespace Signorini
{
  namespace Solver
  {
    double
    absolute_product_norm(const TrilinosWrappers::SparseMatrix &K,
                          const TrilinosWrappers::MPI::Vector  &x,
                          const AffineConstraints<double>      &constraints,
                          const MPI_Comm                        comm,
                          const TrilinosWrappers::MPI::Vector  &s)
    {
      if (K.m() == 0)
        return 0;
      // Epetra rows directly (the owned rows of the system are not one
      // contiguous range), the columns looked up by global index in the
      // ghosted vector's own map.
      const Epetra_CrsMatrix &A   = K.trilinos_matrix();
      const auto             &map = x.trilinos_vector().Map();
      const double           *xv  = x.trilinos_vector()[0];
      // s in its own map (the system's ghost layout may have moved on).
      const double *sv   = s.size() > 0 ? s.trilinos_vector()[0] : nullptr;
      const auto   *smap = s.size() > 0 ? &s.trilinos_vector().Map() : nullptr;
      double        sum  = 0;
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          if (constraints.is_constrained(
                static_cast<types::global_dof_index>(A.GRID64(r))))
            continue;
          int     n = 0;
          double *values;
          int    *columns;
          A.ExtractMyRowView(r, n, values, columns);
          double row = 0;
          for (int k = 0; k < n; ++k)
            {
              const auto column =
                TrilinosWrappers::global_column_index(A, columns[k]);
              const int local = map.LID(static_cast<int>(column));
              if (local >= 0)
                {
                  const int ls =
                    smap ? smap->LID(static_cast<int>(column)) : -1;
                  row += std::abs(values[k]) *
                         (std::abs(xv[local]) + (ls >= 0 ? sv[ls] : 0.));
                }
            }
          sum += row * row;
        }
      return std::sqrt(Utilities::MPI::sum(sum, comm));
    }
  } // namespace Solver
} // namespace Signorini
