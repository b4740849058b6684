#ifndef signorini_source_contact_helpers_h
#define signorini_source_contact_helpers_h

// Helpers shared by the source files of ContactProblem (private to
// source/contact/).

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <string>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    namespace internal
    {
      using namespace dealii;

      inline std::string
      pair_name(const unsigned int p)
      {
        return "subsection 'Contact/Pair " + std::to_string(p + 1) + "'";
      }


      // The master faces whose boxes meet @p box, in master_faces order.
      // The tree's own order follows its packing, which sorts box centres
      // and so breaks ties (faces of a structured mesh in a row) by the
      // round-off of the iterate; the mortar cuts and the search's ties must
      // not depend on that (it differs with the MPI partition).
      template <int dim>
      std::vector<unsigned int>
      faces_meeting(
        const RTree<std::pair<BoundingBox<dim>, unsigned int>> &tree,
        const BoundingBox<dim>                                 &box)
      {
        std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
        tree.query(boost::geometry::index::intersects(box),
                   std::back_inserter(hits));
        std::vector<unsigned int> faces;
        faces.reserve(hits.size());
        for (const auto &hit : hits)
          faces.push_back(hit.second);
        std::sort(faces.begin(), faces.end());
        return faces;
      }

      // Exclusive prefix sum over ranks.
      inline types::global_dof_index
      offset_of(const types::global_dof_index n, const MPI_Comm comm)
      {
        types::global_dof_index offset = 0;
        const auto              all    = Utilities::MPI::all_gather(comm, n);
        for (unsigned int r = 0; r < Utilities::MPI::this_mpi_process(comm);
             ++r)
          offset += all[r];
        return offset;
      }
    } // namespace internal
  }   // namespace Contact
} // namespace Signorini

#endif
