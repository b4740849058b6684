// Pairing: search of the master, projection, mortar segmentation, re-
// projection within Newton.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/base/output_files.h>
#include <signorini/contact/distributed_vectors.h>
#include <signorini/contact/pairing.h>
#include <signorini/contact/segmentation.h>

#include "helpers.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>

namespace Signorini
{
  namespace Contact
  {
    using internal::faces_meeting;


    template <int dim>
    Pairing<dim>::Pairing(
      const Parameters                                         &parameters,
      const Surfaces<dim>                                      &surfaces,
      std::vector<std::unique_ptr<Obstacles::Interface<dim>>> &&obstacles_in,
      const MPI_Comm                                            comm)
        : parameters(parameters)
        , surfaces(surfaces)
        , comm(comm)
        , obstacles(std::move(obstacles_in))
        , motion_at_start(parameters.contact.pairs.size())
    {
      const auto &contact = parameters.contact;
      mortar              = contact.rule == IntegrationRule::mortar;
      segment_order       = exact_segment_order<dim>(parameters.fe_degree);
      // With the mortar rule, a rigid analytic master has no faces to cut
      // its slave faces by: they use the nodal rule, one law per multiplier
      // node. Statuses at Gauss points with interpolated multipliers may
      // admit no consistent active set (B4 ironing cycles without end);
      // at the nodes they do, and on rigid Hertz the nodal rule is also
      // the more accurate one (doc/robustness.md).
      rule = mortar ? std::make_unique<FixedRule<dim>>(IntegrationRule::nodal,
                                                       1,
                                                       parameters.fe_degree) :
                      std::make_unique<FixedRule<dim>>(contact.rule,
                                                       contact.order,
                                                       parameters.fe_degree);
      for (unsigned int p = 0; p < contact.pairs.size(); ++p)
        {
          const auto &pair = contact.pairs[p];
          if (pair.master_is_body())
            motions.emplace_back();
          else
            motions.push_back(std::make_unique<Obstacles::Motion<dim>>(
              pair.obstacle_motion,
              pair.obstacle_rotation,
              pair.rotation_centre,
              parameters.boundary_conditions.constants,
              internal::pair_name(p)));
        }
    }


    template <int dim>
    void
    Pairing<dim>::setup()
    {
      for (unsigned int p = 0; p < obstacles.size(); ++p)
        if (obstacles[p])
          obstacles[p]->set_length_scale(surfaces.pair_scales().face_size[p]);
      // The rule's points on every owned slave face (the mortar rule cuts
      // the faces of meshed pairs at every pairing).
      point_store.clear();
      for (unsigned int f = 0; f < surfaces.slave_faces().size(); ++f)
        {
          const auto &quadrature = rule->face_quadrature(f);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            point_store.push_back(
              make_point(f, q, quadrature.point(q), quadrature.weight(q)));
        }
    }


    template <int dim>
    std::string
    Pairing<dim>::non_finite_motion(const double time) const
    {
      for (unsigned int p = 0; p < motions.size(); ++p)
        if (motions[p])
          {
            const auto m      = motions[p]->at(time);
            bool       moved  = true;
            bool       turned = true;
            for (unsigned int i = 0; i < dim; ++i)
              {
                moved = moved && std::isfinite(m.translation[i]);
                for (unsigned int j = 0; j < dim; ++j)
                  turned = turned && std::isfinite(m.rotation[i][j]);
              }
            if (!moved || !turned)
              {
                std::ostringstream s;
                s << "; " << internal::pair_name(p) << ", parameter '"
                  << (moved ? "Obstacle rotation" : "Obstacle motion")
                  << "' is not finite at t = " << std::scientific
                  << std::setprecision(4) << time;
                return s.str();
              }
          }
      return "";
    }


    template <int dim>
    std::array<double, 2>
    Pairing<dim>::obstacle_increment_products(const double time,
                                              const double start,
                                              const double previous) const
    {
      // Each obstacle's rigid motion at the three times, once.
      std::vector<std::array<Obstacles::RigidMotion<dim>, 3>> at(
        motions.size());
      for (unsigned int p = 0; p < motions.size(); ++p)
        if (motions[p])
          at[p] = {{motions[p]->at(time),
                    motions[p]->at(start),
                    motions[p]->at(previous)}};
      std::array<double, 2> products{{0., 0.}};
      for (const auto &point : point_store)
        {
          const unsigned int p = surfaces.slave_faces()[point.face].pair;
          if (!motions[p] || !point.paired)
            continue;
          // The obstacle's material point at the paired master point.
          const Point<dim> X =
            obstacles[p]->get_motion().inverse(point.x_m_rigid);
          const Point<dim>     at_start = at[p][1].apply(X);
          const Tensor<1, dim> d_new    = at[p][0].apply(X) - at_start;
          const Tensor<1, dim> d_old    = at_start - at[p][2].apply(X);
          products[0] += d_new * d_old;
          products[1] += d_old * d_old;
        }
      return products;
    }


    template <int dim>
    std::string
    Pairing<dim>::rule_description() const
    {
      std::ostringstream text;
      if (mortar)
        {
          text << "mortar (segment-based, " << segment_order
               << (dim == 2 ? " Gauss points per segment" :
                              " points per direction on each triangle")
               << ")";
          for (const auto &obstacle : obstacles)
            if (obstacle)
              {
                text << ", nodal on rigid masters";
                break;
              }
        }
      else
        text << rule->name() << ", "
             << Utilities::MPI::sum(
                  static_cast<unsigned int>(point_store.size()), comm)
             << " contact points";
      return text.str();
    }


    template <int dim>
    void
    Pairing<dim>::pair(const TrilinosWrappers::MPI::Vector &state,
                       const double                         time,
                       const double                         t0)
    {
      const auto &pairs = parameters.contact.pairs;
      time_paired       = time;
      start_paired      = t0;

      // Rigid obstacles at time t, and where they were at the step start.
      motion_at_start.resize(pairs.size());
      for (unsigned int p = 0; p < pairs.size(); ++p)
        if (obstacles[p])
          {
            motion_at_start[p] = motions[p]->at(t0);
            obstacles[p]->set_motion(motions[p]->at(time));
          }

      // Master faces in the current configuration and their boxes.
      std::vector<std::vector<Point<dim>>> x_master(
        surfaces.master_faces().size());
      std::vector<Point<dim>> inside(surfaces.master_faces().size());
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
      for (unsigned int m = 0; m < surfaces.master_faces().size(); ++m)
        {
          surfaces.master_nodes(m, state, x_master[m], inside[m]);
          BoundingBox<dim> box(x_master[m]);
          box.extend(
            0.5 *
            surfaces.pair_scales().face_size[surfaces.master_faces()[m].pair]);
          boxes.emplace_back(box, m);
        }
      const auto tree = pack_rtree(boxes);

      if (mortar)
        segment(state, x_master, tree);

      unsigned int n_pinned = 0;
      n_deep                = 0;
      ++pairings_in_step;
      for (auto &point : point_store)
        n_pinned += pair_point(point, state, x_master, inside, tree);
      n_newly_pinned = Utilities::MPI::sum(n_pinned, comm);
      n_deep         = Utilities::MPI::sum(n_deep, comm);
      set_multiplier_basis();
    }


    template <int dim>
    bool
    Pairing<dim>::pair_point(ContactPoint<dim>                   &point,
                             const TrilinosWrappers::MPI::Vector &state,
                             const Nodes                         &x_master,
                             const std::vector<Point<dim>>       &inside,
                             const Tree                          &tree)
    {
      const auto        &contact = parameters.contact;
      const auto        &face    = surfaces.slave_faces()[point.face];
      const unsigned int p       = face.pair;
      const Point<dim>   x_e =
        surfaces.slave_position(point.face, point.psi, point.x_ref, state);

      point.paired      = false;
      point.master_face = -1;
      // Pairs the point with master face m if its projection onto m
      // converges within the tolerance (also just outside the face).
      const auto pair_with_face = [&](const int m) {
        const auto proj = project_onto_face(x_e, x_master[m], inside[m]);
        if (!proj.converged || proj.violation > contact.projection_tolerance)
          return false;
        point.paired      = true;
        point.master_face = m;
        take_projection(point, proj);
        return true;
      };
      if (obstacles[p])
        {
          const auto projection = obstacles[p]->project(x_e);
          point.paired          = true;
          point.normal          = projection.normal;
          point.x_m_rigid       = projection.x_m;
          // The increment since the step start of the obstacle's material
          // point now at x^m.
          point.rigid_increment =
            projection.x_m -
            motion_at_start[p].apply(
              obstacles[p]->get_motion().inverse(projection.x_m));
        }
      else if (point.geometric.pinned_face >= 0 && !mortar)
        {
          // Pinned by a pairing 2-cycle: the face is kept while the
          // projection onto it stays within the tolerance.
          if (!pair_with_face(point.geometric.pinned_face))
            point.geometric.pinned_face = -1;
        }
      else if (point.segment_master >= 0)
        // Mortar: the master face of the point's piece (the search below
        // only if the projection leaves that face).
        pair_with_face(point.segment_master);
      if (!obstacles[p] && !point.paired)
        search_master(point, x_e, x_master, inside, tree);

      // Pairing 2-cycle: back on the face of two pairings before.
      bool pinned = false;
      if (!mortar && !obstacles[p] && point.geometric.pinned_face < 0 &&
          point.master_face >= 0 && pairings_in_step >= 3 &&
          point.master_face == point.geometric.face_2 &&
          point.master_face != point.geometric.face_1)
        {
          point.geometric.pinned_face = point.master_face;
          pinned                      = true;
        }
      point.geometric.face_2 = point.geometric.face_1;
      point.geometric.face_1 = point.master_face;
      // The contact normal points into the master (theory.md F2), along
      // the slave's outward normal.
      if (!point.paired)
        point.normal = point.slave_normal;
      // The 3D crossing axis of T is the slave face's, the same at every
      // pairing, so that Lambda keeps its meaning over the run (the axis of
      // each current normal switched where |n_x| crossed 0.8, turning T by
      // 90 degrees and Lambda with it); only a normal turned to within 18
      // degrees of that axis takes its own.
      const unsigned int axis = surfaces.slave_faces()[point.face].tangent_axis;
      point.tangent_axis      = std::abs(point.normal[axis]) <= 0.95 ?
                                  axis :
                                  tangent_axis<dim>(point.normal);
      point.tangents = tangent_basis<dim>(point.normal, point.tangent_axis);
      return pinned;
    }


    template <int dim>
    void
    Pairing<dim>::search_master(ContactPoint<dim>             &point,
                                const Point<dim>              &x_e,
                                const Nodes                   &x_master,
                                const std::vector<Point<dim>> &inside,
                                const Tree                    &tree)
    {
      const unsigned int p = surfaces.slave_faces()[point.face].pair;
      BoundingBox<dim>   query(std::make_pair(x_e, x_e));
      query.extend(0.5 * surfaces.pair_scales().face_size[p]);
      const auto hits = faces_meeting(tree, query);
      // Inside projections first (closest), then the smallest violation
      // within the tolerance. A point on the edge between two master faces
      // is equally close to both up to round-off: distances within 1e-10
      // of the face size are a tie, broken by the lower face index
      // (partition-independent), so that the round-off of the iterate
      // (number of ranks, BLAS kernels) does not pick the face and its
      // normal.
      const double tie         = 1e-10 * surfaces.pair_scales().face_size[p];
      double       best_inside = std::numeric_limits<double>::max();
      double       best_violation =
        parameters.contact.projection_tolerance * (1 + 1e-12);
      FaceProjection<dim> best;
      int                 best_face      = -1;
      bool                best_is_inside = false;
      for (const unsigned int m : hits)
        {
          if (surfaces.master_faces()[m].pair != p)
            continue;
          const auto proj = project_onto_face(x_e, x_master[m], inside[m]);
          if (!proj.converged)
            continue;
          const double distance = x_e.distance(proj.x_m);
          if (proj.inside)
            {
              if (distance < best_inside - tie ||
                  (distance <= best_inside + tie && best_is_inside &&
                   m < static_cast<unsigned int>(best_face)))
                {
                  best_inside    = distance;
                  best           = proj;
                  best_face      = m;
                  best_is_inside = true;
                }
            }
          else if (!best_is_inside && proj.violation < best_violation)
            {
              best_violation = proj.violation;
              best           = proj;
              best_face      = m;
            }
        }
      if (best_face >= 0)
        {
          point.paired      = true;
          point.master_face = best_face;
          take_projection(point, best);
        }
      else
        pair_deep(point, x_e, x_master, inside, tree);
    }


    template <int dim>
    void
    Pairing<dim>::set_multiplier_basis()
    {
      // Dual multipliers only on slave faces whose points are all paired:
      // on a face that leaves the master partly, psi~ (negative lobes)
      // would weigh the gap of the paired part alone.
      std::vector<bool> covered(surfaces.slave_faces().size(), true);
      for (const auto &point : point_store)
        covered[point.face] = covered[point.face] && point.paired;
      for (auto &point : point_store)
        {
          const auto &face = surfaces.slave_faces()[point.face];
          point.psi_lambda = point.psi;
          if (face.dual.empty() || !covered[point.face])
            continue;
          const unsigned int n = point.psi.size();
          for (unsigned int l = 0; l < n; ++l)
            {
              point.psi_lambda[l] = 0;
              for (unsigned int m = 0; m < n; ++m)
                point.psi_lambda[l] += face.dual[l * n + m] * point.psi[m];
            }
        }
    }


    template <int dim>
    void
    Pairing<dim>::pair_deep(ContactPoint<dim>             &point,
                            const Point<dim>              &x_e,
                            const Nodes                   &x_master,
                            const std::vector<Point<dim>> &inside,
                            const Tree                    &tree)
    {
      // A slave point deeper in the master body than the search box reaches
      // (a deep initial interpenetration, or a large load step) is paired
      // from the penetrated side: with the nearest master faces onto which
      // it projects inside the face and behind it (g > 0). Dropping it
      // would silently lose the contact.
      const unsigned int p = surfaces.slave_faces()[point.face].pair;
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
      tree.query(boost::geometry::index::nearest(x_e, 8),
                 std::back_inserter(hits));
      std::vector<unsigned int> faces;
      for (const auto &hit : hits)
        if (surfaces.master_faces()[hit.second].pair == p)
          faces.push_back(hit.second);
      std::sort(faces.begin(), faces.end()); // partition-independent ties
      double              best_distance = std::numeric_limits<double>::max();
      int                 best_face     = -1;
      FaceProjection<dim> best;
      for (const unsigned int m : faces)
        {
          const auto proj = project_onto_face(x_e, x_master[m], inside[m]);
          if (!proj.converged || !proj.inside ||
              (x_e - proj.x_m) * proj.normal <= 0)
            continue;
          const double distance = x_e.distance(proj.x_m);
          if (distance < best_distance)
            {
              best_distance = distance;
              best_face     = m;
              best          = proj;
            }
        }
      if (best_face < 0)
        return;
      point.paired      = true;
      point.master_face = best_face;
      take_projection(point, best);
      ++n_deep;
    }


    template <int dim>
    void
    Pairing<dim>::segment(const TrilinosWrappers::MPI::Vector &state,
                          const Nodes                         &x_master,
                          const Tree                          &tree)
    {
      Points old_points;
      old_points.swap(point_store);
      unsigned int                                 next_old = 0;
      std::vector<Point<dim>>                      x_slave;
      std::vector<const std::vector<Point<dim>> *> candidates;
      std::vector<unsigned int>                    candidate_face;
      for (unsigned int f = 0; f < surfaces.slave_faces().size(); ++f)
        {
          const auto        &face      = surfaces.slave_faces()[f];
          const unsigned int p         = face.pair;
          const std::size_t  first_new = point_store.size();
          if (obstacles[p])
            {
              // Analytic master: nothing to cut, nodal rule (see the
              // constructor).
              const auto &quadrature = rule->face_quadrature(f);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                point_store.push_back(
                  make_point(f, q, quadrature.point(q), quadrature.weight(q)));
            }
          else
            {
              x_slave = face.X;
              for (unsigned int k = 0; k < x_slave.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  x_slave[k][c] +=
                    state[face.node_dofs[face.k_node[k] * dim + c]];
              BoundingBox<dim> box(x_slave);
              box.extend(0.5 * surfaces.pair_scales().face_size[p]);
              candidates.clear();
              candidate_face.clear();
              for (const auto m : faces_meeting(tree, box))
                if (surfaces.master_faces()[m].pair == p)
                  {
                    candidates.push_back(&x_master[m]);
                    candidate_face.push_back(m);
                  }
              const auto cut =
                segment_slave_face<dim>(x_slave, candidates, segment_order);
              for (unsigned int q = 0; q < cut.points.size(); ++q)
                {
                  point_store.push_back(
                    make_point(f, q, cut.points[q], cut.weights[q]));
                  point_store.back().segment_master =
                    cut.master[q] >= 0 ? candidate_face[cut.master[q]] : -1;
                }
            }
          // Statuses carried over from the nearest old point of the face,
          // so that an unchanged contact state counts no change.
          while (next_old < old_points.size() && old_points[next_old].face < f)
            ++next_old;
          for (std::size_t i = first_new; i < point_store.size(); ++i)
            {
              double best = std::numeric_limits<double>::max();
              for (std::size_t j = next_old;
                   j < old_points.size() && old_points[j].face == f;
                   ++j)
                if (const double d2 =
                      (old_points[j].xi - point_store[i].xi).norm_square();
                    d2 < best)
                  {
                    best                  = d2;
                    point_store[i].status = old_points[j].status;
                    point_store[i].friction_active =
                      old_points[j].friction_active;
                    point_store[i].slip_direction =
                      old_points[j].slip_direction;
                    // The geometric loop's history and freeze (the
                    // segmentation changes with every pairing).
                    const auto &o = old_points[j].geometric;
                    auto       &g = point_store[i].geometric;
                    g.status_1    = o.status_1;
                    g.status_2    = o.status_2;
                    g.direction_1 = o.direction_1;
                    g.direction_2 = o.direction_2;
                    g.frozen      = o.frozen;
                    // The freeze only where the loop froze the point.
                    const auto &n    = old_points[j].newton;
                    auto       &h    = point_store[i].newton;
                    h.was_frozen     = o.frozen;
                    h.freeze_contact = o.frozen && n.freeze_contact;
                    h.freeze_stick   = o.frozen && n.freeze_stick;
                    h.frozen_slip_direction =
                      o.frozen ? n.frozen_slip_direction : Tensor<1, dim>();
                  }
            }
        }
    }


    template <int dim>
    ContactPoint<dim>
    Pairing<dim>::make_point(const unsigned int    f,
                             const unsigned int    q,
                             const Point<dim - 1> &xi,
                             const double          w) const
    {
      const auto       &face = surfaces.slave_faces()[f];
      ContactPoint<dim> point;
      point.face = f;
      point.q    = q;
      point.xi   = xi;
      std::vector<double> N;
      face_shape_values<dim>(face.X.size(), xi, N);
      point.psi.resize(face.node_local.size());
      for (unsigned int k = 0; k < face.X.size(); ++k)
        point.psi[face.k_node[k]] = N[k];
      point.psi_lambda    = point.psi; // the dual basis is set by pair()
      const auto geometry = face_geometry<dim>(face.X, xi);
      point.x_ref         = geometry.x;
      // Axisymmetric: the contact ring of radius r = x carries 2 pi r. A
      // point on a node (nodal rule) stands for the node's share of the
      // face, so its radius is the N_k-weighted mean radius of the face:
      // the lumped consistent weight, not zero on the axis.
      double ring = 1;
      if (parameters.axisymmetric)
        {
          ring = 2 * numbers::PI * geometry.x[0];
          for (unsigned int k = 0; k < face.X.size(); ++k)
            if (std::abs(N[k] - 1) < 1e-12)
              {
                const QGauss<dim - 1> gauss(3);
                std::vector<double>   N_q;
                double                num = 0, den = 0;
                for (unsigned int q = 0; q < gauss.size(); ++q)
                  {
                    face_shape_values<dim>(face.X.size(), gauss.point(q), N_q);
                    const auto g = face_geometry<dim>(face.X, gauss.point(q));
                    num += gauss.weight(q) * g.jacobian * N_q[k] * g.x[0];
                    den += gauss.weight(q) * g.jacobian * N_q[k];
                  }
                ring = 2 * numbers::PI * num / den;
              }
        }
      point.weight       = w * geometry.jacobian * ring;
      point.slave_normal = geometry.normal * face.outward_normal > 0 ?
                             geometry.normal :
                             -geometry.normal;
      return point;
    }


    template <int dim>
    void
    Pairing<dim>::take_projection(ContactPoint<dim>         &point,
                                  const FaceProjection<dim> &proj) const
    {
      point.xi_m   = proj.xi;
      point.normal = proj.normal;
      face_shape_values<dim>(surfaces.n_face_nodes(), proj.xi, point.N_m);
    }


    template <int dim>
    double
    Pairing<dim>::gap(const ContactPoint<dim>             &point,
                      const TrilinosWrappers::MPI::Vector &state) const
    {
      if (!point.paired)
        return -std::numeric_limits<double>::max();
      const Point<dim> x_e =
        surfaces.slave_position(point.face, point.psi, point.x_ref, state);
      const Point<dim> x_m =
        point.master_face < 0 ?
          point.x_m_rigid :
          surfaces.master_position(point.master_face, point.N_m, state);
      return (x_e - x_m) * point.normal +
             parameters.contact.pairs[surfaces.slave_faces()[point.face].pair]
               .gap_offset;
    }


    template <int dim>
    Tensor<1, dim - 1>
    Pairing<dim>::slip(const ContactPoint<dim>             &point,
                       const TrilinosWrappers::MPI::Vector &state,
                       const TrilinosWrappers::MPI::Vector &start) const
    {
      // v = P (Delta u^e - Delta u^m), in the tangent basis of the point.
      Tensor<1, dim> v =
        surfaces.slave_position(point.face, point.psi, point.x_ref, state) -
        surfaces.slave_position(point.face, point.psi, point.x_ref, start);
      v -=
        point.master_face < 0 ?
          point.rigid_increment :
          surfaces.master_increment(point.master_face, point.N_m, state, start);
      Tensor<1, dim - 1> t;
      for (unsigned int k = 0; k < dim - 1; ++k)
        t[k] = v * point.tangents[k];
      return t;
    }


    template class Pairing<2>;
    template class Pairing<3>;
  } // namespace Contact
} // namespace Signorini
