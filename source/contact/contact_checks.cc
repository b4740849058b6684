// Reference checks of a converged contact state that the residual does not
// restate: action = reaction between the displacement rows and the
// multipliers, and the direction of friction against the slip of the
// bodies (ContactProblem::law_checks()).
#include <deal.II/base/mpi.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/contact/distributed_vectors.h>

#include <algorithm>
#include <limits>
#include <set>

namespace Signorini
{
  namespace Contact
  {
    namespace
    {
      // Cosine of the angle between a and b (1 if either is zero).
      template <int dim>
      double
      cosine(const Tensor<1, dim> &a, const Tensor<1, dim> &b)
      {
        const double n = a.norm() * b.norm();
        return n > 0 ? (a * b) / n : 1.;
      }

      // | |f_t| / (mu |f_n|) - 1 |: Coulomb's law in slip.
      template <int dim>
      double
      coulomb_deviation(const Tensor<1, dim> &f_t,
                        const double          f_n,
                        const double          mu)
      {
        const double bound = mu * std::abs(f_n);
        return bound > 0 ? std::abs(f_t.norm() / bound - 1) :
                           std::numeric_limits<double>::infinity();
      }

      // A slipping point or node whose friction force on the master @p f_t
      // (normal part @p f_n) and slip @p v are measurable: whether the
      // friction opposes the slip on the slave, and how far |f_t| is from
      // mu |f_n|.
      template <typename LawCheck, int dim>
      void
      add_slip_sample(LawCheck             &r,
                      const Tensor<1, dim> &f_t,
                      const Tensor<1, dim> &v,
                      const double          f_n,
                      const double          mu)
      {
        // f is the force on the master: the slave receives -f, which
        // opposes v iff f_t . v > 0.
        ++r.n_slipping;
        const double c = cosine(f_t, v);
        r.n_opposed += c > 0;
        r.min_cosine = std::min(r.min_cosine, c);
        r.max_deviation =
          std::max(r.max_deviation, coulomb_deviation(f_t, f_n, mu));
      }

      template <int dim>
      Tensor<1, dim>
      tangential_force(const ContactPoint<dim> &point)
      {
        return point.force - (point.force * point.normal) * point.normal;
      }

      template <int dim>
      Tensor<1, dim>
      slip_vector(const ContactPoint<dim> &point)
      {
        Tensor<1, dim> v;
        for (unsigned int k = 0; k < dim - 1; ++k)
          v += point.slip[k] * point.tangents[k];
        return v;
      }
    } // namespace


    // The force on the master at @p point from the multipliers of @p state,
    // each in the basis the law reads it in (lambda with psi_lambda, dual
    // with statuses per node; Lambda with psi): the traction on the slave
    // is lambda n + mu lambda_f T Lambda, the force on the master its
    // opposite.
    template <int dim>
    Tensor<1, dim>
    ContactProblem<dim>::multiplier_force(
      const ContactPoint                  &point,
      const TrilinosWrappers::MPI::Vector &state) const
    {
      const auto        &face   = surfaces.slave_faces()[point.face];
      const unsigned int p      = face.pair;
      const double       mu     = parameters.contact.pairs[p].friction;
      const unsigned int n_l    = face.lambda_dofs.size();
      double             lambda = 0;
      for (unsigned int l = 0; l < n_l; ++l)
        lambda += point.psi_lambda[l] * state[face.lambda_dofs[l]];
      Tensor<1, dim> force = -lambda * point.normal;
      if (mu == 0)
        return force;
      if (node_statuses.friction_by_node(p))
        // Per node: mu lambda_l T Lambda_l, interpolated with psi~.
        for (unsigned int l = 0; l < n_l; ++l)
          for (unsigned int k = 0; k < dim - 1; ++k)
            force -= mu * point.psi_lambda[l] * state[face.lambda_dofs[l]] *
                     state[face.friction_dofs[l * (dim - 1) + k]] *
                     point.tangents[k];
      else
        {
          Tensor<1, dim> T_Lambda;
          for (unsigned int l = 0; l < n_l; ++l)
            for (unsigned int k = 0; k < dim - 1; ++k)
              T_Lambda += point.psi[l] *
                          state[face.friction_dofs[l * (dim - 1) + k]] *
                          point.tangents[k];
          force -= mu * lambda * T_Lambda;
        }
      return force;
    }


    template <int dim>
    std::vector<typename ContactProblem<dim>::LawCheck>
    ContactProblem<dim>::law_checks(
      const TrilinosWrappers::MPI::Vector &state,
      const std::vector<Tensor<1, dim>>   &slips) const
    {
      const auto &points = pairing.points();
      using internal::add_entry;
      const unsigned int    n_pairs = parameters.contact.pairs.size();
      std::vector<LawCheck> result(n_pairs);

      // Per node of a pair with friction statuses per node: its force
      // sum_k w psi_l f (components 0..dim-1), its weighted slip
      // sum_k w psi~_l v (dim..2dim-1) and its normal sum_k w psi_l n
      // (2dim..3dim-1), global coordinates.
      std::vector<TrilinosWrappers::MPI::Vector> nodal;
      if (node_statuses.any_friction())
        for (unsigned int c = 0; c < 3 * dim; ++c)
          nodal.push_back(surfaces.writable_multipliers());

      // The largest slip and friction force of each pair (the scale below
      // which a slipping point's direction is round-off).
      // The slip is the bodies' (@p slips), never the one the law was
      // given: a slip of the law with the wrong sign would otherwise be
      // confirmed by the law it drove.
      SlipScales          scales{std::vector<double>(n_pairs, 0.),
                        std::vector<double>(n_pairs, 0.)};
      std::vector<double> difference(n_pairs, 0.);
      for (unsigned int i = 0; i < points.size(); ++i)
        if (points[i].paired && i < slips.size())
          {
            const auto        &point = points[i];
            const unsigned int p     = surfaces.slave_faces()[point.face].pair;
            scales.v_max[p] = std::max(scales.v_max[p], slips[i].norm());
            scales.f_max[p] =
              std::max(scales.f_max[p], tangential_force(point).norm());
            if (point.status != PointStatus::free)
              difference[p] =
                std::max(difference[p], (slip_vector(point) - slips[i]).norm());
          }
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          scales.v_max[p] = Utilities::MPI::max(scales.v_max[p], comm);
          scales.f_max[p] = Utilities::MPI::max(scales.f_max[p], comm);
          difference[p]   = Utilities::MPI::max(difference[p], comm);
          if (scales.v_max[p] > 0)
            result[p].max_slip_difference = difference[p] / scales.v_max[p];
        }

      for (unsigned int i = 0; i < points.size(); ++i)
        {
          const auto &point = points[i];
          if (!point.paired)
            continue;
          const auto        &face = surfaces.slave_faces()[point.face];
          const unsigned int p    = face.pair;
          const double       mu   = parameters.contact.pairs[p].friction;
          auto              &r    = result[p];
          r.force_rows += point.weight * point.force;
          r.force_multipliers += point.weight * multiplier_force(point, state);
          if (mu == 0 || i >= slips.size())
            continue;
          const Tensor<1, dim> f_t = tangential_force(point);
          const Tensor<1, dim> v   = slips[i];
          if (node_statuses.friction_by_node(p))
            for (unsigned int l = 0; l < face.lambda_dofs.size(); ++l)
              for (unsigned int c = 0; c < dim; ++c)
                {
                  add_entry(nodal[c],
                            face.lambda_dofs[l],
                            point.weight * point.psi[l] * point.force[c]);
                  add_entry(nodal[dim + c],
                            face.lambda_dofs[l],
                            point.weight * point.psi_lambda[l] * v[c]);
                  add_entry(nodal[2 * dim + c],
                            face.lambda_dofs[l],
                            point.weight * point.psi[l] * point.normal[c]);
                }
          else if (point.status == PointStatus::slip && point.friction_active &&
                   scales.measurable(p, f_t, v))
            add_slip_sample(r, f_t, v, point.force * point.normal, mu);
        }
      if (node_statuses.any_friction())
        add_node_slip_samples(nodal, scales, result);

      for (auto &r : result)
        {
          r.force_rows        = Utilities::MPI::sum(r.force_rows, comm);
          r.force_multipliers = Utilities::MPI::sum(r.force_multipliers, comm);
          r.n_slipping        = Utilities::MPI::sum(r.n_slipping, comm);
          r.n_opposed         = Utilities::MPI::sum(r.n_opposed, comm);
          r.min_cosine        = Utilities::MPI::min(r.min_cosine, comm);
          r.max_deviation     = Utilities::MPI::max(r.max_deviation, comm);
        }
      for (unsigned int p = 0; p < n_pairs; ++p)
        result[p].by_node = node_statuses.by_node(p);
      return result;
    }


    // Statuses per node with friction: each owned slipping node once (it
    // is on several faces), its force, weighted slip and normal summed in
    // @p nodal.
    template <int dim>
    void
    ContactProblem<dim>::add_node_slip_samples(
      std::vector<TrilinosWrappers::MPI::Vector> &nodal,
      const SlipScales                           &scales,
      std::vector<LawCheck>                      &result) const
    {
      for (auto &v : nodal)
        v.compress(VectorOperation::add);
      std::set<types::global_dof_index> seen;
      for (const auto &face : surfaces.slave_faces())
        if (node_statuses.friction_by_node(face.pair))
          for (unsigned int l = 0; l < face.lambda_dofs.size(); ++l)
            {
              const auto dof = face.lambda_dofs[l];
              if (!surfaces.owned_multipliers().is_element(dof) ||
                  !seen.insert(dof).second)
                continue;
              const auto *nf = node_statuses.find_friction(dof);
              if (!nf || !nf->active || nf->stick)
                continue;
              Tensor<1, dim> F, W, n;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  F[c] = nodal[c][dof];
                  W[c] = nodal[dim + c][dof];
                  n[c] = nodal[2 * dim + c][dof];
                }
              if (n.norm() == 0)
                continue;
              n /= n.norm();
              const Tensor<1, dim> F_t = F - (F * n) * n;
              if (!scales.measurable(face.pair, F_t, W))
                continue;
              add_slip_sample(result[face.pair],
                              F_t,
                              W,
                              F * n,
                              parameters.contact.pairs[face.pair].friction);
            }
    }


    template std::vector<typename ContactProblem<2>::LawCheck>
    ContactProblem<2>::law_checks(const TrilinosWrappers::MPI::Vector &,
                                  const std::vector<Tensor<1, 2>> &) const;
    template std::vector<typename ContactProblem<3>::LawCheck>
    ContactProblem<3>::law_checks(const TrilinosWrappers::MPI::Vector &,
                                  const std::vector<Tensor<1, 3>> &) const;
  } // namespace Contact
} // namespace Signorini
