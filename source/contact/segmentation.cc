#include <deal.II/base/quadrature_lib.h>

#include <signorini/contact/projection.h>
#include <signorini/contact/segmentation.h>

#include <algorithm>
#include <cmath>

namespace Signorini
{
  namespace Contact
  {
    namespace
    {
      // Lengths (2D) and areas (3D) on the unit slave face below this,
      // and vertices closer than this or this close to the line through
      // their neighbours, are round-off of coincident or nearly coincident
      // edges (matching meshes, hanging nodes, a curved slave carrying the
      // master vertices) and are dropped. Whether clipping leaves such a
      // sliver follows the round-off of the iterate, which differs with the
      // MPI partition and, on several ranks, from run to run (the
      // distributed direct solver is not bit-reproducible: 1e-8 relative in
      // u, about 1e-12 of the face for the nodes), amplified by
      // intersections of nearly parallel edges (seen: vertex pairs 1e-11
      // apart on one run, none on the next). 1e-9 is far above that and
      // far below what matters: a dropped piece changes the face's
      // integrals by less than 1e-9 of the face.
      constexpr double sliver = 1e-9;

      using Polygon = std::vector<Point<2>>;

      double
      cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
      {
        return a[0] * b[1] - a[1] * b[0];
      }

      double
      signed_area(const Polygon &P)
      {
        double A = 0;
        for (unsigned int i = 0; i < P.size(); ++i)
          {
            const Point<2> &a = P[i], &b = P[(i + 1) % P.size()];
            A += a[0] * b[1] - a[1] * b[0];
          }
        return 0.5 * A;
      }

      // The part of convex P on the left of the directed line a -> b
      // (side = +1) or on its right (side = -1): one Sutherland-Hodgman
      // stage.
      Polygon
      clip(const Polygon  &P,
           const Point<2> &a,
           const Point<2> &b,
           const int       side)
      {
        Polygon            out;
        const Tensor<1, 2> e = b - a;
        const auto         s = [&](const Point<2> &x) {
          return side * cross(e, x - a);
        };
        for (unsigned int i = 0; i < P.size(); ++i)
          {
            const Point<2> &p = P[i], &q = P[(i + 1) % P.size()];
            const double    sp = s(p), sq = s(q);
            if (sp >= 0)
              out.push_back(p);
            if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0))
              out.push_back(p + (sp / (sp - sq)) * (q - p));
          }
        return out;
      }

      // Drops repeated and (nearly) collinear vertices, so that a piece has
      // as few triangles as its shape needs.
      Polygon
      simplified(const Polygon &P)
      {
        Polygon Q = P;
        for (bool changed = true; changed && Q.size() > 3;)
          {
            changed = false;
            for (unsigned int i = 0; i < Q.size() && Q.size() > 3; ++i)
              {
                const unsigned int n = Q.size();
                const Point<2>    &a = Q[(i + n - 1) % n], &b = Q[i],
                               &c = Q[(i + 1) % n];
                const double ac   = (c - a).norm();
                const bool   on_line =
                  ac < sliver || std::abs(cross(b - a, c - a)) < sliver * ac;
                if ((b - a).norm() < sliver || on_line)
                  {
                    Q.erase(Q.begin() + i);
                    changed = true;
                  }
              }
          }
        return Q;
      }

      // The same convex polygon starting at the vertex lowest along a fixed
      // oblique direction. Clipping leaves or drops a vertex on a clip line
      // by round-off, which rotates the vertex list; the fan of triangles
      // from P[0], and so the points, must not follow that (the round-off
      // of the iterate differs with the MPI partition). The direction is
      // oblique so that no two vertices of an axis-aligned piece tie.
      Polygon
      canonical(const Polygon &P)
      {
        const auto height = [](const Point<2> &x) {
          return x[0] + 0.6180339887498949 * x[1];
        };
        unsigned int first = 0;
        for (unsigned int i = 1; i < P.size(); ++i)
          if (height(P[i]) < height(P[first]))
            first = i;
        Polygon Q;
        for (unsigned int i = 0; i < P.size(); ++i)
          Q.push_back(P[(first + i) % P.size()]);
        return Q;
      }

      bool
      boxes_overlap(const Polygon &P, const Polygon &Q)
      {
        for (unsigned int d = 0; d < 2; ++d)
          {
            double pmin = 1e300, pmax = -1e300, qmin = 1e300, qmax = -1e300;
            for (const auto &p : P)
              pmin = std::min(pmin, p[d]), pmax = std::max(pmax, p[d]);
            for (const auto &q : Q)
              qmin = std::min(qmin, q[d]), qmax = std::max(qmax, q[d]);
            if (pmax <= qmin || qmax <= pmin)
              return false;
          }
        return true;
      }

      // A counter-clockwise polygon as convex parts: itself, or two
      // triangles split at its reflex vertex (a projected quadrilateral has
      // at most one).
      std::vector<Polygon>
      convex_parts(const Polygon &P)
      {
        const unsigned int n = P.size();
        for (unsigned int i = 0; i < n; ++i)
          {
            const Point<2> &a = P[(i + n - 1) % n], &b = P[i],
                           &c = P[(i + 1) % n];
            if (cross(b - a, c - b) < 0 && n == 4)
              return {{P[i], P[(i + 1) % 4], P[(i + 2) % 4]},
                      {P[i], P[(i + 2) % 4], P[(i + 3) % 4]}};
          }
        return {P};
      }
    } // namespace


    template <>
    Segmentation<2>
    segment_slave_face<2>(
      const std::vector<Point<2>>                      &slave,
      const std::vector<const std::vector<Point<2>> *> &candidates,
      const unsigned int                                n_points)
    {
      const Tensor<1, 2> d = face_geometry<2>(slave, Point<1>(0.5)).normal;
      struct Interval
      {
        double lo, hi;
        int    master;
      };
      std::vector<Interval> covered;
      std::vector<double>   cuts = {0., 1.};
      for (unsigned int m = 0; m < candidates.size(); ++m)
        {
          // The face's two vertices are its first nodes.
          const auto r0 =
            intersect_line_with_face<2>(slave, (*candidates[m])[0], d);
          const auto r1 =
            intersect_line_with_face<2>(slave, (*candidates[m])[1], d);
          if (!r0.converged || !r1.converged)
            continue;
          const double lo = std::min(r0.xi[0], r1.xi[0]);
          const double hi = std::max(r0.xi[0], r1.xi[0]);
          if (hi <= sliver || lo >= 1 - sliver || hi - lo < sliver)
            continue;
          covered.push_back({lo, hi, static_cast<int>(m)});
          for (const double c : {lo, hi})
            if (c > 0 && c < 1)
              cuts.push_back(c);
        }
      std::sort(cuts.begin(), cuts.end());

      Segmentation<2> result;
      const QGauss<1> gauss(n_points);
      for (unsigned int i = 0; i + 1 < cuts.size(); ++i)
        {
          const double a = cuts[i], b = cuts[i + 1];
          if (b - a < sliver)
            continue;
          const double mid    = 0.5 * (a + b);
          int          master = -1;
          for (const auto &c : covered)
            if (c.lo <= mid && mid <= c.hi)
              {
                master = c.master;
                break;
              }
          ++result.n_pieces;
          for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              result.points.emplace_back(a + (b - a) * gauss.point(q)[0]);
              result.weights.push_back((b - a) * gauss.weight(q));
              result.master.push_back(master);
            }
        }
      return result;
    }


    namespace
    {
      // Q intersected with the convex polygon C.
      Polygon
      intersect(Polygon Q, const Polygon &C)
      {
        for (unsigned int e = 0; e < C.size() && Q.size() >= 3; ++e)
          Q = clip(Q, C[e], C[(e + 1) % C.size()], +1);
        return Q;
      }


      // Q minus convex C as disjoint convex pieces, appended to @p out:
      // for edge e, the part of Q inside edges 0..e-1 and outside edge e.
      void
      subtract(Polygon Q, const Polygon &C, std::vector<Polygon> &out)
      {
        for (unsigned int e = 0; e < C.size(); ++e)
          {
            const Point<2> &a = C[e], &b = C[(e + 1) % C.size()];
            const Polygon   O = clip(Q, a, b, -1);
            if (O.size() >= 3 && signed_area(O) >= sliver)
              out.push_back(O);
            Q = clip(Q, a, b, +1);
            if (Q.size() < 3 || signed_area(Q) < sliver)
              break;
          }
      }


      // The master faces @p candidates carried onto the slave face along
      // its centre normal @p d, as convex CCW parts of the unit square's
      // plane with their master index.
      std::vector<std::pair<Polygon, int>>
      master_clips(const std::vector<Point<3>>                      &slave,
                   const std::vector<const std::vector<Point<3>> *> &candidates,
                   const Tensor<1, 3>                               &d,
                   const Polygon                                    &square)
      {
        // The master faces carried onto the slave face, as convex CCW parts.
        std::vector<std::pair<Polygon, int>> clips;
        for (unsigned int m = 0; m < candidates.size(); ++m)
          {
            // Vertices (0,0), (1,0), (1,1), (0,1) of the master face in
            // FE_Q<2> order 0, 1, 3, 2.
            Polygon P;
            bool    ok = true;
            for (const unsigned int k : {0u, 1u, 3u, 2u})
              {
                const auto r =
                  intersect_line_with_face<3>(slave, (*candidates[m])[k], d);
                ok &= r.converged;
                P.push_back(r.xi);
              }
            if (!ok)
              continue;
            const double A = signed_area(P);
            if (std::abs(A) < sliver)
              continue;
            if (A < 0)
              std::reverse(P.begin(), P.end());
            if (!boxes_overlap(P, square))
              continue;
            for (auto &C : convex_parts(P))
              clips.emplace_back(std::move(C), static_cast<int>(m));
          }

        return clips;
      }


      // The unit square cut into convex pieces, each with the master face
      // over it (-1: none).
      std::vector<std::pair<Polygon, int>>
      square_pieces(const std::vector<std::pair<Polygon, int>> &clips,
                    const Polygon                              &square)
      {
        // The usual case, master faces that do not overlap one another: each
        // covers (unit square) x (its polygon), one convex piece.
        std::vector<std::pair<Polygon, int>> pieces;
        double                               covered = 0;
        for (const auto &[C, m] : clips)
          {
            Polygon I = intersect(square, C);
            if (I.size() >= 3 && signed_area(I) >= sliver)
              {
                covered += signed_area(I);
                pieces.emplace_back(std::move(I), m);
              }
          }
        if (covered > 1 + 1e-10)
          {
            // Overlapping master faces (a folded master surface): partition
            // the square in turn, so that each part counts once (the first
            // master face covering it).
            pieces.clear();
            std::vector<Polygon> free = {square};
            for (const auto &[C, m] : clips)
              {
                std::vector<Polygon> still;
                for (const auto &Q : free)
                  {
                    Polygon I =
                      boxes_overlap(Q, C) ? intersect(Q, C) : Polygon();
                    if (I.size() < 3 || signed_area(I) < sliver)
                      {
                        still.push_back(Q);
                        continue;
                      }
                    pieces.emplace_back(std::move(I), m);
                    subtract(Q, C, still);
                  }
                free.swap(still);
              }
            for (auto &Q : free)
              pieces.emplace_back(std::move(Q), -1);
          }
        else if (covered < 1 - 1e-10)
          {
            // Part of the face has no master (the edge of the master
            // surface): the rest of the square, in convex pieces.
            std::vector<Polygon> free = {square};
            for (const auto &[C, m] : clips)
              {
                std::vector<Polygon> still;
                for (const auto &Q : free)
                  {
                    // Q is cut only where C covers a part of it: a master
                    // face that merely touches Q along an edge (its box
                    // overlapping Q's by round-off) must not split Q, or the
                    // pieces, and so the points, follow the round-off of the
                    // iterate (which differs with the MPI partition).
                    const Polygon I =
                      boxes_overlap(Q, C) ? intersect(Q, C) : Polygon();
                    if (I.size() < 3 || signed_area(I) < sliver)
                      still.push_back(Q);
                    else
                      subtract(Q, C, still);
                  }
                free.swap(still);
              }
            for (auto &Q : free)
              pieces.emplace_back(std::move(Q), -1);
          }

        return pieces;
      }


      // Quadrature points of the pieces: each fanned into triangles with
      // @p n_points Witherden-Vincent points.
      Segmentation<3>
      triangulate(const std::vector<std::pair<Polygon, int>> &pieces,
                  const unsigned int                          n_points)
      {
        Segmentation<3>                   result;
        const QWitherdenVincentSimplex<2> triangle(n_points);
        for (const auto &[piece, master] : pieces)
          {
            const Polygon P = canonical(simplified(piece));
            ++result.n_pieces;
            for (unsigned int i = 1; i + 1 < P.size(); ++i)
              {
                const Tensor<1, 2> e1 = P[i] - P[0], e2 = P[i + 1] - P[0];
                const double       J = cross(e1, e2); // twice the area
                if (J < 2 * sliver)
                  continue;
                for (unsigned int q = 0; q < triangle.size(); ++q)
                  {
                    const Point<2> &r = triangle.point(q);
                    result.points.push_back(P[0] + r[0] * e1 + r[1] * e2);
                    result.weights.push_back(J * triangle.weight(q));
                    result.master.push_back(master);
                  }
              }
          }
        return result;
      }
    } // namespace


    template <>
    Segmentation<3>
    segment_slave_face<3>(
      const std::vector<Point<3>>                      &slave,
      const std::vector<const std::vector<Point<3>> *> &candidates,
      const unsigned int                                n_points)
    {
      const Tensor<1, 3> d = face_geometry<3>(slave, Point<2>(0.5, 0.5)).normal;
      const Polygon      square = {Point<2>(0, 0),
                                   Point<2>(1, 0),
                                   Point<2>(1, 1),
                                   Point<2>(0, 1)};
      const auto         clips  = master_clips(slave, candidates, d, square);
      return triangulate(square_pieces(clips, square), n_points);
    }
  } // namespace Contact
} // namespace Signorini
