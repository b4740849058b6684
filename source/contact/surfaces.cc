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

#include <signorini/base/errors.h>
#include <signorini/contact/distributed_vectors.h>
#include <signorini/contact/projection.h>
#include <signorini/contact/surfaces.h>

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
    using internal::writable_vector;


    namespace
    {
      // The mean of a slave node's face normals, summed in a fixed order
      // (the same on any rank count).
      template <int dim>
      Tensor<1, dim>
      mean_normal(std::vector<Tensor<1, dim>> normals)
      {
        std::sort(normals.begin(),
                  normals.end(),
                  [](const Tensor<1, dim> &a, const Tensor<1, dim> &b) {
                    return std::lexicographical_compare(a.begin_raw(),
                                                        a.end_raw(),
                                                        b.begin_raw(),
                                                        b.end_raw());
                  });
        Tensor<1, dim> n;
        for (const auto &m : normals)
          n += m;
        return n / n.norm();
      }


      // What the Dirichlet lines of a slave node (@p dofs, its faces'
      // @p normals) hold: a direction along a normal excludes the node
      // from contact (info.exclude_contact); the directions along the face
      // and their DoFs are returned; a line to other nodes' DoFs is a
      // hanging node's (info.hanging). A line of a DoF in @p ignored_pins
      // is left out.
      template <int dim>
      std::pair<std::vector<Tensor<1, dim>>,
                std::vector<types::global_dof_index>>
      held_directions(const std::array<types::global_dof_index, dim> &dofs,
                      const std::vector<Tensor<1, dim>>              &normals,
                      const AffineConstraints<double>         &u_constraints,
                      const std::set<types::global_dof_index> *ignored_pins,
                      NodeInfo                                &info)
      {
        std::pair<std::vector<Tensor<1, dim>>,
                  std::vector<types::global_dof_index>>
          tangential;
        for (unsigned int c = 0; c < dim; ++c)
          if (const auto *entries =
                u_constraints.get_constraint_entries(dofs[c]))
            {
              // The direction a Dirichlet line holds: e_c, or for a line
              // among the node's own DoFs (a normal, tangential or
              // direction condition) e_c - sum_j w_j e_j.
              Tensor<1, dim> held;
              held[c] = 1;
              for (const auto &[j, w] : *entries)
                {
                  const auto d = std::find(dofs.begin(), dofs.end(), j);
                  if (d == dofs.end())
                    {
                      held = Tensor<1, dim>();
                      break;
                    }
                  held[d - dofs.begin()] -= w;
                }
              if (held.norm() == 0)
                {
                  if (c == 0)
                    info.hanging = *entries;
                  continue;
                }
              if (ignored_pins && ignored_pins->count(dofs[c]) > 0)
                continue;
              bool along_normal = false;
              for (const auto &n : normals)
                along_normal |= std::abs(n * held) > 0.5 * held.norm();
              if (along_normal)
                info.exclude_contact = true;
              else
                {
                  tangential.first.push_back(held);
                  tangential.second.push_back(dofs[c]);
                }
            }
        return tangential;
      }
    } // namespace


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
    struct Surfaces<dim>::Scan
    {
      std::map<types::boundary_id, unsigned int> slave_of, master_of;
      struct SeenNode
      {
        std::array<types::global_dof_index, dim> dofs;
        std::vector<Tensor<1, dim>>              normals;
        unsigned int                             pair;
      };
      std::map<types::global_dof_index, SeenNode> seen;
      std::vector<double>          h_sum, h_count, e_max, e_master;
      std::vector<MasterFace<dim>> own_master_faces;
      std::vector<MasterLine>      own_master_lines;
      // Outward normals at slave face centres; positions of support points.
      std::unique_ptr<FEFaceValues<dim>> centre_values;
    };


    template <int dim>
    Surfaces<dim>::Surfaces(const Parameters           &parameters,
                            const Mapping<dim>         &mapping,
                            const FESystem<dim>        &fe,
                            const DoFHandler<dim>      &dof_handler,
                            const Bulk::Materials<dim> &materials,
                            const MPI_Comm              comm)
        : parameters(parameters)
        , mapping(mapping)
        , fe(fe)
        , dof_handler(dof_handler)
        , materials(materials)
        , comm(comm)
        , face_fe(parameters.fe_degree)
    {
    }


    template <int dim>
    typename Surfaces<dim>::Counts
    Surfaces<dim>::setup(const AffineConstraints<double>         &u_constraints,
                         const IndexSet                          &owned_u,
                         const std::vector<bool>                 &dual_pair,
                         const std::set<types::global_dof_index> &pins)
    {
      n_displacements = dof_handler.n_dofs();
      auto scan       = scan_boundary(u_constraints);
      sum_pair_scales(scan);
      auto counts = number_multipliers(scan, owned_u, u_constraints, pins);
      gather_master_faces(scan);
      counts.n_axis = close_axis_multipliers();
      finish_slave_faces(dual_pair);
      return counts;
    }


    template <int dim>
    typename Surfaces<dim>::Scan
    Surfaces<dim>::scan_boundary(const AffineConstraints<double> &u_constraints)
    {
      const auto        &pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
      Scan               scan;
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
      slaves.clear();
      masters.clear();
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
    Surfaces<dim>::add_slave_face(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    f,
      const unsigned int                                    p,
      const std::vector<types::global_dof_index>           &cell_dofs,
      Scan                                                 &scan)
    {
      scan.centre_values->reinit(cell, f);
      SlaveFace<dim> face;
      face.cell           = cell;
      face.face           = f;
      face.pair           = p;
      face.outward_normal = scan.centre_values->normal_vector(0);
      face.tangent_axis   = tangent_axis<dim>(face.outward_normal);
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
          face.X[k] =
            mapping.transform_unit_to_real_cell(cell,
                                                fe.unit_support_point(cell_i));
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
          scan.e_max[p] = std::max(
            scan.e_max[p],
            materials.at(cell->material_id())->representative_modulus());
          slaves.push_back(face);
        }
    }


    template <int dim>
    void
    Surfaces<dim>::add_master_face(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    f,
      const unsigned int                                    p,
      const std::vector<types::global_dof_index>           &cell_dofs,
      const AffineConstraints<double>                      &u_constraints,
      Scan                                                 &scan)
    {
      MasterFace<dim> face;
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
          const auto [c, k] = fe.face_system_to_component_index(i);
          const unsigned int cell_i =
            fe.face_to_cell_index(i,
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
    Surfaces<dim>::sum_pair_scales(const Scan &scan)
    {
      const unsigned int n_pairs = parameters.contact.pairs.size();
      scales.face_size.assign(n_pairs, 0.);
      scales.slave_modulus.assign(n_pairs, 0.);
      scales.master_modulus.assign(n_pairs, 0.);
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          const double hs = Utilities::MPI::sum(scan.h_sum[p], comm);
          const double hc = Utilities::MPI::sum(scan.h_count[p], comm);
          if (hc == 0)
            throw InputError(pair_name(p) +
                             ", parameter 'Slave boundary id': no boundary "
                             "face of the mesh has these ids. Use ids the "
                             "mesh has (see 'Boundary ids' of the bodies).");
          scales.face_size[p]     = hs / hc;
          scales.slave_modulus[p] = Utilities::MPI::max(scan.e_max[p], comm);
          scales.master_modulus[p] =
            Utilities::MPI::max(scan.e_master[p], comm);
        }
    }


    template <int dim>
    typename Surfaces<dim>::Counts
    Surfaces<dim>::gather_node_info(
      const std::vector<std::pair<types::global_dof_index, NodeInfo>> &own)
    {
      node_info.clear();
      pin_nodes.clear();
      Counts counts;
      for (const auto &from_rank : Utilities::MPI::all_gather(comm, own))
        for (const auto &[dof0, info] : from_rank)
          {
            counts.n_excluded_contact += info.exclude_contact;
            counts.n_excluded_friction += info.exclude_friction;
            counts.n_held_tangent += !info.friction_held.empty();
            counts.n_hanging += !info.hanging.empty();
            if (info.pin != numbers::invalid_dof_index)
              {
                Pin pin{info.lambda, info.friction, {}};
                pin.a[0] = 1;
                for (unsigned int k = 0; k < info.friction_held.size(); ++k)
                  pin.a[k] = info.friction_held[k];
                pin_nodes.emplace(info.pin, pin);
              }
            node_info.emplace(dof0, info);
          }
      return counts;
    }


    template <int dim>
    typename Surfaces<dim>::Counts
    Surfaces<dim>::number_multipliers(
      const Scan                              &scan,
      const IndexSet                          &owned_u,
      const AffineConstraints<double>         &u_constraints,
      const std::set<types::global_dof_index> &pins)
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
      n_lambdas   = Utilities::MPI::sum(n_owned_nodes, comm);
      n_frictions = Utilities::MPI::sum(n_owned_friction, comm) * (dim - 1);
      const types::global_dof_index lambda_offset =
        n_displacements + offset_of(n_owned_nodes, comm);
      const types::global_dof_index friction_offset =
        n_displacements + n_lambdas +
        offset_of(n_owned_friction, comm) * (dim - 1);

      std::vector<std::pair<types::global_dof_index, NodeInfo>> own;
      types::global_dof_index                                   jf = 0;
      for (unsigned int j = 0; j < owned_nodes.size(); ++j)
        {
          const auto &node = scan.seen.at(owned_nodes[j]);
          NodeInfo    info;
          // A pin against a meshed master holds the node, not the master
          // point beneath it, which the contact rows still tie to it:
          // they stay the plain ones (theory.md F8, pins).
          const auto held =
            held_directions<dim>(node.dofs,
                                 node.normals,
                                 u_constraints,
                                 pairs[node.pair].master_is_body() ? &pins :
                                                                     nullptr,
                                 info);
          const auto &tangential      = held.first;
          const auto &tangential_dofs = held.second;
          const bool  friction        = pairs[node.pair].friction > 0;
          info.lambda                 = lambda_offset + j;
          if (friction)
            info.friction = friction_offset + (dim - 1) * jf++;
          if (friction && !info.exclude_contact)
            {
              const auto a =
                held_tangent(mean_normal(node.normals), tangential);
              info.exclude_friction = !a;
              if (a && a->norm() > 0)
                info.friction_held.assign(a->begin_raw(), a->end_raw());
              // One tangent held, by a pin at a point, against a rigid
              // master: its rows there are the pin's support force
              // (theory.md F8, pins).
              if (tangential_dofs.size() == 1 &&
                  pins.count(tangential_dofs[0]) > 0 &&
                  (dim == 2 || info.friction_held.size() == dim - 1))
                info.pin = tangential_dofs[0];
            }
          info.pair = node.pair;
          own.emplace_back(owned_nodes[j], std::move(info));
        }
      Counts counts = gather_node_info(own);

      owned = IndexSet(n_system());
      if (n_owned_nodes > 0)
        owned.add_range(lambda_offset, lambda_offset + n_owned_nodes);
      if (n_owned_friction > 0)
        owned.add_range(friction_offset,
                        friction_offset + n_owned_friction * (dim - 1));
      owned.compress();
      owned_system = IndexSet(n_system());
      owned_system.add_indices(owned_u);
      owned_system.add_indices(owned);
      owned_system.compress();
      return counts;
    }


    template <int dim>
    void
    Surfaces<dim>::gather_master_faces(Scan &scan)
    {
      // The multipliers of this rank's slave faces (and of the parents of
      // their hanging node_info) and the master faces' DoFs with those of
      // their constraint lines are the ghosts of the contact rows.
      extra = IndexSet(n_system());
      extra.add_indices(owned);
      const auto add_node = [&](const types::global_dof_index dof0) {
        const auto &info = node_info.at(dof0);
        extra.add_index(info.lambda);
        if (info.friction != numbers::invalid_dof_index)
          extra.add_range(info.friction, info.friction + dim - 1);
      };
      for (const auto &face : slaves)
        for (unsigned int l = 0; l < face.node_local.size(); ++l)
          {
            const auto dof0 = face.node_dofs[l * dim];
            add_node(dof0);
            for (const auto &h : node_info.at(dof0).hanging)
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
            masters.push_back(face);
            if (r != rank)
              masters.back().own_cell = -1;
            for (const auto d : face.dofs)
              extra.add_index(d);
          }
      std::sort(masters.begin(),
                masters.end(),
                [](const MasterFace<dim> &a, const MasterFace<dim> &b) {
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
      ghost_multipliers = IndexSet(n_system());
      ghost_multipliers.add_indices(extra.get_view(n_displacements, n_system()),
                                    n_displacements);
      ghost_multipliers.compress();

      const auto &pairs = parameters.contact.pairs;
      for (unsigned int p = 0; p < pairs.size(); ++p)
        if (pairs[p].master_is_body() &&
            std::none_of(masters.begin(),
                         masters.end(),
                         [p](const MasterFace<dim> &f) { return f.pair == p; }))
          throw InputError(pair_name(p) +
                           ", parameter 'Master boundary id': no boundary "
                           "face of the mesh has these ids. Use ids the "
                           "mesh has (see 'Boundary ids' of the bodies).");
    }


    template <int dim>
    void
    Surfaces<dim>::finish_slave_faces(const std::vector<bool> &dual_pair)
    {
      // Multiplier numbers and exclusions of the slave faces' nodes; dual
      // multipliers (node-status pairs) on the faces without a hanging node
      // (whose multiplier interpolates its parents' and is no unknown of
      // its own: the face keeps psi there).
      for (auto &face : slaves)
        {
          const unsigned int n_l     = face.node_local.size();
          bool               hanging = false;
          face.lambda_dofs.clear();
          face.friction_dofs.clear();
          face.excluded_contact.assign(n_l, false);
          face.excluded_friction.assign(n_l, false);
          face.held.clear();
          face.pin.clear();
          for (unsigned int l = 0; l < n_l; ++l)
            {
              const auto &info = node_info.at(face.node_dofs[l * dim]);
              face.lambda_dofs.push_back(info.lambda);
              if (info.friction != numbers::invalid_dof_index)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  face.friction_dofs.push_back(info.friction + k);
              hanging |= !info.hanging.empty() || !info.closure.empty();
              const bool held =
                info.exclude_friction || !info.friction_held.empty();
              face.excluded_contact[l]  = info.exclude_contact;
              face.excluded_friction[l] = info.exclude_contact ||
                                          !info.closure.empty() ||
                                          (held && !info.hanging.empty());
              Tensor<2, dim - 1> Q;
              if (held && !face.excluded_friction[l])
                {
                  Tensor<1, dim - 1> a;
                  for (unsigned int k = 0; k < info.friction_held.size(); ++k)
                    a[k] = info.friction_held[k];
                  Q = outer_product(a, a);
                  if (info.exclude_friction) // both held
                    for (unsigned int k = 0; k < dim - 1; ++k)
                      Q[k][k] = 1;
                }
              face.held.push_back(Q);
              face.pin.push_back(face.excluded_friction[l] ?
                                   numbers::invalid_dof_index :
                                   info.pin);
            }
          face.dual.clear();
          if (dual_pair[face.pair] && !hanging)
            face.dual = dual_basis(face);
        }
    }


    template <int dim>
    unsigned int
    Surfaces<dim>::close_axis_multipliers()
    {
      // In an axisymmetric model a slave node on the axis (r = 0) has the
      // weight int psi_l 2 pi r over its face; for a straight quadratic face
      // that is exactly zero (int_0^1 (1 - 3x + 2x^2) x dx = 0), and on a
      // curved one it is a small difference of round-off size to a few
      // percent of its neighbours', so its multiplier enters no
      // displacement row (a singular tangent) or one with a vanishing
      // weight (the force of the node over ~0). The pressure is symmetric
      // about the axis, p = a + b r^2 near it: its multiplier is taken from the
      // two nearest nodes of the face, lambda_0 = (r_2^2 lambda_1 - r_1^2
      // lambda_2) / (r_2^2 - r_1^2), and its Lambda is zero (no radial traction
      // on the axis).
      using Entries = std::vector<std::pair<types::global_dof_index, double>>;
      std::vector<std::pair<types::global_dof_index, Entries>> own;
      for (const auto &face : slaves)
        {
          const unsigned int n = face.X.size();
          if (!parameters.axisymmetric || dim != 2 || n < 3)
            continue; // linear faces: the axis node has a positive weight
          const double length = face.X.front().distance(face.X[1]);
          for (unsigned int k = 0; k < n; ++k)
            {
              if (std::abs(face.X[k][0]) > 1e-9 * length)
                continue;
              // The two other nodes nearest the axis.
              std::vector<std::pair<double, unsigned int>> by_radius;
              for (unsigned int m = 0; m < n; ++m)
                if (m != k)
                  by_radius.emplace_back(face.X[m][0], m);
              std::sort(by_radius.begin(), by_radius.end());
              const double r1 = by_radius[0].first, r2 = by_radius[1].first;
              if (r1 <= 1e-9 * length || r2 <= r1)
                continue; // a face along the axis: no radius to extrapolate

              const auto dof = [&](const unsigned int m) {
                return face.node_dofs[face.k_node[m] * dim];
              };
              own.emplace_back(dof(k),
                               Entries{{dof(by_radius[0].second),
                                        r2 * r2 / (r2 * r2 - r1 * r1)},
                                       {dof(by_radius[1].second),
                                        -r1 * r1 / (r2 * r2 - r1 * r1)}});
            }
        }
      unsigned int n_closed = 0;
      for (const auto &from_rank : Utilities::MPI::all_gather(comm, own))
        for (const auto &[dof0, entries] : from_rank)
          {
            auto &info = node_info.at(dof0);
            if (info.closure.empty())
              {
                info.closure = entries;
                ++n_closed;
              }
          }
      return n_closed;
    }


    template <int dim>
    void
    Surfaces<dim>::add_constraint_lines(
      AffineConstraints<double> &constraints) const
    {
      const IndexSet &local = constraints.get_local_lines();
      const auto      can   = [&](const types::global_dof_index i) {
        return (local.size() == 0 || local.is_element(i)) &&
               !constraints.is_constrained(i);
      };
      for (const auto &[dof0, info] : node_info)
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
                                            node_info.at(parent).lambda,
                                            w);
                }
            }
          const bool closed = !info.closure.empty() && !info.exclude_contact &&
                              info.hanging.empty();
          if (closed && can(info.lambda))
            {
              constraints.add_line(info.lambda);
              for (const auto &[parent, c] : info.closure)
                constraints.add_entry(info.lambda,
                                      node_info.at(parent).lambda,
                                      c);
            }
          // A node with a held tangent keeps Lambda (its rows decide per
          // node, theory.md F8), unless it is hanging: then Lambda = 0.
          const bool held =
            info.exclude_friction || !info.friction_held.empty();
          if (has_friction &&
              (info.exclude_contact || !info.hanging.empty() || closed))
            {
              for (unsigned int k = 0; k < dim - 1; ++k)
                if (can(info.friction + k))
                  {
                    constraints.add_line(info.friction + k);
                    if (!info.exclude_contact && !held && !closed)
                      for (const auto &[parent, w] : info.hanging)
                        constraints.add_entry(info.friction + k,
                                              node_info.at(parent).friction + k,
                                              w);
                  }
            }
        }
      for (const auto &[d, entries] : master_lines)
        if (can(d))
          {
            constraints.add_line(d);
            constraints.add_entries(d, entries);
          }
    }


    template <int dim>
    std::vector<double>
    Surfaces<dim>::dual_basis(const SlaveFace<dim> &face) const
    {
      // Face mass matrix M_lm = integral psi_l psi_m (with the weights of
      // the contact points: reference Jacobian, 2 pi r if axisymmetric),
      // D_l = sum_m M_lm; psi~ = D M^-1 psi is biorthogonal to psi.
      const unsigned int    n = face.node_local.size();
      const QGauss<dim - 1> gauss(parameters.fe_degree + 2);
      FullMatrix<double>    M(n, n);
      std::vector<double>   N;
      for (unsigned int q = 0; q < gauss.size(); ++q)
        {
          face_shape_values<dim>(face.X.size(), gauss.point(q), N);
          const auto   g = face_geometry<dim>(face.X, gauss.point(q));
          const double w =
            gauss.weight(q) * g.jacobian *
            (parameters.axisymmetric ? 2 * numbers::PI * g.x[0] : 1.);
          for (unsigned int k = 0; k < N.size(); ++k)
            for (unsigned int kk = 0; kk < N.size(); ++kk)
              M(face.k_node[k], face.k_node[kk]) += w * N[k] * N[kk];
        }
      std::vector<double> D(n, 0.);
      for (unsigned int l = 0; l < n; ++l)
        for (unsigned int m = 0; m < n; ++m)
          D[l] += M(l, m);
      FullMatrix<double> M_inverse(n, n);
      M_inverse.invert(M);
      std::vector<double> dual(n * n);
      for (unsigned int l = 0; l < n; ++l)
        for (unsigned int m = 0; m < n; ++m)
          dual[l * n + m] = D[l] * M_inverse(l, m);
      return dual;
    }


    template class Surfaces<2>;
    template class Surfaces<3>;
  } // namespace Contact
} // namespace Signorini
