// Contact surfaces: slave and master faces, multiplier numbering, exclusions
// at Dirichlet conditions, constraint lines.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/contact/contact_problem.h>
#include <signorini/contact/distributed_vectors.h>
#include <signorini/contact/segmentation.h>
#include <signorini/postprocess/output_files.h>

#include "helpers.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <set>

namespace Signorini
{
  namespace Contact
  {
    using internal::add_entry;
    using internal::faces_meeting;
    using internal::offset_of;
    using internal::pair_name;
    using internal::writable_vector;


    template <int dim>
    void
    ContactProblem<dim>::setup(const AffineConstraints<double> &u_constraints,
                               const IndexSet                  &owned_u,
                               ConditionalOStream              &pcout)
    {
      const auto        &pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
      n_u                        = dof_handler.n_dofs();

      // Which pair a boundary id is slave / master of.
      std::map<types::boundary_id, unsigned int> slave_of, master_of;
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          for (const auto id : pairs[p].slave_ids)
            if (!slave_of.emplace(id, p).second)
              throw InputError(pair_name(p) +
                               ", parameter 'Slave boundary "
                               "id': boundary " +
                               std::to_string(id) +
                               " is already the slave surface of " +
                               pair_name(slave_of[id]) +
                               ". Each slave boundary belongs to one pair.");
          if (pairs[p].master_is_body())
            for (const auto id : pairs[p].master_ids)
              master_of.emplace(id, p);
        }

      // Slave nodes seen by this rank, keyed by their x-DoF.
      struct SeenNode
      {
        std::array<types::global_dof_index, dim> dofs;
        std::vector<Tensor<1, dim>>              normals;
        unsigned int                             pair;
      };
      std::map<types::global_dof_index, SeenNode> seen;

      const QGauss<dim - 1>                centre_quadrature(1);
      FEFaceValues<dim>                    centre_values(fe,
                                      centre_quadrature,
                                      update_normal_vectors);
      const unsigned int                   n_cell_dofs = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> cell_dofs(n_cell_dofs);
      std::vector<double> h_sum(n_pairs, 0.), h_count(n_pairs, 0.),
        e_max(n_pairs, 0.), e_master(n_pairs, 0.);
      slave_faces.clear();
      master_faces.clear();
      own_master_cells.clear();

      // Master faces this rank owns, packed for the all-gather.
      std::vector<double>                  master_reals;
      std::vector<types::global_dof_index> master_ints;
      std::vector<types::global_dof_index> line_ints;
      std::vector<double>                  line_reals;
      const unsigned int   n_face_nodes = face_fe.n_dofs_per_cell();
      const MappingQ1<dim> mapping;

      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const auto id = cell->face(f)->boundary_id();
                cell->get_dof_indices(cell_dofs);
                if (const auto s = slave_of.find(id); s != slave_of.end())
                  {
                    const unsigned int p = s->second;
                    centre_values.reinit(cell, f);
                    SlaveFace face;
                    face.cell           = cell;
                    face.face           = f;
                    face.pair           = p;
                    face.outward_normal = centre_values.normal_vector(0);
                    for (unsigned int i = 0; i < n_cell_dofs; ++i)
                      if (fe.has_support_on_face(i, f))
                        {
                          face.u_local.push_back(i);
                          const auto ci = fe.system_to_component_index(i);
                          if (ci.first != 0)
                            continue;
                          face.node_local.push_back(i);
                          auto &node = seen[cell_dofs[i]];
                          for (unsigned int c = 0; c < dim; ++c)
                            node.dofs[c] =
                              cell_dofs[fe.component_to_system_index(
                                c, ci.second)];
                          node.normals.push_back(face.outward_normal);
                          node.pair = p;
                        }
                    // The face map in FE_Q<dim-1> order (as the master
                    // faces) and the links to node_local / u_local.
                    face.X.resize(n_face_nodes);
                    face.k_node.resize(n_face_nodes);
                    for (unsigned int i = 0; i < fe.n_dofs_per_face(); ++i)
                      {
                        const auto [c, k] =
                          fe.face_system_to_component_index(i);
                        if (c != 0)
                          continue;
                        const unsigned int cell_i =
                          fe.face_to_cell_index(i,
                                                f,
                                                cell->face_orientation(f),
                                                cell->face_flip(f),
                                                cell->face_rotation(f));
                        face.X[k] = mapping.transform_unit_to_real_cell(
                          cell, fe.unit_support_point(cell_i));
                        face.k_node[k] = std::find(face.node_local.begin(),
                                                   face.node_local.end(),
                                                   cell_i) -
                                         face.node_local.begin();
                      }
                    face.node_dofs.resize(face.node_local.size() * dim);
                    for (unsigned int l = 0; l < face.node_local.size(); ++l)
                      for (unsigned int c = 0; c < dim; ++c)
                        face.node_dofs[l * dim + c] =
                          cell_dofs[fe.component_to_system_index(
                            c,
                            fe.system_to_component_index(face.node_local[l])
                              .second)];
                    for (const auto i : face.u_local)
                      {
                        const auto ci = fe.system_to_component_index(i);
                        face.u_comp.push_back(ci.first);
                        for (unsigned int l = 0; l < face.node_local.size();
                             ++l)
                          if (fe.system_to_component_index(face.node_local[l])
                                .second == ci.second)
                            face.u_node.push_back(l);
                      }
                    if (cell->is_locally_owned())
                      {
                        h_sum[p] += cell->face(f)->diameter();
                        h_count[p] += 1;
                        e_max[p] = std::max(e_max[p],
                                            materials.at(cell->material_id())
                                              ->representative_modulus());
                        slave_faces.push_back(face);
                      }
                  }
                else if (const auto m = master_of.find(id);
                         m != master_of.end() && cell->is_locally_owned())
                  {
                    master_ints.push_back(m->second);
                    const auto id = cell->id().template to_binary<dim>();
                    for (const auto k : id)
                      master_ints.push_back(k);
                    master_ints.push_back(f);
                    master_ints.push_back(own_master_cells.size());
                    own_master_cells.push_back(cell);
                    e_master[m->second] =
                      std::max(e_master[m->second],
                               materials.at(cell->material_id())
                                 ->representative_modulus());
                    // Nodes in the face's FE_Q<dim-1> order (see
                    // project_onto_face), dim DoFs each.
                    std::vector<types::global_dof_index> node_dofs(
                      n_face_nodes * dim);
                    std::vector<Point<dim>> X(n_face_nodes);
                    for (unsigned int i = 0; i < fe.n_dofs_per_face(); ++i)
                      {
                        const auto [c, k] =
                          fe.face_system_to_component_index(i);
                        const unsigned int cell_i =
                          fe.face_to_cell_index(i,
                                                f,
                                                cell->face_orientation(f),
                                                cell->face_flip(f),
                                                cell->face_rotation(f));
                        node_dofs[k * dim + c] = cell_dofs[cell_i];
                        if (c == 0)
                          X[k] = mapping.transform_unit_to_real_cell(
                            cell, fe.unit_support_point(cell_i));
                      }
                    for (const auto d : node_dofs)
                      {
                        master_ints.push_back(d);
                        if (const auto *entries =
                              u_constraints.get_constraint_entries(d))
                          {
                            line_ints.push_back(d);
                            line_ints.push_back(entries->size());
                            for (const auto &e : *entries)
                              {
                                line_ints.push_back(e.first);
                                line_reals.push_back(e.second);
                              }
                          }
                      }
                    for (const auto &x : X)
                      for (unsigned int d = 0; d < dim; ++d)
                        master_reals.push_back(x[d]);
                    const Point<dim> c = cell->center();
                    for (unsigned int d = 0; d < dim; ++d)
                      master_reals.push_back(c[d]);
                  }
              }

      // Coefficients (formulation.md 8, "magic coefficients"): rho_n = c_n
      // E / h with h the mean slave face size and E the softer body's
      // Young's modulus (slave, or a meshed master that is softer: a gap
      // error is resisted by the softer body, and rho_n from a stiff slave
      // on a soft master weighs the gap 1/contrast too much);
      // rho_t = c_t rho_n / (mu p_ref) makes the tangential stiffness mu p_ref
      // rho_t of a sticking point comparable to rho_n (see
      // update_coefficients); before any pressure is known p_ref = 1e-3 E.
      rho_n.assign(n_pairs, 0.);
      rho_t.assign(n_pairs, 0.);
      p_ref.assign(n_pairs, 0.);
      face_size.assign(n_pairs, 0.);
      youngs.assign(n_pairs, 0.);
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          const double hs = Utilities::MPI::sum(h_sum[p], comm);
          const double hc = Utilities::MPI::sum(h_count[p], comm);
          const double E  = Utilities::MPI::max(e_max[p], comm);
          const double Em = Utilities::MPI::max(e_master[p], comm);
          if (hc == 0)
            throw InputError(pair_name(p) +
                             ", parameter 'Slave boundary id': no boundary "
                             "face of the mesh has these ids. Use ids the "
                             "mesh has (see 'Boundary ids' of the bodies).");
          face_size[p] = hs / hc;
          youngs[p]    = E;
          rho_n[p] = pairs[p].rho_n_factor * (Em > 0 ? std::min(E, Em) : E) /
                     face_size[p];
          p_ref[p] = 1e-3 * E;
          rho_t[p] = pairs[p].friction > 0 ? pairs[p].rho_t_factor * rho_n[p] /
                                               (pairs[p].friction * p_ref[p]) :
                                             1.;
          if (obstacles[p])
            obstacles[p]->set_length_scale(face_size[p]);
        }

      // Owned slave nodes: exclusion (Dirichlet on a component along the
      // face normal -> no contact; along the face -> no friction) and
      // hanging-node weights, decided by the owner.
      std::vector<types::global_dof_index> owned_nodes;
      for (const auto &[dof0, node] : seen)
        if (owned_u.is_element(dof0))
          owned_nodes.push_back(dof0);
      std::sort(owned_nodes.begin(), owned_nodes.end());
      types::global_dof_index n_owned_friction = 0;
      for (const auto d : owned_nodes)
        if (pairs[seen[d].pair].friction > 0)
          ++n_owned_friction;
      const types::global_dof_index n_owned_nodes = owned_nodes.size();
      n_lambda      = Utilities::MPI::sum(n_owned_nodes, comm);
      n_friction    = Utilities::MPI::sum(n_owned_friction, comm) * (dim - 1);
      n_nodes_total = n_lambda;
      const types::global_dof_index lambda_offset =
        n_u + offset_of(n_owned_nodes, comm);
      const types::global_dof_index friction_offset =
        n_u + n_lambda + offset_of(n_owned_friction, comm) * (dim - 1);

      std::vector<double> node_pack;
      {
        types::global_dof_index jf = 0;
        for (unsigned int j = 0; j < owned_nodes.size(); ++j)
          {
            const auto &node            = seen[owned_nodes[j]];
            bool        exclude_contact = false, exclude_friction = false;
            std::vector<std::pair<types::global_dof_index, double>> hanging;
            for (unsigned int c = 0; c < dim; ++c)
              if (const auto *entries =
                    u_constraints.get_constraint_entries(node.dofs[c]))
                {
                  if (!entries->empty())
                    {
                      if (c == 0)
                        hanging = *entries;
                      continue;
                    }
                  for (const auto &n : node.normals)
                    (std::abs(n[c]) > 0.5 ? exclude_contact :
                                            exclude_friction) = true;
                }
            const bool friction = pairs[node.pair].friction > 0;
            node_pack.push_back(owned_nodes[j]);
            node_pack.push_back(lambda_offset + j);
            node_pack.push_back(friction ? friction_offset + (dim - 1) * jf++ :
                                           -1.);
            node_pack.push_back(exclude_contact);
            node_pack.push_back(exclude_friction && friction);
            node_pack.push_back(node.pair);
            node_pack.push_back(hanging.size());
            for (const auto &[d, w] : hanging)
              {
                node_pack.push_back(d);
                node_pack.push_back(w);
              }
          }
      }
      nodes.clear();
      unsigned int n_excluded_contact = 0, n_excluded_friction = 0,
                   n_hanging = 0;
      for (const auto &pack : Utilities::MPI::all_gather(comm, node_pack))
        for (unsigned int i = 0; i < pack.size();)
          {
            NodeInfo   info;
            const auto dof0 = static_cast<types::global_dof_index>(pack[i]);
            info.lambda     = static_cast<types::global_dof_index>(pack[i + 1]);
            if (pack[i + 2] >= 0)
              info.friction = static_cast<types::global_dof_index>(pack[i + 2]);
            info.exclude_contact  = pack[i + 3] != 0;
            info.exclude_friction = pack[i + 4] != 0;
            info.pair             = static_cast<unsigned int>(pack[i + 5]);
            const unsigned int nh = static_cast<unsigned int>(pack[i + 6]);
            i += 7;
            for (unsigned int k = 0; k < nh; ++k, i += 2)
              info.hanging.emplace_back(
                static_cast<types::global_dof_index>(pack[i]), pack[i + 1]);
            n_excluded_contact += info.exclude_contact;
            n_excluded_friction +=
              !info.exclude_contact && info.exclude_friction;
            n_hanging += !info.hanging.empty();
            nodes.emplace(dof0, std::move(info));
          }

      owned_multipliers = IndexSet(n_system());
      if (n_owned_nodes > 0)
        owned_multipliers.add_range(lambda_offset,
                                    lambda_offset + n_owned_nodes);
      if (n_owned_friction > 0)
        owned_multipliers.add_range(friction_offset,
                                    friction_offset +
                                      n_owned_friction * (dim - 1));
      owned_multipliers.compress();

      // Multiplier numbers of the slave faces.
      extra = IndexSet(n_system());
      extra.add_indices(owned_multipliers);
      const auto add_node = [&](const types::global_dof_index dof0) {
        const auto &info = nodes.at(dof0);
        extra.add_index(info.lambda);
        if (info.friction != numbers::invalid_dof_index)
          extra.add_range(info.friction, info.friction + dim - 1);
      };
      for (auto &face : slave_faces)
        {
          face.cell->get_dof_indices(cell_dofs);
          for (const auto i : face.node_local)
            {
              const auto &info = nodes.at(cell_dofs[i]);
              face.lambda_dofs.push_back(info.lambda);
              add_node(cell_dofs[i]);
              for (const auto &h : info.hanging)
                add_node(h.first);
              if (info.friction != numbers::invalid_dof_index)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  face.friction_dofs.push_back(info.friction + k);
            }
        }

      // Master faces and the constraint lines of their DoFs, from all ranks.
      const auto all_reals = Utilities::MPI::all_gather(comm, master_reals);
      const auto all_ints  = Utilities::MPI::all_gather(comm, master_ints);
      const unsigned int key_size =
        std::tuple_size<CellId::binary_type>::value + 1;
      for (unsigned int r = 0; r < all_ints.size(); ++r)
        {
          const bool   mine = r == Utilities::MPI::this_mpi_process(comm);
          unsigned int ir   = 0;
          for (unsigned int ii = 0; ii < all_ints[r].size();)
            {
              MasterFace face;
              face.pair = all_ints[r][ii++];
              face.key.assign(all_ints[r].begin() + ii,
                              all_ints[r].begin() + ii + key_size);
              ii += key_size;
              const int own_cell = all_ints[r][ii++];
              face.own_cell      = mine ? own_cell : -1;
              face.dofs.assign(all_ints[r].begin() + ii,
                               all_ints[r].begin() + ii + n_face_nodes * dim);
              ii += n_face_nodes * dim;
              face.X.resize(n_face_nodes);
              for (auto &x : face.X)
                for (unsigned int d = 0; d < dim; ++d)
                  x[d] = all_reals[r][ir++];
              for (unsigned int d = 0; d < dim; ++d)
                face.inside[d] = all_reals[r][ir++];
              for (const auto d : face.dofs)
                extra.add_index(d);
              master_faces.push_back(std::move(face));
            }
        }
      // The gathered order follows the partition; the search (ties between
      // equally good faces) and the mortar cuts (the first master face that
      // covers a piece of an overlapped slave face) must not.
      std::sort(master_faces.begin(),
                master_faces.end(),
                [](const MasterFace &a, const MasterFace &b) {
                  return a.key < b.key;
                });
      master_lines.clear();
      {
        const auto all_line_ints = Utilities::MPI::all_gather(comm, line_ints);
        const auto all_line_reals =
          Utilities::MPI::all_gather(comm, line_reals);
        std::set<types::global_dof_index> done;
        for (unsigned int r = 0; r < all_line_ints.size(); ++r)
          {
            unsigned int ir = 0;
            for (unsigned int ii = 0; ii < all_line_ints[r].size();)
              {
                const auto         d  = all_line_ints[r][ii++];
                const unsigned int ne = all_line_ints[r][ii++];
                std::vector<std::pair<types::global_dof_index, double>> e;
                for (unsigned int k = 0; k < ne; ++k)
                  {
                    e.emplace_back(all_line_ints[r][ii++],
                                   all_line_reals[r][ir++]);
                    extra.add_index(e.back().first);
                  }
                if (done.insert(d).second)
                  master_lines.emplace_back(d, std::move(e));
              }
          }
      }
      extra.compress();
      // Vectors over the multipliers alone (weighted gaps, initial
      // multipliers, nodal fields) hold no u entries: their ghosts are the
      // multiplier part of 'extra'. A u index there has no owner in such a
      // vector, and Epetra's import then shifts the ghost values it fills
      // (garbage at nodes on partition boundaries on 3 ranks).
      multiplier_ghosts = IndexSet(n_system());
      multiplier_ghosts.add_indices(extra.get_view(n_u, n_system()), n_u);
      multiplier_ghosts.compress();

      for (unsigned int p = 0; p < n_pairs; ++p)
        if (pairs[p].master_is_body())
          {
            bool found = false;
            for (const auto &f : master_faces)
              found |= (f.pair == p);
            if (!found)
              throw InputError(pair_name(p) +
                               ", parameter 'Master boundary id': no boundary "
                               "face of the mesh has these ids. Use ids the "
                               "mesh has (see 'Boundary ids' of the bodies).");
          }

      // Node-status pairs: dual multipliers on the faces without a hanging
      // node (whose multiplier interpolates its parents' and is no
      // unknown of its own: the face keeps psi there).
      for (auto &face : slave_faces)
        {
          bool hanging = false;
          face.excluded_contact.assign(face.node_local.size(), false);
          face.excluded_friction.assign(face.node_local.size(), false);
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              const auto &info = nodes.at(face.node_dofs[l * dim]);
              hanging |= !info.hanging.empty();
              face.excluded_contact[l] = info.exclude_contact;
              face.excluded_friction[l] =
                info.exclude_contact || info.exclude_friction;
            }
          face.dual.clear();
          if (node_status_pair[face.pair] && !hanging)
            face.dual = dual_basis(face);
        }

      // Contact points: the rule's points on every owned slave face (the
      // mortar rule cuts the faces of meshed pairs at every pairing).
      points.clear();
      for (unsigned int f = 0; f < slave_faces.size(); ++f)
        {
          const auto &quadrature = rule->face_quadrature(f);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            points.push_back(
              make_point(f, q, quadrature.point(q), quadrature.weight(q)));
        }

      const unsigned int n_points_total =
        Utilities::MPI::sum(static_cast<unsigned int>(points.size()), comm);
      pcout << "Contact: " << n_pairs << " pair(s), rule ";
      if (mortar)
        {
          pcout << "mortar (segment-based, " << segment_order
                << (dim == 2 ? " Gauss points per segment" :
                               " points per direction on each triangle")
                << ")";
          for (const auto &obstacle : obstacles)
            if (obstacle)
              {
                pcout << ", nodal on rigid masters";
                break;
              }
        }
      else
        pcout << rule->name() << ", " << n_points_total << " contact points";
      pcout << " on "
            << Utilities::MPI::sum(
                 static_cast<unsigned int>(slave_faces.size()), comm)
            << " slave faces, " << n_lambda << " slave nodes" << std::endl;
      for (unsigned int p = 0; p < n_pairs; ++p)
        pcout << "  pair " << p + 1 << ": mu = " << pairs[p].friction
              << ", h = " << std::setprecision(4) << face_size[p]
              << ", rho_n = " << rho_n[p] << ", rho_t = " << rho_t[p]
              << std::setprecision(6) << std::endl;
      for (unsigned int p = 0; p < n_pairs; ++p)
        if (obstacles[p] && !obstacles[p]->approximate_derivatives().empty())
          pcout << "  pair " << p + 1 << ": "
                << obstacles[p]->approximate_derivatives()
                << ": the contact Jacobian is not exact" << std::endl;
      if (n_excluded_contact + n_excluded_friction > 0)
        pcout << "  over-constraint: " << n_excluded_contact
              << " slave node(s) with a Dirichlet condition along the normal "
                 "excluded from contact, "
              << n_excluded_friction
              << " with a tangential one excluded from friction" << std::endl;
      if (n_hanging > 0)
        pcout << "  " << n_hanging
              << " hanging slave node(s): multipliers interpolated"
              << std::endl;
    }


    template <int dim>
    void
    ContactProblem<dim>::add_constraint_lines(
      AffineConstraints<double> &constraints) const
    {
      const IndexSet &local = constraints.get_local_lines();
      const auto      can   = [&](const types::global_dof_index i) {
        return (local.size() == 0 || local.is_element(i)) &&
               !constraints.is_constrained(i);
      };
      for (const auto &[dof0, info] : nodes)
        {
          const bool has_friction = info.friction != numbers::invalid_dof_index;
          if (info.exclude_contact || !info.hanging.empty())
            {
              if (can(info.lambda))
                {
                  constraints.add_line(info.lambda);
                  if (!info.exclude_contact)
                    for (const auto &[parent, w] : info.hanging)
                      constraints.add_entry(info.lambda,
                                            nodes.at(parent).lambda,
                                            w);
                }
            }
          if (has_friction && (info.exclude_contact || info.exclude_friction ||
                               !info.hanging.empty()))
            for (unsigned int k = 0; k < dim - 1; ++k)
              if (can(info.friction + k))
                {
                  constraints.add_line(info.friction + k);
                  if (!info.exclude_contact && !info.exclude_friction)
                    for (const auto &[parent, w] : info.hanging)
                      constraints.add_entry(info.friction + k,
                                            nodes.at(parent).friction + k,
                                            w);
                }
        }
      for (const auto &[d, entries] : master_lines)
        if (can(d))
          {
            constraints.add_line(d);
            constraints.add_entries(d, entries);
          }
    }


    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace Contact
} // namespace Signorini
