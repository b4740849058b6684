#ifndef signorini_contact_surface_data_h
#define signorini_contact_surface_data_h

// The data of the contact surfaces that ContactProblem keeps: slave and
// master faces, slave nodes with their multipliers, the friction status of
// a multiplier node and its anti-cycling history.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/dofs/dof_handler.h>

#include <utility>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    /** A slave face of this rank: its cell, DoFs, multipliers and face map. */
    template <int dim>
    struct SlaveFace
    {
      typename DoFHandler<dim>::active_cell_iterator cell;
      unsigned int                                   face;
      unsigned int                                   pair;
      std::vector<unsigned int>            u_local;    // cell dofs on face
      std::vector<unsigned int>            node_local; // comp-0 cell dofs
      std::vector<types::global_dof_index> lambda_dofs;
      std::vector<types::global_dof_index> friction_dofs;  // node-major
      Tensor<1, dim>                       outward_normal; // at centre
      // The 3D crossing axis of the tangent frames of the face's points,
      // tangent_axis(outward_normal) of the reference face, kept over the
      // run (Pairing::pair_point).
      unsigned int tangent_axis = 0;
      // The face map: reference node positions in FE_Q<dim-1> order
      // (as for master faces); k_node[k] = l, the node_local index of
      // face node k; u_node[a], u_comp[a]: node and component of u_local[a];
      // node_dofs[l * dim + c]: displacement DoF of node l, component c.
      std::vector<Point<dim>>              X;
      std::vector<unsigned int>            k_node, u_node, u_comp;
      std::vector<types::global_dof_index> node_dofs;
      // Node-status pairs: the dual (biorthogonal) multiplier basis,
      // psi~_l = sum_m dual[l * n + m] psi_m with n = node_local.size(),
      // so that the integral of psi~_l psi_m over the face is
      // delta_lm D_l; empty: the multipliers use psi.
      std::vector<double> dual;
      // Per node: excluded from contact (a Dirichlet condition along the
      // normal), and whose Lambda a constraint line holds (excluded from
      // contact, on the axis, or hanging with a tangent held).
      std::vector<bool> excluded_contact, excluded_friction;
      // Per node: Q, the projector onto the tangents a Dirichlet condition
      // holds, in the node's tangent frame (tau_1, tau_2): 1 in 2D, the
      // identity in 3D with both held, a (x) a with one held (a unit).
      // Zero: none held. A held node keeps Lambda and its friction law;
      // sticking, its rows along the held tangents become Q Lambda = 0
      // (its slip there is the condition's, and the support carries the
      // force), theory.md F8. Written by Surfaces::finish_slave_faces.
      std::vector<Tensor<2, dim - 1>> held;
      // Per node: the DoF of the pin holding its one held tangent (an 'At
      // point' condition), else invalid. Sticking, its rows along Q are
      // the pin's support force R_d = 0 (the pin carries only what
      // friction cannot), added by PinRows. Written with held.
      std::vector<types::global_dof_index> pin;
    };


    /** A master face (of any rank): node positions, DoFs and identity. */
    template <int dim>
    struct MasterFace
    {
      unsigned int                         pair;
      std::vector<Point<dim>>              X;      // reference node positions
      std::vector<types::global_dof_index> dofs;   // node-major, dim each
      Point<dim>                           inside; // reference cell centre
      // Partition-independent identity (the cell's CellId and the face
      // number): master_faces is sorted by it, so that the search and the
      // mortar cuts see the faces in the same order on any rank count.
      std::vector<unsigned int> key;
      int own_cell = -1; // index into own_master_cells, -1: another rank's

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &pair &X &dofs &inside &key &own_cell;
      }
    };


    /** A constraint line of a master DoF: the DoF and its entries. */
    using MasterLine =
      std::pair<types::global_dof_index,
                std::vector<std::pair<types::global_dof_index, double>>>;


    /** A slave node: its multiplier DoFs, pair, exclusions and hanging-node
     * weights. */
    struct NodeInfo
    {
      types::global_dof_index lambda           = numbers::invalid_dof_index;
      types::global_dof_index friction         = numbers::invalid_dof_index;
      unsigned int            pair             = 0;
      bool                    exclude_contact  = false;
      bool                    exclude_friction = false;
      // 3D, one tangent held: a in the node's frame; empty otherwise
      // (SlaveFace::held is built from it and exclude_friction, which
      // means both held).
      std::vector<double> friction_held;
      // The DoF of the pin ('At point' line) holding its one held tangent;
      // invalid: none (SlaveFace::pin).
      types::global_dof_index pin = numbers::invalid_dof_index;
      std::vector<std::pair<types::global_dof_index, double>> hanging;
      // A node on the axis of an axisymmetric model on a quadratic face,
      // whose weight int psi_l 2 pi r is zero or nearly: its lambda from the
      // next two nodes of its face (dof0, coefficient), by the symmetry of
      // the pressure; its Lambda is zero (Surfaces::close_axis_multipliers).
      std::vector<std::pair<types::global_dof_index, double>> closure;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &lambda &friction &pair &exclude_contact &exclude_friction
          &friction_held &pin &hanging &closure;
      }
    };


    // A node frozen by anti-cycling (frozen = true) keeps its stick or
    // slip status; frozen in slip, H holds the frozen unit direction and
    // the slip row does not depend on the node's H.
    //
    // A pinned node (theory.md F8, pins; a its held tangent, b the free
    // one in 3D) has three statuses, from its H (whose a-part is Lambda*,
    // the Lambda along a at which the pin carries nothing):
    // stick (|H| <= 1): the pin carries nothing;
    // saturated (|H| > 1, |b . H| <= 1): it sticks along b and its friction
    // is saturated along a, a . Lambda = sign(a . H) (1 - (b .
    // Lambda)^2)^(1/2), the pin carrying the rest (in 2D the only status
    // besides stick); slip (|b . H| > 1): it slides along b, so Coulomb's law
    // puts all of its friction against that slip, H = (b . H) b, and the pin
    // carries the whole demand along a. Written by
    // NodeStatuses::decide_friction().
    template <int dim>
    struct NodeFriction
    {
      bool               active    = false;
      bool               stick     = false;
      bool               saturated = false;
      bool               frozen    = false;
      Tensor<1, dim - 1> H;
    };
    // The free tangent b of a pinned node whose held tangent is @p a (both
    // in the node's frame): a turned by 90 degrees (3D; zero in 2D). Its
    // sign does not matter where it is used.
    template <int dim>
    inline Tensor<1, dim - 1>
    free_tangent(const Tensor<1, dim - 1> &a)
    {
      Tensor<1, dim - 1> b;
      if constexpr (dim == 3)
        {
          b[0] = -a[1];
          b[1] = a[0];
        }
      return b;
    }
    // Anti-cycling of the friction status per node, as for points
    // (start_newton_solve()): the status of two iterates back, the cycles
    // and changes in this Newton solve, the freeze (stick, or slip along
    // q) and what the plain law says under it.
    template <int dim>
    struct NodeCycle
    {
      NodeFriction<dim>  before;
      unsigned int       cycles = 0, changes = 0;
      bool               was_frozen = false, freeze = false;
      bool               freeze_stick = false, refrozen = false;
      Tensor<1, dim - 1> q;
      bool               plain_violated = false;
      NodeFriction<dim>  plain;
    };
  } // namespace Contact
} // namespace Signorini

#endif
