#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <signorini/base/errors.h>
#include <signorini/base/format.h>
#include <signorini/base/input_checks.h>
#include <signorini/bulk/boundary_conditions.h>

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


      // A Cartesian value u_dof = value; false if the DoF is constrained
      // already (a hanging node, an earlier condition).
      template <int dim>
      bool
      add_line(const types::global_dof_index dof,
               const double                  value,
               AffineConstraints<double>    &values,
               AffineConstraints<double>    &update)
      {
        if (values.is_constrained(dof))
          return false;
        values.add_line(dof);
        values.set_inhomogeneity(dof, value);
        update.add_line(dof);
        return true;
      }


      // The DoFs of one support point, one per displacement component.
      template <int dim>
      using Node = std::array<types::global_dof_index, dim>;

      // The support points on the faces of boundaries @p ids of the cells
      // this rank knows (owned and ghost), with their positions.
      template <int dim>
      std::map<Node<dim>, Point<dim>>
      boundary_nodes(const Mapping<dim>              &mapping,
                     const DoFHandler<dim>           &dof_handler,
                     const std::vector<unsigned int> &ids)
      {
        const auto                          &fe = dof_handler.get_fe();
        std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
        std::map<Node<dim>, Point<dim>>      nodes;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  std::count(ids.begin(),
                             ids.end(),
                             cell->face(f)->boundary_id()))
                {
                  cell->get_dof_indices(cell_dofs);
                  for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
                    if (fe.system_to_component_index(i).first == 0 &&
                        fe.has_support_on_face(i, f))
                      {
                        const unsigned int base =
                          fe.system_to_component_index(i).second;
                        Node<dim> node;
                        for (unsigned int c = 0; c < dim; ++c)
                          node[c] =
                            cell_dofs[fe.component_to_system_index(c, base)];
                        if (nodes.count(node) == 0)
                          nodes[node] = mapping.transform_unit_to_real_cell(
                            cell, fe.unit_support_point(i));
                      }
                }
        return nodes;
      }

      // A linear relation sum_i a_i u_i = g among the DoFs of one node.
      struct Relation
      {
        std::map<types::global_dof_index, double> a;
        double                                    g = 0;
      };

      // The coefficients of @p relation along the components of @p node.
      template <int dim>
      Tensor<1, dim>
      along(const Relation &relation, const Node<dim> &node)
      {
        Tensor<1, dim> a;
        for (unsigned int c = 0; c < dim; ++c)
          if (const auto i = relation.a.find(node[c]); i != relation.a.end())
            a[c] = i->second;
        return a;
      }

      // Adds @p relation among the DoFs of @p node as a constraint line:
      // the node's DoFs constrained already (by earlier conditions) are
      // eliminated from it first, then it is solved for the free DoF with
      // the largest coefficient. So two conditions meeting at a node (two
      // rollers at a corner, a roller and a Cartesian value) combine
      // without a cycle. A relation that earlier lines imply adds nothing;
      // a node whose DoF is constrained from outside the node (a hanging
      // node) keeps its lines, as for Cartesian values.
      //
      // Returns the line added, as u_pivot = sum_j w_j u_j + g: the pivot
      // and its entries (pivot invalid_dof_index: none added).
      template <int dim>
      std::pair<types::global_dof_index,
                std::vector<std::pair<types::global_dof_index, double>>>
      add_relation(Relation                   relation,
                   const Node<dim>           &node,
                   AffineConstraints<double> &values,
                   AffineConstraints<double> &update)
      {
        std::pair<types::global_dof_index,
                  std::vector<std::pair<types::global_dof_index, double>>>
               added{numbers::invalid_dof_index, {}};
        double scale = 0;
        for (const auto &[i, a] : relation.a)
          scale = std::max(scale, std::abs(a));
        for (bool again = true; again;)
          {
            again = false;
            for (const auto [i, a] : relation.a)
              if (values.is_constrained(i))
                {
                  const auto *entries = values.get_constraint_entries(i);
                  for (const auto &[j, w] : *entries)
                    if (std::find(node.begin(), node.end(), j) == node.end())
                      return added; // hanging
                  relation.g -= a * values.get_inhomogeneity(i);
                  relation.a.erase(i);
                  for (const auto &[j, w] : *entries)
                    relation.a[j] += a * w;
                  again = true;
                  break;
                }
          }
        types::global_dof_index pivot   = numbers::invalid_dof_index;
        double                  largest = 1e-12 * scale;
        for (const auto &[i, a] : relation.a)
          if (std::abs(a) > largest)
            {
              largest = std::abs(a);
              pivot   = i;
            }
        if (pivot == numbers::invalid_dof_index)
          return added;
        const double a_p = relation.a[pivot];
        values.add_line(pivot);
        update.add_line(pivot);
        added.first = pivot;
        for (const auto &[i, a] : relation.a)
          if (i != pivot && a != 0)
            {
              values.add_entry(pivot, i, -a / a_p);
              update.add_entry(pivot, i, -a / a_p);
              added.second.emplace_back(i, -a / a_p);
            }
        values.set_inhomogeneity(pivot, relation.g / a_p);
        return added;
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
      locally_owned         = owned;
      dirichlet_dofs.assign(parameters.dirichlet.size(), {});
      held_nodes.clear();
      held_index.clear();
      point_line_dofs.clear();
      for (unsigned int k = 0; k < parameters.dirichlet.size(); ++k)
        {
          const auto &d = parameters.dirichlet[k];
          dirichlet_functions[k]->set_time(time);
          if (!d.at_point.empty())
            {
              add_point_constraint(k, dof_handler, tolerance, values, update);
              continue;
            }
          if (d.frame == DirichletFrame::normal ||
              d.frame == DirichletFrame::tangential)
            {
              add_flux_constraint(k, mapping, dof_handler, values, update);
              continue;
            }
          if (d.frame == DirichletFrame::direction)
            {
              add_direction_constraint(k, mapping, dof_handler, values, update);
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
          const std::set<types::boundary_id> ids(d.boundary_ids.begin(),
                                                 d.boundary_ids.end());
          std::map<types::global_dof_index, unsigned int> component_of;
          for (const auto c : d.components)
            {
              std::vector<bool> component(dim, false);
              component[c] = true;
              const IndexSet dofs =
                DoFTools::extract_boundary_dofs(dof_handler,
                                                ComponentMask(component),
                                                ids);
              for (const auto dof : dofs)
                {
                  component_of[dof] = c;
                  if (owned.is_element(dof))
                    dirichlet_dofs[k].emplace_back(dof, c);
                }
            }
          std::sort(dirichlet_dofs[k].begin(), dirichlet_dofs[k].end());
          // The node of each DoF: its support force is shared among the
          // conditions that hold the node (supports()).
          std::map<types::global_dof_index, Node<dim>> node_of;
          for (const auto &[node, point] :
               boundary_nodes(mapping, dof_handler, d.boundary_ids))
            for (const auto dof : node)
              node_of[dof] = node;
          for (const auto &[dof, value] : boundary_values)
            if (add_line<dim>(dof, value, values, update) &&
                component_of.count(dof) > 0 && node_of.count(dof) > 0)
              {
                Tensor<1, dim> a;
                a[component_of[dof]] = 1;
                hold(k, node_of[dof], a);
              }
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
                      const unsigned int c     = d.components[i];
                      const auto         dof   = face->vertex_dof_index(v, c);
                      const bool         added = add_line<dim>(
                        dof, f.value(face->vertex(v), i), values, update);
                      if (owned.is_element(dof))
                        dirichlet_dofs[k].emplace_back(dof, c);
                      if (added)
                        {
                          point_line_dofs.insert(dof);
                          Node<dim> node;
                          for (unsigned int j = 0; j < dim; ++j)
                            node[j] = face->vertex_dof_index(v, j);
                          Tensor<1, dim> a;
                          a[c] = 1;
                          hold(k, node, a);
                        }
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


    // u.n = v.n (normal) or u - v parallel to n (tangential: the
    // tangential part of u is that of v) on the condition's boundaries. The
    // normal at a node is deal.II's (the average over the node's faces, as
    // its normal-flux constraints compute it; a node where they find two
    // normals, an edge, is held at v). deal.II's own tangential constraints
    // are not used: their values are right only where v has no component
    // along the normal's largest coordinate. Only nodes on locally owned
    // cells are constrained: their faces are all known on this rank, so
    // every rank computes the same lines.
    template <int dim>
    void
    BoundaryConditions<dim>::add_flux_constraint(
      const unsigned int         k,
      const Mapping<dim>        &mapping,
      const DoFHandler<dim>     &dof_handler,
      AffineConstraints<double> &values,
      AffineConstraints<double> &update)
    {
      const auto                        &d = parameters.dirichlet[k];
      const auto                        &v = *dirichlet_functions[k];
      const std::set<types::boundary_id> ids(d.boundary_ids.begin(),
                                             d.boundary_ids.end());
      std::map<types::boundary_id, const Function<dim> *> on_boundary;
      for (const auto id : ids)
        on_boundary[id] = &v;
      AffineConstraints<double> lines;
      lines.reinit(DoFTools::extract_locally_relevant_dofs(dof_handler));
      if (d.frame == DirichletFrame::normal)
        VectorTools::compute_nonzero_normal_flux_constraints(
          dof_handler, 0, ids, on_boundary, lines, mapping);
      else
        VectorTools::compute_no_normal_flux_constraints(
          dof_handler, 0, ids, lines, mapping);
      const IndexSet active =
        DoFTools::extract_locally_active_dofs(dof_handler);
      const auto nodes = boundary_nodes(mapping, dof_handler, d.boundary_ids);
      for (const auto &[node, point] : nodes)
        {
          if (!active.is_element(node[0]))
            continue;
          std::vector<unsigned int> constrained; // components with a line
          for (unsigned int c = 0; c < dim; ++c)
            if (lines.is_constrained(node[c]))
              constrained.push_back(c);
          if (constrained.empty())
            continue;
          if (d.frame == DirichletFrame::normal)
            for (const unsigned int c : constrained)
              {
                // u_c - sum_j w_j u_j = g.
                Relation relation;
                relation.a[node[c]] = 1;
                for (const auto &[j, w] :
                     *lines.get_constraint_entries(node[c]))
                  relation.a[j] -= w;
                relation.g = lines.get_inhomogeneity(node[c]);
                if (add_relation<dim>(relation, node, values, update).first !=
                    numbers::invalid_dof_index)
                  hold(k, node, along<dim>(relation, node));
              }
          else if (constrained.size() > 1)
            for (unsigned int c = 0; c < dim; ++c)
              {
                Relation relation; // an edge: u = v
                relation.a[node[c]] = 1;
                relation.g          = v.value(point, c);
                if (add_relation<dim>(relation, node, values, update).first !=
                    numbers::invalid_dof_index)
                  hold(k, node, along<dim>(relation, node));
              }
          else
            {
              // The normal line u_c = sum_j w_j u_j, w_j = -n_j / n_c: u - v
              // along n is u_j - v_j = -w_j (u_c - v_c) for j != c.
              const unsigned int c = constrained[0];
              Tensor<1, dim>     w;
              for (const auto &[j, weight] :
                   *lines.get_constraint_entries(node[c]))
                for (unsigned int i = 0; i < dim; ++i)
                  if (node[i] == j)
                    w[i] = weight;
              for (unsigned int i = 0; i < dim; ++i)
                if (i != c)
                  {
                    Relation relation;
                    relation.a[node[i]] = 1;
                    relation.a[node[c]] = w[i];
                    relation.g = v.value(point, i) + w[i] * v.value(point, c);
                    if (add_relation<dim>(relation, node, values, update)
                          .first != numbers::invalid_dof_index)
                      hold(k, node, along<dim>(relation, node));
                  }
            }
        }
      record_node_dofs(k, nodes, dof_handler.locally_owned_dofs());
    }


    // u.d = g along the unit direction d at every node of the condition's
    // boundary faces.
    template <int dim>
    void
    BoundaryConditions<dim>::add_direction_constraint(
      const unsigned int         k,
      const Mapping<dim>        &mapping,
      const DoFHandler<dim>     &dof_handler,
      AffineConstraints<double> &values,
      AffineConstraints<double> &update)
    {
      const auto    &d = parameters.dirichlet[k];
      Tensor<1, dim> n;
      for (unsigned int i = 0; i < dim; ++i)
        n[i] = d.direction[i];
      n /= n.norm();
      const auto nodes = boundary_nodes(mapping, dof_handler, d.boundary_ids);
      for (const auto &[node, point] : nodes)
        {
          Relation relation;
          for (unsigned int j = 0; j < dim; ++j)
            relation.a[node[j]] = n[j];
          relation.g = dirichlet_functions[k]->value(point, 0);
          if (add_relation<dim>(relation, node, values, update).first !=
              numbers::invalid_dof_index)
            hold(k, node, along<dim>(relation, node));
        }
      record_node_dofs(k, nodes, dof_handler.locally_owned_dofs());
    }


    template <int dim>
    void
    BoundaryConditions<dim>::hold(
      const unsigned int                              k,
      const std::array<types::global_dof_index, dim> &node,
      const Tensor<1, dim>                           &a)
    {
      if (!locally_owned.is_element(node[0]))
        return;
      const auto [it, added] = held_index.emplace(node, held_nodes.size());
      if (added)
        held_nodes.push_back({node, {}});
      held_nodes[it->second].relations.emplace_back(k, a);
    }


    template <int dim>
    void
    BoundaryConditions<dim>::record_node_dofs(
      const unsigned int k,
      const std::map<std::array<types::global_dof_index, dim>, Point<dim>>
                     &nodes,
      const IndexSet &owned)
    {
      for (const auto &[node, point] : nodes)
        for (unsigned int c = 0; c < dim; ++c)
          if (owned.is_element(node[c]))
            dirichlet_dofs[k].emplace_back(node[c], c);
      std::sort(dirichlet_dofs[k].begin(), dirichlet_dofs[k].end());
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
                      std::vector<std::array<bool, dim>>(n),
                      {}};
      // The support force f at a node held by conditions with relations
      // a_k . u = g_k (a Cartesian value: a_k = e_c) is the sum of their
      // forces mu_k a_k: the equilibrium of the node's free motions (those
      // with a_k . v = 0 for all k) puts f in the span of the a_k. Solving
      // (A^T A) mu = A^T f charges each condition its own part, whatever
      // the order in which the lines were added and which DoF each was
      // solved for; the reactions sum to the total support force.
      for (const auto &held : held_nodes)
        {
          const unsigned int m = held.relations.size();
          Tensor<1, dim>     f;
          for (unsigned int c = 0; c < dim; ++c)
            f[c] = support_force[held.dofs[c]];
          FullMatrix<double> G(m, m);
          Vector<double>     rhs(m), mu(m);
          for (unsigned int i = 0; i < m; ++i)
            {
              rhs(i) = held.relations[i].second * f;
              for (unsigned int j = 0; j < m; ++j)
                G(i, j) = held.relations[i].second * held.relations[j].second;
            }
          G.gauss_jordan();
          G.vmult(mu, rhs);
          Tensor<1, dim> node_force;
          for (unsigned int i = 0; i < m; ++i)
            {
              s.reactions[held.relations[i].first] +=
                mu(i) * held.relations[i].second;
              node_force += mu(i) * held.relations[i].second;
            }
          s.node_forces.emplace_back(held.dofs[0], node_force);
        }
      for (unsigned int k = 0; k < n; ++k)
        {
          Tensor<1, dim> count;
          for (const auto &[dof, component] : dirichlet_dofs[k])
            {
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
