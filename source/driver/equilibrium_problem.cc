// The equilibrium problem of the Newton solver: the residual at the
// iterate and what the convergence rules need of it, the log rows, the
// linearised solve (with the rigid motions nothing holds), the saved
// state of trial iterates, the Jacobian check.
#include <deal.II/base/utilities.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/errors.h>
#include <signorini/contact/jacobian_check.h>
#include <signorini/driver/equilibrium_problem.h>
#include <signorini/solver/roundoff.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

namespace Signorini
{
  // The contact points and statistics of an iterate.
  template <int dim>
  struct EquilibriumProblem<dim>::IterateSnapshot
      : public Solver::NonlinearProblem::Snapshot
  {
    std::shared_ptr<const typename Contact::ContactProblem<dim>::PointsState>
                               points;
    Contact::ContactStatistics statistics;
  };


  template <int dim>
  EquilibriumProblem<dim>::EquilibriumProblem(
    const Parameters                    &parameters,
    DiscreteSystem<dim>                 &system,
    const Bulk::Materials<dim>          &materials,
    const Bulk::BoundaryConditions<dim> &boundary_conditions,
    Bulk::Assembler<dim>                &bulk,
    Contact::ContactProblem<dim>        &contact,
    Solver::LinearSolver<dim>           &linear_solver,
    Postprocess::RunReport<dim>         &report,
    TimerOutput                         &timer,
    ConditionalOStream                  &pcout)
      : parameters(parameters)
      , system(system)
      , materials(materials)
      , boundary_conditions(boundary_conditions)
      , bulk(bulk)
      , contact(contact)
      , linear_solver(linear_solver)
      , report(report)
      , timer(timer)
      , pcout(pcout)
  {
    for (const auto &[id, material] : materials)
      {
        materials_linear &= material->is_linear();
        finite_strain |=
          material->kinematics() == Material::Kinematics::finite_strain;
      }
    linear_solver.set_bulk_linear(materials_linear);
  }


  template <int dim>
  void
  EquilibriumProblem<dim>::setup()
  {
    // A new mesh: no first update of the old one is pending.
    first_update        = nullptr;
    bulk_jacobian_ready = false;
    rigid_modes.setup(system.mapping,
                      system.dof_handler,
                      system.constraints_update,
                      system.owned_system,
                      parameters.axisymmetric,
                      system.mpi_communicator);
    position_scale.clear();
    if (finite_strain)
      {
        TrilinosWrappers::MPI::Vector        owned(system.owned_system,
                                            system.mpi_communicator);
        std::vector<types::global_dof_index> dofs(
          system.dof_handler.get_fe().n_dofs_per_cell());
        for (const auto &cell : system.dof_handler.active_cell_iterators())
          if (!cell->is_artificial())
            {
              cell->get_dof_indices(dofs);
              for (const auto i : dofs)
                if (system.owned_system.is_element(i))
                  owned[i] = std::max<double>(owned[i], cell->diameter());
            }
        owned.compress(VectorOperation::insert);
        position_scale.reinit(system.owned_system,
                              system.relevant_system,
                              system.mpi_communicator);
        position_scale = owned;
      }
  }


  template <int dim>
  void
  EquilibriumProblem<dim>::start_solve()
  {
    bulk_jacobian_ready = false;
    // rho_t follows the pressure level once per Newton solve: changing it
    // between iterates would change the equations being solved and spoil
    // the quadratic convergence.
    if (contact.active())
      {
        contact.update_coefficients(system.state);
        contact.start_newton_solve();
      }
  }


  template <int dim>
  Solver::Evaluation
  EquilibriumProblem<dim>::evaluate(const bool trial)
  {
    // A Newton iterate's evaluation also assembles the bulk Jacobian: the
    // iterate's solve needs it unless the iterate converged, so a Newton
    // solve of n iterations assembles the bulk n + 1 times (before: a
    // residual at every iterate and again with the Jacobian for each
    // solve, 2n + 1). A line-search trial needs its residual only.
    assemble_bulk(!trial);
    // The round-off scale || |K| |x| || of this iterate's bulk Jacobian at
    // this iterate (before: of the last solve's matrix and state, which
    // after a step cut were those of the failed attempt: a run-away
    // iterate's scale then accepted the restarted step's first iterate).
    if (!trial)
      matrix_roundoff =
        Solver::absolute_product_norm(system.matrix,
                                      system.state,
                                      first_update ? *first_update :
                                                     system.constraints_update,
                                      system.mpi_communicator,
                                      position_scale);
    assemble_contact(false, system.constraints_update, !trial);
    Solver::Evaluation e;
    e.block = block_residuals();
    // A trial (line search) is judged by its residual norm alone.
    if (trial)
      return e;
    // The force level: internal and external forces, not the residual.
    // Its multiplier rows (scaled by rho_n) hold rho_n times the initial
    // gaps at a 'closed' start, and its displacement rows rho_n times the
    // gap of a point that just closed, so a level taken from it (and every
    // relative tolerance) would depend on the Normal coefficient.
    e.force = std::max(system.internal_force.l2_norm(),
                       system.external_force.l2_norm());
    // Round-off scales: || |K| |x| || of the bulk Jacobian at this iterate
    // (above), and rho_n |x| of the gaps, which are differences of
    // positions (ContactProblem::roundoff_scale()).
    e.bulk_roundoff = matrix_roundoff;
    if (contact.active())
      {
        e.contact_roundoff    = contact.roundoff_scale();
        e.n_changed           = contact_statistics.n_changed;
        e.frozen_contradicted = contact_statistics.n_violated > 0;
      }
    e.linear_at_fixed_statuses =
      materials_linear &&
      (!contact.active() || contact.linear_at_fixed_statuses());
    e.values_pending = first_update != nullptr;
    return e;
  }


  template <int dim>
  void
  EquilibriumProblem<dim>::record_iterate(const unsigned int        iteration,
                                          const Solver::Evaluation &evaluation,
                                          const double              force_level,
                                          const bool                converged)
  {
    report.log_iterate(iteration,
                       evaluation.block,
                       force_level,
                       contact.active() ? &contact_statistics : nullptr,
                       contact.active() &&
                         contact.contact_surfaces().n_friction() > 0,
                       converged);
  }


  template <int dim>
  std::string
  EquilibriumProblem<dim>::non_finite_cause() const
  {
    return boundary_conditions.non_finite(report.position.time,
                                          system.triangulation,
                                          system.mpi_communicator) +
           inversion_cause();
  }


  // The inverted cells of the last assembly, and the cell of the smallest
  // det F over all ranks (ties of symmetric cells broken by the centre, so
  // that 1 and N ranks name the same cell).
  template <int dim>
  std::string
  EquilibriumProblem<dim>::inversion_cause() const
  {
    using Inversion = typename Bulk::Assembler<dim>::Inversion;
    Inversion named;
    for (const Inversion &rank :
         Utilities::MPI::all_gather(system.mpi_communicator, bulk.inversion()))
      if (rank.n_cells > 0)
        {
          if (named.n_cells == 0 ||
              named.named_instead_by(rank.smallest_J, rank.where))
            {
              named.smallest_J = rank.smallest_J;
              named.where      = rank.where;
            }
          named.n_cells += rank.n_cells;
        }
    if (named.n_cells == 0)
      return "";
    std::ostringstream text;
    text << "; " << named.n_cells
         << " cell(s) inverted at finite strain (det F <= 0 at a quadrature "
            "point or an output point; smallest det F = "
         << std::setprecision(3) << named.smallest_J
         << " in the cell centred at (";
    for (unsigned int d = 0; d < dim; ++d)
      text << (d ? ", " : "") << std::setprecision(4) << named.where[d];
    text << ") of the reference mesh). There the mesh cannot follow the "
            "deformation: a smaller load step, a finer mesh there, or a "
            "support or contact that the body lacks at that place";
    return text.str();
  }


  template <int dim>
  void
  EquilibriumProblem<dim>::check_iterate()
  {
    if (parameters.newton.check_jacobian && contact.active())
      check_jacobian();
  }


  // A frozen point (anti-cycling) that the plain law contradicts at the
  // converged iterate is released.
  template <int dim>
  void
  EquilibriumProblem<dim>::release_contradicted()
  {
    unsigned int       refrozen = 0;
    const unsigned int n        = contact.release_frozen(refrozen);
    report.counts.points_released += n;
    report.counts.points_frozen += refrozen;
    if (parameters.output.verbosity != Verbosity::quiet)
      {
        pcout << "    frozen point(s) that the contact law contradicts: " << n
              << " released";
        if (refrozen > 0)
          pcout << ", " << refrozen
                << " frozen again in the friction status the law asks for";
        pcout << std::endl;
      }
  }


  // Release extrapolation (a shrinking contact zone: the points released
  // early stay open for this solve only), the Jacobian, the rigid motions
  // it does not hold, the linear solve.
  template <int dim>
  Solver::LinearisedStep
  EquilibriumProblem<dim>::solve_linearised(const unsigned int iteration)
  {
    unsigned int n_early = 0;
    if (contact.active() && iteration >= 1)
      if (const unsigned int n = contact.extrapolate_releases(); n > 0)
        {
          n_early = n;
          report.add_early_releases(n);
          if (parameters.output.verbosity != Verbosity::quiet)
            pcout << "    release extrapolation: " << n
                  << " point(s) opened for this solve" << std::endl;
        }
    if (!bulk_jacobian_ready)
      assemble_bulk(true);
    // Not newton_rhs = bulk_rhs: after that assignment the two ranks of
    // tests/body_force_per_body_2d (one without contact terms) took
    // different paths in the next compress() and the run hung.
    system.newton_rhs = 0;
    system.newton_rhs.add(1., system.bulk_rhs);
    assemble_contact(true,
                     first_update ? *first_update : system.constraints_update,
                     false);
    bulk_jacobian_ready = false; // the matrix now holds the contact terms
    if (contact.active())
      contact.clear_releases();
    Solver::LinearisedStep step;
    step.held_motions = hold_free_motions(iteration);
    TimerOutput::Scope t(timer, "linear solve");
    step.update.reinit(system.owned_system, system.mpi_communicator);
    const unsigned int krylov =
      linear_solver.solve(system.matrix, step.update, system.newton_rhs);
    report.counts.krylov_iterations += krylov;
    report.counts.krylov_max = std::max(report.counts.krylov_max, krylov);
    (first_update ? *first_update : system.constraints_update)
      .distribute(step.update);
    step.prescribes_values = first_update != nullptr;
    first_update           = nullptr;
    step.exact             = krylov == 0 && n_early == 0;
    return step;
  }


  template <int dim>
  TrilinosWrappers::MPI::Vector
  EquilibriumProblem<dim>::iterate() const
  {
    TrilinosWrappers::MPI::Vector owned(system.owned_system,
                                        system.mpi_communicator);
    owned = system.state;
    return owned;
  }


  template <int dim>
  void
  EquilibriumProblem<dim>::set_iterate(
    const TrilinosWrappers::MPI::Vector &owned)
  {
    system.state = owned;
    system.update_solution();
    bulk_jacobian_ready = false;
  }


  template <int dim>
  std::unique_ptr<Solver::NonlinearProblem::Snapshot>
  EquilibriumProblem<dim>::save() const
  {
    auto snapshot        = std::make_unique<IterateSnapshot>();
    snapshot->points     = contact.save_points();
    snapshot->statistics = contact_statistics;
    return snapshot;
  }


  template <int dim>
  void
  EquilibriumProblem<dim>::restore(
    const Solver::NonlinearProblem::Snapshot &snapshot)
  {
    const auto &saved = dynamic_cast<const IterateSnapshot &>(snapshot);
    contact.restore_points(*saved.points);
    contact_statistics = saved.statistics;
  }


  // -R = F_ext - F_int of the bulk on the free DoFs into newton_rhs and,
  // without constraints, F_int and F_ext for reactions and the force scale.
  template <int dim>
  void
  EquilibriumProblem<dim>::assemble_bulk(const bool with_jacobian)
  {
    TimerOutput::Scope t(timer, "bulk assembly");
    system.newton_rhs     = 0;
    system.internal_force = 0;
    system.external_force = 0;
    // A linear bulk's Jacobian is kept per layout; a first update's pass
    // assembles it anyway, as its right-hand side holds -K_fd delta.
    const bool kept = with_jacobian && materials_linear &&
                      first_update == nullptr &&
                      linear_bulk_layout == system.layout_count;
    const bool assemble_jacobian = with_jacobian && !kept;
    if (assemble_jacobian)
      system.matrix = 0;
    // The Jacobian's right-hand side: a first update that moves prescribed
    // values distributes the cell residuals once more, through its own
    // constraints, carrying the increments into it (-K_fd delta);
    // otherwise it is the residual itself (the same homogeneous
    // constraints), copied below.
    std::optional<typename Bulk::Assembler<dim>::LinearSystemRhs>
      first_update_rhs;
    if (assemble_jacobian && first_update)
      {
        system.bulk_rhs = 0;
        first_update_rhs.emplace(
          typename Bulk::Assembler<dim>::LinearSystemRhs{*first_update,
                                                         system.bulk_rhs});
      }
    // The bulk rows of pinned DoFs (theory.md F8, pins), kept with a
    // kept linear Jacobian.
    std::optional<typename Bulk::Assembler<dim>::PinRows> pin_rows;
    if (assemble_jacobian && !system.pin_dofs.empty())
      {
        system.pin_rows  = 0;
        system.pin_shift = 0;
        pin_rows.emplace(typename Bulk::Assembler<dim>::PinRows{
          system.pin_dofs, system.pin_rows, system.pin_shift});
      }
    bulk.assemble(system.dof_handler,
                  system.solution,
                  system.history,
                  system.constraints_update,
                  assemble_jacobian ? &system.matrix : nullptr,
                  system.newton_rhs,
                  system.internal_force,
                  system.external_force,
                  first_update_rhs ? &*first_update_rhs : nullptr,
                  pin_rows ? &*pin_rows : nullptr);
    if (pin_rows)
      {
        system.pin_rows.compress(VectorOperation::add);
        system.pin_shift.compress(VectorOperation::add);
      }
    system.newton_rhs.compress(VectorOperation::add);
    system.internal_force.compress(VectorOperation::add);
    system.external_force.compress(VectorOperation::add);
    share_pin_loads();
    if (assemble_jacobian)
      {
        system.matrix.compress(VectorOperation::add);
        // The constraints of a first update differ from the homogeneous
        // ones in their inhomogeneities only, which reach the right-hand
        // side only: the matrix is the same.
        if (materials_linear)
          {
            // A new layout: the copy takes the matrix's pattern first, so
            // that copy_from() copies values only, on every rank alike.
            // deal.II 9.4's copy_from() decides per rank whether the
            // columns of the old copy still match (a rank whose part of
            // the contact couplings moved copies the layout, the others
            // only the values), and the two paths reach different
            // collective calls (an Epetra assertion at load step 12 of
            // prm/cattaneo_mindlin_2d.prm on 2 ranks).
            linear_bulk_matrix.reinit(system.matrix);
            linear_bulk_matrix.copy_from(system.matrix);
            linear_bulk_layout = system.layout_count;
          }
      }
    if (kept)
      system.matrix.copy_from(linear_bulk_matrix);
    if (first_update_rhs)
      system.bulk_rhs.compress(VectorOperation::add);
    else if (with_jacobian)
      {
        system.bulk_rhs = 0;
        system.bulk_rhs.add(1., system.newton_rhs);
      }
    bulk_jacobian_ready = with_jacobian;
  }


  // The bulk's force F_int - F_ext at the pinned DoFs, for the statuses of
  // their nodes (NodeStatuses::pin_demand), on every rank.
  template <int dim>
  void
  EquilibriumProblem<dim>::share_pin_loads()
  {
    if (system.pin_dofs.empty())
      return;
    std::vector<std::pair<types::global_dof_index, double>> owned;
    for (const auto d : system.pin_dofs)
      if (system.locally_owned.is_element(d))
        owned.emplace_back(d,
                           system.internal_force[d] - system.external_force[d]);
    std::map<types::global_dof_index, double> loads;
    for (const auto &from_rank :
         Utilities::MPI::all_gather(system.mpi_communicator, owned))
      loads.insert(from_rank.begin(), from_rank.end());
    contact.set_pin_loads(std::move(loads));
  }


  // The bulk's part of the rows of each sticking pinned node this rank
  // owns (the contact's are added by the contact assembly): along its held
  // tangent a, a_k R_d = 0, the pin's support force, with R_d = F_int -
  // F_ext at the pinned DoF d and dR_d its Jacobian row (pin_rows); the
  // linear system of a first update has -K_dc g_c too (pin_shift).
  template <int dim>
  void
  EquilibriumProblem<dim>::add_pin_rows(const bool with_matrix)
  {
    const auto &pins = contact.contact_surfaces().pins();
    for (const auto d : contact.sticking_pins())
      {
        if (!system.locally_owned.is_element(d))
          continue;
        const auto &pin = pins.at(d);
        double      rhs = system.external_force[d] - system.internal_force[d];
        if (with_matrix && first_update)
          rhs -= system.pin_shift[d];
        std::vector<types::global_dof_index> columns;
        std::vector<double>                  values;
        if (with_matrix)
          for (auto it = system.pin_rows.begin(d); it != system.pin_rows.end(d);
               ++it)
            {
              columns.push_back(it->column());
              values.push_back(it->value());
            }
        for (unsigned int k = 0; k < dim - 1; ++k)
          {
            if (pin.a[k] == 0)
              continue;
            const types::global_dof_index l = pin.friction + k;
            system.newton_rhs.add(std::vector<types::global_dof_index>{l},
                                  std::vector<double>{pin.a[k] * rhs});
            for (unsigned int j = 0; j < columns.size(); ++j)
              system.matrix.add(l, columns[j], pin.a[k] * values[j]);
          }
      }
  }


  template <int dim>
  void
  EquilibriumProblem<dim>::assemble_contact(
    const bool                       with_matrix,
    const AffineConstraints<double> &constraints,
    const bool                       new_iterate)
  {
    system.contact_force = 0;
    if (contact.active())
      {
        TimerOutput::Scope tc(timer, "contact assembly");
        contact_statistics =
          contact.assemble(system.state,
                           system.state_step_start,
                           constraints,
                           with_matrix ? &system.matrix : nullptr,
                           system.newton_rhs,
                           system.contact_force,
                           new_iterate);
        add_pin_rows(with_matrix);
      }
    if (with_matrix)
      system.matrix.compress(VectorOperation::add);
    system.newton_rhs.compress(VectorOperation::add);
    system.contact_force.compress(VectorOperation::add);
  }


  template <int dim>
  std::array<double, 3>
  EquilibriumProblem<dim>::block_residuals() const
  {
    const types::global_dof_index n_u = system.dof_handler.n_dofs();
    const types::global_dof_index n_l =
      contact.active() ? contact.contact_surfaces().n_lambda() : 0;
    std::array<double, 3> block = {{0, 0, 0}};
    for (const auto i : system.owned_system)
      block[i < n_u ? 0 : (i < n_u + n_l ? 1 : 2)] +=
        system.newton_rhs[i] * system.newton_rhs[i];
    for (auto &b : block)
      b = std::sqrt(Utilities::MPI::sum(b, system.mpi_communicator));
    return block;
  }


  template <int dim>
  std::string
  EquilibriumProblem<dim>::hold_free_motions(const unsigned int iteration)
  {
    const auto free =
      rigid_modes.find(system.matrix, system.dof_handler.n_dofs());
    if (free.empty())
      return "";
    std::string list;
    for (const auto &m : free)
      list += (list.empty() ? "" : "; ") + rigid_modes.describe(m);
    // Friction can hold the motion once its points have a threshold: at
    // the first iterate after they close it is zero (theory.md F3.3),
    // and while every point slips there is no tangential stiffness. The
    // motion's share of the update is then set to zero for this solve.
    const bool friction_may_hold =
      contact.active() && contact.contact_surfaces().n_friction() > 0 &&
      contact_statistics.n_contact > 0;
    if (!friction_may_hold)
      {
        const std::string what =
          "nothing holds " + list +
          " (no Dirichlet condition constrains it and no closed contact "
          "point resists it), so the linear system is singular";
        // At a later iterate the contact held the body at the first: the
        // iteration has opened it (an excursion of Newton, e.g. through a
        // plastic zone), and a smaller step may not; the step is cut.
        if (iteration > 0)
          throw LinearSolveError(what);
        throw RunError(
          "load step " + std::to_string(report.position.step) +
          ", Newton iterate 0: " + what +
          ". Support the body along that motion (a Dirichlet condition on "
          "that component, on one node if the body must stay free "
          "otherwise: 'Boundary conditions/Dirichlet k/At point'), drive it "
          "by a prescribed displacement, or let it start in contact "
          "('Contact/Initial status = closed').");
      }
    rigid_modes.hold(system.matrix, system.dof_handler.n_dofs(), free);
    if (parameters.output.verbosity != Verbosity::quiet)
      pcout << "    held for this solve (friction without threshold or "
               "slipping everywhere): "
            << list << std::endl;
    return list;
  }


  // Development check (Newton/Check Jacobian, contact/jacobian_check.h) at
  // the current iterate. The step floors: 1e-6 of the mesh diameter, 1e-3
  // of the largest modulus, and 1 (with a floor of 1e-6 E, lambda = 0 after
  // an open solve gave steps of 1e-12 E and central differences of
  // round-off noise, 6e-5).
  template <int dim>
  void
  EquilibriumProblem<dim>::check_jacobian()
  {
    double E_max = 0;
    for (const auto &[id, material] : materials)
      E_max = std::max(E_max, material->representative_modulus());
    const auto saved_statistics = contact_statistics;
    const auto result =
      Contact::check_jacobian(contact,
                              system.state,
                              system.state_step_start,
                              system.constraints_update,
                              system.matrix,
                              system.newton_rhs,
                              system.contact_force,
                              system.dof_handler.n_dofs(),
                              {{1e-6 * system.model_size, 1e-3 * E_max, 1.}});
    contact_statistics = saved_statistics;
    jacobian_error_max = std::max(jacobian_error_max, result.worst);
    pcout << "      Jacobian check: " << result.n_checked << " columns, "
          << result.n_kinked << " at a kink, max relative error "
          << std::scientific << std::setprecision(1) << result.worst
          << std::defaultfloat << std::endl;
  }


  template class EquilibriumProblem<2>;
  template class EquilibriumProblem<3>;
} // namespace Signorini
