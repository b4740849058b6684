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
    using internal::writable_vector;

    namespace
    {
      std::string
      pair_name(const unsigned int p)
      {
        return "subsection 'Contact/Pair " + std::to_string(p + 1) + "'";
      }

      template <int dim>
      Tensor<1, dim>
      to_tensor(const std::vector<double> &v)
      {
        Tensor<1, dim> t;
        for (unsigned int d = 0; d < dim; ++d)
          t[d] = v[d];
        return t;
      }

      // The master faces whose boxes meet @p box, in master_faces order.
      // The tree's own order follows its packing, which sorts box centres
      // and so breaks ties (faces of a structured mesh in a row) by the
      // round-off of the iterate; the mortar cuts and the search's ties must
      // not depend on that (it differs with the MPI partition).
      template <int dim>
      std::vector<unsigned int>
      faces_meeting(
        const RTree<std::pair<BoundingBox<dim>, unsigned int>> &tree,
        const BoundingBox<dim> &                                box)
      {
        std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
        tree.query(boost::geometry::index::intersects(box),
                   std::back_inserter(hits));
        std::vector<unsigned int> faces;
        faces.reserve(hits.size());
        for (const auto &hit : hits)
          faces.push_back(hit.second);
        std::sort(faces.begin(), faces.end());
        return faces;
      }

      // Exclusive prefix sum over ranks.
      types::global_dof_index
      offset_of(const types::global_dof_index n, const MPI_Comm comm)
      {
        types::global_dof_index offset = 0;
        const auto              all    = Utilities::MPI::all_gather(comm, n);
        for (unsigned int r = 0; r < Utilities::MPI::this_mpi_process(comm);
             ++r)
          offset += all[r];
        return offset;
      }
    } // namespace


    template <int dim>
    ContactProblem<dim>::ContactProblem(
      const Parameters &                                                parameters,
      const FESystem<dim> &                                             fe,
      const DoFHandler<dim> &                                           dof_handler,
      const Bulk::Materials<dim> &materials,
      std::vector<std::unique_ptr<Obstacles::Interface<dim>>> &&obstacles_in,
      const MPI_Comm                                                    comm)
      : parameters(parameters)
      , dof_handler(dof_handler)
      , fe(fe)
      , materials(materials)
      , obstacles(std::move(obstacles_in))
      , comm(comm)
      , face_fe(parameters.fe_degree)
    {
      const auto &contact = parameters.contact;
      mortar = contact.rule == IntegrationRule::mortar;
      segment_order =
        contact.segment_order > 0 ?
          contact.segment_order :
          exact_segment_order<dim>(parameters.fe_degree);
      // With the mortar rule, a rigid analytic master has no faces to cut
      // its slave faces by: they use the nodal rule, one law per multiplier
      // node. Statuses at Gauss points with interpolated multipliers may
      // admit no consistent active set (B4 ironing cycles without end);
      // at the nodes they do, and on rigid Hertz the nodal rule is also
      // the more accurate one (doc/robustness.md).
      rule = mortar ? std::make_unique<FixedRule<dim>>(IntegrationRule::nodal,
                                                       1,
                                                       parameters.fe_degree) :
                      std::make_unique<FixedRule<dim>>(contact.rule,
                                                       contact.order,
                                                       parameters.fe_degree);
      for (unsigned int p = 0; p < contact.pairs.size(); ++p)
        {
          const auto &pair = contact.pairs[p];
          // Statuses per multiplier node: integration-point rules, meshed
          // master (the others have one law per node).
          node_status_pair.push_back(
            contact.node_status && contact.rule != IntegrationRule::nodal &&
            pair.master_is_body());
          friction_node_pair.push_back(node_status_pair.back() &&
                                       pair.friction > 0);
          any_friction_node = any_friction_node || friction_node_pair.back();
          any_node_status = any_node_status || node_status_pair.back();
          // Newton on the geometry: rigid obstacles with their own normal.
          newton_geometry_pair.push_back(
            contact.newton_geometry &&
            (pair.friction == 0 || contact.newton_geometry_all) &&
            !pair.master_is_body() &&
            contact.normal == NormalChoice::master);
          // Newton on the pairing of a meshed master ('newton' only; auto
          // keeps the fixed point, doc/robustness.md): frictionless (the
          // slip of a meshed pair is not linearised in the geometry),
          // fixed points (the mortar rule cuts faces at each pairing) and
          // the master normal.
          newton_pairing_pair.push_back(
            contact.newton_geometry_all && pair.friction == 0 &&
            pair.master_is_body() && !mortar &&
            contact.normal == NormalChoice::master);
          pairing_exact = (p == 0 || pairing_exact) &&
                          newton_geometry_pair.back() &&
                          !(contact.frozen_threshold && pair.friction > 0);
          // A frictionless meshed master paired at fixed points and
          // normals within each Newton solve.
          const bool frictionless_fixed_body =
            pair.friction == 0 && pair.master_is_body() &&
            !newton_pairing_pair.back();
          // Pairing at status changes: those pairs, with a point rule.
          pairing_in_newton = (p == 0 || pairing_in_newton) &&
                              contact.pairing_at_status_changes && !mortar &&
                              frictionless_fixed_body;
          linear_statuses =
            (p == 0 || linear_statuses) &&
            (frictionless_fixed_body ||
             (pair.friction == 0 && obstacles[p] && obstacles[p]->flat()));
          if (pair.master_is_body())
            {
              motions.emplace_back();
              continue;
            }
          auto motion = std::make_unique<FunctionParser<dim>>(dim);
          try
            {
              motion->initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                                 std::vector<std::string>(
                                   pair.obstacle_motion.begin(),
                                   pair.obstacle_motion.begin() + dim),
                                 parameters.boundary_conditions.constants,
                                 true);
              motion->value(Point<dim>(), 0);
            }
          catch (const ExceptionBase &)
            {
              throw InputError(pair_name(p) +
                               ", parameter 'Obstacle motion': cannot parse "
                               "the expressions; give Dimension expressions "
                               "of t separated by ';'.");
            }
          motions.push_back(std::move(motion));
        }
    }


    template <int dim>
    LawParameters
    ContactProblem<dim>::law_parameters(const unsigned int p) const
    {
      LawParameters law;
      law.rho_n              = rho_n[p];
      law.rho_t              = rho_t[p];
      law.mu                 = parameters.contact.pairs[p].friction;
      law.threshold_newton   = !parameters.contact.frozen_threshold;
      law.threshold_coupling = parameters.contact.threshold_coupling;
      law.penalty            = parameters.contact.penalty;
      law.zero_threshold     = 1e-12 * youngs[p];
      if (law.mu > 0)
        {
          // Friction law of a point with inactive friction, weighted like
          // an active point at 1e-4 of the pressure level: unit invariant,
          // and small enough that a node at the contact edge (mortar and
          // Gauss rules mix free and active points in its Lambda row)
          // follows its active points. See doc/robustness.md for the sweep
          // of the factor.
          constexpr double free_weight = 1e-4;
          law.free_friction_scale =
            free_weight * law.mu * p_ref[p] / rho_t[p];
        }
      return law;
    }


    template <int dim>
    std::vector<double>
    ContactProblem<dim>::dual_basis(const SlaveFace &face) const
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
          const auto g = face_geometry<dim>(face.X, gauss.point(q));
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


    template <int dim>
    typename ContactProblem<dim>::ContactPoint
    ContactProblem<dim>::make_point(const unsigned int    f,
                                    const unsigned int    q,
                                    const Point<dim - 1> &xi,
                                    const double          w) const
    {
      const auto & face = slave_faces[f];
      ContactPoint point;
      point.face = f;
      point.q    = q;
      point.xi   = xi;
      std::vector<double> N;
      face_shape_values<dim>(face.X.size(), xi, N);
      point.psi.resize(face.node_local.size());
      for (unsigned int k = 0; k < face.X.size(); ++k)
        point.psi[face.k_node[k]] = N[k];
      point.psi_lambda = point.psi; // the dual basis is set by pair()
      const auto geometry = face_geometry<dim>(face.X, xi);
      point.x_ref         = geometry.x;
      // Axisymmetric: the contact ring of radius r = x carries 2 pi r. A
      // point on a node (nodal rule) stands for the node's share of the
      // face, so its radius is the N_k-weighted mean radius of the face:
      // the lumped consistent weight, not zero on the axis.
      double ring = 1;
      if (parameters.axisymmetric)
        {
          ring = 2 * numbers::PI * geometry.x[0];
          for (unsigned int k = 0; k < face.X.size(); ++k)
            if (std::abs(N[k] - 1) < 1e-12)
              {
                const QGauss<dim - 1> gauss(3);
                std::vector<double>   N_q;
                double                num = 0, den = 0;
                for (unsigned int q = 0; q < gauss.size(); ++q)
                  {
                    face_shape_values<dim>(face.X.size(), gauss.point(q), N_q);
                    const auto g = face_geometry<dim>(face.X, gauss.point(q));
                    num += gauss.weight(q) * g.jacobian * N_q[k] * g.x[0];
                    den += gauss.weight(q) * g.jacobian * N_q[k];
                  }
                ring = 2 * numbers::PI * num / den;
              }
        }
      point.weight = w * geometry.jacobian * ring;
      point.slave_normal  = geometry.normal * face.outward_normal > 0 ?
                              geometry.normal :
                              -geometry.normal;
      return point;
    }


    template <int dim>
    Point<dim>
    ContactProblem<dim>::slave_position(
      const ContactPoint &                 point,
      const TrilinosWrappers::MPI::Vector &state) const
    {
      const auto &face = slave_faces[point.face];
      Point<dim>  x    = point.x_ref;
      for (unsigned int l = 0; l < point.psi.size(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          x[c] += point.psi[l] * state[face.node_dofs[l * dim + c]];
      return x;
    }


    template <int dim>
    double
    ContactProblem<dim>::point_gap(
      const ContactPoint &                 point,
      const TrilinosWrappers::MPI::Vector &state) const
    {
      if (!point.paired)
        return -std::numeric_limits<double>::max();
      const Point<dim> x_e = slave_position(point, state);
      Point<dim>       x_m = point.x_m_rigid;
      if (point.master_face >= 0)
        {
          const auto &m = master_faces[point.master_face];
          x_m           = Point<dim>();
          for (unsigned int k = 0; k < m.X.size(); ++k)
            for (unsigned int c = 0; c < dim; ++c)
              x_m[c] += point.N_m[k] * (m.X[k][c] + state[m.dofs[k * dim + c]]);
        }
      return (x_e - x_m) * point.normal +
             parameters.contact.pairs[slave_faces[point.face].pair].gap_offset;
    }


    template <int dim>
    Tensor<1, dim - 1>
    ContactProblem<dim>::point_slip(
      const ContactPoint &                 point,
      const TrilinosWrappers::MPI::Vector &state,
      const TrilinosWrappers::MPI::Vector &start) const
    {
      // v = P (Delta u^e - Delta u^m), in the tangent basis of the point.
      Tensor<1, dim> v =
        slave_position(point, state) - slave_position(point, start);
      if (point.master_face < 0)
        v -= point.rigid_increment;
      else
        {
          const auto &m = master_faces[point.master_face];
          for (unsigned int k = 0; k < m.X.size(); ++k)
            for (unsigned int c = 0; c < dim; ++c)
              v[c] -= point.N_m[k] * (state[m.dofs[k * dim + c]] -
                                      start[m.dofs[k * dim + c]]);
        }
      Tensor<1, dim - 1> t;
      for (unsigned int k = 0; k < dim - 1; ++k)
        t[k] = v * point.tangents[k];
      return t;
    }


    template <int dim>
    void
    ContactProblem<dim>::setup(const AffineConstraints<double> &u_constraints,
                               const IndexSet &                 owned_u,
                               ConditionalOStream &             pcout)
    {
      const auto &       pairs   = parameters.contact.pairs;
      const unsigned int n_pairs = pairs.size();
      n_u                        = dof_handler.n_dofs();

      // Which pair a boundary id is slave / master of.
      std::map<types::boundary_id, unsigned int> slave_of, master_of;
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          for (const auto id : pairs[p].slave_ids)
            if (!slave_of.emplace(id, p).second)
              throw InputError(pair_name(p) + ", parameter 'Slave boundary "
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

      const QGauss<dim - 1> centre_quadrature(1);
      FEFaceValues<dim>     centre_values(fe,
                                      centre_quadrature,
                                      update_normal_vectors);
      const unsigned int    n_cell_dofs = fe.n_dofs_per_cell();
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
      const unsigned int n_face_nodes = face_fe.n_dofs_per_cell();
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
                              cell_dofs[fe.component_to_system_index(c,
                                                                     ci.second)];
                          node.normals.push_back(face.outward_normal);
                          node.pair = p;
                        }
                    // The face map in FE_Q<dim-1> order (as the master
                    // faces) and the links to node_local / u_local.
                    face.X.resize(n_face_nodes);
                    face.k_node.resize(n_face_nodes);
                    for (unsigned int i = 0; i < fe.n_dofs_per_face(); ++i)
                      {
                        const auto [c, k] = fe.face_system_to_component_index(i);
                        if (c != 0)
                          continue;
                        const unsigned int cell_i = fe.face_to_cell_index(
                          i,
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
                        for (unsigned int l = 0; l < face.node_local.size(); ++l)
                          if (fe.system_to_component_index(face.node_local[l])
                                .second == ci.second)
                            face.u_node.push_back(l);
                      }
                    if (cell->is_locally_owned())
                      {
                        h_sum[p] += cell->face(f)->diameter();
                        h_count[p] += 1;
                        e_max[p] = std::max(
                          e_max[p],
                          materials.at(cell->material_id())->representative_modulus());
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
                    e_master[m->second] = std::max(
                      e_master[m->second],
                      materials.at(cell->material_id())->representative_modulus());
                    // Nodes in the face's FE_Q<dim-1> order (see
                    // project_onto_face), dim DoFs each.
                    std::vector<types::global_dof_index> node_dofs(
                      n_face_nodes * dim);
                    std::vector<Point<dim>> X(n_face_nodes);
                    for (unsigned int i = 0; i < fe.n_dofs_per_face(); ++i)
                      {
                        const auto [c, k] = fe.face_system_to_component_index(i);
                        const unsigned int cell_i = fe.face_to_cell_index(
                          i,
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
      // rho_t = c_t rho_n / (mu p_ref) makes the tangential stiffness mu p_ref rho_t of a sticking
      // point comparable to rho_n (see update_coefficients); before any
      // pressure is known p_ref = 1e-3 E.
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
          rho_n[p]     = pairs[p].rho_n_factor *
                     (Em > 0 ? std::min(E, Em) : E) / face_size[p];
          p_ref[p]     = 1e-3 * E;
          rho_t[p]     = pairs[p].friction > 0 ?
                           pairs[p].rho_t_factor * rho_n[p] /
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
      n_lambda   = Utilities::MPI::sum(n_owned_nodes, comm);
      n_friction = Utilities::MPI::sum(n_owned_friction, comm) * (dim - 1);
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
            const auto &node = seen[owned_nodes[j]];
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
            NodeInfo info;
            const auto dof0 = static_cast<types::global_dof_index>(pack[i]);
            info.lambda     = static_cast<types::global_dof_index>(pack[i + 1]);
            if (pack[i + 2] >= 0)
              info.friction =
                static_cast<types::global_dof_index>(pack[i + 2]);
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
        const auto all_line_ints  = Utilities::MPI::all_gather(comm, line_ints);
        const auto all_line_reals = Utilities::MPI::all_gather(comm, line_reals);
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
              face.excluded_contact[l]  = info.exclude_contact;
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
            << Utilities::MPI::sum(static_cast<unsigned int>(
                                     slave_faces.size()),
                                   comm)
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
          if (has_friction &&
              (info.exclude_contact || info.exclude_friction ||
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


    template <int dim>
    void
    ContactProblem<dim>::pair(const TrilinosWrappers::MPI::Vector &state,
                              const double                         time,
                              const double                         t0,
                              const bool within_newton)
    {
      const auto &pairs = parameters.contact.pairs;

      // Rigid obstacles at time t; their displacement since the step start.
      std::vector<Tensor<1, dim>> rigid_increment(pairs.size());
      for (unsigned int p = 0; p < pairs.size(); ++p)
        if (obstacles[p])
          {
            Tensor<1, dim> d0, d1;
            for (unsigned int c = 0; c < dim; ++c)
              {
                motions[p]->set_time(t0);
                d0[c] = motions[p]->value(Point<dim>(), c);
                motions[p]->set_time(time);
                d1[c] = motions[p]->value(Point<dim>(), c);
              }
            obstacles[p]->set_translation(d1);
            rigid_increment[p] = d1 - d0;
          }

      // Master faces in the current configuration and their boxes.
      std::vector<std::vector<Point<dim>>> x_master(master_faces.size());
      std::vector<Point<dim>>              inside(master_faces.size());
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
      for (unsigned int m = 0; m < master_faces.size(); ++m)
        {
          master_face_position(m, state, x_master[m], inside[m]);
          BoundingBox<dim> box(x_master[m]);
          box.extend(0.5 * face_size[master_faces[m].pair]);
          boxes.emplace_back(box, m);
        }
      const auto tree = pack_rtree(boxes);

      if (mortar)
        segment(state, x_master, tree);

      const auto &       contact      = parameters.contact;
      const unsigned int freeze_after = contact.freeze_after_cycles;
      unsigned int       n_pinned     = 0;
      n_deep                          = 0;
      pairings_in_step += within_newton ? 0 : 1;
      for (auto &point : points)
        {
          const auto &       face = slave_faces[point.face];
          const unsigned int p    = face.pair;
          const Point<dim>   x_e  = slave_position(point, state);
          double             lambda = 0;
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            lambda += state[face.lambda_dofs[l]] * point.psi[l];
          point.lambda_frozen = lambda;

          point.paired      = false;
          point.master_face = -1;
          // Pairs the point with master face m if its projection onto m
          // converges within the tolerance (also just outside the face).
          const auto pair_with_face = [&](const int m) {
            const auto proj = project_onto_face(x_e, x_master[m], inside[m]);
            if (!proj.converged ||
                proj.violation > contact.projection_tolerance)
              return false;
            point.paired      = true;
            point.master_face = m;
            take_projection(point, proj);
            return true;
          };
          if (obstacles[p])
            {
              const auto projection = obstacles[p]->project(x_e);
              point.paired          = true;
              point.normal          = projection.normal;
              point.x_m_rigid       = projection.x_m;
              point.rigid_increment = rigid_increment[p];
            }
          else if (point.pinned_face >= 0 && !mortar)
            {
              // Pinned by a pairing 2-cycle: the face is kept while the
              // projection onto it stays within the tolerance.
              if (!pair_with_face(point.pinned_face))
                point.pinned_face = -1;
            }
          else if (point.segment_master >= 0)
            // Mortar: the master face of the point's piece (the search
            // below only if the projection leaves that face).
            pair_with_face(point.segment_master);
          if (!obstacles[p] && !point.paired)
            {
              BoundingBox<dim> query(std::make_pair(x_e, x_e));
              query.extend(0.5 * face_size[p]);
              const auto hits = faces_meeting(tree, query);
              // Inside projections first (closest), then the smallest
              // violation within the tolerance.
              double best_inside = std::numeric_limits<double>::max();
              double best_violation =
                contact.projection_tolerance * (1 + 1e-12);
              FaceProjection<dim> best;
              int                 best_face = -1;
              bool                best_is_inside = false;
              for (const unsigned int m : hits)
                {
                  if (master_faces[m].pair != p)
                    continue;
                  const auto proj =
                    project_onto_face(x_e, x_master[m], inside[m]);
                  if (!proj.converged)
                    continue;
                  const double distance = x_e.distance(proj.x_m);
                  if (proj.inside)
                    {
                      if (distance < best_inside)
                        {
                          best_inside    = distance;
                          best           = proj;
                          best_face      = m;
                          best_is_inside = true;
                        }
                    }
                  else if (!best_is_inside && proj.violation < best_violation)
                    {
                      best_violation = proj.violation;
                      best           = proj;
                      best_face      = m;
                    }
                }
              if (best_face >= 0)
                {
                  point.paired      = true;
                  point.master_face = best_face;
                  take_projection(point, best);
                }
              else
                pair_deep(point, x_e, x_master, inside, tree);
            }
          // Pairing 2-cycle: back on the face of two pairings before.
          if (!within_newton && !mortar && !obstacles[p] &&
              point.pinned_face < 0 && freeze_after > 0 &&
              point.master_face >= 0 && pairings_in_step >= 3 &&
              point.master_face == point.geo_face_2 &&
              point.master_face != point.geo_face_1)
            {
              point.pinned_face = point.master_face;
              ++n_pinned;
            }
          if (!within_newton)
            {
              point.geo_face_2 = point.geo_face_1;
              point.geo_face_1 = point.master_face;
            }
          // The contact normal points into the master (formulation.md 2),
          // along the slave's outward normal.
          if (!point.paired)
            point.normal = point.slave_normal;
          // Normal choice (nodal rule only, checked at input).
          if (contact.normal == NormalChoice::slave)
            point.normal = point.slave_normal;
          else if (contact.normal == NormalChoice::average && point.paired)
            {
              point.normal += point.slave_normal;
              point.normal /= point.normal.norm();
            }
          // The 3D crossing axis of T is kept until the next pairing, so
          // that T stays smooth in n when n follows the iterate.
          point.tangent_axis = tangent_axis<dim>(point.normal);
          point.tangents =
            tangent_basis<dim>(point.normal, point.tangent_axis);
        }
      n_newly_pinned = Utilities::MPI::sum(n_pinned, comm);
      n_deep         = Utilities::MPI::sum(n_deep, comm);

      // Dual multipliers only on slave faces whose points are all paired:
      // on a face that leaves the master partly, psi~ (negative lobes)
      // would weigh the gap of the paired part alone.
      std::vector<bool> covered(slave_faces.size(), true);
      for (const auto &point : points)
        covered[point.face] = covered[point.face] && point.paired;
      for (auto &point : points)
        {
          const auto &face = slave_faces[point.face];
          point.psi_lambda = point.psi;
          if (face.dual.empty() || !covered[point.face])
            continue;
          const unsigned int n = point.psi.size();
          for (unsigned int l = 0; l < n; ++l)
            {
              point.psi_lambda[l] = 0;
              for (unsigned int m = 0; m < n; ++m)
                point.psi_lambda[l] += face.dual[l * n + m] * point.psi[m];
            }
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::pair_deep(
      ContactPoint &                                          point,
      const Point<dim> &                                      x_e,
      const std::vector<std::vector<Point<dim>>> &           x_master,
      const std::vector<Point<dim>> &                         inside,
      const RTree<std::pair<BoundingBox<dim>, unsigned int>> &tree)
    {
      // A slave point deeper in the master body than the search box reaches
      // (a deep initial interpenetration, or a large load step) is paired
      // from the penetrated side: with the nearest master faces onto which
      // it projects inside the face and behind it (g > 0). Dropping it
      // would silently lose the contact.
      const unsigned int p = slave_faces[point.face].pair;
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
      tree.query(boost::geometry::index::nearest(x_e, 8),
                 std::back_inserter(hits));
      std::vector<unsigned int> faces;
      for (const auto &hit : hits)
        if (master_faces[hit.second].pair == p)
          faces.push_back(hit.second);
      std::sort(faces.begin(), faces.end()); // partition-independent ties
      double              best_distance = std::numeric_limits<double>::max();
      int                 best_face     = -1;
      FaceProjection<dim> best;
      for (const unsigned int m : faces)
        {
          const auto proj = project_onto_face(x_e, x_master[m], inside[m]);
          if (!proj.converged || !proj.inside ||
              (x_e - proj.x_m) * proj.normal <= 0)
            continue;
          const double distance = x_e.distance(proj.x_m);
          if (distance < best_distance)
            {
              best_distance = distance;
              best_face     = m;
              best          = proj;
            }
        }
      if (best_face < 0)
        return;
      point.paired      = true;
      point.master_face = best_face;
      take_projection(point, best);
      ++n_deep;
    }


    template <int dim>
    void
    ContactProblem<dim>::segment(
      const TrilinosWrappers::MPI::Vector &                   state,
      const std::vector<std::vector<Point<dim>>> &           x_master,
      const RTree<std::pair<BoundingBox<dim>, unsigned int>> &tree)
    {
      std::vector<ContactPoint> old_points;
      old_points.swap(points);
      unsigned int next_old = 0;
      n_pieces              = 0;
      std::vector<Point<dim>>                       x_slave;
      std::vector<const std::vector<Point<dim>> *> candidates;
      std::vector<unsigned int>                     candidate_face;
      for (unsigned int f = 0; f < slave_faces.size(); ++f)
        {
          const auto &       face = slave_faces[f];
          const unsigned int p    = face.pair;
          const std::size_t  first_new = points.size();
          if (obstacles[p])
            {
              // Analytic master: nothing to cut, nodal rule (see the
              // constructor).
              const auto &quadrature = rule->face_quadrature(f);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                points.push_back(
                  make_point(f, q, quadrature.point(q), quadrature.weight(q)));
            }
          else
            {
              x_slave = face.X;
              for (unsigned int k = 0; k < x_slave.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  x_slave[k][c] +=
                    state[face.node_dofs[face.k_node[k] * dim + c]];
              BoundingBox<dim> box(x_slave);
              box.extend(0.5 * face_size[p]);
              candidates.clear();
              candidate_face.clear();
              for (const auto m : faces_meeting(tree, box))
                if (master_faces[m].pair == p)
                  {
                    candidates.push_back(&x_master[m]);
                    candidate_face.push_back(m);
                  }
              const auto cut =
                segment_slave_face<dim>(x_slave, candidates, segment_order);
              n_pieces += cut.n_pieces;
              for (unsigned int q = 0; q < cut.points.size(); ++q)
                {
                  points.push_back(
                    make_point(f, q, cut.points[q], cut.weights[q]));
                  points.back().segment_master =
                    cut.master[q] >= 0 ? candidate_face[cut.master[q]] : -1;
                }
            }
          // Statuses carried over from the nearest old point of the face,
          // so that an unchanged contact state counts no change.
          while (next_old < old_points.size() &&
                 old_points[next_old].face < f)
            ++next_old;
          for (std::size_t i = first_new; i < points.size(); ++i)
            {
              double best = std::numeric_limits<double>::max();
              for (std::size_t j = next_old;
                   j < old_points.size() && old_points[j].face == f;
                   ++j)
                if (const double d2 =
                      (old_points[j].xi - points[i].xi).norm_square();
                    d2 < best)
                  {
                    best                     = d2;
                    points[i].status         = old_points[j].status;
                    points[i].friction_active = old_points[j].friction_active;
                    points[i].slip_direction  = old_points[j].slip_direction;
                    // The geometric loop's history and freeze (the
                    // segmentation changes with every pairing).
                    const auto &o               = old_points[j];
                    points[i].geo_status_1      = o.geo_status_1;
                    points[i].geo_status_2      = o.geo_status_2;
                    points[i].geo_direction_1   = o.geo_direction_1;
                    points[i].geo_direction_2   = o.geo_direction_2;
                    points[i].geometric_freeze  = o.geometric_freeze;
                    points[i].was_frozen        = o.geometric_freeze;
                    points[i].freeze_contact =
                      o.geometric_freeze && o.freeze_contact;
                    points[i].freeze_stick =
                      o.geometric_freeze && o.freeze_stick;
                    points[i].frozen_slip_direction =
                      o.geometric_freeze ? o.frozen_slip_direction :
                                           Tensor<1, dim>();
                  }
            }
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::update_coefficients(
      const TrilinosWrappers::MPI::Vector &state)
    {
      const auto &       pairs = parameters.contact.pairs;
      std::vector<double> sum2(pairs.size(), 0.), count(pairs.size(), 0.);
      // Pressures at or below the zero threshold (e.g. the 'closed'
      // initial multipliers, see set_initial_multipliers) are not a
      // pressure level: they would make rho_t enormous.
      for (const auto &[dof0, node] : nodes)
        if (owned_multipliers.is_element(node.lambda) &&
            state[node.lambda] < -law_parameters(node.pair).zero_threshold)
          {
            sum2[node.pair] += state[node.lambda] * state[node.lambda];
            count[node.pair] += 1;
          }
      for (unsigned int p = 0; p < pairs.size(); ++p)
        {
          const double s = Utilities::MPI::sum(sum2[p], comm);
          const double n = Utilities::MPI::sum(count[p], comm);
          if (pairs[p].friction > 0 && n > 0 && s > 0)
            {
              p_ref[p] = std::sqrt(s / n);
              rho_t[p] = pairs[p].rho_t_factor * rho_n[p] /
                         (pairs[p].friction * p_ref[p]);
            }
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::point_dofs(
      const ContactPoint &                        point,
      const std::vector<types::global_dof_index> &cell_dofs,
      std::vector<types::global_dof_index> &      dofs) const
    {
      const auto &face = slave_faces[point.face];
      dofs.clear();
      for (const auto i : face.u_local)
        dofs.push_back(cell_dofs[i]);
      if (point.master_face >= 0)
        for (const auto d : master_faces[point.master_face].dofs)
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
      for (const auto &point : points)
        {
          slave_faces[point.face].cell->get_dof_indices(cell_dofs);
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
      const AffineConstraints<double> &  constraints) const
    {
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs;
      int                                  last_face = -1;
      // Points of one slave face paired with one master face couple the
      // same unknowns: one entry block per (slave face, master face).
      std::set<int> masters_of_face;
      for (const auto &point : points)
        {
          const auto &face = slave_faces[point.face];
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
    void
    ContactProblem<dim>::set_initial_multipliers(
      const TrilinosWrappers::MPI::Vector &state,
      TrilinosWrappers::MPI::Vector &      state_owned) const
    {
      const auto status = parameters.contact.initial_status;
      // lambda_aug = lambda - rho_n g = -/+ delta at every point, as the
      // psi-weighted average over the node's points. 'penetrating': the
      // points that touch (g >= 0 up to the round-off of mesh coordinates,
      // 1e-8 of the face size) start closed, as where they penetrate; the
      // others keep lambda = 0 (lambda_aug = -rho_n g: open).
      const double touch_tolerance = 1e-8;
      auto num = writable_vector(owned_multipliers, multiplier_ghosts, comm);
      auto den = writable_vector(owned_multipliers, multiplier_ghosts, comm);
      for (const auto &point : points)
        {
          const auto &       face = slave_faces[point.face];
          const unsigned int p    = face.pair;
          const double       g    = point_gap(point, state);
          // delta: half the zero friction threshold of the law (see
          // law_parameters), so that lambda_aug = -/+ delta sets the normal
          // status strictly while the friction of a point closed this way
          // starts inactive, as for a point that has just closed
          // (formulation.md 3.3). A larger delta would be a tiny nonzero
          // threshold: Lambda = F_t / (mu delta) of order 1e8 at the first
          // iterate.
          const double delta = 0.5 * law_parameters(p).zero_threshold;
          if (status != InitialStatus::open && !point.paired)
            continue;
          double target;
          if (status == InitialStatus::closed)
            target = std::min(0., rho_n[p] * std::max(g, -1e300 / rho_n[p])) -
                     delta;
          else if (status == InitialStatus::penetrating)
            target = g >= -touch_tolerance * face_size[p] ? -delta : 0.;
          else
            target = std::max(0., rho_n[p] * g) + delta;
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              const double w = point.weight * point.psi[l];
              add_entry(num, face.lambda_dofs[l], w * target);
              add_entry(den, face.lambda_dofs[l], w);
            }
        }
      num.compress(VectorOperation::add);
      den.compress(VectorOperation::add);
      for (const auto i : owned_multipliers)
        if (i < n_u + n_lambda && den[i] != 0)
          state_owned[i] = num[i] / den[i];
      state_owned.compress(VectorOperation::insert);
    }


    template <int dim>
    PointResponse<dim>
    ContactProblem<dim>::node_status_response(const ContactPoint &   point,
                                              const PointState<dim> &s) const
    {
      // The multiplier force -lambda n (the law's -lambda_aug n without
      // the augmentation; lambda = 0 at free nodes); the point is labelled
      // with the status of its nearest node (statistics and output).
      PointResponse<dim> r{};
      const auto &face = slave_faces[point.face];
      const auto  nearest =
        std::max_element(point.psi.begin(), point.psi.end()) - point.psi.begin();
      r.in_contact = point.paired && node_active.at(face.lambda_dofs[nearest]);
      r.status     = r.in_contact ? PointStatus::slip : PointStatus::free;
      r.friction_active = false;
      if (r.in_contact && friction_node_pair[face.pair])
        {
          // Labelled with the friction status of the same node; the
          // friction force and rows are the assembly's (per node).
          const auto &nf    = node_friction.at(face.lambda_dofs[nearest]);
          r.friction_active = nf.active;
          if (nf.active && nf.stick)
            r.status = PointStatus::stick;
          else if (nf.active)
            for (unsigned int k = 0; k < dim - 1; ++k)
              r.slip_direction += nf.H[k] / nf.H.norm() * s.tangents[k];
        }
      if (point.paired)
        {
          r.force          = -s.lambda * s.normal;
          r.dforce_dlambda = -s.normal;
        }
      return r;
    }


    template <int dim>
    unsigned int
    ContactProblem<dim>::decide_node_statuses(
      const TrilinosWrappers::MPI::Vector &state,
      const TrilinosWrappers::MPI::Vector &start,
      const bool                           new_iterate,
      ContactStatistics &                  stats)
    {
      // Weighted gap G_l and weight D_l of every node (faces of all ranks).
      // P_l: the paired share of the node (psi >= 0); a node without
      // paired points has no gap and stays free.
      auto G = writable_vector(owned_multipliers, multiplier_ghosts, comm);
      auto D = writable_vector(owned_multipliers, multiplier_ghosts, comm);
      auto P = writable_vector(owned_multipliers, multiplier_ghosts, comm);
      // Frictional pairs: the weighted slip W_l = sum_k w_k psi_l T^T v_k,
      // component k in the vector of index k (by the node's lambda DoF).
      std::vector<TrilinosWrappers::MPI::Vector> W;
      if (any_friction_node)
        for (unsigned int k = 0; k < dim - 1; ++k)
          W.push_back(writable_vector(owned_multipliers, multiplier_ghosts, comm));
      for (const auto &point : points)
        {
          const auto &face = slave_faces[point.face];
          if (!node_status_pair[face.pair])
            continue;
          const double g = point.paired ? point_gap(point, state) : 0.;
          const bool   slip = point.paired && friction_node_pair[face.pair];
          const auto   v =
            slip ? point_slip(point, state, start) : Tensor<1, dim - 1>();
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              const double w = point.weight * point.psi_lambda[l];
              add_entry(G, face.lambda_dofs[l], w * g);
              add_entry(D, face.lambda_dofs[l], w);
              if (point.paired)
                add_entry(P, face.lambda_dofs[l], point.weight * point.psi[l]);
              if (slip)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  add_entry(W[k], face.lambda_dofs[l], w * v[k]);
            }
        }
      G.compress(VectorOperation::add);
      D.compress(VectorOperation::add);
      P.compress(VectorOperation::add);
      TrilinosWrappers::MPI::Vector G_read(owned_multipliers, multiplier_ghosts, comm);
      TrilinosWrappers::MPI::Vector D_read(owned_multipliers, multiplier_ghosts, comm);
      TrilinosWrappers::MPI::Vector P_read(owned_multipliers, multiplier_ghosts, comm);
      G_read = G;
      D_read = D;
      P_read = P;
      std::vector<TrilinosWrappers::MPI::Vector> W_read(W.size());
      for (unsigned int k = 0; k < W.size(); ++k)
        {
          W[k].compress(VectorOperation::add);
          W_read[k].reinit(owned_multipliers, multiplier_ghosts, comm);
          W_read[k] = W[k];
        }
      unsigned int changed = 0;
      for (const auto &face : slave_faces)
        if (node_status_pair[face.pair])
          for (const auto dof : face.lambda_dofs)
            {
              const bool active = P_read[dof] > 0 &&
                                  node_in_contact(state[dof],
                                                  G_read[dof],
                                                  D_read[dof],
                                                  rho_n[face.pair]) &&
                                  node_release.count(dof) == 0;
              const auto it = node_active.find(dof);
              if (it != node_active.end() && it->second == active)
                continue;
              // Counted once, by the owner (a node is on several faces).
              if (owned_multipliers.is_element(dof) &&
                  (it != node_active.end() || active))
                ++changed;
              node_active[dof] = active;
            }
      // Friction status per node (theory.md, "Friction status per node"):
      // active if in contact with a threshold above zero (formulation.md
      // 3.3); H_l = Lambda_l + rho_t W_l / D_l; stick iff |H_l| <= 1 (the
      // round-off tie as in the point law). Each node once (it is on
      // several faces), then its anti-cycling.
      std::set<types::global_dof_index> seen;
      if (any_friction_node)
        for (unsigned int f = 0; f < slave_faces.size(); ++f)
          {
            const auto &face = slave_faces[f];
            if (!friction_node_pair[face.pair])
              continue;
            const auto law = law_parameters(face.pair);
            for (unsigned int l = 0; l < face.lambda_dofs.size(); ++l)
              {
                const auto   dof = face.lambda_dofs[l];
                if (!seen.insert(dof).second)
                  continue;
                NodeFriction nf;
                nf.active = node_active.at(dof) &&
                            std::abs(state[dof]) > law.zero_threshold &&
                            D_read[dof] > 0;
                if (nf.active)
                  {
                    for (unsigned int k = 0; k < dim - 1; ++k)
                      nf.H[k] =
                        state[face.friction_dofs[l * (dim - 1) + k]] +
                        law.rho_t * W_read[k][dof] / D_read[dof];
                    nf.stick = nf.H.norm() <= 1. + stick_tie;
                  }
                const auto  it    = node_friction.find(dof);
                const bool  owned = owned_multipliers.is_element(dof);
                const auto *previous =
                  it == node_friction.end() ? nullptr : &it->second;
                const auto used = node_anti_cycling(
                  dof, nf, previous, new_iterate, owned, stats);
                if (owned && friction_status_differs(previous, used))
                  ++changed;
                node_friction[dof] = used;
              }
          }
      return changed;
    }


    template <int dim>
    bool
    ContactProblem<dim>::friction_status_differs(const NodeFriction *previous,
                                                 const NodeFriction &now)
    {
      if (!previous)
        return now.active;
      return previous->active != now.active || previous->stick != now.stick ||
             (now.active && !now.stick && !previous->stick &&
              previous->H * now.H < 0);
    }


    template <int dim>
    typename ContactProblem<dim>::NodeFriction
    ContactProblem<dim>::node_anti_cycling(
      const types::global_dof_index dof,
      const NodeFriction &          nf,
      const NodeFriction *          previous,
      const bool                    new_iterate,
      const bool                    owned,
      ContactStatistics &           stats)
    {
      const unsigned int freeze_after = parameters.contact.freeze_after_cycles;
      auto               found        = node_cycle.find(dof);
      if (found == node_cycle.end())
        {
          NodeCycle c;
          c.before = previous ? *previous : NodeFriction();
          found    = node_cycle.emplace(dof, c).first;
        }
      NodeCycle &  c    = found->second;
      NodeFriction used = nf;
      // Frozen (only while the node is in contact with a threshold): the
      // status of the freeze; the plain law's status is kept for the
      // check at convergence (release_frozen()).
      c.plain_violated = false;
      if (c.freeze && nf.active)
        {
          used.frozen = true;
          used.stick  = c.freeze_stick;
          if (!c.freeze_stick)
            used.H = c.q;
          c.plain          = nf;
          c.plain_violated = c.freeze_stick ? !nf.stick :
                                              (nf.stick || nf.H * c.q < 0);
          if (owned)
            {
              ++stats.n_frozen;
              stats.n_violated += c.plain_violated;
            }
        }
      if (!new_iterate)
        return used;
      // A return to the status of two iterates back (a 2-cycle), or more
      // than 2 N changes (longer cycles), as for points.
      const bool changed =
        friction_status_differs(previous, used) && !used.frozen;
      c.changes += changed;
      const bool back =
        changed && iterates_recorded >= 2 &&
        (!friction_status_differs(&c.before, used) ||
         (freeze_after > 0 && c.changes > 2 * freeze_after));
      if (back)
        {
          ++c.cycles;
          stats.n_cycling += owned;
        }
      // Frozen from the next evaluation on, slipping along the last slip
      // direction of the cycle (the cycle went through stick, or reversed:
      // then the current one).
      if (back && freeze_after > 0 && c.cycles >= freeze_after &&
          !c.was_frozen && used.active)
        {
          const Tensor<1, dim - 1> h =
            !used.stick ? used.H :
                          (previous && previous->active && !previous->stick ?
                             previous->H :
                             Tensor<1, dim - 1>());
          if (h.norm() > 0)
            {
              c.was_frozen   = true;
              c.freeze       = true;
              c.freeze_stick = false;
              c.q            = h / h.norm();
              stats.n_newly_frozen += owned;
            }
        }
      c.before = previous ? *previous : NodeFriction();
      return used;
    }


    template <int dim>
    void
    ContactProblem<dim>::master_face_position(
      const unsigned int                   m,
      const TrilinosWrappers::MPI::Vector &state,
      std::vector<Point<dim>> &            x,
      Point<dim> &                         inside) const
    {
      const auto &face = master_faces[m];
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
    ContactProblem<dim>::update_projections(
      const TrilinosWrappers::MPI::Vector &state)
    {
      std::vector<Point<dim>> x_face;
      Point<dim>              inside;
      for (auto &point : points)
        {
          point.reprojected = false;
          if (!newton_pairing_pair[slave_faces[point.face].pair] ||
              !point.paired || point.master_face < 0)
            continue;
          master_face_position(point.master_face, state, x_face, inside);
          const auto proj =
            project_onto_face(slave_position(point, state), x_face, inside);
          // Off the face (beyond the projection tolerance): the pairing's
          // projection stays, frozen, until the next pairing finds the
          // point's new face.
          if (!proj.converged ||
              proj.violation > parameters.contact.projection_tolerance)
            continue;
          point.reprojected = true;
          take_projection(point, proj);
          point.tangents =
            tangent_basis<dim>(point.normal, point.tangent_axis);
        }
    }


    template <int dim>
    ContactStatistics
    ContactProblem<dim>::assemble(const TrilinosWrappers::MPI::Vector &state,
                                  const TrilinosWrappers::MPI::Vector &start,
                                  const AffineConstraints<double> &constraints,
                                  TrilinosWrappers::SparseMatrix * matrix,
                                  TrilinosWrappers::MPI::Vector &  rhs,
                                  TrilinosWrappers::MPI::Vector &contact_force,
                                  const bool new_iterate)
    {
      ContactStatistics stats;
      const unsigned int freeze_after = parameters.contact.freeze_after_cycles;
      // Normal status per node (decided before the point loop: a node's
      // status needs the points of all its faces).
      update_projections(state);
      if (any_node_status)
        {
          stats.n_changed +=
            decide_node_statuses(state, start, new_iterate, stats);
          // The statuses of the next solve (release extrapolation).
          if (matrix)
            node_active_solved = node_active;
        }
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> dofs;
      FullMatrix<double>                   K, K_group;
      Vector<double>                       F, F_group;
      std::vector<types::global_dof_index> group_dofs;
      int                                  group_face = -1, group_master = -1;
      // Per-point work arrays, sized per point but allocated once.
      std::vector<double>       N_e, Nd;
      std::vector<unsigned int> comp;
      std::vector<NodeStatusRow<dim>> node_rows;
      struct NodeData
      {
        const NodeFriction *status;
        double              lambda;
        Tensor<1, dim - 1>  Lambda;
      };
      std::vector<NodeData> node_data; // friction status per node
      std::vector<Point<dim>>         x_face;
      const auto                           flush = [&]() {
        if (group_dofs.empty())
          return;
        if (matrix)
          constraints.distribute_local_to_global(
            K_group, F_group, group_dofs, *matrix, rhs);
        else
          constraints.distribute_local_to_global(F_group, group_dofs, rhs);
        group_dofs.clear();
      };

      for (auto &point : points)
        {
          const auto &face = slave_faces[point.face];
          if (point.q == 0)
            face.cell->get_dof_indices(cell_dofs);
          const unsigned int p    = face.pair;
          const auto         law  = law_parameters(p);
          const bool         fric = law.mu > 0;

          // Point state (formulation.md 2).
          const unsigned int n_e = face.u_local.size();
          const unsigned int n_l = face.node_local.size();
          const std::vector<double> &psi = point.psi;
          // Multiplier basis: psi, or the dual psi~ (node-status pairs).
          const std::vector<double> &psi_c = point.psi_lambda;
          N_e.resize(n_e);
          Point<dim>                 x_e = point.x_ref;
          Tensor<1, dim>             du_e;
          for (unsigned int a = 0; a < n_e; ++a)
            {
              const unsigned int i = face.u_local[a];
              const unsigned int c = face.u_comp[a];
              N_e[a]               = psi[face.u_node[a]];
              x_e[c] += N_e[a] * state[cell_dofs[i]];
              du_e[c] += N_e[a] * (state[cell_dofs[i]] - start[cell_dofs[i]]);
            }
          PointState<dim> s;
          s.lambda            = 0;
          double lambda_shown = 0; // with psi (output)
          for (unsigned int l = 0; l < n_l; ++l)
            {
              s.lambda += psi_c[l] * state[face.lambda_dofs[l]];
              lambda_shown += psi[l] * state[face.lambda_dofs[l]];
              if (fric)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  s.Lambda[k] +=
                    psi[l] * state[face.friction_dofs[l * (dim - 1) + k]];
            }
          // Newton on the geometry of a rigid obstacle: projection, normal
          // and tangents of the current iterate, and dn/du for the
          // Jacobian (added after the law below).
          const bool geometry_newton =
            newton_geometry_pair[p] && point.paired;
          Tensor<2, dim>       dn_du, dslip_du;
          Tensor<1, dim>       surface_slip;
          if (geometry_newton)
            {
              const auto proj = obstacles[p]->project(x_e);
              point.normal    = proj.normal;
              point.x_m_rigid = proj.x_m;
              point.tangents =
                tangent_basis<dim>(point.normal, point.tangent_axis);
              dn_du    = proj.dnormal;
              dslip_du = proj.dclosest;
              // Slip on the obstacle's surface: the closest point now
              // against that of the step-start position carried with the
              // obstacle (a normal approach is no slip, whatever n does).
              surface_slip =
                proj.x_m -
                obstacles[p]->project(x_e - du_e + point.rigid_increment).x_m;
            }
          s.normal          = point.normal;
          s.tangents        = point.tangents;
          s.lambda_f_frozen = point.lambda_frozen;

          const MasterFace *master =
            point.master_face >= 0 ? &master_faces[point.master_face] : nullptr;
          const unsigned int n_m = master ? master->dofs.size() : 0;
          Point<dim>         x_m = point.x_m_rigid;
          Tensor<1, dim>     du_m = point.rigid_increment;
          if (master)
            {
              x_m  = Point<dim>();
              du_m = Tensor<1, dim>();
              for (unsigned int k = 0; k < master->X.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const auto d = master->dofs[k * dim + c];
                    x_m[c] += point.N_m[k] * (master->X[k][c] + state[d]);
                    du_m[c] += point.N_m[k] * (state[d] - start[d]);
                  }
            }
          if (point.paired)
            s.gap = (x_e - x_m) * s.normal +
                    parameters.contact.pairs[p].gap_offset;
          else
            s.gap = -1e30; // no master in reach: free
          s.slip = geometry_newton ? surface_slip : du_e - du_m;
          s.slip -= (s.slip * s.normal) * s.normal;

          s.freeze_contact        = point.freeze_contact;
          s.frozen_slip_direction = point.frozen_slip_direction;
          s.freeze_stick          = point.freeze_stick;
          s.release               = point.release;
          const bool by_node      = node_status_pair[p];
          // A point whose multiplier nodes are all excluded from contact
          // (friction) by a Dirichlet condition (formulation.md 8) carries
          // no contact (friction) force: its multipliers are held at zero,
          // and the plain law would act there as a penalty of stiffness
          // rho_n (rho_t) on the master. The nodal rule's points are nodes.
          LawParameters point_law = law;
          if (!by_node)
            {
              bool contact_out = true, friction_out = true;
              for (unsigned int l = 0; l < n_l; ++l)
                if (psi[l] > 1e-12)
                  {
                    contact_out &= face.excluded_contact[l];
                    friction_out &= face.excluded_friction[l];
                  }
              s.release |= contact_out;
              if (friction_out)
                point_law.mu = 0;
            }
          auto r = by_node ? node_status_response(point, s) :
                             evaluate_contact_law(s, point_law);
          // Friction status per node: the friction force of the multipliers,
          // -mu lambda_l T Lambda_l of each node with active friction
          // interpolated like lambda (theory.md, "Friction status per
          // node").
          const bool node_friction_rows = by_node && fric;
          Tensor<1, dim - 1> slip_t; // T^T v (s.slip is tangential)
          for (unsigned int k = 0; k < dim - 1; ++k)
            slip_t[k] = point.paired ? s.slip * s.tangents[k] : 0.;
          // Status, lambda_l and Lambda_l of the face's nodes, looked up
          // once per point (force, rows and derivatives below).
          node_data.resize(node_friction_rows ? n_l : 0);
          for (unsigned int l = 0; l < node_data.size(); ++l)
            {
              auto &d  = node_data[l];
              d.status = &node_friction.at(face.lambda_dofs[l]);
              d.lambda = state[face.lambda_dofs[l]];
              for (unsigned int k = 0; k < dim - 1; ++k)
                d.Lambda[k] = state[face.friction_dofs[l * (dim - 1) + k]];
            }
          if (point.paired)
            for (unsigned int l = 0; l < node_data.size(); ++l)
              if (node_data[l].status->active)
                for (unsigned int k = 0; k < dim - 1; ++k)
                  r.force += -law.mu * psi_c[l] * node_data[l].lambda *
                             node_data[l].Lambda[k] * s.tangents[k];
          if (geometry_newton)
            add_geometric_derivatives(
              r, s, surface_slip, dslip_du, dn_du, point.tangent_axis);

          // Statistics and the values for output.
          ++stats.n_points;
          stats.n_unpaired += !point.paired;
          if (r.in_contact)
            {
              ++stats.n_contact;
              if (fric && r.friction_active)
                (r.status == PointStatus::stick ? stats.n_stick :
                                                  stats.n_slip)++;
            }
          // The status label of a law response ('slip' also for a closed
          // point without friction).
          const auto label = [fric](const PointResponse<dim> &response) {
            return !response.in_contact ?
                     PointStatus::free :
                     (fric && response.friction_active ? response.status :
                                                         PointStatus::slip);
          };
          const PointStatus status = label(r);
          // A point that closed with a zero threshold (friction inactive,
          // formulation.md 3.3) and one with friction on are different
          // branches of the law even when both are labelled 'slip'.
          // A slip direction that turned by more than 90 degrees (in 2D:
          // reversed) is another branch of the slip law too.
          const bool reversed = status == PointStatus::slip &&
                                point.status == PointStatus::slip &&
                                r.slip_direction * point.slip_direction < 0;
          // (Node-status points: the node changes are counted instead.)
          const bool changed = !by_node &&
                               ((status != point.status) ||
                                (r.friction_active != point.friction_active) ||
                                reversed);
          stats.n_reversed += reversed;
          stats.n_changed += changed;

          // Anti-cycling (formulation.md 8), see start_newton_solve().
          const bool frozen = point.freeze_contact && !by_node;
          if (frozen)
            {
              // What the plain law says at this iterate.
              PointState<dim> plain       = s;
              plain.freeze_contact        = false;
              plain.frozen_slip_direction = Tensor<1, dim>();
              plain.freeze_stick          = false;
              const auto        rp = evaluate_contact_law(plain, point_law);
              const PointStatus plain_status = label(rp);
              ++stats.n_frozen;
              const bool violated =
                plain_status != status ||
                (status == PointStatus::slip &&
                 rp.slip_direction * r.slip_direction < 0);
              point.plain_status    = plain_status;
              point.plain_direction = rp.slip_direction;
              point.plain_violated  = violated;
              if (point.geometric_freeze)
                {
                  ++stats.n_geometric_frozen;
                  stats.n_geometric_violated += violated;
                }
              else
                stats.n_violated += violated;
            }
          if (new_iterate && !frozen && !by_node)
            {
              // Back to the status of two iterates before (a 2-cycle), or
              // changed more than 2 N times (longer cycles).
              point.changes += changed;
              const bool back =
                changed && iterates_recorded >= 2 &&
                ((status == point.status_before &&
                  (status != PointStatus::slip ||
                   r.slip_direction * point.direction_before >= 0)) ||
                 (freeze_after > 0 && point.changes > 2 * freeze_after));
              if (back)
                {
                  ++point.cycles;
                  ++stats.n_cycling;
                }
              if (back && freeze_after > 0 && point.cycles >= freeze_after &&
                  !point.was_frozen)
                {
                  // Freeze from the next evaluation on: in contact if the
                  // cycle went through 'free', slipping in the last slip
                  // direction if it went through stick or reversed.
                  point.was_frozen = true;
                  ++stats.n_newly_frozen;
                  freeze_for_cycle(point,
                                   status,
                                   r.slip_direction,
                                   point.status,
                                   point.slip_direction,
                                   fric);
                }
            }
          if (new_iterate)
            {
              point.status_before    = point.status;
              point.direction_before = point.slip_direction;
            }
          point.status          = status;
          point.friction_active = r.friction_active;
          point.slip_direction  = r.slip_direction;
          point.gap    = s.gap;
          point.lambda = lambda_shown;
          point.Lambda = s.Lambda;
          point.force  = r.force;
          for (unsigned int k = 0; k < dim - 1; ++k)
            point.slip[k] = s.slip * s.tangents[k];

          // Local dofs: e | m | lambda | Lambda.
          const unsigned int n_f = fric ? n_l * (dim - 1) : 0;
          const unsigned int o_c = n_e + n_m, o_f = o_c + n_l;
          const unsigned int n   = o_f + n_f;
          point_dofs(point, cell_dofs, dofs);
          AssertDimension(dofs.size(), n);

          // Shape value and component of each displacement column, with the
          // sign of d = u^e - u^m.
          Nd.resize(n_e + n_m);
          comp.resize(n_e + n_m);
          for (unsigned int a = 0; a < n_e; ++a)
            {
              Nd[a]   = N_e[a];
              comp[a] = face.u_comp[a];
            }
          for (unsigned int b = 0; b < n_m; ++b)
            {
              Nd[n_e + b]   = -point.N_m[b / dim];
              comp[n_e + b] = b % dim;
            }

          const double w  = point.weight;
          const double sc = rho_n[p]; // row scaling of lambda rows
          const double sf = rho_t[p]; // row scaling of Lambda rows
          F.reinit(n);
          for (unsigned int a = 0; a < n_e + n_m; ++a)
            F[a] = -w * Nd[a] * r.force[comp[a]];
          // The Signorini row of each node: the point's law, or the
          // node's status (node_status_row).
          auto &rows = node_rows;
          rows.resize(n_l);
          for (unsigned int l = 0; l < n_l; ++l)
            rows[l] =
              by_node ?
                node_status_row(node_active.at(face.lambda_dofs[l]) &&
                                  point.paired,
                                point.paired ? s.gap : 0.,
                                state[face.lambda_dofs[l]],
                                s.normal,
                                rho_n[p]) :
                NodeStatusRow<dim>{r.r_c, r.drc_dd, 0.};
          for (unsigned int l = 0; l < n_l; ++l)
            {
              F[o_c + l] = -sc * w * psi_c[l] * rows[l].r_c;
              for (unsigned int k = 0; k < (fric ? dim - 1 : 0); ++k)
                F[o_f + l * (dim - 1) + k] = -sf * w * psi[l] * r.r_f[k];
            }
          // Friction rows of a node-status pair, per node: free (or zero
          // threshold) s Lambda_l; stick -mu lambda_l W_l (its weighted
          // slip closed); slip (mu lambda_l / rho_t) D_l (Lambda_l - q_l),
          // q_l = H_l / |H_l|; each point adds its share w psi_l.
          for (unsigned int l = 0; l < node_data.size(); ++l)
            {
              const auto & nf  = *node_data[l].status;
              const double lam = node_data[l].lambda;
              const auto & L   = node_data[l].Lambda;
              for (unsigned int k = 0; k < dim - 1; ++k)
                {
                  const double r_f =
                    !nf.active ? law.free_friction_scale * L[k] :
                    nf.stick   ? -law.mu * lam * slip_t[k] :
                                 law.mu * lam / law.rho_t *
                                 (L[k] - nf.H[k] / nf.H.norm());
                  F[o_f + l * (dim - 1) + k] += -sf * w * psi_c[l] * r_f;
                }
            }
          for (unsigned int a = 0; a < n_e + n_m; ++a)
            add_entry(contact_force, dofs[a], -F[a]);

          if (matrix)
            {
              K.reinit(n, n);
              for (unsigned int a = 0; a < n_e + n_m; ++a)
                {
                  for (unsigned int b = 0; b < n_e + n_m; ++b)
                    K(a, b) =
                      w * Nd[a] * Nd[b] * r.dforce_dd[comp[a]][comp[b]];
                  for (unsigned int l = 0; l < n_l; ++l)
                    {
                      K(a, o_c + l) =
                        w * Nd[a] * psi_c[l] * r.dforce_dlambda[comp[a]];
                      K(o_c + l, a) = sc * w * psi_c[l] * Nd[a] *
                                      rows[l].drc_dd[comp[a]];
                      for (unsigned int k = 0; k < (fric ? dim - 1 : 0); ++k)
                        {
                          K(a, o_f + l * (dim - 1) + k) =
                            w * Nd[a] * psi[l] *
                            r.dforce_dLambda[k][comp[a]];
                          K(o_f + l * (dim - 1) + k, a) =
                            sf * w * psi[l] * Nd[a] * r.drf_dd[k][comp[a]];
                        }
                    }
                }
              // Newton on the pairing of a meshed master: the force
              // f = (f . n) n turns with n, and the master rows follow
              // N_m(xi_m); the gap needs nothing more (at the closest
              // point, dg = n . (du^e - N_m du^m) exactly).
              if (point.reprojected)
                {
                  Point<dim> inside;
                  master_face_position(point.master_face, state, x_face, inside);
                  const auto D = face_projection_derivatives<dim>(
                    x_e, x_face, point.xi_m, s.normal);
                  const double phi = r.force * s.normal;
                  for (unsigned int j = 0; j < n_e + n_m; ++j)
                    {
                      // Column j: slave DoF j (moves x_e by N_e e_c) or
                      // component c of master support point k.
                      const unsigned int c = comp[j];
                      Tensor<1, dim>     dn;
                      Tensor<1, dim - 1> dxi;
                      const unsigned int k = j < n_e ? 0 : (j - n_e) / dim;
                      for (unsigned int i = 0; i < dim; ++i)
                        dn[i] = j < n_e ? N_e[j] * D.dn_dp[i][c] :
                                          D.dn_dX[k][i][c];
                      for (unsigned int a = 0; a < dim - 1; ++a)
                        dxi[a] = j < n_e ? N_e[j] * D.dxi_dp[a][c] :
                                           D.dxi_dX[k][a][c];
                      for (unsigned int a = 0; a < n_e + n_m; ++a)
                        {
                          const double dNd =
                            a < n_e ? 0. : -(D.dN[(a - n_e) / dim] * dxi);
                          K(a, j) += w * (dNd * r.force[comp[a]] +
                                          Nd[a] * phi * dn[comp[a]]);
                        }
                    }
                }
              for (unsigned int l = 0; l < n_l; ++l)
                for (unsigned int m = 0; m < n_l; ++m)
                  {
                    K(o_c + l, o_c + m) =
                      by_node ? (l == m ? sc * w * psi_c[l] *
                                            rows[l].drc_dlambda_own :
                                          0.) :
                                sc * w * psi[l] * psi[m] * r.drc_dlambda;
                    for (unsigned int k = 0; k < (fric ? dim - 1 : 0); ++k)
                      {
                        K(o_f + l * (dim - 1) + k, o_c + m) =
                          sf * w * psi[l] * psi[m] * r.drf_dlambda[k];
                        for (unsigned int kk = 0; kk < dim - 1; ++kk)
                          K(o_f + l * (dim - 1) + k,
                            o_f + m * (dim - 1) + kk) =
                            sf * w * psi[l] * psi[m] * r.drf_dLambda[k][kk];
                      }
                  }
            }

          // Their derivatives (the status of each node fixed).
          if (matrix)
            for (unsigned int l = 0; l < node_data.size(); ++l)
              {
                const auto &       nf  = *node_data[l].status;
                const double       lam = node_data[l].lambda;
                const auto &       L   = node_data[l].Lambda;
                const double       wl  = sf * w * psi_c[l];
                const unsigned int of  = o_f + l * (dim - 1);
                if (!nf.active)
                  {
                    for (unsigned int k = 0; k < dim - 1; ++k)
                      K(of + k, of + k) += wl * law.free_friction_scale;
                    continue;
                  }
                if (point.paired)
                  {
                    // Displacement rows: d/dlambda_l, d/dLambda_l.
                    Tensor<1, dim> TL;
                    for (unsigned int k = 0; k < dim - 1; ++k)
                      TL += L[k] * s.tangents[k];
                    for (unsigned int a = 0; a < n_e + n_m; ++a)
                      {
                        K(a, o_c + l) +=
                          w * Nd[a] * (-law.mu * psi_c[l] * TL[comp[a]]);
                        for (unsigned int k = 0; k < dim - 1; ++k)
                          K(a, of + k) +=
                            w * Nd[a] *
                            (-law.mu * psi_c[l] * lam * s.tangents[k][comp[a]]);
                      }
                  }
                if (nf.stick)
                  {
                    if (point.paired)
                      for (unsigned int k = 0; k < dim - 1; ++k)
                        {
                          for (unsigned int a = 0; a < n_e + n_m; ++a)
                            K(of + k, a) += wl * (-law.mu * lam) *
                                            s.tangents[k][comp[a]] * Nd[a];
                          K(of + k, o_c + l) += wl * (-law.mu * slip_t[k]);
                        }
                    continue;
                  }
                // Slip: K_B = (I - q q) / |H|, dH/dLambda_l = I,
                // dH/du = rho_t / D_l dW/du.
                // Frozen in slip: q fixed, K_B = 0.
                const double       nH = nf.H.norm();
                Tensor<2, dim - 1> KB;
                if (!nf.frozen)
                  for (unsigned int k = 0; k < dim - 1; ++k)
                    for (unsigned int kk = 0; kk < dim - 1; ++kk)
                      KB[k][kk] =
                        ((k == kk) - nf.H[k] * nf.H[kk] / (nH * nH)) / nH;
                for (unsigned int k = 0; k < dim - 1; ++k)
                  {
                    for (unsigned int kk = 0; kk < dim - 1; ++kk)
                      K(of + k, of + kk) += wl * law.mu * lam / law.rho_t *
                                            ((k == kk) - KB[k][kk]);
                    K(of + k, o_c + l) +=
                      wl * law.mu / law.rho_t * (L[k] - nf.H[k] / nH);
                    if (point.paired)
                      for (unsigned int a = 0; a < n_e + n_m; ++a)
                        {
                          double KBT = 0;
                          for (unsigned int kk = 0; kk < dim - 1; ++kk)
                            KBT += KB[k][kk] * s.tangents[kk][comp[a]];
                          K(of + k, a) += wl * (-law.mu * lam) * KBT * Nd[a];
                        }
                  }
              }

          // Points of one slave face paired with one master face share
          // their unknowns: sum them and distribute once per group (a
          // mortar face has tens of points per master face).
          if (static_cast<int>(point.face) != group_face ||
              point.master_face != group_master)
            {
              flush();
              group_face   = point.face;
              group_master = point.master_face;
              group_dofs   = dofs;
              F_group.reinit(n);
              if (matrix)
                K_group.reinit(n, n);
            }
          F_group += F;
          if (matrix)
            K_group.add(1., K);
        }
      flush();

      stats.n_points   = Utilities::MPI::sum(stats.n_points, comm);
      stats.n_unpaired = Utilities::MPI::sum(stats.n_unpaired, comm);
      stats.n_contact  = Utilities::MPI::sum(stats.n_contact, comm);
      stats.n_stick    = Utilities::MPI::sum(stats.n_stick, comm);
      stats.n_slip     = Utilities::MPI::sum(stats.n_slip, comm);
      stats.n_changed  = Utilities::MPI::sum(stats.n_changed, comm);
      stats.n_reversed = Utilities::MPI::sum(stats.n_reversed, comm);
      if (new_iterate)
        ++iterates_recorded;
      stats.n_cycling  = Utilities::MPI::sum(stats.n_cycling, comm);
      stats.n_frozen   = Utilities::MPI::sum(stats.n_frozen, comm);
      stats.n_newly_frozen = Utilities::MPI::sum(stats.n_newly_frozen, comm);
      stats.n_violated = Utilities::MPI::sum(stats.n_violated, comm);
      stats.n_geometric_frozen =
        Utilities::MPI::sum(stats.n_geometric_frozen, comm);
      stats.n_geometric_violated =
        Utilities::MPI::sum(stats.n_geometric_violated, comm);
      return stats;
    }


    template <int dim>
    void
    ContactProblem<dim>::start_newton_solve()
    {
      iterates_recorded = 0;
      node_cycle.clear();
      for (auto &[dof, nf] : node_friction)
        nf.frozen = false;
      node_release.clear();
      node_extrapolated.clear();
      node_kept.clear();
      for (auto &point : points)
        {
          point.release      = false;
          point.extrapolated = false;
          point.keep_closed  = false;
          point.status_before         = point.status;
          point.direction_before      = point.slip_direction;
          point.cycles                = 0;
          point.changes               = 0;
          point.refrozen              = false;
          // A status frozen by the geometric loop stays for the step.
          point.was_frozen = point.geometric_freeze;
          if (!point.geometric_freeze)
            clear_freeze(point);
        }
    }


    template <int dim>
    void
    ContactProblem<dim>::start_geometric_loop()
    {
      for (auto &point : points)
        {
          point.geo_status_1     = point.status;
          point.geo_status_2     = point.status;
          point.geo_direction_1  = point.slip_direction;
          point.geo_direction_2  = point.slip_direction;
          point.geometric_freeze = false;
          point.geo_face_1       = -1;
          point.geo_face_2       = -1;
          point.pinned_face      = -1;
          clear_freeze(point);
        }
      pairings_in_step = 0;
      n_newly_pinned   = 0;
    }


    template <int dim>
    unsigned int
    ContactProblem<dim>::end_geometric_iteration(const unsigned int g)
    {
      const unsigned int freeze_after = parameters.contact.freeze_after_cycles;
      unsigned int       n            = 0;
      for (auto &point : points)
        {
          const PointStatus status = point.status;
          const auto &      dir    = point.slip_direction;
          // Same status as two pairings before (a slip in a direction not
          // turned against it), different from the last one (or reversed).
          const bool same_as_2 =
            status == point.geo_status_2 &&
            (status != PointStatus::slip || dir * point.geo_direction_2 >= 0);
          const bool differs_from_1 =
            status != point.geo_status_1 ||
            (status == PointStatus::slip && dir * point.geo_direction_1 < 0);
          if (freeze_after > 0 && g >= 3 && !point.geometric_freeze &&
              same_as_2 && differs_from_1)
            {
              ++n;
              point.geometric_freeze = true;
              point.was_frozen       = true;
              freeze_for_cycle(point,
                               status,
                               dir,
                               point.geo_status_1,
                               point.geo_direction_1,
                               true);
            }
          point.geo_status_2    = point.geo_status_1;
          point.geo_direction_2 = point.geo_direction_1;
          point.geo_status_1    = status;
          point.geo_direction_1 = dir;
        }
      return Utilities::MPI::sum(n, comm);
    }


    template <int dim>
    unsigned int
    ContactProblem<dim>::release_frozen(unsigned int &refrozen)
    {
      unsigned int n = 0, again = 0;
      for (auto &point : points)
        if (point.freeze_contact && !point.geometric_freeze)
          {
            // The first contradiction of a frozen point whose friction is
            // active: frozen once more, in the stick or slip status the
            // plain law asks for (released, it would enter its stick/slip
            // or reversal cycle again). Otherwise released.
            if (!point.refrozen && point.plain_violated &&
                point.plain_status != PointStatus::free &&
                point.friction_active)
              {
                ++again;
                point.refrozen = true;
                point.freeze_stick =
                  point.plain_status == PointStatus::stick;
                point.frozen_slip_direction =
                  point.plain_status == PointStatus::slip ?
                    point.plain_direction :
                    Tensor<1, dim>();
              }
            else
              {
                ++n;
                clear_freeze(point);
              }
          }
      // Nodes (friction status per node): the same rule.
      for (auto &[dof, c] : node_cycle)
        if (c.freeze && c.plain_violated)
          {
            const bool owned = owned_multipliers.is_element(dof);
            if (!c.refrozen && c.plain.active)
              {
                again += owned;
                c.refrozen     = true;
                c.freeze_stick = c.plain.stick;
                if (!c.plain.stick && c.plain.H.norm() > 0)
                  c.q = c.plain.H / c.plain.H.norm();
              }
            else
              {
                n += owned;
                c.freeze = false;
              }
          }
      refrozen = Utilities::MPI::sum(again, comm);
      return Utilities::MPI::sum(n, comm);
    }


    template <int dim>
    unsigned int
    ContactProblem<dim>::extrapolate_releases()
    {
      if (!parameters.contact.release_extrapolation)
        return 0;
      const unsigned int n_pairs = parameters.contact.pairs.size();
      // The status carriers of every pair (points; multiplier nodes on
      // node-status pairs) by class at this iterate: tension (closed in
      // the last solve, open now), compression (closed both), open (both),
      // entered (open in the last solve, closed now).
      enum : int
      {
        tension = 0,
        compression,
        open,
        entered
      };
      const auto class_of = [](const bool before, const bool now) {
        return before ? (now ? compression : tension) : (now ? entered : open);
      };
      struct Carrier
      {
        Point<dim> x;
        int        kind;
        int        point; // index into points, or -1 (node)
        types::global_dof_index dof;
        bool                    kept; // closed again after such a release
      };
      std::vector<std::vector<Carrier>> carriers(n_pairs);
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          auto &             point = points[i];
          const unsigned int p     = slave_faces[point.face].pair;
          const bool         now   = point.status != PointStatus::free;
          // Released early and closed again: not released early again in
          // this Newton solve.
          if (point.extrapolated && now)
            point.keep_closed = true;
          point.extrapolated = false;
          if (!node_status_pair[p])
            carriers[p].push_back(
              {point.x_ref,
               class_of(point.status_before != PointStatus::free, now),
               static_cast<int>(i),
               0,
               point.keep_closed || point.freeze_contact});
        }
      std::set<types::global_dof_index> seen;
      for (const auto &face : slave_faces)
        if (node_status_pair[face.pair])
          for (unsigned int k = 0; k < face.X.size(); ++k)
            {
              const auto dof = face.lambda_dofs[face.k_node[k]];
              if (!seen.insert(dof).second)
                continue;
              const bool now = node_active.at(dof);
              if (node_extrapolated.count(dof) && now)
                node_kept.insert(dof);
              const auto before = node_active_solved.find(dof);
              carriers[face.pair].push_back(
                {face.X[k],
                 class_of(before != node_active_solved.end() &&
                            before->second,
                          now),
                 -1,
                 dof,
                 node_kept.count(dof) > 0});
            }
      node_extrapolated.clear();

      unsigned int n_released = 0;
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          // Frictionless pairs only: with friction the tension band does
          // not follow the halving (SSNV128 in one step: 9 -> 11 Newton).
          if (law_parameters(p).mu > 0)
            continue;
          // All carriers of the pair, from all ranks (coordinates and
          // class).
          std::vector<double> pack;
          for (const auto &c : carriers[p])
            {
              for (unsigned int d = 0; d < dim; ++d)
                pack.push_back(c.x[d]);
              pack.push_back(c.kind);
            }
          std::vector<std::pair<Point<dim>, unsigned int>> all, band;
          std::vector<int>                                 kind;
          for (const auto &part : Utilities::MPI::all_gather(comm, pack))
            for (unsigned int i = 0; i + dim < part.size(); i += dim + 1)
              {
                Point<dim> x;
                for (unsigned int d = 0; d < dim; ++d)
                  x[d] = part[i + d];
                const int k = static_cast<int>(part[i + dim]);
                if (k == tension)
                  band.emplace_back(x, band.size());
                all.emplace_back(x, all.size());
                kind.push_back(k);
              }
          // Only while the zone shrinks: none entered, some in tension.
          if (band.empty() ||
              std::find(kind.begin(), kind.end(), int(entered)) != kind.end())
            continue;
          const auto band_tree = pack_rtree(band);
          const auto all_tree  = pack_rtree(all);
          // Candidates: carriers in compression whose mirror image across
          // their nearest tension carrier lies in the band (the carrier
          // nearest to the image is in tension), with their distance to it.
          std::vector<std::pair<const Carrier *, double>> candidates;
          for (const auto &c : carriers[p])
            {
              if (c.kind != compression || c.kept)
                continue;
              std::vector<std::pair<Point<dim>, unsigned int>> hit;
              band_tree.query(boost::geometry::index::nearest(c.x, 1),
                              std::back_inserter(hit));
              const Point<dim> image    = c.x + 2. * (hit[0].first - c.x);
              const double     distance = c.x.distance(hit[0].first);
              hit.clear();
              all_tree.query(boost::geometry::index::nearest(image, 1),
                             std::back_inserter(hit));
              if (kind[hit[0].second] == tension)
                candidates.emplace_back(&c, distance);
            }
          // At most as many as the band holds, and at most half of those in
          // compression, the nearest to the band first: on a graded mesh a
          // band of a few long elements mirrors onto the whole zone, and
          // a pair left without contact would float.
          const std::size_t n_band = band.size();
          const std::size_t n_compression =
            std::count(kind.begin(), kind.end(), int(compression));
          const std::size_t cap = std::min(n_band, n_compression / 2);
          std::vector<double> mine_d;
          for (const auto &c : candidates)
            mine_d.push_back(c.second);
          std::vector<double> distances;
          for (const auto &part : Utilities::MPI::all_gather(comm, mine_d))
            distances.insert(distances.end(), part.begin(), part.end());
          if (cap == 0 || distances.empty())
            continue;
          std::sort(distances.begin(), distances.end());
          const double limit = distances[std::min(cap, distances.size()) - 1];
          for (const auto &candidate : candidates)
            {
              if (candidate.second > limit)
                continue;
              const Carrier &c = *candidate.first;
              if (c.point >= 0)
                {
                  points[c.point].release      = true;
                  points[c.point].extrapolated = true;
                  ++n_released;
                }
              else
                {
                  node_release.insert(c.dof);
                  node_extrapolated.insert(c.dof);
                  n_released += owned_multipliers.is_element(c.dof);
                }
            }
        }
      return Utilities::MPI::sum(n_released, comm);
    }


    template <int dim>
    void
    ContactProblem<dim>::clear_releases()
    {
      for (auto &point : points)
        point.release = false;
      node_release.clear();
    }


    template <int dim>
    struct ContactProblem<dim>::PointsState
    {
      std::vector<ContactPoint>                       points;
      std::map<types::global_dof_index, bool>         node_active;
      std::map<types::global_dof_index, NodeFriction> node_friction;
      std::map<types::global_dof_index, NodeCycle>    node_cycle;
      unsigned int                                    iterates_recorded;
    };


    template <int dim>
    std::shared_ptr<const typename ContactProblem<dim>::PointsState>
    ContactProblem<dim>::save_points() const
    {
      return std::make_shared<const PointsState>(
        PointsState{
          points, node_active, node_friction, node_cycle, iterates_recorded});
    }


    template <int dim>
    void
    ContactProblem<dim>::restore_points(const PointsState &saved)
    {
      points            = saved.points;
      node_active       = saved.node_active;
      node_friction     = saved.node_friction;
      node_cycle        = saved.node_cycle;
      iterates_recorded = saved.iterates_recorded;
    }


    template <int dim>
    double
    ContactProblem<dim>::roundoff_scale() const
    {
      double sum = 0;
      for (const auto &point : points)
        if (point.paired)
          sum += std::pow(2 * point.weight *
                            rho_n[slave_faces[point.face].pair] *
                            point.x_ref.norm(),
                          2);
      return std::sqrt(Utilities::MPI::sum(sum, comm));
    }


    template <int dim>
    std::vector<typename ContactProblem<dim>::PairSummary>
    ContactProblem<dim>::summary() const
    {
      std::vector<PairSummary> result(parameters.contact.pairs.size());
      // Node-status pairs: the normal and tangential forces in the contact
      // frames are summed per multiplier node (the force F_l = sum w psi_l f
      // that node l carries, against the psi-weighted normal): with dual
      // multipliers the traction at single points oscillates, its nodal
      // forces do not.
      std::vector<TrilinosWrappers::MPI::Vector> nodal;
      if (any_node_status)
        for (unsigned int c = 0; c < 2 * dim; ++c)
          nodal.push_back(writable_vector(owned_multipliers, multiplier_ghosts, comm));
      for (const auto &point : points)
        {
          const auto &face = slave_faces[point.face];
          auto &      r    = result[face.pair];
          r.force += point.weight * point.force;
          if (node_status_pair[face.pair])
            {
              for (unsigned int l = 0; l < face.lambda_dofs.size(); ++l)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const double w = point.weight * point.psi[l];
                    add_entry(nodal[c], face.lambda_dofs[l], w * point.force[c]);
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
          // Stick and slip: points whose friction law is active (a closed
          // point excluded from friction, or with a zero threshold, is
          // closed without friction, as in the Newton lines).
          r.n_stick += point.status == PointStatus::stick;
          r.n_slip +=
            point.status == PointStatus::slip && point.friction_active;
        }
      if (any_node_status)
        {
          for (auto &v : nodal)
            v.compress(VectorOperation::add);
          // Each owned node once (the owner adds it).
          std::set<types::global_dof_index> seen;
          for (const auto &face : slave_faces)
            if (node_status_pair[face.pair])
              for (const auto dof : face.lambda_dofs)
                if (owned_multipliers.is_element(dof) &&
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
      for (unsigned int p = 0; p < result.size(); ++p)
        if (obstacles[p])
          {
            result[p].rigid                 = true;
            result[p].obstacle_displacement = obstacles[p]->get_translation();
          }
      for (unsigned int p = 0; p < result.size(); ++p)
        {
          auto &r = result[p];
          r.max_gap   = Utilities::MPI::max(r.max_gap, comm);
          r.n_paired  = Utilities::MPI::sum(r.n_paired, comm);
          r.face_size = face_size[p];
        }
      for (auto &r : result)
        {
          r.force     = Utilities::MPI::sum(r.force, comm);
          r.p_max     = Utilities::MPI::max(r.p_max, comm);
          r.normal_force_local =
            Utilities::MPI::sum(r.normal_force_local, comm);
          r.tangential_force_local =
            Utilities::MPI::sum(r.tangential_force_local, comm);
          r.n_points  = Utilities::MPI::sum(r.n_points, comm);
          r.n_contact = Utilities::MPI::sum(r.n_contact, comm);
          r.n_stick   = Utilities::MPI::sum(r.n_stick, comm);
          r.n_slip    = Utilities::MPI::sum(r.n_slip, comm);
        }
      return result;
    }


    template <int dim>
    std::vector<typename ContactProblem<dim>::PointRecord>
    ContactProblem<dim>::gather_points() const
    {
      std::vector<double> pack;
      for (const auto &point : points)
        {
          const unsigned int p = slave_faces[point.face].pair;
          const double       mu = parameters.contact.pairs[p].friction;
          pack.push_back(p);
          for (unsigned int d = 0; d < dim; ++d)
            pack.push_back(point.x_ref[d]);
          pack.push_back(point.weight);
          pack.push_back(-point.lambda);
          for (unsigned int k = 0; k < dim - 1; ++k)
            pack.push_back(mu * point.lambda * point.Lambda[k]);
          pack.push_back(point.gap);
          for (unsigned int k = 0; k < dim - 1; ++k)
            pack.push_back(point.slip[k]);
          pack.push_back(static_cast<double>(point.status));
          pack.push_back(point.paired);
        }
      std::vector<PointRecord> records;
      for (const auto &part : Utilities::MPI::all_gather(comm, pack))
        for (unsigned int i = 0; i < part.size();)
          {
            PointRecord r;
            r.pair = static_cast<unsigned int>(part[i++]);
            for (unsigned int d = 0; d < dim; ++d)
              r.x[d] = part[i++];
            r.weight = part[i++];
            r.p      = part[i++];
            for (unsigned int k = 0; k < dim - 1; ++k)
              r.traction[k] = part[i++];
            r.gap = part[i++];
            for (unsigned int k = 0; k < dim - 1; ++k)
              r.slip[k] = part[i++];
            r.status = static_cast<PointStatus>(static_cast<int>(part[i++]));
            r.paired = part[i++] != 0;
            records.push_back(r);
          }
      std::sort(records.begin(),
                records.end(),
                [](const PointRecord &a, const PointRecord &b) {
                  if (a.pair != b.pair)
                    return a.pair < b.pair;
                  for (unsigned int d = 0; d < dim; ++d)
                    if (std::abs(a.x[d] - b.x[d]) > 1e-12 * (1 + std::abs(a.x[d])))
                      return a.x[d] < b.x[d];
                  return false;
                });
      return records;
    }


    template <int dim>
    std::string
    ContactProblem<dim>::write_csv(const std::string &filename) const
    {
      const auto records = gather_points();
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return "";
      return Postprocess::write_atomically(filename, [&](std::ostream &csv) {
        const char *  axis[] = {"x", "y", "z"};
        csv << "pair";
        for (unsigned int d = 0; d < dim; ++d)
          csv << "," << axis[d];
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
            // A closed point of a frictionless pair has no stick or slip.
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
    ContactProblem<dim>::nodal_fields(const DoFHandler<dim> &scalar_dofs) const
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
        names.size() + 1,
        writable_vector(owned, relevant, comm));

      std::vector<types::global_dof_index> scalar_cell_dofs(
        scalar_dofs.get_fe().n_dofs_per_cell());
      for (const auto &point : points)
        {
          const auto &face = slave_faces[point.face];
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
            parameters.contact.pairs[slave_faces[point.face].pair].friction;
          std::vector<double> values = {-point.lambda,
                                        point.paired ? point.gap : 0.,
                                        static_cast<double>(point.status)};
          for (unsigned int k = 0; k < dim - 1; ++k)
            values.push_back(mu * point.lambda * point.Lambda[k]);
          for (unsigned int k = 0; k < dim - 1; ++k)
            values.push_back(point.slip[k]);
          for (unsigned int l = 0; l < face.node_local.size(); ++l)
            {
              const unsigned int i = face.node_local[l];
              const double w = point.weight * point.psi[l];
              const auto   d =
                scalar_cell_dofs[fe.system_to_component_index(i).second];
              for (unsigned int v = 0; v < values.size(); ++v)
                add_entry(sums[v], d, w * values[v]);
              add_entry(sums.back(), d, w);
            }
        }
      for (auto &s : sums)
        s.compress(VectorOperation::add);
      std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector>> result;
      for (unsigned int v = 0; v < names.size(); ++v)
        {
          TrilinosWrappers::MPI::Vector owned_values(owned, comm);
          for (const auto i : owned)
            if (sums.back()[i] != 0)
              owned_values[i] = sums[v][i] / sums.back()[i];
          owned_values.compress(VectorOperation::insert);
          TrilinosWrappers::MPI::Vector ghosted(owned, relevant, comm);
          ghosted = owned_values;
          result.emplace_back(names[v], ghosted);
        }
      return result;
    }

    template <int dim>
    void
    ContactProblem<dim>::multipliers_to_field(
      const TrilinosWrappers::MPI::Vector &state,
      TrilinosWrappers::MPI::Vector &      field) const
    {
      // A node may lie on slave faces of several ranks and on none of its
      // owner's: every rank writes the nodes of its faces (the same
      // values), averaged through a count.
      IndexSet touched(dof_handler.n_dofs());
      for (const auto &face : slave_faces)
        for (const auto d : face.node_dofs)
          touched.add_index(d);
      touched.compress();
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      auto            num   = writable_vector(owned, touched, comm);
      auto            den   = writable_vector(owned, touched, comm);
      for (const auto &face : slave_faces)
        for (unsigned int l = 0; l < face.node_local.size(); ++l)
          {
            const auto &info = nodes.at(face.node_dofs[l * dim]);
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
    ContactProblem<dim>::multipliers_from_field(
      const TrilinosWrappers::MPI::Vector &field,
      TrilinosWrappers::MPI::Vector &      state_owned) const
    {
      auto num = writable_vector(owned_multipliers, multiplier_ghosts, comm);
      auto den = writable_vector(owned_multipliers, multiplier_ghosts, comm);
      for (const auto &face : slave_faces)
        for (unsigned int l = 0; l < face.node_local.size(); ++l)
          {
            const auto &info = nodes.at(face.node_dofs[l * dim]);
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
      for (const auto i : owned_multipliers)
        state_owned[i] = den[i] != 0 ? num[i] / den[i] : 0.;
      state_owned.compress(VectorOperation::insert);
    }


    template <int dim>
    std::vector<typename DoFHandler<dim>::active_cell_iterator>
    ContactProblem<dim>::contact_zone_cells() const
    {
      std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
      std::vector<unsigned int> master_active(master_faces.size(), 0);
      std::vector<bool>         slave_active(slave_faces.size(), false);
      for (const auto &point : points)
        if (point.status != PointStatus::free)
          {
            slave_active[point.face] = true;
            if (point.master_face >= 0)
              master_active[point.master_face] = 1;
          }
      for (unsigned int f = 0; f < slave_faces.size(); ++f)
        if (slave_active[f])
          cells.push_back(slave_faces[f].cell);
      Utilities::MPI::max(master_active, comm, master_active);
      for (unsigned int m = 0; m < master_faces.size(); ++m)
        if (master_faces[m].own_cell >= 0 && master_active[m] != 0)
          cells.push_back(own_master_cells[master_faces[m].own_cell]);
      return cells;
    }

    template class ContactProblem<2>;
    template class ContactProblem<3>;
  } // namespace Contact
} // namespace Signorini
