#ifndef signorini_contact_contact_point_h
#define signorini_contact_contact_point_h

// A contact point of a slave face, in the groups of the data path: fixed
// slave data (setup), its pairing (pairing.cc), the last law evaluation
// (assembler.cc; output and checks read it), and its history within the
// current Newton solve and the current step's geometric loop
// (active_set_history.cc).

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <signorini/contact/contact_law.h>

#include <array>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    /** The history of a point within the current Newton solve: anti-
     * cycling (status cycles, freezes) and release extrapolation. Reset by
     * start_newton_solve() (a freeze of the geometric loop stays for the
     * step). */
    template <int dim>
    struct NewtonHistory
    {
      PointStatus    status_before = PointStatus::free; // iterate k-2
      Tensor<1, dim> direction_before;                  // slip direction at k-2
      unsigned int   cycles     = 0;
      unsigned int   changes    = 0;
      bool           was_frozen = false;
      // The freeze the law sees (PointState): contact held closed, slip
      // direction held (zero: not frozen), stick held.
      bool           freeze_contact = false;
      Tensor<1, dim> frozen_slip_direction;
      bool           freeze_stick = false;
      // What the plain law said at the last evaluation of a frozen point,
      // and whether the point was frozen a second time in this solve.
      PointStatus    plain_status = PointStatus::free;
      Tensor<1, dim> plain_direction;
      bool           plain_violated = false;
      bool           refrozen       = false;
      // Release extrapolation: open for the next solve (release),
      // released that way at the last solve (extrapolated), closed again
      // after such a release (keep_closed: not again in this solve).
      bool release = false, extrapolated = false, keep_closed = false;
    };

    /** The history of a point within the current step's geometric loop:
     * converged statuses at the end of the last two geometric iterations
     * (frozen for the step after a cycle), and the master faces of the
     * last two pairings (-1: none yet) with the face a pairing 2-cycle
     * pinned the point to. Reset by start_geometric_loop() at the start
     * of each step. */
    template <int dim>
    struct GeometricHistory
    {
      PointStatus    status_1 = PointStatus::free;
      PointStatus    status_2 = PointStatus::free;
      Tensor<1, dim> direction_1, direction_2;
      bool           frozen = false;
      int            face_1 = -1, face_2 = -1, pinned_face = -1;
    };

    template <int dim>
    struct ContactPoint
    {
      // Slave data, fixed for the point's lifetime: its face (index into
      // slave_faces) and index among the face's points, position xi on the
      // unit face, psi_l(xi) in node_local order, the multiplier basis (psi
      // or the dual psi~), reference position, weight (rule weight x
      // reference Jacobian), outward normal, and with the mortar rule the
      // master face of the point's piece.
      unsigned int        face;
      unsigned int        q;
      Point<dim - 1>      xi;
      std::vector<double> psi;
      std::vector<double> psi_lambda;
      Point<dim>          x_ref;
      double              weight = 0;
      Tensor<1, dim>      slave_normal;
      int                 segment_master = -1;

      // Pairing: the master face (-1: rigid or unpaired), its shape values
      // at the projection xi_m, the frame (normal, tangents; the 3D axis of
      // the tangents fixed at pairing), and for a rigid obstacle the
      // closest point and the obstacle's increment over the step there.
      bool                                paired      = false;
      int                                 master_face = -1;
      std::vector<double>                 N_m;
      Point<dim - 1>                      xi_m;
      Tensor<1, dim>                      normal;
      std::array<Tensor<1, dim>, dim - 1> tangents;
      unsigned int                        tangent_axis = 0;
      Point<dim>                          x_m_rigid;
      Tensor<1, dim>                      rigid_increment;

      // The last evaluation: status and law branch (theory.md F3.3),
      // slip direction h / |h| if slipping, and the values written out.
      PointStatus        status          = PointStatus::free;
      bool               friction_active = false;
      Tensor<1, dim>     slip_direction;
      double             gap = 0, lambda = 0;
      Tensor<1, dim - 1> Lambda, slip;
      Tensor<1, dim>     force;

      NewtonHistory<dim>    newton;
      GeometricHistory<dim> geometric;
    };
  } // namespace Contact
} // namespace Signorini

#endif
