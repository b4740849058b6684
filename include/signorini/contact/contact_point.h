#ifndef signorini_contact_contact_point_h
#define signorini_contact_contact_point_h

// A contact point of a slave face: fixed slave data, its pairing, the
// status of the last law evaluation, the anti-cycling and geometric-loop
// history, and the values written out.

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

    template <int dim>
    struct ContactPoint
    {
      unsigned int   face; // index into slave_faces
      unsigned int   q;    // index among the face's points
      // Slave data, fixed for the point's lifetime: position xi on the
      // unit face, psi_l(xi) in node_local order, reference position,
      // weight (rule weight x reference Jacobian) and outward normal.
      Point<dim - 1>      xi;
      std::vector<double> psi;
      std::vector<double> psi_lambda; // multiplier basis: psi or psi~
      Point<dim>          x_ref;
      double              weight = 0;
      Tensor<1, dim>      slave_normal;
      int segment_master = -1; // mortar: master face of the point's piece
      bool           paired      = false;
      int            master_face = -1; // -1: rigid or unpaired
      std::vector<double> N_m;         // master shape values at xi_m
      Point<dim - 1>      xi_m;        // projection on the master face
      Tensor<1, dim> normal;
      std::array<Tensor<1, dim>, dim - 1> tangents;
      unsigned int   tangent_axis = 0; // 3D axis of T, fixed at pairing
      Point<dim>     x_m_rigid;
      Tensor<1, dim> rigid_increment;
      // Last evaluation:
      PointStatus        status = PointStatus::free;
      bool               friction_active = false; // law branch, 3.3
      // Anti-cycling history of the current Newton solve.
      PointStatus    status_before = PointStatus::free; // iterate k-2
      Tensor<1, dim> direction_before;  // slip direction at k-2
      unsigned int   cycles     = 0;
      unsigned int   changes    = 0;
      bool           was_frozen = false;
      bool           freeze_contact = false;
      Tensor<1, dim> frozen_slip_direction; // zero: not frozen
      bool           freeze_stick = false;
      // Release extrapolation: open for the next solve (release),
      // released that way at the last solve (extrapolated), closed again
      // after such a release (keep_closed: not again in this solve).
      bool release = false, extrapolated = false, keep_closed = false;
      // Geometric loop: converged statuses at the end of the last two
      // geometric iterations of the step; frozen for the step.
      PointStatus    geo_status_1 = PointStatus::free;
      PointStatus    geo_status_2 = PointStatus::free;
      Tensor<1, dim> geo_direction_1, geo_direction_2;
      bool           geometric_freeze = false;
      // What the plain law said at the last evaluation of a frozen point,
      // and whether the point was frozen a second time in this solve.
      PointStatus    plain_status = PointStatus::free;
      Tensor<1, dim> plain_direction;
      bool           plain_violated = false;
      bool           refrozen       = false;
      // Master faces of the last two pairings of the step (-1: none yet),
      // and the face a pairing 2-cycle pinned the point to.
      int geo_face_1 = -1, geo_face_2 = -1, pinned_face = -1;
      Tensor<1, dim>     slip_direction;          // h / |h| if slipping
      double             gap = 0, lambda = 0;
      Tensor<1, dim - 1> Lambda, slip;
      Tensor<1, dim>     force;
    };
  } // namespace Contact
} // namespace Signorini

#endif
