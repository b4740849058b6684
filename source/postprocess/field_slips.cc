// The slip of the contact points from the displacement field, independent
// of the law's own slip (field_slips.h).
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include <signorini/contact/projection.h>
#include <signorini/postprocess/field_slips.h>

#include <algorithm>

namespace Signorini
{
  namespace Postprocess
  {
    namespace
    {
      // A point of a body's boundary moved towards the centre of its cell
      // by 1e-6 of their distance: inside that cell, and outside the cells
      // of another body that touches the boundary there by far more than
      // the search tolerance below.
      template <int dim>
      Point<dim>
      inside(const Point<dim> &x, const Point<dim> &centre)
      {
        return x + 1e-6 * (centre - x);
      }
    } // namespace


    template <int dim>
    std::vector<Tensor<1, dim>>
    field_slips(const Contact::ContactProblem<dim> &contact,
                const StepData<dim>                &data)
    {
      const auto &pairing  = contact.contact_pairing();
      const auto &surfaces = contact.contact_surfaces();
      const auto &points   = pairing.points();

      // The material points: each paired point's slave point and, on a
      // meshed master, the point of its master face; (slave, master)
      // indices into them.
      constexpr unsigned int  none = numbers::invalid_unsigned_int;
      std::vector<Point<dim>> at;
      std::vector<std::array<unsigned int, 2>> index(points.size(),
                                                     {{none, none}});
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          const auto &point = points[i];
          if (!point.paired)
            continue;
          const auto &face = surfaces.slave_faces()[point.face];
          index[i][0]      = at.size();
          at.push_back(inside(point.x_ref, face.cell->center()));
          if (point.master_face < 0)
            continue;
          // A projection just outside the face (within the projection
          // tolerance) is taken at the face's edge.
          const auto    &master = surfaces.master_faces()[point.master_face];
          Point<dim - 1> xi     = point.xi_m;
          for (unsigned int d = 0; d < dim - 1; ++d)
            xi[d] = std::clamp(xi[d], 0., 1.);
          std::vector<double> N;
          Contact::face_shape_values<dim>(master.X.size(), xi, N);
          Point<dim> X;
          for (unsigned int k = 0; k < master.X.size(); ++k)
            X += N[k] * (master.X[k] - Point<dim>());
          index[i][1] = at.size();
          at.push_back(inside(X, master.inside));
        }

      // u and u_start there (deal.II's evaluation, on any rank's cells).
      Utilities::MPI::RemotePointEvaluation<dim> cache(1e-10);
      cache.reinit(at, data.dof_handler.get_triangulation(), data.mapping);
      const auto u = VectorTools::point_values<dim>(cache,
                                                    data.dof_handler,
                                                    data.displacement);
      const auto u0 =
        VectorTools::point_values<dim>(cache,
                                       data.dof_handler,
                                       data.displacement_step_start);

      const auto [time, start] = pairing.paired_times();
      std::vector<Tensor<1, dim>> slips(points.size());
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          const auto &point = points[i];
          // A point the evaluation did not find keeps a zero slip: the
          // check does not measure it.
          const auto [e, m] = index[i];
          if (e == none || !cache.point_found(e) ||
              (m != none && !cache.point_found(m)))
            continue;
          Tensor<1, dim> v = u[e] - u0[e];
          if (m != none)
            v -= u[m] - u0[m];
          else
            {
              // The obstacle's material point now at the slave point's
              // position x_e, and where it was at the step start.
              const unsigned int p    = surfaces.slave_faces()[point.face].pair;
              const Point<dim>   x_e  = point.x_ref + u[e];
              const auto         now  = pairing.obstacle_motion(p, time);
              const auto         then = pairing.obstacle_motion(p, start);
              v -= x_e - then.apply(now.inverse(x_e));
            }
          slips[i] = v - (v * point.normal) * point.normal;
        }
      return slips;
    }
  } // namespace Postprocess
} // namespace Signorini

template std::vector<dealii::Tensor<1, 2>>
Signorini::Postprocess::field_slips(
  const Signorini::Contact::ContactProblem<2> &,
  const Signorini::Postprocess::StepData<2> &);
template std::vector<dealii::Tensor<1, 3>>
Signorini::Postprocess::field_slips(
  const Signorini::Contact::ContactProblem<3> &,
  const Signorini::Postprocess::StepData<3> &);
