// The contact problem's construction, coefficients, point data and DoF
// couplings (the other members: surfaces.cc, pairing.cc, statuses.cc,
// active_set_history.cc, assembly.cc, output.cc).
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
    using internal::pair_name;


    template <int dim>
    ContactProblem<dim>::ContactProblem(
      const Parameters                                         &parameters,
      const Mapping<dim>                                       &mapping,
      const FESystem<dim>                                      &fe,
      const DoFHandler<dim>                                    &dof_handler,
      const Bulk::Materials<dim>                               &materials,
      std::vector<std::unique_ptr<Obstacles::Interface<dim>>> &&obstacles_in,
      const MPI_Comm                                            comm)
        : parameters(parameters)
        , mapping(mapping)
        , dof_handler(dof_handler)
        , fe(fe)
        , materials(materials)
        , comm(comm)
        , surfaces(parameters, mapping, fe, dof_handler, materials, comm)
        , pairing(parameters, surfaces, std::move(obstacles_in), comm)
        , coefficients(parameters.contact)
        , history(parameters.contact, surfaces, node_status_pair, comm)
    {
      const auto &contact = parameters.contact;
      for (unsigned int p = 0; p < contact.pairs.size(); ++p)
        {
          const auto &pair = contact.pairs[p];
          // Statuses per multiplier node: integration-point rules, meshed
          // master (the others have one law per node).
          node_status_pair.push_back(contact.rule != IntegrationRule::nodal &&
                                     pair.master_is_body());
          friction_node_pair.push_back(node_status_pair.back() &&
                                       pair.friction > 0);
          any_friction_node = any_friction_node || friction_node_pair.back();
          any_node_status   = any_node_status || node_status_pair.back();
          // Newton on the geometry (projection, normal and curvature at
          // every iterate) for frictionless rigid obstacles; the geometric
          // loop for the others (doc/robustness.md, "Geometry in Newton").
          newton_geometry_pair.push_back(pair.friction == 0 &&
                                         !pair.master_is_body());
          pairing_exact =
            (p == 0 || pairing_exact) && newton_geometry_pair.back();
          // A frictionless meshed master paired at fixed points and
          // normals within each Newton solve.
          const bool frictionless_fixed_body =
            pair.friction == 0 && pair.master_is_body();
          linear_statuses = (p == 0 || linear_statuses) &&
                            (frictionless_fixed_body ||
                             (pair.friction == 0 && pairing.obstacle(p) &&
                              pairing.obstacle(p)->flat()));
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::setup(const AffineConstraints<double> &u_constraints,
                               const IndexSet                  &owned_u,
                               ConditionalOStream              &pcout)
    {
      const auto counts =
        surfaces.setup(u_constraints, owned_u, node_status_pair);
      set_coefficients();
      pairing.setup();
      print_setup(pcout, counts);
    }


    template <int dim>
    void
    ContactProblem<dim>::set_coefficients()
    {
      const auto &scales = surfaces.pair_scales();
      coefficients.set(scales.face_size,
                       scales.slave_modulus,
                       scales.master_modulus);
    }


    template <int dim>
    void
    ContactProblem<dim>::print_setup(
      ConditionalOStream                   &pcout,
      const typename Surfaces<dim>::Counts &counts) const
    {
      const auto        &pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
      pcout << "Contact: " << n_pairs << " pair(s), rule "
            << pairing.rule_description();
      pcout << " on "
            << Utilities::MPI::sum(
                 static_cast<unsigned int>(surfaces.slave_faces().size()), comm)
            << " slave faces, " << surfaces.n_lambda() << " slave nodes"
            << std::endl;
      for (unsigned int p = 0; p < n_pairs; ++p)
        pcout << "  pair " << p + 1 << ": mu = " << pairs[p].friction
              << ", h = " << std::setprecision(4)
              << surfaces.pair_scales().face_size[p]
              << ", rho_n = " << coefficients.normal(p)
              << ", rho_t = " << coefficients.tangential(p)
              << std::setprecision(6) << std::endl;
      for (unsigned int p = 0; p < n_pairs; ++p)
        if (pairing.obstacle(p) &&
            !pairing.obstacle(p)->approximate_derivatives().empty())
          pcout << "  pair " << p + 1 << ": "
                << pairing.obstacle(p)->approximate_derivatives()
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
    double
    ContactProblem<dim>::point_gap(
      const ContactPoint                  &point,
      const TrilinosWrappers::MPI::Vector &state) const
    {
      if (!point.paired)
        return -std::numeric_limits<double>::max();
      const Point<dim> x_e = slave_position(point, state);
      const Point<dim> x_m =
        point.master_face < 0 ?
          point.x_m_rigid :
          surfaces.master_position(point.master_face, point.N_m, state);
      return (x_e - x_m) * point.normal +
             parameters.contact.pairs[surfaces.slave_faces()[point.face].pair]
               .gap_offset;
    }


    template <int dim>
    Tensor<1, dim - 1>
    ContactProblem<dim>::point_slip(
      const ContactPoint                  &point,
      const TrilinosWrappers::MPI::Vector &state,
      const TrilinosWrappers::MPI::Vector &start) const
    {
      // v = P (Delta u^e - Delta u^m), in the tangent basis of the point.
      Tensor<1, dim> v =
        slave_position(point, state) - slave_position(point, start);
      v -=
        point.master_face < 0 ?
          point.rigid_increment :
          surfaces.master_increment(point.master_face, point.N_m, state, start);
      Tensor<1, dim - 1> t;
      for (unsigned int k = 0; k < dim - 1; ++k)
        t[k] = v * point.tangents[k];
      return t;
    }


    template <int dim>
    void
    ContactProblem<dim>::update_coefficients(
      const TrilinosWrappers::MPI::Vector &state)
    {
      const auto         &pairs = parameters.contact.pairs;
      std::vector<double> sum2(pairs.size(), 0.), count(pairs.size(), 0.);
      // Pressures at or below the zero threshold (e.g. the 'closed'
      // initial multipliers, see set_initial_multipliers) are not a
      // pressure level: they would make rho_t enormous.
      for (const auto &[dof0, node] : surfaces.nodes())
        if (surfaces.owned_multipliers().is_element(node.lambda) &&
            state[node.lambda] < -coefficients.law(node.pair).zero_threshold)
          {
            sum2[node.pair] += state[node.lambda] * state[node.lambda];
            count[node.pair] += 1;
          }
      for (unsigned int p = 0; p < pairs.size(); ++p)
        {
          const double s = Utilities::MPI::sum(sum2[p], comm);
          const double n = Utilities::MPI::sum(count[p], comm);
          if (n > 0 && s > 0)
            coefficients.set_pressure_level(p, std::sqrt(s / n));
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::point_dofs(
      const ContactPoint                         &point,
      const std::vector<types::global_dof_index> &cell_dofs,
      std::vector<types::global_dof_index>       &dofs) const
    {
      const auto &face = surfaces.slave_faces()[point.face];
      dofs.clear();
      for (const auto i : face.u_local)
        dofs.push_back(cell_dofs[i]);
      if (point.master_face >= 0)
        for (const auto d : surfaces.master_faces()[point.master_face].dofs)
          dofs.push_back(d);
      dofs.insert(dofs.end(), face.lambda_dofs.begin(), face.lambda_dofs.end());
      dofs.insert(dofs.end(),
                  face.friction_dofs.begin(),
                  face.friction_dofs.end());
    }


    template <int dim>
    std::vector<types::global_dof_index>
    ContactProblem<dim>::coupled_dofs() const
    {
      std::vector<types::global_dof_index> mine, dofs,
        cell_dofs(fe.n_dofs_per_cell());
      for (const auto &point : pairing.points())
        {
          surfaces.slave_faces()[point.face].cell->get_dof_indices(cell_dofs);
          point_dofs(point, cell_dofs, dofs);
          mine.insert(mine.end(), dofs.begin(), dofs.end());
        }
      std::vector<types::global_dof_index> all;
      for (const auto &part : Utilities::MPI::all_gather(comm, mine))
        all.insert(all.end(), part.begin(), part.end());
      std::sort(all.begin(), all.end());
      all.erase(std::unique(all.begin(), all.end()), all.end());
      return all;
    }


    template <int dim>
    void
    ContactProblem<dim>::add_sparsity(
      TrilinosWrappers::SparsityPattern &sparsity,
      const AffineConstraints<double>   &constraints) const
    {
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs;
      int                                  last_face = -1;
      // Points of one slave face paired with one master face couple the
      // same unknowns: one entry block per (slave face, master face).
      std::set<int> masters_of_face;
      for (const auto &point : pairing.points())
        {
          const auto &face = surfaces.slave_faces()[point.face];
          if (static_cast<int>(point.face) != last_face)
            {
              face.cell->get_dof_indices(cell_dofs);
              last_face = point.face;
              masters_of_face.clear();
            }
          if (!masters_of_face.insert(point.master_face).second)
            continue;
          point_dofs(point, cell_dofs, dofs);
          constraints.add_entries_local_to_global(dofs, sparsity, false);
        }
    }


    template <int dim>
    struct ContactProblem<dim>::PointsState
    {
      std::vector<ContactPoint>                       points;
      std::map<types::global_dof_index, bool>         node_active;
      std::map<types::global_dof_index, NodeFriction> node_friction;
      typename ActiveSetHistory<dim>::Snapshot        history;
    };


    template <int dim>
    std::shared_ptr<const typename ContactProblem<dim>::PointsState>
    ContactProblem<dim>::save_points() const
    {
      return std::make_shared<const PointsState>(PointsState{
        pairing.points(), node_active, node_friction, history.save()});
    }


    template <int dim>
    void
    ContactProblem<dim>::restore_points(const PointsState &saved)
    {
      pairing.points() = saved.points;
      node_active   = saved.node_active;
      node_friction = saved.node_friction;
      history.restore(saved.history);
    }


    template <int dim>
    double
    ContactProblem<dim>::roundoff_scale() const
    {
      double sum = 0;
      for (const auto &point : pairing.points())
        if (point.paired)
          sum += std::pow(2 * point.weight *
                            coefficients.normal(
                              surfaces.slave_faces()[point.face].pair) *
                            point.x_ref.norm(),
                          2);
      return std::sqrt(Utilities::MPI::sum(sum, comm));
    }


    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace Contact
} // namespace Signorini
