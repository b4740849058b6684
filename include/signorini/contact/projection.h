#ifndef signorini_contact_projection_h
#define signorini_contact_projection_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * Result of the closest-point projection of a point p onto one master
     * face (pairing step of doc/theory.md section 2). Lengths in [m].
     */
    template <int dim>
    struct FaceProjection
    {
      /**
       * Reference coordinates xi^m of the projection on [0,1]^(dim-1) [-].
       * Not clamped: it may lie outside the reference face, see `inside`.
       */
      Point<dim - 1> xi;

      /**
       * Projected point x^m = x(xi) in the current configuration [m].
       */
      Point<dim> x_m;

      /**
       * Unit normal n at xi, pointing into the master body (oriented with the
       * caller's inside point: n . (inside_point - x_m) > 0).
       */
      Tensor<1, dim> normal;

      /**
       * Covariant tangent vectors a_k = dx/dxi_k at xi [m] (not normalised,
       * not orthogonal in general). The orthonormal basis T of section 2 is
       * rebuilt from `normal` by the caller.
       */
      std::array<Tensor<1, dim>, dim - 1> tangents;

      /**
       * Signed distance g = (p - x^m) . n [m] (section 2, without g_0):
       * g > 0 means p lies on the master side (interpenetration).
       */
      double gap = 0.;

      /**
       * true iff the Newton iteration met its step tolerance.
       */
      bool converged = false;

      /**
       * true iff xi lies in [0,1]^(dim-1) up to tol_xi.
       */
      bool inside = false;

      /**
       * max_k max(-xi_k, xi_k - 1, 0) [-]: how far xi lies outside the
       * reference face. Among candidate faces where no projection is
       * `inside`, the one with the smallest violation is the natural choice.
       */
      double violation = 0.;

      /**
       * Number of Newton iterations used.
       */
      unsigned int n_iterations = 0;
    };


    /**
     * Closest-point projection of p onto ONE master face, given by the
     * current positions of its Lagrange support points (doc/theory.md
     * section 2, "Pairing"). The face map is
     *   x(xi) = sum_k N_k(xi) X_k,  xi in [0,1]^(dim-1),
     * with N_k the shape functions of FE_Q<dim-1>(degree), so `face_points`
     * must be in deal.II's FE_Q<dim-1> numbering (vertices, then line
     * midpoints, then the centre), i.e. the order of
     * FE_Q<dim-1>(degree).get_unit_support_points():
     *   2D, Q1: x0, x1;          Q2: x0, x1, x_mid;
     *   3D, Q1: the 4 vertices (0,0),(1,0),(0,1),(1,1);
     *       Q2: the 4 vertices, the midpoints of lines x=0, x=1, y=0, y=1,
     *           the centre.
     * The degree (1 or 2) is deduced from face_points.size() (2/3 in 2D,
     * 4/9 in 3D). This is the order of fe.face_to_cell_index(i, face, ...)
     * for an FE_Q<dim> cell; any parametrisation of the face is acceptable
     * since the normal is oriented with inside_point.
     *
     * Damped Newton on f(xi) = |x(xi) - p|^2 / 2 with the full Hessian
     * a_k . a_l + (x - p) . x_{,kl}, falling back to Gauss-Newton
     * a_k . a_l where that is not positive definite; started at the face
     * centre; backtracking on f. Unconstrained: xi may leave [0,1]^(dim-1).
     *
     * @param p            point to project (e.g. a slave contact point) [m]
     * @param face_points  current positions of the face support points [m]
     * @param inside_point any point strictly inside the master cell (e.g. its
     *                     centre) [m]; fixes the orientation of the normal
     * @param tol_xi       tolerance on [0,1]^(dim-1) for `inside` [-]
     * @param max_iterations Newton iteration limit
     */
    template <int dim>
    FaceProjection<dim>
    project_onto_face(const Point<dim>              &p,
                      const std::vector<Point<dim>> &face_points,
                      const Point<dim>              &inside_point,
                      const double                   tol_xi         = 1e-8,
                      const unsigned int             max_iterations = 30);


    /**
     * Where the straight line p + t d meets a face (mortar segmentation,
     * doc/theory.md section 6): solves x(xi) = p + t d for (xi, t) by
     * Newton from the face centre; x(xi) is the face map of
     * project_onto_face (same node order). xi is not clamped.
     */
    template <int dim>
    struct LineIntersection
    {
      Point<dim - 1> xi;
      double         t         = 0.;
      bool           converged = false;
    };

    template <int dim>
    LineIntersection<dim>
    intersect_line_with_face(const std::vector<Point<dim>> &face_points,
                             const Point<dim>              &p,
                             const Tensor<1, dim>          &d);

    /**
     * Values at xi of the @p n_points shape functions of FE_Q<dim-1>
     * (degree 1 or 2, node order as for project_onto_face), closed form.
     */
    template <int dim>
    void
    face_shape_values(const unsigned int    n_points,
                      const Point<dim - 1> &xi,
                      std::vector<double>  &values);

    /**
     * Position, covariant tangents dx/dxi_k and unit normal (not oriented:
     * the right-handed a_0 x a_1 in 3D, a_0 turned clockwise in 2D) of a
     * face map at xi; node order as for project_onto_face.
     */
    template <int dim>
    struct FaceGeometry
    {
      Point<dim>                          x;
      std::array<Tensor<1, dim>, dim - 1> tangents;
      Tensor<1, dim>                      normal;
      double                              jacobian = 0.; // |a_0| or |a_0 x a_1|
    };

    template <int dim>
    FaceGeometry<dim>
    face_geometry(const std::vector<Point<dim>> &face_points,
                  const Point<dim - 1>          &xi);



  } // namespace Contact
} // namespace Signorini

#endif
