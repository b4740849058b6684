// Contact output: pair summaries, gathered point records, CSV, nodal fields,
// cells of the contact zone.
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
#include <signorini/contact/output.h>
#include <signorini/contact/segmentation.h>

#include "helpers.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <tuple>

namespace Signorini
{
  namespace Contact
  {
    using internal::add_entry;
    using internal::writable_vector;

    namespace
    {
      // Records (points or nodes) by pair, then by reference position
      // (lexicographic, equal within round-off): the same order on any
      // number of ranks.
      template <int dim, typename Record>
      void
      sort_by_pair_and_position(std::vector<Record> &records)
      {
        std::sort(
          records.begin(), records.end(), [](const Record &a, const Record &b) {
            if (a.pair != b.pair)
              return a.pair < b.pair;
            for (unsigned int d = 0; d < dim; ++d)
              if (std::abs(a.x[d] - b.x[d]) > 1e-12 * (1 + std::abs(a.x[d])))
                return a.x[d] < b.x[d];
            return false;
          });
      }


      // The pair summaries' sums and extremes over all ranks.
      template <class Summary>
      void
      sum_over_ranks(std::vector<Summary> &result, const MPI_Comm comm)
      {
        for (auto &r : result)
          {
            r.force = Utilities::MPI::sum(r.force, comm);
            r.p_max = Utilities::MPI::max(r.p_max, comm);
            r.area  = Utilities::MPI::sum(r.area, comm);
            r.normal_force_local =
              Utilities::MPI::sum(r.normal_force_local, comm);
            r.tangential_force_local =
              Utilities::MPI::sum(r.tangential_force_local, comm);
            r.n_points  = Utilities::MPI::sum(r.n_points, comm);
            r.n_contact = Utilities::MPI::sum(r.n_contact, comm);
            r.n_stick   = Utilities::MPI::sum(r.n_stick, comm);
            r.n_slip    = Utilities::MPI::sum(r.n_slip, comm);
          }
      }
    } // namespace


    template <int dim>
    Output<dim>::Output(const Parameters        &parameters,
                        const FESystem<dim>     &fe,
                        const DoFHandler<dim>   &dof_handler,
                        const Surfaces<dim>     &surfaces,
                        const Pairing<dim>      &pairing,
                        const NodeStatuses<dim> &node_statuses,
                        const MPI_Comm           comm)
        : parameters(parameters)
        , fe(fe)
        , dof_handler(dof_handler)
        , surfaces(surfaces)
        , pairing(pairing)
        , node_statuses(node_statuses)
        , comm(comm)
    {
    }


    template <int dim>
    void
    Output<dim>::add_node_forces(
      std::vector<TrilinosWrappers::MPI::Vector> &nodal,
      std::vector<PairSummary>                   &result) const
    {
      for (auto &v : nodal)
        v.compress(VectorOperation::add);
      // Each owned node once (the owner adds it).
      std::set<types::global_dof_index> seen;
      for (const auto &face : surfaces.slave_faces())
        if (node_statuses.by_node(face.pair))
          for (const auto dof : face.lambda_dofs)
            if (surfaces.owned_multipliers().is_element(dof) &&
                seen.insert(dof).second)
              {
                Tensor<1, dim> F, n;
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    F[c] = nodal[c][dof];
                    n[c] = nodal[dim + c][dof];
                  }
                if (n.norm() == 0)
                  continue;
                n /= n.norm();
                auto &r = result[face.pair];
                r.normal_force_local += std::abs(F * n);
                r.tangential_force_local += (F - (F * n) * n).norm();
              }
    }


    template <int dim>
    std::vector<typename Output<dim>::PairSummary>
    Output<dim>::summary() const
    {
      std::vector<PairSummary> result(parameters.contact.pairs.size());
      // Node-status pairs: the normal and tangential forces in the contact
      // frames are summed per multiplier node (the force F_l = sum w psi_l f
      // that node l carries, against the psi-weighted normal): with dual
      // multipliers the traction at single points oscillates, its nodal
      // forces do not.
      std::vector<TrilinosWrappers::MPI::Vector> nodal;
      if (node_statuses.any())
        for (unsigned int c = 0; c < 2 * dim; ++c)
          nodal.push_back(surfaces.writable_multipliers());
      for (const auto &point : pairing.points())
        {
          const auto &face = surfaces.slave_faces()[point.face];
          auto       &r    = result[face.pair];
          r.force += point.weight * point.force;
          if (node_statuses.by_node(face.pair))
            {
              for (unsigned int l = 0; l < face.lambda_dofs.size(); ++l)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const double w = point.weight * point.psi[l];
                    add_entry(nodal[c],
                              face.lambda_dofs[l],
                              w * point.force[c]);
                    add_entry(nodal[dim + c],
                              face.lambda_dofs[l],
                              w * point.normal[c]);
                  }
            }
          else if (point.status != PointStatus::free)
            {
              const double f_n = point.force * point.normal;
              r.normal_force_local += point.weight * std::abs(f_n);
              r.tangential_force_local +=
                point.weight * (point.force - f_n * point.normal).norm();
            }
          r.p_max = std::max(r.p_max, -point.lambda);
          if (point.paired)
            {
              ++r.n_paired;
              r.max_gap = std::max(r.max_gap, point.gap);
            }
          ++r.n_points;
          r.n_contact += point.status != PointStatus::free;
          if (point.status != PointStatus::free)
            r.area += point.weight;
          // Stick and slip: points whose friction law is active (a closed
          // point excluded from friction, or with a zero threshold, is
          // closed without friction, as in the Newton lines).
          r.n_stick += point.status == PointStatus::stick;
          r.n_slip +=
            point.status == PointStatus::slip && point.friction_active;
        }
      if (node_statuses.any())
        add_node_forces(nodal, result);
      for (unsigned int p = 0; p < result.size(); ++p)
        if (pairing.obstacle(p))
          {
            result[p].rigid = true;
            result[p].obstacle_displacement =
              pairing.obstacle(p)->get_motion().translation;
          }
      for (unsigned int p = 0; p < result.size(); ++p)
        {
          auto &r     = result[p];
          r.max_gap   = Utilities::MPI::max(r.max_gap, comm);
          r.n_paired  = Utilities::MPI::sum(r.n_paired, comm);
          r.face_size = surfaces.pair_scales().face_size[p];
        }
      sum_over_ranks(result, comm);
      return result;
    }


    template <int dim>
    std::vector<typename Output<dim>::PointRecord>
    Output<dim>::gather_points() const
    {
      std::vector<PointRecord> mine;
      for (const auto &point : pairing.points())
        {
          PointRecord r;
          r.pair          = surfaces.slave_faces()[point.face].pair;
          const double mu = parameters.contact.pairs[r.pair].friction;
          r.x             = point.x_ref;
          r.weight        = point.weight;
          r.p             = -point.lambda;
          r.traction      = mu * point.lambda * point.Lambda;
          r.gap           = point.gap;
          r.slip          = point.slip;
          r.status        = point.status;
          r.paired        = point.paired;
          mine.push_back(r);
        }
      std::vector<PointRecord> records;
      for (const auto &part : Utilities::MPI::all_gather(comm, mine))
        records.insert(records.end(), part.begin(), part.end());
      sort_by_pair_and_position<dim>(records);
      return records;
    }


    // One row per slave node: the nodal values of the VTU fields, the
    // reference and deformed position, the status of the node (pairs with
    // statuses per node) or of its nearest contact point.
    template <int dim>
    std::vector<typename Output<dim>::NodeRecord>
    Output<dim>::gather_nodes(const TrilinosWrappers::MPI::Vector &u) const
    {
      DoFHandler<dim> scalar_dofs(dof_handler.get_triangulation());
      scalar_dofs.distribute_dofs(fe.base_element(0));
      // p, gap, status, traction_k, slip_k: the VTU's nodal values.
      const auto     fields = nodal_fields(scalar_dofs);
      const IndexSet owned  = scalar_dofs.locally_owned_dofs();
      std::vector<types::global_dof_index> cell_dofs(
        scalar_dofs.get_fe().n_dofs_per_cell());
      // The scalar DoF of node l of a slave face.
      const auto node_dof = [&](const SlaveFace<dim> &face,
                                const unsigned int    l) {
        typename DoFHandler<dim>::active_cell_iterator cell(
          &dof_handler.get_triangulation(),
          face.cell->level(),
          face.cell->index(),
          &scalar_dofs);
        cell->get_dof_indices(cell_dofs);
        return cell_dofs[fe.system_to_component_index(face.node_local[l])
                           .second];
      };
      // The reference position of node l of a face (X is in face order).
      const auto node_position = [](const SlaveFace<dim> &face,
                                    const unsigned int    l) {
        for (unsigned int k = 0; k < face.k_node.size(); ++k)
          if (face.k_node[k] == l)
            return face.X[k];
        return Point<dim>();
      };
      // Per node: the nearest contact point's distance, status and pairing.
      std::map<types::global_dof_index, std::tuple<double, PointStatus, bool>>
        nearest;
      for (const auto &point : pairing.points())
        {
          const auto &face = surfaces.slave_faces()[point.face];
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              const double r  = point.x_ref.distance(node_position(face, l));
              const auto   d  = node_dof(face, l);
              const auto   it = nearest.find(d);
              if (it == nearest.end() || r < std::get<0>(it->second))
                nearest[d] = {r, point.status, point.paired};
            }
        }
      std::vector<NodeRecord>           mine;
      std::set<types::global_dof_index> seen;
      for (const auto &face : surfaces.slave_faces())
        for (unsigned int l = 0; l < face.node_local.size(); ++l)
          {
            const auto d = node_dof(face, l);
            if (!owned.is_element(d) || !seen.insert(d).second ||
                nearest.count(d) == 0)
              continue;
            NodeRecord r;
            r.pair = face.pair;
            r.x    = node_position(face, l);
            for (unsigned int c = 0; c < dim; ++c)
              r.x_deformed[c] = r.x[c] + u[face.node_dofs[l * dim + c]];
            r.p   = fields[0].second[d];
            r.gap = fields[1].second[d];
            for (unsigned int k = 0; k < dim - 1; ++k)
              {
                r.traction[k] = fields[3 + k].second[d];
                r.slip[k]     = fields[2 + dim + k].second[d];
              }
            const auto &[distance, status, paired] = nearest[d];
            r.status = node_statuses.by_node(face.pair) ?
                         static_cast<PointStatus>(
                           std::lround(node_status(face.lambda_dofs[l]))) :
                         status;
            r.paired = paired;
            mine.push_back(r);
          }
      std::vector<NodeRecord> records;
      for (const auto &part : Utilities::MPI::gather(comm, mine, 0))
        records.insert(records.end(), part.begin(), part.end());
      sort_by_pair_and_position<dim>(records);
      return records;
    }


    template <int dim>
    std::string
    Output<dim>::write_csv(const std::string                   &filename,
                           const TrilinosWrappers::MPI::Vector &u) const
    {
      const auto records = gather_nodes(u);
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return "";
      return Postprocess::write_atomically(filename, [&](std::ostream &csv) {
        const char *axis[] = {"x", "y", "z"};
        csv << "pair";
        for (unsigned int d = 0; d < dim; ++d)
          csv << "," << axis[d];
        for (unsigned int d = 0; d < dim; ++d)
          csv << "," << axis[d] << "_deformed";
        csv << ",p";
        for (unsigned int k = 0; k < dim - 1; ++k)
          csv << ",traction_t" << k + 1;
        csv << ",gap";
        for (unsigned int k = 0; k < dim - 1; ++k)
          csv << ",slip_t" << k + 1;
        csv << ",status\n";
        csv << std::setprecision(10);
        for (const auto &r : records)
          {
            csv << r.pair + 1;
            for (unsigned int d = 0; d < dim; ++d)
              csv << "," << r.x[d];
            for (unsigned int d = 0; d < dim; ++d)
              csv << "," << r.x_deformed[d];
            csv << "," << r.p;
            for (unsigned int k = 0; k < dim - 1; ++k)
              csv << "," << r.traction[k];
            // No master face, no gap: an empty field (a missing value),
            // not NaN.
            csv << ",";
            if (r.paired)
              csv << r.gap;
            for (unsigned int k = 0; k < dim - 1; ++k)
              csv << "," << r.slip[k];
            // A closed node of a frictionless pair has no stick or slip.
            const bool frictionless =
              parameters.contact.pairs[r.pair].friction == 0;
            csv << ","
                << (frictionless && r.status != PointStatus::free ?
                      "contact" :
                      to_string(r.status))
                << "\n";
          }
      });
    }


    template <int dim>
    std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector>>
    Output<dim>::nodal_fields(const DoFHandler<dim> &scalar_dofs) const
    {
      const IndexSet owned = scalar_dofs.locally_owned_dofs();
      IndexSet       relevant;
      DoFTools::extract_locally_relevant_dofs(scalar_dofs, relevant);
      std::vector<std::string> names = {"contact_pressure", "gap", "status"};
      for (unsigned int k = 0; k < dim - 1; ++k)
        names.push_back("tangential_traction_" + std::to_string(k + 1));
      for (unsigned int k = 0; k < dim - 1; ++k)
        names.push_back("slip_" + std::to_string(k + 1));
      std::vector<TrilinosWrappers::MPI::Vector> sums(
        names.size() + 1, writable_vector(owned, relevant, comm));
      // The same with |psi|: where the psi-weights of a node cancel (the
      // slave node on the axis of quadratic axisymmetric faces, whose
      // weight int psi 2 pi r is zero), the psi-average is a ratio of
      // round-off (p = -3e13 there); the |psi|-average of the points
      // around it is taken instead.
      std::vector<TrilinosWrappers::MPI::Vector> abs_sums(
        names.size() + 1, writable_vector(owned, relevant, comm));

      std::vector<types::global_dof_index> scalar_cell_dofs(
        scalar_dofs.get_fe().n_dofs_per_cell());
      for (const auto &point : pairing.points())
        {
          const auto &face = surfaces.slave_faces()[point.face];
          if (point.q == 0)
            {
              typename DoFHandler<dim>::active_cell_iterator scell(
                &dof_handler.get_triangulation(),
                face.cell->level(),
                face.cell->index(),
                &scalar_dofs);
              scell->get_dof_indices(scalar_cell_dofs);
            }
          const double mu =
            parameters.contact.pairs[surfaces.slave_faces()[point.face].pair]
              .friction;
          // The pressure that carries force (f . n: zero at unpaired
          // points), so that the nodal pressures integrate to the contact
          // force.
          std::vector<double> values = {point.force * point.normal,
                                        point.paired ? point.gap : 0.,
                                        static_cast<double>(point.status)};
          for (unsigned int k = 0; k < dim - 1; ++k)
            values.push_back(mu * point.lambda * point.Lambda[k]);
          for (unsigned int k = 0; k < dim - 1; ++k)
            values.push_back(point.slip[k]);
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              // Weighted with psi: where the multipliers use the dual basis
              // (biorthogonal to psi) the pressure of node l is its
              // multiplier lambda_l and an open node carries none; with
              // psi, L2-weighted averages.
              const unsigned int i = face.node_local[l];
              const double       w = point.weight * point.psi[l];
              const auto         d =
                scalar_cell_dofs[fe.system_to_component_index(i).second];
              // A pair with statuses per node: the node's own status.
              if (node_statuses.by_node(face.pair))
                values[2] = node_status(face.lambda_dofs[l]);
              for (unsigned int v = 0; v < values.size(); ++v)
                {
                  add_entry(sums[v], d, w * values[v]);
                  add_entry(abs_sums[v], d, std::abs(w) * values[v]);
                }
              add_entry(sums.back(), d, w);
              add_entry(abs_sums.back(), d, std::abs(w));
            }
        }
      for (auto &s : sums)
        s.compress(VectorOperation::add);
      for (auto &s : abs_sums)
        s.compress(VectorOperation::add);
      std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector>> result;
      for (unsigned int v = 0; v < names.size(); ++v)
        {
          TrilinosWrappers::MPI::Vector owned_values(owned, comm);
          for (const auto i : owned)
            if (std::abs(sums.back()[i]) > 1e-8 * abs_sums.back()[i])
              owned_values[i] = sums[v][i] / sums.back()[i];
            else if (abs_sums.back()[i] > 0)
              owned_values[i] = abs_sums[v][i] / abs_sums.back()[i];
          owned_values.compress(VectorOperation::insert);
          TrilinosWrappers::MPI::Vector ghosted(owned, relevant, comm);
          ghosted = owned_values;
          result.emplace_back(names[v], ghosted);
        }
      return result;
    }


    template <int dim>
    double
    Output<dim>::node_status(const types::global_dof_index lambda_dof) const
    {
      const auto &normal = node_statuses.normal_statuses();
      const auto  it     = normal.find(lambda_dof);
      if (it == normal.end() || !it->second)
        return static_cast<double>(PointStatus::free);
      const auto *friction = node_statuses.find_friction(lambda_dof);
      return static_cast<double>(friction != nullptr && friction->active &&
                                     friction->stick ?
                                   PointStatus::stick :
                                   PointStatus::slip);
    }


    template <int dim>
    std::vector<typename DoFHandler<dim>::active_cell_iterator>
    Output<dim>::contact_zone_cells() const
    {
      std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
      std::vector<unsigned int> master_active(surfaces.master_faces().size(),
                                              0);
      std::vector<bool> slave_active(surfaces.slave_faces().size(), false);
      for (const auto &point : pairing.points())
        if (point.status != PointStatus::free)
          {
            slave_active[point.face] = true;
            if (point.master_face >= 0)
              master_active[point.master_face] = 1;
          }
      for (unsigned int f = 0; f < surfaces.slave_faces().size(); ++f)
        if (slave_active[f])
          cells.push_back(surfaces.slave_faces()[f].cell);
      Utilities::MPI::max(master_active, comm, master_active);
      for (unsigned int m = 0; m < surfaces.master_faces().size(); ++m)
        if (surfaces.master_faces()[m].own_cell >= 0 && master_active[m] != 0)
          cells.push_back(surfaces.master_cell(surfaces.master_faces()[m]));
      return cells;
    }


    template class Output<2>;
    template class Output<3>;
  } // namespace Contact
} // namespace Signorini
