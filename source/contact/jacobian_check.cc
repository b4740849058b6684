// The finite-difference check of the assembled contact Jacobian
// ('Newton/Check Jacobian'; doc/verification.md lists the tests).
#include <deal.II/base/mpi.h>

#include <signorini/contact/jacobian_check.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    namespace
    {
      // The block of system unknown i: 0 (u), 1 (lambda), 2 (Lambda).
      unsigned int
      block_of(const types::global_dof_index i,
               const types::global_dof_index n_u,
               const types::global_dof_index n_l)
      {
        return i < n_u ? 0 : (i < n_u + n_l ? 1 : 2);
      }


      // Step sizes per block: 1e-6 of the block's largest magnitude, never
      // below 1e-6 of the floor, so that a block that is zero up to
      // round-off is not perturbed by round-off.
      std::array<double, 3>
      step_sizes(const TrilinosWrappers::MPI::Vector &state,
                 const IndexSet                      &owned,
                 const types::global_dof_index        n_u,
                 const types::global_dof_index        n_l,
                 const std::array<double, 3>         &floor,
                 const MPI_Comm                       comm)
      {
        std::array<double, 3> scale = {{0, 0, 0}};
        for (const auto i : owned)
          {
            double &s = scale[block_of(i, n_u, n_l)];
            s         = std::max(s, std::abs(state[i]));
          }
        for (unsigned int b = 0; b < 3; ++b)
          scale[b] =
            1e-6 * std::max(Utilities::MPI::max(scale[b], comm), floor[b]);
        return scale;
      }


      // The owned constrained DoFs that follow each DoF (its share w in
      // their constraint lines: a hanging node, a multiplier line such as
      // a . Lambda = 0): the assembled matrix is condensed, so its column j
      // is the derivative along the lines, and the perturbation of j moves
      // them by w delta.
      std::map<types::global_dof_index,
               std::vector<std::pair<types::global_dof_index, double>>>
      constraint_followers(const AffineConstraints<double> &constraints,
                           const IndexSet                  &owned)
      {
        std::map<types::global_dof_index,
                 std::vector<std::pair<types::global_dof_index, double>>>
          followers;
        for (const auto &line : constraints.get_lines())
          if (owned.is_element(line.index))
            for (const auto &[k, w] : line.entries)
              followers[k].emplace_back(line.index, w);
        return followers;
      }

      // The worst column difference relative to the largest column of the
      // same block: a column that is zero up to round-off has a
      // finite-difference column of pure noise, eps |r| / h, which must not
      // count.
      void
      judge_columns(
        const std::vector<std::pair<unsigned int, double>> &differences,
        const std::array<double, 3>                        &block_size,
        JacobianCheckResult                                &result)
      {
        for (const auto &[b, d] : differences)
          if (block_size[b] > 0)
            {
              result.worst = std::max(result.worst, d / block_size[b]);
              ++result.n_checked;
            }
      }
    } // namespace


    template <int dim>
    JacobianCheckResult
    check_jacobian(ContactProblem<dim>                  &contact,
                   TrilinosWrappers::MPI::Vector        &state,
                   const TrilinosWrappers::MPI::Vector  &step_start,
                   const AffineConstraints<double>      &constraints,
                   const TrilinosWrappers::SparseMatrix &matrix_layout,
                   const TrilinosWrappers::MPI::Vector  &rhs_layout,
                   const TrilinosWrappers::MPI::Vector  &force_layout,
                   const types::global_dof_index         n_u,
                   const std::array<double, 3>          &floor)
    {
      const MPI_Comm                comm  = rhs_layout.get_mpi_communicator();
      const IndexSet                owned = rhs_layout.locally_owned_elements();
      const types::global_dof_index n_l = contact.contact_surfaces().n_lambda();
      TrilinosWrappers::SparseMatrix K;
      K.reinit(matrix_layout);
      K = 0;
      // Right-hand sides with the writable off-rank entries of the layout.
      TrilinosWrappers::MPI::Vector r0 = rhs_layout, r_plus = rhs_layout,
                                    r_minus = rhs_layout;
      r0                                    = 0;
      TrilinosWrappers::MPI::Vector column(owned, comm), unit(column);
      TrilinosWrappers::MPI::Vector force = force_layout;
      contact.assemble(state, step_start, constraints, &K, r0, force);
      K.compress(VectorOperation::add);
      // The friction rows' weights (the multipliers of the base state) are
      // held while the state is perturbed: the matrix does not
      // differentiate them (doc/theory.md section 3.2).
      const TrilinosWrappers::MPI::Vector weight_state = state;

      const std::array<double, 3> scale =
        step_sizes(state, owned, n_u, n_l, floor, comm);

      // The base state with the owned layout, copied entry by entry: an
      // assignment between vectors of different layouts may take a
      // collective code path on some ranks only.
      TrilinosWrappers::MPI::Vector base(owned, comm);
      for (const auto i : owned)
        base[i] = state[i];
      base.compress(VectorOperation::insert);
      const auto followers = constraint_followers(constraints, owned);
      const auto evaluate  = [&](const types::global_dof_index  j,
                                const double                   delta,
                                TrilinosWrappers::MPI::Vector &r) {
        TrilinosWrappers::MPI::Vector perturbed = base;
        // (Set, not added: the compress() below is an insert.)
        if (owned.is_element(j))
          perturbed[j] = base[j] + delta;
        if (const auto f = followers.find(j); f != followers.end())
          for (const auto &[i, w] : f->second)
            perturbed[i] = base[i] + w * delta;
        perturbed.compress(VectorOperation::insert);
        state                 = perturbed;
        r                     = 0;
        const auto statistics = contact.assemble(state,
                                                 step_start,
                                                 constraints,
                                                 nullptr,
                                                 r,
                                                 force,
                                                 false,
                                                 &weight_state);
        r.compress(VectorOperation::add);
        return statistics.n_changed;
      };

      JacobianCheckResult                          result;
      std::array<double, 3>                        block_size = {{0, 0, 0}};
      std::vector<std::pair<unsigned int, double>> differences;
      for (const auto j : contact.coupled_dofs())
        {
          // Each rank knows the constraint lines of its relevant DoFs only;
          // all ranks must take the same branch (collective calls follow).
          if (Utilities::MPI::max(constraints.is_constrained(j) ? 1 : 0, comm) >
              0)
            continue;
          const unsigned int b = block_of(j, n_u, n_l);
          unit                 = 0;
          if (owned.is_element(j))
            unit[j] = 1;
          unit.compress(VectorOperation::insert);
          K.vmult(column, unit);
          // The block's size from every column, also those at a kink: when
          // the few smooth columns of a block are zero up to round-off,
          // their noise is not an error.
          block_size[b]        = std::max(block_size[b], column.linfty_norm());
          const double       h = scale[b];
          const unsigned int flips =
            evaluate(j, h, r_plus) + evaluate(j, -h, r_minus);
          if (flips > 0)
            {
              ++result.n_kinked;
              evaluate(j, 0, r_plus); // statuses back to the base state
              continue;
            }
          r_plus -= r_minus;
          r_plus *= -1. / (2 * h); // the finite-difference column
          column -= r_plus;
          differences.emplace_back(b, column.linfty_norm());
        }
      judge_columns(differences, block_size, result);
      // The state and the statuses of the base state back.
      state = base;
      r0    = 0;
      contact.assemble(state, step_start, constraints, nullptr, r0, force);
      return result;
    }


    template JacobianCheckResult
    check_jacobian<2>(ContactProblem<2> &,
                      TrilinosWrappers::MPI::Vector &,
                      const TrilinosWrappers::MPI::Vector &,
                      const AffineConstraints<double> &,
                      const TrilinosWrappers::SparseMatrix &,
                      const TrilinosWrappers::MPI::Vector &,
                      const TrilinosWrappers::MPI::Vector &,
                      const types::global_dof_index,
                      const std::array<double, 3> &);
    template JacobianCheckResult
    check_jacobian<3>(ContactProblem<3> &,
                      TrilinosWrappers::MPI::Vector &,
                      const TrilinosWrappers::MPI::Vector &,
                      const AffineConstraints<double> &,
                      const TrilinosWrappers::SparseMatrix &,
                      const TrilinosWrappers::MPI::Vector &,
                      const TrilinosWrappers::MPI::Vector &,
                      const types::global_dof_index,
                      const std::array<double, 3> &);
  } // namespace Contact
} // namespace Signorini
