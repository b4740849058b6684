// Contact surfaces: slave and master faces, multiplier numbering, exclusions
// at Dirichlet conditions, constraint lines.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/full_matrix.h>

#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
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
#include <memory>
#include <set>

namespace Signorini
{
  namespace Contact
  {
    using internal::add_entry;
    using internal::offset_of;
    using internal::pair_name;


    /**
     * What setup() collects from this rank's boundary faces before the
     * multipliers are numbered: the pair each boundary id is slave or master
     * of; the slave nodes seen (keyed by their x-DoF) with their DoFs, the
     * normals of their faces and their pair; per pair the sums for the mean
     * slave face size and the largest representative moduli of slave and
     * master; the master faces this rank owns and the constraint lines of
     * their DoFs (sent to every rank).
     */
    template <int dim>
    struct ContactProblem<dim>::SurfaceScan
    {
      std::map<types::boundary_id, unsigned int> slave_of, master_of;
      struct SeenNode
      {
        std::array<types::global_dof_index, dim> dofs;
        std::vector<Tensor<1, dim>>              normals;
        unsigned int                             pair;
      };
      std::map<types::global_dof_index, SeenNode> seen;
      std::vector<double>     h_sum, h_count, e_max, e_master;
      std::vector<MasterFace> own_master_faces;
      std::vector<MasterLine> own_master_lines;
      // Outward normals at slave face centres; positions of support points.
      std::unique_ptr<FEFaceValues<dim>> centre_values;
    };


    template <int dim>
    void
    ContactProblem<dim>::setup(const AffineConstraints<double> &u_constraints,
                               const IndexSet                  &owned_u,
                               ConditionalOStream              &pcout)
    {
      n_u       = dof_handler.n_dofs();
      auto scan = scan_boundary(u_constraints);
      set_coefficients(scan);
      const auto counts = number_multipliers(scan, owned_u, u_constraints);
      gather_master_faces(scan);
      finish_slave_faces();

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
      print_setup(pcout, counts);
    }


    template <int dim>
    typename ContactProblem<dim>::SurfaceScan
    ContactProblem<dim>::scan_boundary(
      const AffineConstraints<double> &u_constraints)
    {
      const auto        &pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
      SurfaceScan        scan;
      scan.centre_values = std::make_unique<FEFaceValues<dim>>(
        mapping, fe, QGauss<dim - 1>(1), update_normal_vectors);
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          for (const auto id : pairs[p].slave_ids)
            if (!scan.slave_of.emplace(id, p).second)
              throw InputError(pair_name(p) +
                               ", parameter 'Slave boundary "
                               "id': boundary " +
                               std::to_string(id) +
                               " is already the slave surface of " +
                               pair_name(scan.slave_of[id]) +
                               ". Each slave boundary belongs to one pair.");
          if (pairs[p].master_is_body())
            for (const auto id : pairs[p].master_ids)
              scan.master_of.emplace(id, p);
        }
      scan.h_sum.assign(n_pairs, 0.);
      scan.h_count.assign(n_pairs, 0.);
      scan.e_max.assign(n_pairs, 0.);
      scan.e_master.assign(n_pairs, 0.);
      slave_faces.clear();
      master_faces.clear();
      own_master_cells.clear();

      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const auto id = cell->face(f)->boundary_id();
                cell->get_dof_indices(cell_dofs);
                if (const auto s = scan.slave_of.find(id);
                    s != scan.slave_of.end())
                  add_slave_face(cell, f, s->second, cell_dofs, scan);
                else if (const auto m = scan.master_of.find(id);
                         m != scan.master_of.end() && cell->is_locally_owned())
                  add_master_face(
                    cell, f, m->second, cell_dofs, u_constraints, scan);
              }
      return scan;
    }


    template <int dim>
    void
    ContactProblem<dim>::add_slave_face(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    f,
      const unsigned int                                    p,
      const std::vector<types::global_dof_index>           &cell_dofs,
      SurfaceScan                                          &scan)
    {
      scan.centre_values->reinit(cell, f);
      SlaveFace face;
      face.cell           = cell;
      face.face           = f;
      face.pair           = p;
      face.outward_normal = scan.centre_values->normal_vector(0);
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        if (fe.has_support_on_face(i, f))
          {
            face.u_local.push_back(i);
            const auto ci = fe.system_to_component_index(i);
            if (ci.first != 0)
              continue;
            face.node_local.push_back(i);
            auto &node = scan.seen[cell_dofs[i]];
            for (unsigned int c = 0; c < dim; ++c)
              node.dofs[c] =
                cell_dofs[fe.component_to_system_index(c, ci.second)];
            node.normals.push_back(face.outward_normal);
            node.pair = p;
          }
      // The face map in FE_Q<dim-1> order (as the master faces) and the
      // links to node_local / u_local.
      const unsigned int n_face_nodes = face_fe.n_dofs_per_cell();
      face.X.resize(n_face_nodes);
      face.k_node.resize(n_face_nodes);
      for (unsigned int i = 0; i < fe.n_dofs_per_face(); ++i)
        {
          const auto [c, k] = fe.face_system_to_component_index(i);
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
          face.k_node[k] =
            std::find(face.node_local.begin(), face.node_local.end(), cell_i) -
            face.node_local.begin();
        }
      face.node_dofs.resize(face.node_local.size() * dim);
      for (unsigned int l = 0; l < face.node_local.size(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          face.node_dofs[l * dim + c] = cell_dofs[fe.component_to_system_index(
            c, fe.system_to_component_index(face.node_local[l]).second)];
      for (const auto i : face.u_local)
        {
          const auto ci = fe.system_to_component_index(i);
          face.u_comp.push_back(ci.first);
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            if (fe.system_to_component_index(face.node_local[l]).second ==
                ci.second)
              face.u_node.push_back(l);
        }
      if (cell->is_locally_owned())
        {
          scan.h_sum[p] += cell->face(f)->diameter();
          scan.h_count[p] += 1;
          scan.e_max[p] =
            std::max(scan.e_max[p],
                     materials.at(cell->material_id())->representative_modulus());
          slave_faces.push_back(face);
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::add_master_face(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    f,
      const unsigned int                                    p,
      const std::vector<types::global_dof_index>           &cell_dofs,
      const AffineConstraints<double>                      &u_constraints,
      SurfaceScan                                          &scan)
    {
      MasterFace face;
      face.pair = p;
      // Partition-independent identity: the cell's CellId and the face.
      const auto id = cell->id().template to_binary<dim>();
      face.key.assign(id.begin(), id.end());
      face.key.push_back(f);
      face.own_cell = own_master_cells.size();
      own_master_cells.push_back(cell);
      scan.e_master[p] =
        std::max(scan.e_master[p],
                 materials.at(cell->material_id())->representative_modulus());
      // Nodes in the face's FE_Q<dim-1> order (see project_onto_face), dim
      // DoFs each.
      const unsigned int n_face_nodes = face_fe.n_dofs_per_cell();
      face.dofs.resize(n_face_nodes * dim);
      face.X.resize(n_face_nodes);
      for (unsigned int i = 0; i < fe.n_dofs_per_face(); ++i)
        {
          const auto [c, k]         = fe.face_system_to_component_index(i);
          const unsigned int cell_i = fe.face_to_cell_index(i,
                                                            f,
                                                            cell->face_orientation(f),
                                                            cell->face_flip(f),
                                                            cell->face_rotation(f));
          face.dofs[k * dim + c] = cell_dofs[cell_i];
          if (c == 0)
            face.X[k] = mapping.transform_unit_to_real_cell(
              cell, fe.unit_support_point(cell_i));
        }
      for (const auto d : face.dofs)
        if (const auto *entries = u_constraints.get_constraint_entries(d))
          scan.own_master_lines.emplace_back(d, *entries);
      face.inside = cell->center();
      scan.own_master_faces.push_back(std::move(face));
    }


    template <int dim>
    void
    ContactProblem<dim>::set_coefficients(const SurfaceScan &scan)
    {
      // Coefficients (formulation.md 8, "magic coefficients"): rho_n = c_n
      // E / h with h the mean slave face size and E the softer body's
      // Young's modulus (slave, or a meshed master that is softer: a gap
      // error is resisted by the softer body, and rho_n from a stiff slave
      // on a soft master weighs the gap 1/contrast too much);
      // rho_t = c_t rho_n / (mu p_ref) makes the tangential stiffness mu p_ref
      // rho_t of a sticking point comparable to rho_n (see
      // update_coefficients); before any pressure is known p_ref = 1e-3 E.
      const auto        &pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
      rho_n.assign(n_pairs, 0.);
      rho_t.assign(n_pairs, 0.);
      p_ref.assign(n_pairs, 0.);
      face_size.assign(n_pairs, 0.);
      youngs.assign(n_pairs, 0.);
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          const double hs = Utilities::MPI::sum(scan.h_sum[p], comm);
          const double hc = Utilities::MPI::sum(scan.h_count[p], comm);
          const double E  = Utilities::MPI::max(scan.e_max[p], comm);
          const double Em = Utilities::MPI::max(scan.e_master[p], comm);
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
    }


    template <int dim>
    typename ContactProblem<dim>::SetupCounts
    ContactProblem<dim>::number_multipliers(
      const SurfaceScan               &scan,
      const IndexSet                  &owned_u,
      const AffineConstraints<double> &u_constraints)
    {
      // Owned slave nodes: exclusion (Dirichlet on a component along the
      // face normal -> no contact; along the face -> no friction) and
      // hanging-node weights, decided by the owner.
      const auto                          &pairs = parameters.contact.pairs;
      std::vector<types::global_dof_index> owned_nodes;
      for (const auto &[dof0, node] : scan.seen)
        if (owned_u.is_element(dof0))
          owned_nodes.push_back(dof0);
      std::sort(owned_nodes.begin(), owned_nodes.end());
      types::global_dof_index n_owned_friction = 0;
      for (const auto d : owned_nodes)
        if (pairs[scan.seen.at(d).pair].friction > 0)
          ++n_owned_friction;
      const types::global_dof_index n_owned_nodes = owned_nodes.size();
      n_lambda      = Utilities::MPI::sum(n_owned_nodes, comm);
      n_friction    = Utilities::MPI::sum(n_owned_friction, comm) * (dim - 1);
      n_nodes_total = n_lambda;
      const types::global_dof_index lambda_offset =
        n_u + offset_of(n_owned_nodes, comm);
      const types::global_dof_index friction_offset =
        n_u + n_lambda + offset_of(n_owned_friction, comm) * (dim - 1);

      std::vector<std::pair<types::global_dof_index, NodeInfo>> own;
      types::global_dof_index                                   jf = 0;
      for (unsigned int j = 0; j < owned_nodes.size(); ++j)
        {
          const auto &node = scan.seen.at(owned_nodes[j]);
          NodeInfo    info;
          for (unsigned int c = 0; c < dim; ++c)
            if (const auto *entries =
                  u_constraints.get_constraint_entries(node.dofs[c]))
              {
                if (!entries->empty())
                  {
                    if (c == 0)
                      info.hanging = *entries;
                    continue;
                  }
                for (const auto &n : node.normals)
                  (std::abs(n[c]) > 0.5 ? info.exclude_contact :
                                          info.exclude_friction) = true;
              }
          const bool friction = pairs[node.pair].friction > 0;
          info.lambda         = lambda_offset + j;
          if (friction)
            info.friction = friction_offset + (dim - 1) * jf++;
          info.exclude_friction &= friction;
          info.pair = node.pair;
          own.emplace_back(owned_nodes[j], std::move(info));
        }
      nodes.clear();
      SetupCounts counts;
      for (const auto &from_rank : Utilities::MPI::all_gather(comm, own))
        for (const auto &[dof0, info] : from_rank)
          {
            counts.n_excluded_contact += info.exclude_contact;
            counts.n_excluded_friction +=
              !info.exclude_contact && info.exclude_friction;
            counts.n_hanging += !info.hanging.empty();
            nodes.emplace(dof0, info);
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
      return counts;
    }


    template <int dim>
    void
    ContactProblem<dim>::gather_master_faces(SurfaceScan &scan)
    {
      // The multipliers of this rank's slave faces (and of the parents of
      // their hanging nodes) and the master faces' DoFs with those of
      // their constraint lines are the ghosts of the contact rows.
      extra = IndexSet(n_system());
      extra.add_indices(owned_multipliers);
      const auto add_node = [&](const types::global_dof_index dof0) {
        const auto &info = nodes.at(dof0);
        extra.add_index(info.lambda);
        if (info.friction != numbers::invalid_dof_index)
          extra.add_range(info.friction, info.friction + dim - 1);
      };
      for (const auto &face : slave_faces)
        for (unsigned int l = 0; l < face.node_local.size(); ++l)
          {
            const auto dof0 = face.node_dofs[l * dim];
            add_node(dof0);
            for (const auto &h : nodes.at(dof0).hanging)
              add_node(h.first);
          }

      // Master faces from all ranks. The gathered order follows the
      // partition; the search (ties between equally good faces) and the
      // mortar cuts (the first master face that covers a piece of an
      // overlapped slave face) must not: sorted by their key.
      const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
      const auto all = Utilities::MPI::all_gather(comm, scan.own_master_faces);
      for (unsigned int r = 0; r < all.size(); ++r)
        for (const auto &face : all[r])
          {
            master_faces.push_back(face);
            if (r != rank)
              master_faces.back().own_cell = -1;
            for (const auto d : face.dofs)
              extra.add_index(d);
          }
      std::sort(master_faces.begin(),
                master_faces.end(),
                [](const MasterFace &a, const MasterFace &b) {
                  return a.key < b.key;
                });
      // Constraint lines of master DoFs, from their owners (the first one
      // of a DoF seen on several ranks).
      master_lines.clear();
      std::set<types::global_dof_index> done;
      for (const auto &from_rank :
           Utilities::MPI::all_gather(comm, scan.own_master_lines))
        for (const auto &[d, entries] : from_rank)
          {
            for (const auto &entry : entries)
              extra.add_index(entry.first);
            if (done.insert(d).second)
              master_lines.emplace_back(d, entries);
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

      const auto &pairs = parameters.contact.pairs;
      for (unsigned int p = 0; p < pairs.size(); ++p)
        if (pairs[p].master_is_body() &&
            std::none_of(master_faces.begin(),
                         master_faces.end(),
                         [p](const MasterFace &f) { return f.pair == p; }))
          throw InputError(pair_name(p) +
                           ", parameter 'Master boundary id': no boundary "
                           "face of the mesh has these ids. Use ids the "
                           "mesh has (see 'Boundary ids' of the bodies).");
    }


    template <int dim>
    void
    ContactProblem<dim>::finish_slave_faces()
    {
      // Multiplier numbers and exclusions of the slave faces' nodes; dual
      // multipliers (node-status pairs) on the faces without a hanging node
      // (whose multiplier interpolates its parents' and is no unknown of
      // its own: the face keeps psi there).
      for (auto &face : slave_faces)
        {
          const unsigned int n_l = face.node_local.size();
          bool               hanging = false;
          face.lambda_dofs.clear();
          face.friction_dofs.clear();
          face.excluded_contact.assign(n_l, false);
          face.excluded_friction.assign(n_l, false);
          for (unsigned int l = 0; l < n_l; ++l)
            {
              const auto &info = nodes.at(face.node_dofs[l * dim]);
              face.lambda_dofs.push_back(info.lambda);
              if (info.friction != numbers::invalid_dof_index)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  face.friction_dofs.push_back(info.friction + k);
              hanging |= !info.hanging.empty();
              face.excluded_contact[l] = info.exclude_contact;
              face.excluded_friction[l] =
                info.exclude_contact || info.exclude_friction;
            }
          face.dual.clear();
          if (node_status_pair[face.pair] && !hanging)
            face.dual = dual_basis(face);
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::print_setup(ConditionalOStream &pcout,
                                     const SetupCounts  &counts) const
    {
      const auto        &pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
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
      if (counts.n_excluded_contact + counts.n_excluded_friction > 0)
        pcout << "  over-constraint: " << counts.n_excluded_contact
              << " slave node(s) with a Dirichlet condition along the normal "
                 "excluded from contact, "
              << counts.n_excluded_friction
              << " with a tangential one excluded from friction" << std::endl;
      if (counts.n_hanging > 0)
        pcout << "  " << counts.n_hanging
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
