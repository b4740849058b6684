// The Simulation as the problem of the Newton solver (Solver::
// NonlinearProblem): the residual at the iterate and what the convergence
// rules need of it, the log rows, the linearised solve (with the rigid
// motions nothing holds), and the iterate's state for trial evaluations.
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/core/simulation.h>
#include <signorini/postprocess/format.h>
#include <signorini/solver/roundoff.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace Signorini
{
  using Postprocess::format;


  // The contact points and statistics of an iterate.
  template <int dim>
  struct Simulation<dim>::IterateSnapshot : public Solver::NonlinearProblem::Snapshot
  {
    std::shared_ptr<const typename Contact::ContactProblem<dim>::PointsState>
                               points;
    Contact::ContactStatistics statistics;
  };


  template <int dim>
  void
  Simulation<dim>::start_solve()
  {
    // rho_t follows the pressure level once per Newton solve: changing it
    // between iterates would change the equations being solved and spoil
    // the quadratic convergence.
    if (contact->active())
      {
        contact->update_coefficients(state);
        contact->start_newton_solve();
      }
  }


  template <int dim>
  Solver::Evaluation
  Simulation<dim>::evaluate(const bool trial)
  {
    assemble(false, trial);
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
    e.force = std::max(internal_force.l2_norm(), external_force.l2_norm());
    // Round-off scales: || |K| |x| || of the last Jacobian at the state it
    // was assembled at (the scale changes little from one iterate to the
    // next, and at the first iterate of a pairing the matrix is not
    // assembled yet), and rho_n |x| of the gaps, which are differences of
    // positions (ContactProblem::roundoff_scale()).
    e.bulk_roundoff = matrix_roundoff;
    if (contact->active())
      {
        e.contact_roundoff    = contact->roundoff_scale();
        e.n_changed           = contact_statistics.n_changed;
        e.frozen_contradicted = contact_statistics.n_violated > 0;
      }
    e.linear_at_fixed_statuses =
      materials_linear &&
      (!contact->active() || contact->linear_at_fixed_statuses());
    return e;
  }


  template <int dim>
  void
  Simulation<dim>::record_iterate(const unsigned int        iteration,
                                  const Solver::Evaluation &evaluation,
                                  const double              force_level,
                                  const bool                converged)
  {
    report.log_iterate(iteration,
                       evaluation.block,
                       force_level,
                       contact->active() ? &contact_statistics : nullptr,
                       contact->active() &&
                         contact->contact_surfaces().n_friction() > 0,
                       converged);
  }


  template <int dim>
  std::string
  Simulation<dim>::non_finite_cause() const
  {
    return boundary_conditions.non_finite(report.position.time,
                                          triangulation,
                                          mpi_communicator);
  }


  template <int dim>
  void
  Simulation<dim>::check_iterate()
  {
    if (parameters.newton.check_jacobian && contact->active())
      check_jacobian();
  }


  // A frozen point (anti-cycling) that the plain law contradicts at the
  // converged iterate is released.
  template <int dim>
  void
  Simulation<dim>::release_contradicted()
  {
    unsigned int       refrozen = 0;
    const unsigned int n        = contact->release_frozen(refrozen);
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
  Simulation<dim>::solve_linearised(const unsigned int iteration)
  {
    unsigned int n_early = 0;
    if (contact->active() && iteration >= 1)
      if (const unsigned int n = contact->extrapolate_releases(); n > 0)
        {
          n_early = n;
          report.add_early_releases(n);
          if (parameters.output.verbosity != Verbosity::quiet)
            pcout << "    release extrapolation: " << n
                  << " point(s) opened for this solve" << std::endl;
        }
    assemble(true);
    if (contact->active())
      contact->clear_releases();
    matrix_roundoff =
      Solver::absolute_product_norm(system_matrix, state, mpi_communicator);
    Solver::LinearisedStep step;
    step.held_motions = hold_free_motions(iteration);
    TimerOutput::Scope t(timer, "linear solve");
    step.update.reinit(owned_system, mpi_communicator);
    const unsigned int krylov =
      linear_solver->solve(system_matrix, step.update, newton_rhs);
    report.counts.krylov_iterations += krylov;
    report.counts.krylov_max = std::max(report.counts.krylov_max, krylov);
    constraints_update.distribute(step.update);
    step.exact = krylov == 0 && n_early == 0;
    return step;
  }


  template <int dim>
  TrilinosWrappers::MPI::Vector
  Simulation<dim>::iterate() const
  {
    TrilinosWrappers::MPI::Vector owned(owned_system, mpi_communicator);
    owned = state;
    return owned;
  }


  template <int dim>
  void
  Simulation<dim>::set_iterate(const TrilinosWrappers::MPI::Vector &owned)
  {
    state = owned;
    update_solution();
  }


  template <int dim>
  std::unique_ptr<Solver::NonlinearProblem::Snapshot>
  Simulation<dim>::save() const
  {
    auto snapshot        = std::make_unique<IterateSnapshot>();
    snapshot->points     = contact->save_points();
    snapshot->statistics = contact_statistics;
    return snapshot;
  }


  template <int dim>
  void
  Simulation<dim>::restore(const Solver::NonlinearProblem::Snapshot &snapshot)
  {
    const auto &saved = dynamic_cast<const IterateSnapshot &>(snapshot);
    contact->restore_points(*saved.points);
    contact_statistics = saved.statistics;
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
