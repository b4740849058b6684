// Contact surfaces, their fields: the current positions of slave and
// master points, the master's increment and nodes, and the multipliers to
// and from finite element fields (adaptivity, output). The faces and the
// multiplier numbering are in surfaces.cc.
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>

#include <signorini/contact/distributed_vectors.h>
#include <signorini/contact/surfaces.h>

#include "helpers.h"

#include <algorithm>
#include <cmath>

namespace Signorini
{
  namespace Contact
  {
    using internal::add_entry;
    using internal::writable_vector;


    template <int dim>
    Point<dim>
    Surfaces<dim>::slave_position(
      const unsigned int                   f,
      const std::vector<double>           &psi,
      const Point<dim>                    &x_ref,
      const TrilinosWrappers::MPI::Vector &state) const
    {
      const auto &face = slaves[f];
      Point<dim>  x    = x_ref;
      for (unsigned int l = 0; l < psi.size(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          x[c] += psi[l] * state[face.node_dofs[l * dim + c]];
      return x;
    }


    template <int dim>
    Point<dim>
    Surfaces<dim>::master_position(
      const unsigned int                   m,
      const std::vector<double>           &N,
      const TrilinosWrappers::MPI::Vector &state) const
    {
      const auto &face = masters[m];
      Point<dim>  x;
      for (unsigned int k = 0; k < face.X.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          x[c] += N[k] * (face.X[k][c] + state[face.dofs[k * dim + c]]);
      return x;
    }


    template <int dim>
    Tensor<1, dim>
    Surfaces<dim>::master_increment(
      const unsigned int                   m,
      const std::vector<double>           &N,
      const TrilinosWrappers::MPI::Vector &state,
      const TrilinosWrappers::MPI::Vector &start) const
    {
      const auto    &face = masters[m];
      Tensor<1, dim> du;
      for (unsigned int k = 0; k < face.X.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          {
            const auto d = face.dofs[k * dim + c];
            du[c] += N[k] * (state[d] - start[d]);
          }
      return du;
    }


    template <int dim>
    void
    Surfaces<dim>::master_nodes(const unsigned int                   m,
                                const TrilinosWrappers::MPI::Vector &state,
                                std::vector<Point<dim>>             &x,
                                Point<dim> &inside) const
    {
      const auto &face = masters[m];
      x.resize(face.X.size());
      Tensor<1, dim> mean_u;
      for (unsigned int k = 0; k < face.X.size(); ++k)
        {
          x[k] = face.X[k];
          for (unsigned int c = 0; c < dim; ++c)
            x[k][c] += state[face.dofs[k * dim + c]];
          mean_u += (x[k] - face.X[k]) / double(face.X.size());
        }
      inside = face.inside + mean_u;
    }


    template <int dim>
    void
    Surfaces<dim>::multipliers_to_field(
      const TrilinosWrappers::MPI::Vector &state,
      TrilinosWrappers::MPI::Vector       &field) const
    {
      // A node may lie on slave faces of several ranks and on none of its
      // owner's: every rank writes the nodes of its faces (the same
      // values), averaged through a count.
      IndexSet touched(dof_handler.n_dofs());
      for (const auto &face : slave_faces())
        for (const auto d : face.node_dofs)
          touched.add_index(d);
      touched.compress();
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      auto            num   = writable_vector(owned, touched, comm);
      auto            den   = writable_vector(owned, touched, comm);
      for (const auto &face : slave_faces())
        for (unsigned int l = 0; l < face.node_local.size(); ++l)
          {
            const auto &info = nodes().at(face.node_dofs[l * dim]);
            for (unsigned int c = 0; c < dim; ++c)
              {
                double value = 0;
                if (c == 0)
                  value = state[info.lambda];
                else if (info.friction != numbers::invalid_dof_index)
                  value = state[info.friction + c - 1];
                add_entry(num, face.node_dofs[l * dim + c], value);
                add_entry(den, face.node_dofs[l * dim + c], 1.);
              }
          }
      num.compress(VectorOperation::add);
      den.compress(VectorOperation::add);
      for (const auto i : owned)
        field[i] = den[i] != 0 ? num[i] / den[i] : 0.;
      field.compress(VectorOperation::insert);
    }


    template <int dim>
    void
    Surfaces<dim>::multipliers_from_field(
      const TrilinosWrappers::MPI::Vector &field,
      TrilinosWrappers::MPI::Vector       &state_owned) const
    {
      auto num = writable_multipliers();
      auto den = writable_multipliers();
      for (const auto &face : slave_faces())
        for (unsigned int l = 0; l < face.node_local.size(); ++l)
          {
            const auto &info = nodes().at(face.node_dofs[l * dim]);
            add_entry(num, info.lambda, field[face.node_dofs[l * dim]]);
            add_entry(den, info.lambda, 1.);
            if (info.friction != numbers::invalid_dof_index)
              for (unsigned int c = 1; c < dim; ++c)
                {
                  add_entry(num,
                            info.friction + c - 1,
                            field[face.node_dofs[l * dim + c]]);
                  add_entry(den, info.friction + c - 1, 1.);
                }
          }
      num.compress(VectorOperation::add);
      den.compress(VectorOperation::add);
      for (const auto i : owned_multipliers())
        state_owned[i] = den[i] != 0 ? num[i] / den[i] : 0.;
      state_owned.compress(VectorOperation::insert);
    }


    template class Surfaces<2>;
    template class Surfaces<3>;
  } // namespace Contact
} // namespace Signorini
