#ifndef signorini_contact_distributed_vectors_h
#define signorini_contact_distributed_vectors_h

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_vector.h>

/**
 * Two small helpers for the multiplier-indexed Trilinos vectors that the
 * contact code sums into over all ranks: each rank adds the contributions of
 * its own contact points to entries it may not own, then
 * compress(VectorOperation::add) gathers them at the owner.
 */
namespace Signorini
{
  namespace Contact
  {
    namespace internal
    {
      using namespace dealii;

      /** Adds @p value to entry @p i of a writable vector (any rank). */
      inline void
      add_entry(TrilinosWrappers::MPI::Vector &v,
                const types::global_dof_index  i,
                const double                   value)
      {
        const TrilinosWrappers::MPI::Vector::size_type index = i;
        v.add(1, &index, &value);
      }

      /** A vector owning @p owned that accepts additions to the entries of
       * @p writable. */
      inline TrilinosWrappers::MPI::Vector
      writable_vector(const IndexSet &owned,
                      const IndexSet &writable,
                      const MPI_Comm  comm)
      {
        TrilinosWrappers::MPI::Vector v;
        v.reinit(owned, writable, comm, true);
        return v;
      }
    } // namespace internal
  }   // namespace Contact
} // namespace Signorini

#endif
