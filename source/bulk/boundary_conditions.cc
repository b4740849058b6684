#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/numerics/vector_tools.h>

#include <signorini/bulk/boundary_conditions.h>
#include <signorini/core/errors.h>
#include <signorini/core/input_checks.h>
#include <signorini/postprocess/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace Signorini
{
  namespace Bulk
  {
    namespace
    {
      // The values of one Dirichlet condition as a function with one
      // component per displacement component: its expression k gives
      // component components[k]; the others (masked out) are zero.
      template <int dim>
      class DirichletValues : public Function<dim>
      {
      public:
        DirichletValues(const FunctionParser<dim>       &values,
                        const std::vector<unsigned int> &components)
            : Function<dim>(dim)
            , values(values)
            , components(components)
        {
        }

        double
        value(const Point<dim> &p, const unsigned int component) const override
        {
          const auto k =
            std::find(components.begin(), components.end(), component);
          return k == components.end() ?
                   0. :
                   values.value(p, k - components.begin());
        }

      private:
        const FunctionParser<dim>       &values;
        const std::vector<unsigned int> &components;
      };


      template <int dim>
      void
      add_line(const types::global_dof_index dof,
               const double                  value,
               AffineConstraints<double>    &values,
               AffineConstraints<double>    &update)
      {
        if (values.is_constrained(dof))
          return;
        values.add_line(dof);
        values.set_inhomogeneity(dof, value);
        update.add_line(dof);
      }
    } // namespace


    template <int dim>
    BoundaryConditions<dim>::BoundaryConditions(
      const BoundaryConditionParameters     &parameters,
      const std::vector<MaterialParameters> &materials)
        : parameters(parameters)
    {
      const auto where = [](const std::string &condition) {
        return "subsection 'Boundary conditions/" + condition +
               "', parameter 'Values'";
      };
      for (unsigned int k = 0; k < parameters.dirichlet.size(); ++k)
        dirichlet_functions.push_back(
          parse_function<dim>(parameters.dirichlet[k].values,
                              parameters.constants,
                              where("Dirichlet " + std::to_string(k + 1))));
      for (unsigned int k = 0; k < parameters.neumann.size(); ++k)
        neumann_functions.push_back(
          parse_function<dim>(parameters.neumann[k].values,
                              parameters.constants,
                              where("Neumann " + std::to_string(k + 1))));
      for (unsigned int k = 0; k < materials.size(); ++k)
        {
          const auto &force = materials[k].body_force;
          body_force_functions[materials[k].material_id] = parse_function<dim>(
            std::vector<std::string>(force.begin(), force.begin() + dim),
            parameters.constants,
            "subsection 'Materials/Material " + std::to_string(k + 1) +
              "', parameter 'Body force'");
          for (unsigned int d = 0; d < dim; ++d)
            any_body_force |= Utilities::trim(force[d]) != "0";
        }
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::has_body_force() const
    {
      return any_body_force;
    }


    template <int dim>
    void
    BoundaryConditions<dim>::check_boundary_ids(
      const std::set<types::boundary_id> &ids) const
    {
      std::string available;
      for (const auto id : ids)
        available += (available.empty() ? "" : ", ") + std::to_string(id);
      const auto check = [&](const std::vector<unsigned int> &listed,
                             const std::string               &condition) {
        for (const auto id : listed)
          if (ids.count(id) == 0)
            throw InputError("subsection 'Boundary conditions/" + condition +
                             "', parameter 'Boundary id': the mesh has no "
                             "boundary with id " +
                             std::to_string(id) + " (it has: " + available +
                             "). Set 'Boundary id' to one of these.");
      };
      for (unsigned int k = 0; k < parameters.dirichlet.size(); ++k)
        check(parameters.dirichlet[k].boundary_ids,
              "Dirichlet " + std::to_string(k + 1));
      for (unsigned int k = 0; k < parameters.neumann.size(); ++k)
        check(parameters.neumann[k].boundary_ids,
              "Neumann " + std::to_string(k + 1));
    }


    template <int dim>
    void
    BoundaryConditions<dim>::set_load_time(const double time)
    {
      for (auto &f : neumann_functions)
        f->set_time(time);
      for (auto &[id, f] : body_force_functions)
        f->set_time(time);
    }


    template <int dim>
    void
    BoundaryConditions<dim>::add_dirichlet_constraints(
      const double               time,
      const Mapping<dim>        &mapping,
      const DoFHandler<dim>     &dof_handler,
      const double               tolerance,
      AffineConstraints<double> &values,
      AffineConstraints<double> &update)
    {
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      dirichlet_dofs.assign(parameters.dirichlet.size(), {});
      for (unsigned int k = 0; k < parameters.dirichlet.size(); ++k)
        {
          const auto &d = parameters.dirichlet[k];
          dirichlet_functions[k]->set_time(time);
          if (!d.at_point.empty())
            {
              add_point_constraint(k, dof_handler, tolerance, values, update);
              continue;
            }
          // The support points of the faces, through the mapping (on a
          // curved boundary's manifold for Q2).
          const DirichletValues<dim> function(*dirichlet_functions[k],
                                              d.components);
          std::map<types::boundary_id, const Function<dim> *> on_boundary;
          for (const auto id : d.boundary_ids)
            on_boundary[id] = &function;
          std::vector<bool> mask(dim, false);
          for (const auto c : d.components)
            mask[c] = true;
          std::map<types::global_dof_index, double> boundary_values;
          VectorTools::interpolate_boundary_values(mapping,
                                                   dof_handler,
                                                   on_boundary,
                                                   boundary_values,
                                                   ComponentMask(mask));
          for (const auto &[dof, value] : boundary_values)
            add_line<dim>(dof, value, values, update);

          const std::set<types::boundary_id> ids(d.boundary_ids.begin(),
                                                 d.boundary_ids.end());
          for (const auto c : d.components)
            {
              std::vector<bool> component(dim, false);
              component[c] = true;
              IndexSet dofs =
                DoFTools::extract_boundary_dofs(dof_handler,
                                                ComponentMask(component),
                                                ids);
              dofs = dofs & owned;
              for (const auto dof : dofs)
                dirichlet_dofs[k].emplace_back(dof, c);
            }
          std::sort(dirichlet_dofs[k].begin(), dirichlet_dofs[k].end());
        }
    }


    template <int dim>
    void
    BoundaryConditions<dim>::add_point_constraint(
      const unsigned int         k,
      const DoFHandler<dim>     &dof_handler,
      const double               tolerance,
      AffineConstraints<double> &values,
      AffineConstraints<double> &update)
    {
      const auto      &d     = parameters.dirichlet[k];
      const auto      &f     = *dirichlet_functions[k];
      const Point<dim> point = to_point<dim>(d.at_point, "Dirichlet/At point");
      const IndexSet  &owned = dof_handler.locally_owned_dofs();
      unsigned int     found = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && std::count(d.boundary_ids.begin(),
                                                  d.boundary_ids.end(),
                                                  face->boundary_id()))
              for (const unsigned int v : face->vertex_indices())
                if (face->vertex(v).distance(point) <= tolerance)
                  for (unsigned int i = 0; i < d.components.size(); ++i)
                    {
                      const unsigned int c   = d.components[i];
                      const auto         dof = face->vertex_dof_index(v, c);
                      add_line<dim>(dof,
                                    f.value(face->vertex(v), i),
                                    values,
                                    update);
                      if (owned.is_element(dof))
                        dirichlet_dofs[k].emplace_back(dof, c);
                      ++found;
                    }
      if (Utilities::MPI::sum(found, dof_handler.get_communicator()) == 0)
        throw InputError(
          "subsection 'Boundary conditions/Dirichlet " + std::to_string(k + 1) +
          "', parameter 'At point': no mesh node of the listed boundary "
          "id(s) lies at this point. Give the coordinates of a vertex of that "
          "boundary.");
      std::sort(dirichlet_dofs[k].begin(), dirichlet_dofs[k].end());
      dirichlet_dofs[k].erase(std::unique(dirichlet_dofs[k].begin(),
                                          dirichlet_dofs[k].end()),
                              dirichlet_dofs[k].end());
    }


    template <int dim>
    Supports<dim>
    BoundaryConditions<dim>::supports(
      const TrilinosWrappers::MPI::Vector &support_force,
      const TrilinosWrappers::MPI::Vector &solution,
      const double                         force_scale,
      const MPI_Comm                       mpi_communicator) const
    {
      const unsigned int n = dirichlet_dofs.size();
      Supports<dim>      s{std::vector<Tensor<1, dim>>(n),
                      std::vector<Tensor<1, dim>>(n),
                      std::vector<std::array<bool, dim>>(n)};
      for (unsigned int k = 0; k < n; ++k)
        {
          Tensor<1, dim> count;
          for (const auto &[dof, component] : dirichlet_dofs[k])
            {
              s.reactions[k][component] += support_force[dof];
              s.displacement[k][component] += solution[dof];
              count[component] += 1;
            }
          count = Utilities::MPI::sum(count, mpi_communicator);
          s.displacement[k] =
            Utilities::MPI::sum(s.displacement[k], mpi_communicator);
          for (unsigned int d = 0; d < dim; ++d)
            {
              s.components[k][d] = count[d] > 0;
              if (count[d] > 0)
                s.displacement[k][d] /= count[d];
              // Round-off (relative to the force level) is printed as zero
              // so the output does not depend on the number of MPI ranks.
              s.reactions[k][d] =
                Utilities::MPI::sum(s.reactions[k][d], mpi_communicator);
              if (std::abs(s.reactions[k][d]) < 1e-12 * force_scale)
                s.reactions[k][d] = 0;
            }
        }
      return s;
    }


    template <int dim>
    std::string
    BoundaryConditions<dim>::non_finite(const double              t,
                                        const Triangulation<dim> &triangulation,
                                        const MPI_Comm mpi_communicator) const
    {
      std::vector<std::pair<std::string, FunctionParser<dim> *>> loads;
      for (unsigned int k = 0; k < dirichlet_functions.size(); ++k)
        loads.emplace_back("Dirichlet " + std::to_string(k + 1),
                           dirichlet_functions[k].get());
      for (unsigned int k = 0; k < neumann_functions.size(); ++k)
        loads.emplace_back("Neumann " + std::to_string(k + 1),
                           neumann_functions[k].get());
      const double none = std::numeric_limits<double>::max();
      std::string  text;
      for (const auto &[name, f] : loads)
        {
          // The first vertex of an owned cell where a component is not
          // finite, reduced to the smallest rank that has one.
          const double t_before = f->get_time();
          f->set_time(t);
          std::vector<double> where(dim + 1, none);
          for (const auto &cell : triangulation.active_cell_iterators())
            if (cell->is_locally_owned() && where[0] == none)
              for (const unsigned int v : cell->vertex_indices())
                {
                  bool finite = true;
                  for (unsigned int c = 0; c < f->n_components; ++c)
                    finite =
                      finite && std::isfinite(f->value(cell->vertex(v), c));
                  if (!finite)
                    {
                      where[0] =
                        Utilities::MPI::this_mpi_process(mpi_communicator);
                      for (unsigned int d = 0; d < dim; ++d)
                        where[d + 1] = cell->vertex(v)[d];
                      break;
                    }
                }
          f->set_time(t_before);
          for (const auto &w :
               Utilities::MPI::all_gather(mpi_communicator, where))
            if (w[0] != none)
              {
                text += "; subsection 'Boundary conditions/" + name +
                        "', parameter 'Values' is not finite at t = " +
                        Postprocess::format(t, 4) + ", x = (";
                for (unsigned int d = 0; d < dim; ++d)
                  text += (d ? ", " : "") + Postprocess::format(w[d + 1], 4);
                text += ")";
                break;
              }
        }
      return text;
    }


    template class BoundaryConditions<2>;
    template class BoundaryConditions<3>;
  } // namespace Bulk
} // namespace Signorini
