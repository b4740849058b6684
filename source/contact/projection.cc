#include <deal.II/base/exceptions.h>
#include <deal.II/base/tensor.h>

#include <signorini/contact/projection.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    namespace
    {
      /**
       * Degree (1 or 2) of a face given by @p n_points nodes of
       * FE_Q<dim-1>(degree).
       */
      template <int dim>
      unsigned int
      face_degree(const unsigned int n_points)
      {
        const unsigned int q1 = dim == 2 ? 2 : 4, q2 = dim == 2 ? 3 : 9;
        AssertThrow(n_points == q1 || n_points == q2,
                    ExcMessage("project_onto_face: a face needs 2 (Q1) or 3 "
                               "(Q2) points in 2D, 4 (Q1) or 9 (Q2) in 3D."));
        return n_points == q1 ? 1 : 2;
      }

      /**
       * Face map and its first and second derivatives at xi.
       */
      template <int dim>
      struct FaceMapValues
      {
        Point<dim>                          x;
        std::array<Tensor<1, dim>, dim - 1> a;    // dx/dxi_k
        Tensor<1, dim> a2[dim - 1][dim - 1] = {}; // d2x/dxi_k dxi_l
      };

      // 1D Lagrange basis of degree 1 (nodes 0, 1) or 2 (nodes 0, 1, 1/2:
      // FE_Q's order, vertices first) with first and second derivatives.
      struct Lagrange1D
      {
        double v[3], d[3], dd[3];
      };

      inline Lagrange1D
      lagrange_1d(const unsigned int degree, const double x)
      {
        Lagrange1D l{};
        if (degree == 1)
          {
            l.v[0] = 1 - x, l.v[1] = x;
            l.d[0] = -1, l.d[1] = 1;
          }
        else
          {
            l.v[0]  = (1 - x) * (1 - 2 * x);
            l.v[1]  = x * (2 * x - 1);
            l.v[2]  = 4 * x * (1 - x);
            l.d[0]  = 4 * x - 3;
            l.d[1]  = 4 * x - 1;
            l.d[2]  = 4 - 8 * x;
            l.dd[0] = 4, l.dd[1] = 4, l.dd[2] = -8;
          }
        return l;
      }

      // FE_Q<2>(degree) node k as the tensor index (a, b) of 1D nodes
      // (0, 1, 1/2): vertices (0,0) (1,0) (0,1) (1,1), then the midpoints of
      // the lines x = 0, x = 1, y = 0, y = 1, then the centre.
      constexpr unsigned int quad_a[9] = {0, 1, 0, 1, 0, 1, 2, 2, 2};
      constexpr unsigned int quad_b[9] = {0, 0, 1, 1, 2, 2, 0, 1, 2};

      /**
       * Face map and its first and second derivatives at xi, from the
       * closed-form tensor-product Lagrange basis of FE_Q<dim-1>(degree)
       * (checked against FE_Q in tests/projection).
       */
      template <int dim>
      FaceMapValues<dim>
      evaluate_face_map(const std::vector<Point<dim>> &X,
                        const Point<dim - 1>          &xi)
      {
        const unsigned int degree = face_degree<dim>(X.size());
        FaceMapValues<dim> v;
        for (unsigned int k = 0; k < dim - 1; ++k)
          v.a[k] = Tensor<1, dim>();
        if constexpr (dim == 2)
          {
            const Lagrange1D l = lagrange_1d(degree, xi[0]);
            for (unsigned int n = 0; n < X.size(); ++n)
              {
                v.x += l.v[n] * X[n];
                v.a[0] += l.d[n] * X[n];
                v.a2[0][0] += l.dd[n] * X[n];
              }
          }
        else
          {
            const Lagrange1D lx = lagrange_1d(degree, xi[0]);
            const Lagrange1D ly = lagrange_1d(degree, xi[1]);
            for (unsigned int n = 0; n < X.size(); ++n)
              {
                const unsigned int   a = quad_a[n], b = quad_b[n];
                const Tensor<1, dim> x = X[n];
                v.x += (lx.v[a] * ly.v[b]) * x;
                v.a[0] += (lx.d[a] * ly.v[b]) * x;
                v.a[1] += (lx.v[a] * ly.d[b]) * x;
                v.a2[0][0] += (lx.dd[a] * ly.v[b]) * x;
                v.a2[1][1] += (lx.v[a] * ly.dd[b]) * x;
                v.a2[0][1] += (lx.d[a] * ly.d[b]) * x;
              }
            v.a2[1][0] = v.a2[0][1];
          }
        return v;
      }

      template <int dim>
      Tensor<1, dim>
      unit_normal(const std::array<Tensor<1, dim>, dim - 1> &a);

      template <>
      Tensor<1, 2>
      unit_normal<2>(const std::array<Tensor<1, 2>, 1> &a)
      {
        Tensor<1, 2> n;
        n[0] = a[0][1];
        n[1] = -a[0][0];
        return n / n.norm();
      }

      template <>
      Tensor<1, 3>
      unit_normal<3>(const std::array<Tensor<1, 3>, 2> &a)
      {
        const Tensor<1, 3> n = cross_product_3d(a[0], a[1]);
        return n / n.norm();
      }

      /**
       * Is the symmetric (dim-1)x(dim-1) matrix H positive definite?
       */
      template <int d>
      bool
      positive_definite(const Tensor<2, d> &H)
      {
        if (d == 1)
          return H[0][0] > 0.;
        return H[0][0] > 0. && determinant(H) > 0.;
      }
    } // namespace


    template <int dim>
    FaceProjection<dim>
    project_onto_face(const Point<dim>              &p,
                      const std::vector<Point<dim>> &face_points,
                      const Point<dim>              &inside_point,
                      const double                   tol_xi,
                      const unsigned int             max_iterations)
    {
      static_assert(dim == 2 || dim == 3, "dim must be 2 or 3");
      // Steps below this (reference coordinates) end the iteration; the step
      // is applied, so quadratic convergence leaves ~1e-20 behind.
      constexpr double step_tolerance = 1e-10;
      // Largest accepted step in reference coordinates (damping).
      constexpr double max_step = 0.5;
      // Steps below this are taken without line search (see below).
      constexpr double small_step = 1e-6;

      const auto objective = [&](const Point<dim - 1> &xi) {
        return 0.5 * (evaluate_face_map(face_points, xi).x - p).norm_square();
      };

      FaceProjection<dim> result;
      Point<dim - 1>      xi;
      for (unsigned int k = 0; k < dim - 1; ++k)
        xi[k] = 0.5;

      for (unsigned int it = 0; it < max_iterations; ++it)
        {
          result.n_iterations        = it + 1;
          const FaceMapValues<dim> v = evaluate_face_map(face_points, xi);
          const Tensor<1, dim>     r = v.x - p;

          Tensor<1, dim - 1> grad;
          Tensor<2, dim - 1> H_gn, H;
          for (unsigned int k = 0; k < dim - 1; ++k)
            {
              grad[k] = r * v.a[k];
              for (unsigned int l = 0; l < dim - 1; ++l)
                {
                  H_gn[k][l] = v.a[k] * v.a[l];
                  H[k][l]    = H_gn[k][l] + r * v.a2[k][l];
                }
            }
          if (!positive_definite(H))
            H = H_gn;
          AssertThrow(positive_definite(H),
                      ExcMessage("project_onto_face: degenerate face."));

          Tensor<1, dim - 1> step     = -(invert(H) * grad);
          double             step_max = 0.;
          for (unsigned int k = 0; k < dim - 1; ++k)
            step_max = std::max(step_max, std::abs(step[k]));
          if (step_max > max_step)
            {
              step *= max_step / step_max;
              step_max = max_step;
            }

          if (step_max < step_tolerance)
            {
              xi += step;
              result.converged = true;
              break;
            }

          // Backtracking (Armijo) on f, a descent direction since H is SPD,
          // while the step is large. A small step is taken whole: there f
          // falls by about |step|^2 |a|^2, which is below the round-off of f
          // (|r| eps |x|) for steps under about 1e-8, so that the test
          // would halve such a step at random and the iteration would end
          // unconverged on round-off (a 2-rank run then paired a contact
          // point with a face 2 mm away). Newton on the polynomial face map
          // is in its quadratic range there.
          double alpha = 1.;
          if (step_max > small_step)
            {
              const double f0    = 0.5 * r.norm_square();
              const double slope = grad * step;
              for (unsigned int b = 0; b < 20; ++b, alpha *= 0.5)
                if (objective(xi + alpha * step) <= f0 + 1e-4 * alpha * slope)
                  break;
            }
          xi += alpha * step;
        }

      const FaceMapValues<dim> v = evaluate_face_map(face_points, xi);
      result.xi                  = xi;
      result.x_m                 = v.x;
      result.tangents            = v.a;
      result.normal              = unit_normal<dim>(v.a);
      if (result.normal * (inside_point - result.x_m) < 0.)
        result.normal = -result.normal;
      result.gap = (p - result.x_m) * result.normal;

      result.violation = 0.;
      for (unsigned int k = 0; k < dim - 1; ++k)
        result.violation = std::max({result.violation, -xi[k], xi[k] - 1.});
      result.inside = (result.violation <= tol_xi);
      return result;
    }


    template <int dim>
    void
    face_shape_values(const unsigned int    n_points,
                      const Point<dim - 1> &xi,
                      std::vector<double>  &values)
    {
      const unsigned int degree = face_degree<dim>(n_points);
      values.resize(n_points);
      const Lagrange1D lx = lagrange_1d(degree, xi[0]);
      if constexpr (dim == 2)
        for (unsigned int n = 0; n < n_points; ++n)
          values[n] = lx.v[n];
      else
        {
          const Lagrange1D ly = lagrange_1d(degree, xi[1]);
          for (unsigned int n = 0; n < n_points; ++n)
            values[n] = lx.v[quad_a[n]] * ly.v[quad_b[n]];
        }
    }


    template <int dim>
    FaceGeometry<dim>
    face_geometry(const std::vector<Point<dim>> &face_points,
                  const Point<dim - 1>          &xi)
    {
      const FaceMapValues<dim> v = evaluate_face_map(face_points, xi);
      FaceGeometry<dim>        g;
      g.x        = v.x;
      g.tangents = v.a;
      if constexpr (dim == 2)
        g.jacobian = v.a[0].norm();
      else
        g.jacobian = cross_product_3d(v.a[0], v.a[1]).norm();
      g.normal = unit_normal<dim>(v.a);
      return g;
    }


    template <int dim>
    LineIntersection<dim>
    intersect_line_with_face(const std::vector<Point<dim>> &face_points,
                             const Point<dim>              &p,
                             const Tensor<1, dim>          &d)
    {
      LineIntersection<dim> result;
      for (unsigned int k = 0; k < dim - 1; ++k)
        result.xi[k] = 0.5;
      // F(xi, t) = x(xi) - p - t d; columns of dF: a_0 (, a_1), -d.
      for (unsigned int it = 0; it < 30; ++it)
        {
          const FaceMapValues<dim> v =
            evaluate_face_map(face_points, result.xi);
          const Tensor<1, dim> F = v.x - p - result.t * d;
          Tensor<2, dim>       J;
          for (unsigned int r = 0; r < dim; ++r)
            {
              for (unsigned int k = 0; k < dim - 1; ++k)
                J[r][k] = v.a[k][r];
              J[r][dim - 1] = -d[r];
            }
          const double det = determinant(J);
          if (!(std::abs(det) > 1e-14 * std::pow(d.norm(), dim) *
                                  std::pow(v.a[0].norm() + 1e-300, dim - 1)))
            return result; // line parallel to the face
          const Tensor<1, dim> step     = -(invert(J) * F);
          double               step_max = 0.;
          for (unsigned int k = 0; k < dim - 1; ++k)
            {
              result.xi[k] += step[k];
              step_max = std::max(step_max, std::abs(step[k]));
            }
          result.t += step[dim - 1];
          if (step_max < 1e-13)
            {
              result.converged = true;
              break;
            }
        }
      return result;
    }


    // ------------------------------------------------- instantiations

#define SIGNORINI_INSTANTIATE(dim)                                          \
  template FaceProjection<dim> project_onto_face<dim>(                      \
    const Point<dim> &,                                                     \
    const std::vector<Point<dim>> &,                                        \
    const Point<dim> &,                                                     \
    const double,                                                           \
    const unsigned int);                                                    \
  template LineIntersection<dim> intersect_line_with_face<dim>(             \
    const std::vector<Point<dim>> &,                                        \
    const Point<dim> &,                                                     \
    const Tensor<1, dim> &);                                                \
  template void              face_shape_values<dim>(const unsigned int,     \
                                       const Point<dim - 1> &, \
                                       std::vector<double> &); \
  template FaceGeometry<dim> face_geometry<dim>(                            \
    const std::vector<Point<dim>> &, const Point<dim - 1> &);

    SIGNORINI_INSTANTIATE(2)
    SIGNORINI_INSTANTIATE(3)

#undef SIGNORINI_INSTANTIATE

  } // namespace Contact
} // namespace Signorini
