#ifndef signorini_source_contact_helpers_h
#define signorini_source_contact_helpers_h

// Helpers shared by the source files of ContactProblem (private to
// source/contact/).

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/contact/assembler.h>
#include <signorini/contact/contact_problem.h>

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


    /**
     * Everything the assembly of one contact point computes on the way from
     * the iterate to its local rows (theory.md F2 to 5): the law of its
     * pair, the kinematics of the slave and master points, the point state
     * and the law's response, the friction status of its multiplier nodes
     * (node path), and the layout of its local unknowns e | m | lambda |
     * Lambda. One object serves all points (its arrays are allocated once).
     */
    template <int dim>
    struct Assembler<dim>::PointEvaluation
    {
      // The law of the pair; friction on; statuses per multiplier node
      // (node path) or per point.
      LawParameters law;
      bool          fric = false, by_node = false;

      // Slave point: N_e[a], the shape value of local displacement column
      // a; position x_e and increment du_e since the step start.
      std::vector<double> N_e;
      Point<dim>          x_e;
      Tensor<1, dim>      du_e;
      // Meshed master face (nullptr: rigid obstacle or unpaired) and its
      // number of displacement columns.
      const MasterFace *master = nullptr;
      unsigned int      n_m    = 0;

      // Newton on the geometry of a frictionless rigid obstacle: dn/du.
      bool           geometry_newton = false;
      Tensor<2, dim> dn_du;

      PointState<dim>    s;
      double             lambda_shown = 0; // lambda with psi (output)
      PointResponse<dim> r;
      Tensor<1, dim - 1> slip_t; // T^T v

      // Friction status, lambda_l, the weight lambda_l of its friction
      // rows (at the iterate) and Lambda_l of the face's multiplier nodes
      // (node path with friction; empty otherwise).
      struct NodeData
      {
        const NodeFriction *status;
        double              lambda, row_lambda;
        Tensor<1, dim - 1>  Lambda;
      };
      std::vector<NodeData> node_data;

      // Local unknowns: n_e slave and n_m master displacement columns,
      // n_l multipliers lambda from o_c, n_f friction multipliers from
      // o_f; n in all. Nd[a]: shape value of displacement column a with
      // the sign of d = u^e - u^m, comp[a]: its component. rows[l]: the
      // Signorini row of multiplier node l.
      unsigned int                    n_e = 0, n_l = 0, n_f = 0;
      unsigned int                    o_c = 0, o_f = 0, n = 0;
      std::vector<double>             Nd;
      std::vector<unsigned int>       comp;
      std::vector<NodeStatusRow<dim>> rows;
    };
  } // namespace Contact
} // namespace Signorini

#endif
