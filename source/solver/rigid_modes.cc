#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/trilinos_index_access.h>

#include <Epetra_CrsMatrix.h>

#include <signorini/geometry/parts.h>
#include <signorini/solver/rigid_modes.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

namespace Signorini
{
  namespace Solver
  {
    template <int dim>
    double
    rigid_mode_value(const unsigned int m,
                     const unsigned int c,
                     const Point<dim>  &x,
                     const Point<dim>  &centre)
    {
      if (m < dim)
        return c == m ? 1. : 0.;
      const Tensor<1, dim> r = x - centre;
      if constexpr (dim == 2)
        return c == 0 ? -r[1] : r[0];
      else
        {
          // omega = e_a, a = m - dim: (e_a x r)_c
          const unsigned int a = m - dim, b = (a + 1) % 3, d = (a + 2) % 3;
          return c == b ? -r[d] : c == d ? r[b] : 0.;
        }
    }


    template <int dim>
    std::string
    rigid_mode_name(const unsigned int m)
    {
      const char *axis[] = {"x", "y", "z"};
      if (m < dim)
        return std::string("rigid translation along ") + axis[m];
      return std::string("rigid rotation about ") +
             (dim == 2 ? "z" : axis[m - dim]);
    }


    namespace
    {
      // A pin candidate: the largest |t_i|, then the smallest position.
      struct Candidate
      {
        double                  value = -1;
        double                  x0 = 0, x1 = 0, x2 = 0;
        unsigned int            component = 0;
        types::global_dof_index dof       = numbers::invalid_dof_index;

        bool
        better_than(const Candidate &o) const
        {
          if (value != o.value)
            return value > o.value;
          if (x0 != o.x0)
            return x0 < o.x0;
          if (x1 != o.x1)
            return x1 < o.x1;
          if (x2 != o.x2)
            return x2 < o.x2;
          return component < o.component;
        }

        template <class Archive>
        void
        serialize(Archive &ar, const unsigned int)
        {
          ar &value &x0 &x1 &x2 &component &dof;
        }
      };
    } // namespace


    template <int dim>
    void
    RigidModes<dim>::setup(const Mapping<dim>              &mapping,
                           const DoFHandler<dim>           &dof_handler,
                           const AffineConstraints<double> &constraints,
                           const IndexSet                  &owned_system,
                           const bool                       axisymmetric,
                           const MPI_Comm                   comm_)
    {
      comm  = comm_;
      owned = owned_system;
      const std::vector<unsigned int> part =
        find_bodies(dof_handler.get_triangulation());
      const unsigned int n_bodies = bodies.size();

      // Axisymmetric (x = r): only the axial translation is rigid.
      std::vector<unsigned int> modes;
      for (unsigned int m = 0; m < n_rigid_modes<dim>; ++m)
        if (!axisymmetric || m == 1)
          modes.push_back(m);
      n_modes = modes.size();

      const auto                          &fe = dof_handler.get_fe();
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      std::vector<std::vector<Candidate>>  best(n_bodies,
                                               std::vector<Candidate>(n_modes));
      for (auto &body : bodies)
        {
          body.modes.resize(n_modes);
          for (auto &v : body.modes)
            v.reinit(owned, comm);
        }
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dofs);
            typename Triangulation<dim>::cell_iterator ancestor = cell;
            while (ancestor->level() > 0)
              ancestor = ancestor->parent();
            const unsigned int coarse = ancestor->index();
            for (unsigned int i = 0; i < dofs.size(); ++i)
              {
                const unsigned int c = fe.system_to_component_index(i).first;
                if (c >= dim || !owned.is_element(dofs[i]))
                  continue;
                const auto *entries =
                  constraints.get_constraint_entries(dofs[i]);
                if (entries != nullptr && !entries->empty())
                  continue; // hanging: follows its parents
                const Point<dim> x =
                  mapping.transform_unit_to_real_cell(cell,
                                                      fe.unit_support_point(i));
                for (const unsigned int b : {part[coarse], n_bodies - 1})
                  for (unsigned int k = 0; k < n_modes; ++k)
                    {
                      const double t = rigid_mode_value<dim>(
                        modes[k], c, x, bodies[b].centroid);
                      bodies[b].modes[k][dofs[i]] = t;
                      if (constraints.is_constrained(dofs[i]))
                        continue; // a pin there would hold nothing
                      Candidate candidate;
                      candidate.value     = std::abs(t);
                      candidate.x0        = x[0];
                      candidate.x1        = x[1];
                      candidate.x2        = dim == 3 ? x[dim - 1] : 0.;
                      candidate.component = c;
                      candidate.dof       = dofs[i];
                      if (candidate.better_than(best[b][k]))
                        best[b][k] = candidate;
                    }
              }
          }
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          for (auto &v : bodies[b].modes)
            v.compress(VectorOperation::insert);
          bodies[b].pins.resize(n_modes);
          for (unsigned int k = 0; k < n_modes; ++k)
            {
              Candidate chosen;
              for (const auto &c : Utilities::MPI::all_gather(comm, best[b][k]))
                if (c.better_than(chosen))
                  chosen = c;
              bodies[b].pins[k] = chosen.dof;
            }
        }
      mode_ids = modes;
    }


    // Each part of the mesh, and with several parts all of them together
    // (two free bodies pressed together hold each other, not their joint
    // motion): bodies with their material and the centroid of their coarse
    // vertices. Returns the part of each coarse cell.
    template <int dim>
    std::vector<unsigned int>
    RigidModes<dim>::find_bodies(const Triangulation<dim> &tria)
    {
      unsigned int       n_parts  = 0;
      const auto         part     = Geometry::coarse_parts(tria, n_parts);
      const unsigned int n_bodies = n_parts > 1 ? n_parts + 1 : 1;
      bodies.assign(n_bodies, Body());
      std::vector<std::set<unsigned int>> vertices(n_bodies);
      for (auto cell = tria.begin(0); cell != tria.end(0); ++cell)
        for (const unsigned int b : {part[cell->index()], n_bodies - 1})
          {
            if (bodies[b].modes.empty() && vertices[b].empty())
              bodies[b].material = cell->material_id();
            for (const unsigned int v : cell->vertex_indices())
              vertices[b].insert(cell->vertex_index(v));
          }
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          for (const auto v : vertices[b])
            bodies[b].centroid += tria.get_vertices()[v];
          bodies[b].centroid /= double(vertices[b].size());
        }
      return part;
    }


    template <int dim>
    std::pair<double, double>
    RigidModes<dim>::scales(const TrilinosWrappers::SparseMatrix &K,
                            const types::global_dof_index         n_u) const
    {
      // Epetra rows directly: the owned rows of the system (u and
      // multipliers) are not one contiguous range, which deal.II's row
      // iterators need.
      const Epetra_CrsMatrix &A       = K.trilinos_matrix();
      double                  scale_u = 0, scale_m = 0;
      for (int r = 0; r < A.NumMyRows(); ++r)
        {
          const auto row = static_cast<types::global_dof_index>(
            TrilinosWrappers::global_row_index(A, r));
          int     n = 0;
          double *values;
          int    *columns;
          A.ExtractMyRowView(r, n, values, columns);
          for (int k = 0; k < n; ++k)
            {
              const auto column = static_cast<types::global_dof_index>(
                TrilinosWrappers::global_column_index(A, columns[k]));
              if (row < n_u && column == row)
                scale_u = std::max(scale_u, std::abs(values[k]));
              else if (row >= n_u && column < n_u)
                scale_m = std::max(scale_m, std::abs(values[k]));
            }
        }
      return {Utilities::MPI::max(scale_u, comm),
              Utilities::MPI::max(scale_m, comm)};
    }


    template <int dim>
    std::vector<typename RigidModes<dim>::Motion>
    RigidModes<dim>::find(const TrilinosWrappers::SparseMatrix &K,
                          const types::global_dof_index         n_u) const
    {
      // Scales: the largest diagonal entry of the displacement rows and the
      // largest displacement coupling of the multiplier rows (areas, not
      // stiffnesses: about E h smaller).
      const auto [scale_u, scale_m] = scales(K, n_u);

      std::vector<Motion> motions;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          std::vector<TrilinosWrappers::MPI::Vector> Kt(
            n_modes, TrilinosWrappers::MPI::Vector(owned, comm));
          const auto n_before = motions.size();
          for (unsigned int k = 0; k < n_modes; ++k)
            {
              // The joint motion of all bodies only when no body alone has
              // that motion free (its springs hold the joint one too).
              if (bodies.size() > 1 && b + 1 == bodies.size() &&
                  std::any_of(motions.begin(), motions.end(), [&](auto &m) {
                    return m.mode == k;
                  }))
                continue;
              const auto &t = bodies[b].modes[k];
              K.vmult(Kt[k], t);
              double r_u = 0, r_m = 0;
              for (const auto row : owned)
                (row < n_u ? r_u : r_m) =
                  std::max(row < n_u ? r_u : r_m, std::abs(Kt[k][row]));
              r_u                = Utilities::MPI::max(r_u, comm);
              r_m                = Utilities::MPI::max(r_m, comm);
              const double t_max = t.linfty_norm();
              if (t_max == 0)
                continue;
              if (r_u <= 1e-8 * scale_u * t_max &&
                  r_m <= 1e-8 * scale_m * t_max)
                motions.push_back({b, k, {}});
            }
          // A body (not the joint motion) that no single mode moves freely:
          // a combination may (an inclined roller's translation).
          if (motions.size() == n_before &&
              (bodies.size() == 1 || b + 1 < bodies.size()))
            for (auto &m : find_combinations(b, Kt, n_u, scale_u, scale_m))
              motions.push_back(std::move(m));
        }
      return motions;
    }


    template <int dim>
    std::vector<typename RigidModes<dim>::Motion>
    RigidModes<dim>::find_combinations(
      const unsigned int                                b,
      const std::vector<TrilinosWrappers::MPI::Vector> &Kt,
      const types::global_dof_index                     n_u,
      const double                                      scale_u,
      const double                                      scale_m) const
    {
      // G_kl = (K t_k . K t_l) with the u and multiplier rows scaled by
      // their scales, N_kl = t_k . t_l: a combination alpha with
      // alpha^T G alpha <= 1e-16 alpha^T N alpha moves the body at no
      // force (relative to the stiffness, as for a single mode).
      const auto               &t = bodies[b].modes;
      std::vector<unsigned int> used;
      for (unsigned int k = 0; k < n_modes; ++k)
        if (t[k].linfty_norm() > 0)
          used.push_back(k);
      const unsigned int n = used.size();
      if (n < 2)
        return {};
      LAPACKFullMatrix<double> G(n, n), N(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j <= i; ++j)
          {
            double g = 0;
            for (const auto row : owned)
              {
                const double s = row < n_u ? scale_u : scale_m;
                if (s > 0)
                  g += Kt[used[i]][row] * Kt[used[j]][row] / (s * s);
              }
            g       = Utilities::MPI::sum(g, comm);
            G(i, j) = G(j, i) = g;
            N(i, j) = N(j, i) = t[used[i]] * t[used[j]];
          }
      std::vector<Vector<double>> alpha(n, Vector<double>(n));
      try
        {
          G.compute_generalized_eigenvalues_symmetric(N, alpha);
        }
      catch (const ExceptionBase &)
        {
          return {}; // N singular: the modes are not independent here
        }
      std::vector<Motion> motions;
      for (unsigned int i = 0; i < n; ++i)
        if (G.eigenvalue(i).real() <= 1e-16)
          {
            // Largest weight 1, at the mode named for the pin.
            unsigned int largest = 0;
            for (unsigned int k = 1; k < n; ++k)
              if (std::abs(alpha[i][k]) > std::abs(alpha[i][largest]))
                largest = k;
            Motion m{b, used[largest], std::vector<double>(n_modes, 0.)};
            for (unsigned int k = 0; k < n; ++k)
              m.weights[used[k]] = alpha[i][k] / alpha[i][largest];
            motions.push_back(std::move(m));
          }
      return motions;
    }


    template <int dim>
    void
    RigidModes<dim>::hold(TrilinosWrappers::SparseMatrix &K,
                          const types::global_dof_index   n_u,
                          const std::vector<Motion>      &motions) const
    {
      const double scale_u = scales(K, n_u).first;
      for (const auto &m : motions)
        {
          const auto pin = bodies[m.body].pins[m.mode];
          if (pin != numbers::invalid_dof_index && owned.is_element(pin))
            K.add(pin, pin, scale_u);
        }
      K.compress(VectorOperation::add);
    }


    template <int dim>
    std::string
    RigidModes<dim>::describe(const Motion &motion) const
    {
      std::ostringstream text;
      const auto        &body = bodies[motion.body];
      if (bodies.size() > 1 && motion.body + 1 == bodies.size())
        text << "all bodies together";
      else
        {
          text << "the body of material " << int(body.material) << " (centre (";
          for (unsigned int d = 0; d < dim; ++d)
            text << (d ? ", " : "") << std::setprecision(4) << body.centroid[d];
          text << "))";
        }
      if (motion.weights.empty())
        {
          text << ": " << rigid_mode_name<dim>(mode_ids[motion.mode]);
          return text.str();
        }
      // A combination: its translation and rotation parts.
      Tensor<1, dim>              translation;
      Tensor<1, dim == 2 ? 1 : 3> rotation;
      for (unsigned int k = 0; k < n_modes; ++k)
        (mode_ids[k] < dim ? translation[mode_ids[k]] :
                             rotation[mode_ids[k] - dim]) += motion.weights[k];
      const auto vector = [](const auto &v) {
        std::ostringstream out;
        out << "(";
        for (unsigned int d = 0; d < v.dimension; ++d)
          out << (d ? ", " : "") << std::setprecision(4)
              << (std::abs(v[d]) < 1e-6 * v.norm() ? 0. : v[d]);
        out << ")";
        return out.str();
      };
      const double size = std::max(translation.norm(), rotation.norm());
      if (rotation.norm() <= 1e-6 * size)
        text << ": rigid translation along " << vector(translation / size);
      else
        text << ": a rigid motion combining the translation "
             << vector(translation) << " and the rotation " << vector(rotation)
             << " about its centre";
      return text.str();
    }


    template double
    rigid_mode_value<2>(const unsigned int,
                        const unsigned int,
                        const Point<2> &,
                        const Point<2> &);
    template double
    rigid_mode_value<3>(const unsigned int,
                        const unsigned int,
                        const Point<3> &,
                        const Point<3> &);
    template std::string
    rigid_mode_name<2>(const unsigned int);
    template std::string
    rigid_mode_name<3>(const unsigned int);
    template class RigidModes<2>;
    template class RigidModes<3>;
  } // namespace Solver
} // namespace Signorini
