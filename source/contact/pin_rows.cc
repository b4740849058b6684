// The contact's part of the rows of a sticking pinned node (theory.md F8,
// pins): a slave node whose one held tangent a pin at a point holds, and
// which sticks, takes as its friction rows along that tangent the pin's
// support force R_d = 0, so that the pin carries only what friction
// cannot. R_d is the unconstrained residual of the pinned DoF d: the
// contact's rows of d are added here, the bulk's by EquilibriumProblem.
#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>

#include <signorini/bulk/assembler.h>
#include <signorini/contact/assembler.h>
#include <signorini/contact/distributed_vectors.h>

namespace Signorini
{
  namespace Contact
  {
    template <int dim>
    void
    Assembler<dim>::find_sticking_pins()
    {
      stick_pins.clear();
      if (surfaces.pins().empty())
        return;
      // A node's status is known on the ranks that hold its faces, the
      // same on each: their union.
      std::vector<types::global_dof_index> known;
      for (const auto &[dof, pin] : surfaces.pins())
        if (const auto *f = node_statuses.find_friction(pin.lambda);
            f != nullptr && f->active && f->stick)
          known.push_back(dof);
      for (const auto &from_rank : Utilities::MPI::all_gather(comm, known))
        stick_pins.insert(from_rank.begin(), from_rank.end());
    }


    template <int dim>
    void
    Assembler<dim>::add_pin_rows(
      const unsigned int                          a,
      const FullMatrix<double>                   &K,
      const Vector<double>                       &F,
      const std::vector<types::global_dof_index> &dofs,
      const AffineConstraints<double>            &constraints,
      TrilinosWrappers::SparseMatrix             *matrix,
      TrilinosWrappers::MPI::Vector              &rhs) const
    {
      const auto &pin = surfaces.pins().at(dofs[a]);
      // The linear system's right-hand side has -K g of the prescribed
      // increments g (a first update), as the distributed rows have.
      double shifted = F[a];
      if (matrix)
        for (unsigned int j = 0; j < dofs.size(); ++j)
          if (constraints.is_inhomogeneously_constrained(dofs[j]))
            shifted -= K(a, j) * constraints.get_inhomogeneity(dofs[j]);
      // Rows kept as they are, columns condensed.
      FullMatrix<double> row(1, dofs.size());
      for (unsigned int k = 0; k < dim - 1; ++k)
        {
          if (pin.a[k] == 0)
            continue;
          const types::global_dof_index l = pin.friction + k;
          internal::add_entry(rhs, l, pin.a[k] * shifted);
          if (!matrix)
            continue;
          for (unsigned int j = 0; j < dofs.size(); ++j)
            row(0, j) = pin.a[k] * K(a, j);
          Bulk::rows_as_they_are().distribute_local_to_global(
            row, {l}, constraints, dofs, *matrix);
        }
    }


    template class Assembler<2>;
    template class Assembler<3>;
  } // namespace Contact
} // namespace Signorini
