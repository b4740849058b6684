// Adaptive refinement within and between load steps and the transfer of
// the state to the new mesh.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/base/errors.h>
#include <signorini/driver/simulation.h>
#include <signorini/geometry/mesh_checks.h>

#include <algorithm>
#include <cmath>

namespace Signorini
{
  namespace
  {
    // Sets the refinement flag of every cell of the active contact zone and
    // of every coarser cell whose centre lies within its own diameter of a
    // zone cell (of the ball around the zone cell's centre with half its
    // diameter): each coarser level lies two cells deep under the zone.
    // Under a one-cell skin the nodal pressure carried the period of the
    // coarse cells beneath, and p0 stalled (doc/performance.md, "Adaptive
    // marking"). The zone cells of every rank are seen, so the flags do not
    // depend on the partition.
    template <int dim>
    void
    mark_contact_zone(
      const std::vector<typename DoFHandler<dim>::active_cell_iterator> &zone,
      parallel::distributed::Triangulation<dim> &triangulation,
      const MPI_Comm                             comm)
    {
      std::vector<double> local; // per zone cell: centre, diameter, level
      for (const auto &cell : zone)
        {
          cell->clear_coarsen_flag();
          cell->set_refine_flag();
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(cell->center()[d]);
          local.push_back(cell->diameter());
          local.push_back(cell->level());
        }
      std::vector<std::pair<Point<dim>, unsigned int>> centres;
      std::vector<std::pair<double, unsigned int>>     size_level;
      double                                           largest = 0;
      for (const auto &part : Utilities::MPI::all_gather(comm, local))
        for (std::size_t k = 0; k + dim + 1 < part.size(); k += dim + 2)
          {
            Point<dim> z;
            for (unsigned int d = 0; d < dim; ++d)
              z[d] = part[k + d];
            centres.emplace_back(z, size_level.size());
            size_level.emplace_back(
              part[k + dim], static_cast<unsigned int>(part[k + dim + 1]));
            largest = std::max(largest, part[k + dim]);
          }
      const auto tree = pack_rtree(centres);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned() && !cell->refine_flag_set())
          {
            const Point<dim> c = cell->center();
            const double     h = cell->diameter();
            BoundingBox<dim> around(std::make_pair(c, c));
            around.extend(h + 0.5 * largest);
            for (const auto &[z, k] :
                 tree | boost::geometry::index::adaptors::queried(
                          boost::geometry::index::intersects(around)))
              if (size_level[k].second >
                    static_cast<unsigned int>(cell->level()) &&
                  c.distance(z) - 0.5 * size_level[k].first < h)
                {
                  cell->clear_coarsen_flag();
                  cell->set_refine_flag();
                  break;
                }
          }
    }

    // The largest displacement gradient |grad u| at the cell centres, over
    // all ranks: the scale of the round-off of Kelly's gradient jumps.
    template <int dim>
    double
    largest_gradient(const Mapping<dim>                  &mapping,
                     const FiniteElement<dim>            &fe,
                     const DoFHandler<dim>               &dof_handler,
                     const TrilinosWrappers::MPI::Vector &solution,
                     const MPI_Comm                       comm)
    {
      FEValues<dim> values(mapping, fe, QGauss<dim>(1), update_gradients);
      std::vector<Tensor<2, dim>>      gradient(1);
      const FEValuesExtractors::Vector displacement(0);
      double                           largest = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            values.reinit(cell);
            values[displacement].get_function_gradients(solution, gradient);
            largest = std::max(largest, gradient[0].norm());
          }
      return Utilities::MPI::max(largest, comm);
    }
  } // namespace


  // Adaptive refinement: the Kelly indicator of the displacement, weighted
  // to the energy norm of each cell's material, marks a fixed fraction of
  // the cells; the active contact zone is always refined, graded. The
  // converged state and the state at the start of the step (displacements,
  // and the multipliers as a nodal field on the slave surface) are
  // interpolated to the new mesh.
  // Marks the cells by Kelly's indicator in the energy norm (and the
  // contact zone), none beyond the maximum level; counts the marked ones
  // on this rank.
  template <int dim>
  void
  Simulation<dim>::mark_cells(unsigned int &n_refine, unsigned int &n_coarsen)
  {
    const auto   &a = parameters.adaptivity;
    Vector<float> indicator(system.triangulation.n_active_cells());
    KellyErrorEstimator<dim>::estimate(system.mapping,
                                       system.dof_handler,
                                       QGauss<dim - 1>(system.fe.degree + 1),
                                       {},
                                       system.solution,
                                       indicator);
    const double gradient_scale = largest_gradient(system.mapping,
                                                   system.fe,
                                                   system.dof_handler,
                                                   system.solution,
                                                   mpi_communicator);
    // Energy norm: sqrt(E) of the cell's material (bodies of different
    // stiffness), and sqrt(r) in axisymmetry (the 2 pi r weight).
    for (const auto &cell : system.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          double w =
            materials.at(cell->material_id())->representative_modulus();
          if (parameters.axisymmetric)
            w *= std::max(cell->center()[0], cell->diameter());
          indicator[cell->active_cell_index()] *= std::sqrt(w);
          // Where the solution is exact on the mesh (a homogeneous
          // deformation) the gradient jumps, and so the indicator, are
          // round-off: marking by them would refine cells by noise, which
          // the units or the ranks change. Below 1e-10 of the gradient's
          // scale (round-off is about 1e-15 of it) the indicator is zero.
          const double floor = 1e-10 * gradient_scale * std::sqrt(w) *
                               std::pow(cell->diameter(), 0.5 * dim);
          if (indicator[cell->active_cell_index()] < floor)
            indicator[cell->active_cell_index()] = 0;
        }
    float largest = 0;
    for (const auto &cell : system.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        largest = std::max(largest, indicator[cell->active_cell_index()]);
    if (Utilities::MPI::max(largest, mpi_communicator) > 0)
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
        system.triangulation,
        indicator,
        a.refinement_fraction,
        a.coarsening_fraction);
    if (a.refine_contact_zone && contact.active())
      mark_contact_zone(contact.contact_output().contact_zone_cells(),
                        system.triangulation,
                        mpi_communicator);
    for (const auto &cell : system.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          if (cell->refine_flag_set() &&
              static_cast<unsigned int>(cell->level()) >= maximum_level)
            cell->clear_refine_flag();
          n_refine += cell->refine_flag_set() ? 1 : 0;
          n_coarsen += cell->coarsen_flag_set() ? 1 : 0;
        }
  }


  // The fields the refinement carries over, in the displacement layout: u
  // and the multiplier field, now and at the step start.
  template <int dim>
  std::vector<TrilinosWrappers::MPI::Vector>
  Simulation<dim>::fields_to_transfer() const
  {
    std::vector<TrilinosWrappers::MPI::Vector> old_vectors;
    for (const auto *source : {&system.state, &system.state_step_start})
      {
        TrilinosWrappers::MPI::Vector u(system.locally_owned, mpi_communicator);
        TrilinosWrappers::MPI::Vector m(system.locally_owned, mpi_communicator);
        for (const auto i : system.locally_owned)
          u[i] = (*source)[i];
        u.compress(VectorOperation::insert);
        if (contact.active())
          contact.contact_surfaces().multipliers_to_field(*source, m);
        for (const auto *v : {&u, &m})
          {
            old_vectors.emplace_back(system.locally_owned,
                                     system.locally_relevant,
                                     mpi_communicator);
            old_vectors.back() = *v;
          }
      }
    return old_vectors;
  }


  template <int dim>
  bool
  Simulation<dim>::adapt_mesh(const double time, const double step_start_time)
  {
    const auto &a = parameters.adaptivity;
    if (maximum_level == 0)
      maximum_level = a.maximum_level > 0 ?
                        a.maximum_level :
                        system.triangulation.n_global_levels() - 1 + a.cycles;
    system.update_solution();
    // Vectors in the displacement layout: u and the multiplier field, now
    // and at the step start.
    std::vector<TrilinosWrappers::MPI::Vector> old_vectors;
    unsigned int                               n_refine = 0, n_coarsen = 0;
    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector>
      transfer(system.dof_handler);
    {
      TimerOutput::Scope t(timer, "adaptation");
      mark_cells(n_refine, n_coarsen);
      n_refine  = Utilities::MPI::sum(n_refine, mpi_communicator);
      n_coarsen = Utilities::MPI::sum(n_coarsen, mpi_communicator);
      if (n_refine + n_coarsen == 0)
        {
          pcout << "  adaptive refinement: no cell marked (all at 'Maximum "
                   "level'?)"
                << std::endl;
          return false;
        }

      old_vectors = fields_to_transfer();
      std::vector<const TrilinosWrappers::MPI::Vector *> pointers;
      for (const auto &v : old_vectors)
        pointers.push_back(&v);
      system.triangulation.prepare_coarsening_and_refinement();
      check_adapted_size();
      transfer.prepare_for_coarsening_and_refinement(pointers);
      system.history.prepare_for_refinement(system.triangulation);
      system.triangulation.execute_coarsening_and_refinement();
      system.history.finish_refinement();
    }
    setup_system();
    TimerOutput::Scope                         t(timer, "adaptation");
    std::vector<TrilinosWrappers::MPI::Vector> new_vectors(
      old_vectors.size(),
      TrilinosWrappers::MPI::Vector(system.locally_owned, mpi_communicator));
    std::vector<TrilinosWrappers::MPI::Vector *> pointers;
    for (auto &v : new_vectors)
      pointers.push_back(&v);
    transfer.interpolate(pointers);
    for (auto &v : new_vectors)
      system.constraints_hanging.distribute(v);

    // Back into the system layout, with the constraint values of each time.
    for (unsigned int k = 0; k < 2; ++k)
      {
        TrilinosWrappers::MPI::Vector s(system.owned_system, mpi_communicator);
        for (const auto i : system.locally_owned)
          s[i] = new_vectors[2 * k][i];
        s.compress(VectorOperation::insert);
        if (contact.active())
          {
            TrilinosWrappers::MPI::Vector m(system.locally_owned,
                                            system.locally_relevant,
                                            mpi_communicator);
            m = new_vectors[2 * k + 1];
            contact.contact_surfaces().multipliers_from_field(m, s);
          }
        system.make_constraints(k == 0 ? time : step_start_time,
                                boundary_conditions,
                                contact);
        system.constraints_values.distribute(s);
        (k == 0 ? system.state : system.state_step_start) = s;
      }
    system.update_solution();
    pcout << "  adaptive refinement: " << n_refine << " cells refined, "
          << n_coarsen << " coarsened -> "
          << system.triangulation.n_global_active_cells() << " cells, "
          << system.dof_handler.n_dofs() << " displacement DoFs";
    if (contact.active())
      pcout << ", " << contact.contact_surfaces().n_lambda() << " lambda, "
            << contact.contact_surfaces().n_friction() << " Lambda";
    pcout << std::endl;
    return true;
  }


  // The refinement flagged by adapt_mesh() (prepared) must stay within
  // 'Geometry/Maximum number of cells'; found during the run, so a RunError.
  template <int dim>
  void
  Simulation<dim>::check_adapted_size() const
  {
    const double n_cells =
      Geometry::cells_after_refinement(system.triangulation);
    if (n_cells > parameters.geometry.maximum_cells)
      throw RunError(
        "adaptive refinement: the next cycle would make " +
        Geometry::cell_estimate_text(n_cells, parameters) +
        ". The results of the completed steps are in '" +
        parameters.output.directory +
        "'. Lower 'Adaptive refinement/Cycles' or 'Refinement fraction', "
        "set its 'Maximum level', or raise 'Geometry/Maximum number of "
        "cells' if the machine has the memory.");
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
