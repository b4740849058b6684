// Load steps and the generalised Newton method: the solve of one step, the
// Newton loop with its convergence rules, line search, failure reports, the
// Jacobian check.
#include <deal.II/base/utilities.h>

#include <signorini/contact/jacobian_check.h>
#include <signorini/core/simulation.h>

#include <algorithm>
#include <signorini/postprocess/format.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace Signorini
{
  using Postprocess::format;


  // One load step (formulation.md 7): Dirichlet values of the new time on
  // the iterate, then the geometric loop (pairing, Newton) with contact, or
  // Newton alone without.
  template <int dim>
  bool
  Simulation<dim>::solve_load_step(const double  time,
                                   const double  step_start_time,
                                   unsigned int &iterations,
                                   const bool    resume)
  {
    start_load_step(time, step_start_time, resume);
    iterations = 0;
    if (!contact->active())
      return newton(iterations);

    const auto &c = parameters.contact;
    contact->start_geometric_loop();
    for (unsigned int g = 1; g <= c.max_geometric_iterations; ++g)
      {
        report.position.geometric = g;
        pair_for_step(time, step_start_time);
        const TrilinosWrappers::MPI::Vector state_at_pairing = state;
        unsigned int its = 0;
        // A pairing that will change is not worth the last quadratic
        // iterations: hand over at 'Tolerance between pairings' (not in
        // the last allowed geometric iteration, nor when a new pairing
        // cannot change the equations).
        const double handover =
          g < c.max_geometric_iterations && !contact->pairing_is_exact() ?
            parameters.newton.tolerance_between_pairings :
            0.;
        const bool ok = newton(its, handover);
        iterations += its;
        if (!ok)
          return false;
        // Rigid obstacles projected at every iterate: nothing to re-pair.
        if (contact->pairing_is_exact())
          return true;
        const double ratio = pairing_change(state_at_pairing);
        if (parameters.output.verbosity != Verbosity::quiet)
          pcout << "    geometric iteration " << g
                << ": change/increment = " << std::scientific
                << std::setprecision(2) << ratio << std::defaultfloat
                << std::endl;
        if (ratio <= c.geometric_tolerance)
          return finish_geometric_loop(handover, iterations);
        // Anti-cycling across pairings: points back at their status of two
        // pairings before keep one status for the rest of the step.
        if (const unsigned int n = contact->end_geometric_iteration(g); n > 0)
          {
            report.counts.cycle_detections += n;
            report.counts.points_frozen += n;
            pcout << "    geometric loop: " << n
                  << " point(s) back at their status of two pairings before:"
                     " status frozen for the rest of the step"
                  << std::endl;
          }
      }
    newton_failure_kind = NewtonFailure::geometric;
    newton_failure      = "the geometric loop did not converge in " +
                     std::to_string(c.max_geometric_iterations) +
                     " pairings ('Contact/Maximum geometric iterations')";
    return false;
  }


  // The loads and Dirichlet values at @p time, and the first iterate: the
  // extrapolated predictor from the step start, or (resume, after mesh
  // adaptation) the state as it is, with state_step_start kept.
  template <int dim>
  void
  Simulation<dim>::start_load_step(const double time,
                                   const double step_start_time,
                                   const bool   resume)
  {
    report.position.time      = time;
    report.position.geometric = 0;
    force_scale       = 0;
    make_constraints(time);
    boundary_conditions.set_load_time(time);
    if (!resume)
      state_step_start = state;
    // Extrapolated predictor: the last converged increment, scaled to this
    // step's size; Dirichlet values then override their entries. One
    // insert per entry: an add after an insert would leave the ranks with
    // and without DoFs in different compress modes (a deadlock).
    const double factor =
      !resume && parameters.load_stepping.extrapolate && last_step_size > 0 ?
        (time - step_start_time) / last_step_size :
        0.;
    TrilinosWrappers::MPI::Vector owned(owned_system, mpi_communicator);
    for (const auto i : owned_system)
      owned[i] = factor != 0 ? state[i] + factor * last_increment[i] :
                               static_cast<double>(state[i]);
    owned.compress(VectorOperation::insert);
    constraints_values.distribute(owned);
    state = owned;
    update_solution();
  }


  // A pairing of the geometric loop (obstacles at @p time), its messages,
  // the initial multipliers at the first pairing of the run, the sparsity
  // pattern of its couplings.
  template <int dim>
  void
  Simulation<dim>::pair_for_step(const double time,
                                 const double step_start_time)
  {
    {
      TimerOutput::Scope t(timer, "pairing");
      contact->pair(state, time, step_start_time);
      if (const unsigned int n = contact->deep_points(); n > 0)
        pcout << "    pairing: " << n
              << " slave point(s) deep inside the master body, paired "
                 "from the penetrated side"
              << std::endl;
      if (const unsigned int n = contact->newly_pinned(); n > 0)
        {
          report.counts.cycle_detections += n;
          report.counts.points_frozen += n;
          pcout << "    geometric loop: " << n
                << " point(s) back on their master face of two pairings"
                   " before: pinned to it for the rest of the step"
                << std::endl;
        }
      if (first_pairing)
        {
          TrilinosWrappers::MPI::Vector owned(owned_system, mpi_communicator);
          owned = state;
          contact->set_initial_multipliers(state, owned);
          // Hanging and excluded multipliers follow their constraint lines
          // from the start: Newton updates are distributed with
          // homogeneous lines, so a start off the lines would stay off.
          constraints_values.distribute(owned);
          state         = owned;
          first_pairing = false;
        }
    }
    TimerOutput::Scope t(timer, "sparsity");
    make_sparsity();
  }


  // Largest displacement change since the pairing against the step's
  // increment (code_aster's criterion, formulation.md 7.3).
  template <int dim>
  double
  Simulation<dim>::pairing_change(
    const TrilinosWrappers::MPI::Vector &state_at_pairing) const
  {
    double change = 0, increment = 0;
    for (const auto i : locally_owned)
      {
        change = std::max(change, std::abs(state[i] - state_at_pairing[i]));
        increment =
          std::max(increment, std::abs(state[i] - state_step_start[i]));
      }
    change    = Utilities::MPI::max(change, mpi_communicator);
    increment = Utilities::MPI::max(increment, mpi_communicator);
    return increment > 0 ? change / increment : 0.;
  }


  // The pairing stays: finish the solve at 'Relative tolerance' (it was
  // handed over at @p handover > 0), unless its last step was exact
  // (linear equations at settled statuses, direct solve) and left a
  // residual above it: a further solve would only stir the round-off.
  template <int dim>
  bool
  Simulation<dim>::finish_geometric_loop(const double  handover,
                                         unsigned int &iterations)
  {
    const bool at_floor =
      handover > 0 && last_newton.exact_at_end &&
      last_newton.residual_at_end > parameters.newton.relative_tolerance;
    if (at_floor)
      pcout << last_newton.exact_floor_line() << std::endl;
    if (handover > 0 && !at_floor)
      {
        unsigned int more = 0;
        const bool   done = newton(more);
        iterations += more;
        if (!done)
          return false;
      }
    if (contact_statistics.n_geometric_frozen > 0)
      pcout << "    geometric loop converged with "
            << contact_statistics.n_geometric_frozen
            << " point(s) frozen by the geometric loop, "
            << contact_statistics.n_geometric_violated
            << " of them against the plain contact law" << std::endl;
    return true;
  }


  // One Newton solve of the current pairing (Solver::NewtonSolver, with
  // this Simulation as its problem).
  template <int dim>
  bool
  Simulation<dim>::newton(unsigned int &iterations, const double tolerance)
  {
    Solver::NewtonSolver::Parameters p;
    p.max_iterations     = parameters.newton.max_iterations;
    p.relative_tolerance = parameters.newton.relative_tolerance;
    p.absolute_tolerance = parameters.newton.absolute_tolerance;
    // The line search damps the status changes of contact; a linear bulk
    // alone has none.
    p.line_search_steps =
      contact->active() ? parameters.newton.line_search_steps : 0;
    p.quiet = parameters.output.verbosity == Verbosity::quiet;
    const Solver::NewtonSolver solver(p, pcout, timer);
    last_newton = solver.solve(*this, force_scale, tolerance);
    iterations  = last_newton.iterations;
    report.counts.line_searches += last_newton.line_searches;
    if (!last_newton.converged)
      {
        newton_failure_kind = last_newton.failure;
        newton_failure      = last_newton.why;
      }
    return last_newton.converged;
  }


  template <int dim>
  std::string
  Simulation<dim>::hold_free_motions(const unsigned int iteration)
  {
    const auto free = rigid_modes.find(system_matrix, dof_handler.n_dofs());
    if (free.empty())
      return "";
    std::string list;
    for (const auto &m : free)
      list += (list.empty() ? "" : "; ") + rigid_modes.describe(m);
    // Friction can hold the motion once its points have a threshold: at
    // the first iterate after they close it is zero (formulation.md 3.3),
    // and while every point slips there is no tangential stiffness. The
    // motion's share of the update is then set to zero for this solve.
    const bool friction_may_hold =
      contact->active() && contact->contact_surfaces().n_friction() > 0 &&
      contact_statistics.n_contact > 0;
    if (!friction_may_hold)
      throw RunError(
        "load step " + std::to_string(report.position.step) +
        ", Newton iterate " + std::to_string(iteration) + ": nothing holds " +
        list +
        " (no Dirichlet condition constrains it and no closed contact point "
        "resists it), so the linear system is singular. Support the body "
        "along that motion (a Dirichlet condition on that component, on one "
        "node if the body must stay free otherwise: 'Boundary "
        "conditions/Dirichlet k/Node'), drive it by a prescribed "
        "displacement, or let it start in contact ('Contact/Initial status "
        "= closed').");
    rigid_modes.hold(system_matrix, dof_handler.n_dofs(), free);
    if (parameters.output.verbosity != Verbosity::quiet)
      pcout << "    held for this solve (friction without threshold or "
               "slipping everywhere): "
            << list << std::endl;
    return list;
  }


  template <int dim>
  std::string
  Simulation<dim>::failure_advice() const
  {
    const std::string smaller =
      parameters.load_stepping.explicit_times ?
        "more times in 'Load stepping/Step times'" :
        "more steps ('Load stepping/Number of steps')";
    switch (newton_failure_kind)
      {
        case NewtonFailure::non_finite:
          return newton_failure.find("is not finite at") != std::string::npos ?
                   "Give a load expression that is finite over the load "
                   "path." :
                   "The loads are finite: the iterate diverged; try " +
                     smaller + ".";
        case NewtonFailure::stagnation:
          return "Either the load has no equilibrium (check it against what "
                 "the supports and friction can carry) or the iteration is "
                 "stuck; " +
                 smaller + " helps only in the second case.";
        case NewtonFailure::geometric:
          return "Raise 'Contact/Maximum geometric iterations' or use " +
                 smaller + ".";
        default:
          return "Raise 'Newton/Maximum iterations' or use " + smaller + ".";
      }
  }


  template <int dim>
  std::array<double, 3>
  Simulation<dim>::block_residuals() const
  {
    const types::global_dof_index n_u = dof_handler.n_dofs();
    const types::global_dof_index n_l =
      contact->active() ? contact->contact_surfaces().n_lambda() : 0;
    std::array<double, 3> block = {{0, 0, 0}};
    for (const auto i : owned_system)
      block[i < n_u ? 0 : (i < n_u + n_l ? 1 : 2)] +=
        newton_rhs[i] * newton_rhs[i];
    for (auto &b : block)
      b = std::sqrt(Utilities::MPI::sum(b, mpi_communicator));
    return block;
  }


  // Development check (Newton/Check Jacobian, contact/jacobian_check.h) at
  // the current iterate. The step floors: 1e-6 of the mesh diameter, 1e-3
  // of the largest modulus, and 1 (with a floor of 1e-6 E, lambda = 0 after
  // an open solve gave steps of 1e-12 E and central differences of
  // round-off noise, 6e-5).
  template <int dim>
  void
  Simulation<dim>::check_jacobian()
  {
    double E_max = 0;
    for (const auto &[id, material] : materials)
      E_max = std::max(E_max, material->representative_modulus());
    const auto saved_statistics = contact_statistics;
    const auto result =
      Contact::check_jacobian(*contact,
                              state,
                              state_step_start,
                              constraints_update,
                              system_matrix,
                              newton_rhs,
                              contact_force,
                              dof_handler.n_dofs(),
                              {{1e-6 * model_size, 1e-3 * E_max, 1.}});
    contact_statistics = saved_statistics;
    jacobian_error_max = std::max(jacobian_error_max, result.worst);
    pcout << "      Jacobian check: " << result.n_checked << " columns, "
          << result.n_kinked << " at a kink, max relative error "
          << std::scientific << std::setprecision(1) << result.worst
          << std::defaultfloat << std::endl;
  }


  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Signorini
