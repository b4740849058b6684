// One load step: the predictor, the geometric loop of pairings and Newton
// solves, what the load stepper needs after a converged or failed
// (sub)step.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <signorini/driver/load_step.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>

namespace Signorini
{
  template <int dim>
  LoadStep<dim>::LoadStep(const Parameters              &parameters,
                          DiscreteSystem<dim>           &system,
                          const Bulk::Assembler<dim>    &bulk,
                          Bulk::BoundaryConditions<dim> &boundary_conditions,
                          Contact::ContactProblem<dim>  &contact,
                          Solver::LinearSolver<dim>     &linear_solver,
                          EquilibriumProblem<dim>       &equilibrium,
                          Postprocess::RunReport<dim>   &report,
                          TimerOutput                   &timer,
                          ConditionalOStream            &pcout)
      : parameters(parameters)
      , system(system)
      , bulk(bulk)
      , boundary_conditions(boundary_conditions)
      , contact(contact)
      , linear_solver(linear_solver)
      , equilibrium(equilibrium)
      , report(report)
      , timer(timer)
      , pcout(pcout)
  {
  }


  template <int dim>
  void
  LoadStep<dim>::mark_converged(const bool with_increment)
  {
    if (with_increment)
      record_increment();
    last_converged = system.state;
  }


  // The anti-cycling of the geometric loop froze @p n points (statuses or
  // master faces back at those of two pairings before): counted as cycles
  // and freezes of the step, and said with @p what.
  template <int dim>
  void
  LoadStep<dim>::count_geometric_freezes(const unsigned int n, const char *what)
  {
    if (n == 0)
      return;
    report.counts.cycle_detections += n;
    report.counts.points_frozen += n;
    pcout << "    geometric loop: " << n << " point(s) back " << what
          << std::endl;
  }


  template <int dim>
  void
  LoadStep<dim>::restart_from_step_start()
  {
    system.state = system.state_step_start;
    system.update_solution();
    last_converged = system.state;
  }


  // One load step (theory.md F7): Dirichlet values of the new time on
  // the iterate, then the geometric loop (pairing, Newton) with contact, or
  // Newton alone without.
  template <int dim>
  bool
  LoadStep<dim>::solve(const double  time,
                       const double  step_start_time,
                       unsigned int &iterations,
                       const bool    resume)
  {
    start(time, step_start_time, resume);
    iterations = 0;
    // A Dirichlet expression that is not finite at this time: the step
    // fails before anything is paired or solved at a NaN state (the
    // pairing would project NaN positions onto the master faces).
    bool finite = true;
    for (const auto &line : system.constraints_values.get_lines())
      finite = finite && std::isfinite(line.inhomogeneity);
    if (Utilities::MPI::min(finite ? 1 : 0, system.mpi_communicator) == 0)
      {
        newton_failure_kind = NewtonFailure::non_finite;
        newton_failure      = "the prescribed displacements are not finite" +
                         equilibrium.non_finite_cause();
        return false;
      }
    // The same for a rigid obstacle's motion (its points would pair with
    // nothing and the body would come free: a silent wrong answer).
    if (contact.active())
      if (const std::string motion = contact.non_finite_motion(time);
          !motion.empty())
        {
          newton_failure_kind = NewtonFailure::non_finite;
          newton_failure =
            "the prescribed obstacle motion is not finite" + motion;
          return false;
        }
    if (!contact.active())
      return newton(iterations);

    const auto &c = parameters.contact;
    contact.start_geometric_loop();
    for (unsigned int g = 1; g <= c.max_geometric_iterations; ++g)
      {
        report.position.geometric = g;
        pair(time, step_start_time);
        const TrilinosWrappers::MPI::Vector state_at_pairing = system.state;
        unsigned int                        its              = 0;
        // A pairing that will change is not worth the last quadratic
        // iterations: hand over at 'Tolerance between pairings' (not in
        // the last allowed geometric iteration, nor when a new pairing
        // cannot change the equations).
        const double handover =
          g < c.max_geometric_iterations && !contact.pairing_is_exact() ?
            parameters.newton.tolerance_between_pairings :
            0.;
        const bool ok = newton(its, handover);
        iterations += its;
        if (!ok)
          return false;
        // Rigid obstacles projected at every iterate: nothing to re-pair.
        if (contact.pairing_is_exact())
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
        count_geometric_freezes(contact.end_geometric_iteration(g),
                                "at their status of two pairings before: "
                                "status frozen for the rest of the step");
      }
    newton_failure_kind = NewtonFailure::geometric;
    newton_failure      = "the geometric loop did not converge in " +
                     std::to_string(c.max_geometric_iterations) +
                     " pairings ('Contact/Maximum geometric iterations')";
    return false;
  }


  // The loads and Dirichlet values at @p time, and the first iterate: the
  // extrapolated predictor from the step start, or (resume, after mesh
  // adaptation) the state as it is, with the state at the step start kept.
  template <int dim>
  void
  LoadStep<dim>::start(const double time,
                       const double step_start_time,
                       const bool   resume)
  {
    report.position.time      = time;
    report.position.geometric = 0;
    force_scale               = 0;
    system.make_constraints(time, boundary_conditions, contact);
    boundary_conditions.set_load_time(time);
    if (!resume)
      system.state_step_start = system.state;
    // Extrapolated predictor: the last converged increment, scaled
    // (predictor_factor()); Dirichlet values then override their entries.
    // One insert per entry: an add after an insert would leave the ranks
    // with and without DoFs in different compress modes (a deadlock).
    const double factor =
      !resume && parameters.load_stepping.extrapolate && last_step_size > 0 ?
        predictor_factor(time, step_start_time) :
        0.;
    TrilinosWrappers::MPI::Vector owned(system.owned_system,
                                        system.mpi_communicator);
    for (const auto i : system.owned_system)
      owned[i] = factor != 0 ? system.state[i] + factor * last_increment[i] :
                               static_cast<double>(system.state[i]);
    owned.compress(VectorOperation::insert);
    // A linear bulk takes the Dirichlet values of the new time in the
    // predictor. A nonlinear bulk is evaluated at equilibrium-like states
    // only: the prescribed values are reached by the step's first Newton
    // update (arm_first_update()), which carries their increments through
    // the Jacobian at the predictor (as deal.II's step-44 applies its
    // Dirichlet increments). Moving the Dirichlet nodes alone would strain
    // the cells next to them as no equilibrium does, and a plastic body
    // would yield there in the predictor. The predictor satisfies the
    // homogeneous relations (hanging nodes, multiplier lines) as a
    // combination of converged states.
    if (equilibrium.linear_bulk())
      system.constraints_values.distribute(owned);
    system.state   = owned;
    values_pending = !equilibrium.linear_bulk();
    equilibrium.impose_in_first_update(nullptr);
    system.update_solution();
  }


  // The scale of the last converged increment in the extrapolated
  // predictor: the factor that best matches the data of the last increment
  // to this step's, in the least-squares sense, for each kind of data that
  // moved in the last increment: the prescribed (Dirichlet) values, the
  // loads (the external force vector of the Neumann tractions and the
  // body force), and the prescribed motion of the rigid obstacles (at
  // their paired points); the mean of the (dimensionless) factors of
  // those that moved. For data proportional along the path it is the
  // ratio of the step sizes; where the data reverse it is negative, and
  // where they turn at a right angle near 0 (an ironing die that stops
  // pressing and starts to slide), so the predictor never continues a
  // motion or a load that the path has left (a plastic body would yield
  // further in the predictor where it unloads). Where none moved: the
  // ratio of the step sizes.
  template <int dim>
  double
  LoadStep<dim>::predictor_factor(const double time,
                                  const double step_start_time)
  {
    const auto &constraints = system.constraints_values;
    double      new_old = 0, old_old = 0;
    for (const auto i : system.locally_owned)
      if (constraints.is_constrained(i) &&
          constraints.get_constraint_entries(i)->empty())
        {
          const double d_new =
            constraints.get_inhomogeneity(i) - system.state[i];
          const double d_old = last_increment[i];
          new_old += d_new * d_old;
          old_old += d_old * d_old;
        }
    std::array<double, 6> products{{new_old, old_old, 0., 0., 0., 0.}};
    const double          previous = step_start_time - last_step_size;
    if (boundary_conditions.has_loads())
      {
        const auto local =
          load_increment_products(time, step_start_time, previous);
        products[2] = local[0];
        products[3] = local[1];
      }
    if (contact.active())
      {
        const auto local =
          contact.obstacle_increment_products(time, step_start_time, previous);
        products[4] = local[0];
        products[5] = local[1];
      }
    Utilities::MPI::sum(ArrayView<const double>(products),
                        system.mpi_communicator,
                        ArrayView<double>(products));
    double       sum_of_factors = 0;
    unsigned int n_factors      = 0;
    for (unsigned int b = 0; b < 3; ++b)
      if (products[2 * b + 1] > 0)
        {
          sum_of_factors += products[2 * b] / products[2 * b + 1];
          ++n_factors;
        }
    return n_factors > 0 ? sum_of_factors / n_factors :
                           (time - step_start_time) / last_step_size;
  }


  // The load increments f_new = F_ext(@p time) - F_ext(@p start) and f_old
  // = F_ext(@p start) - F_ext(@p previous) (the loads do not depend on the
  // displacement): this rank's parts of f_new . f_old and f_old . f_old
  // (owned entries; zero on a rank that owns none), with the load
  // functions left at @p time.
  template <int dim>
  std::array<double, 2>
  LoadStep<dim>::load_increment_products(const double time,
                                         const double start,
                                         const double previous)
  {
    TimerOutput::Scope            t(timer, "predictor loads");
    std::array<Vector<double>, 3> f;
    const std::array<double, 3>   times{{time, start, previous}};
    TrilinosWrappers::MPI::Vector force(system.locally_owned,
                                        system.mpi_communicator);
    for (unsigned int k = 0; k < 3; ++k)
      {
        boundary_conditions.set_load_time(times[k]);
        bulk.assemble_external_force(system.dof_handler,
                                     system.solution,
                                     boundary_conditions.has_body_force(),
                                     force);
        f[k].reinit(system.locally_owned.n_elements());
        unsigned int n = 0;
        for (const auto i : system.locally_owned)
          f[k][n++] = force[i];
      }
    boundary_conditions.set_load_time(time);
    if (f[0].size() == 0)
      return {{0., 0.}};
    f[0] -= f[1];
    f[1] -= f[2];
    // A load that is not finite (a load expression of the user) gives no
    // scale: NaN, which the caller's sum passes to every rank and its
    // test for a positive norm skips. Newton reports the load.
    for (const auto &v : f)
      for (const double x : v)
        if (!std::isfinite(x))
          return {{std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::quiet_NaN()}};
    return {{f[0] * f[1], f[1] * f[1]}};
  }


  // A pairing of the geometric loop (obstacles at @p time), its messages,
  // the initial multipliers at the first pairing of the run, the sparsity
  // pattern of its couplings.
  template <int dim>
  void
  LoadStep<dim>::pair(const double time, const double step_start_time)
  {
    {
      TimerOutput::Scope t(timer, "pairing");
      contact.pair(system.state, time, step_start_time);
      if (const unsigned int n = contact.deep_points(); n > 0)
        pcout << "    pairing: " << n
              << " slave point(s) deep inside the master body, paired "
                 "from the penetrated side"
              << std::endl;
      count_geometric_freezes(contact.newly_pinned(),
                              "on their master face of two pairings before: "
                              "pinned to it for the rest of the step");
      if (first_pairing)
        {
          TrilinosWrappers::MPI::Vector owned(system.owned_system,
                                              system.mpi_communicator);
          owned = system.state;
          contact.set_initial_multipliers(system.state, owned);
          // Hanging and excluded multipliers follow their constraint lines
          // from the start: Newton updates are distributed with
          // homogeneous lines, so a start off the lines would stay off.
          // This also puts the Dirichlet DoFs of a nonlinear bulk at their
          // values: the step's first update (arm_first_update(), after
          // this) then has none left to move.
          system.constraints_values.distribute(owned);
          system.state  = owned;
          first_pairing = false;
        }
    }
    TimerOutput::Scope t(timer, "sparsity");
    system.make_sparsity(contact, linear_solver);
  }


  // Largest displacement change since the pairing against the step's
  // increment (code_aster's criterion, theory.md F7).
  template <int dim>
  double
  LoadStep<dim>::pairing_change(
    const TrilinosWrappers::MPI::Vector &state_at_pairing) const
  {
    double change = 0, increment = 0;
    for (const auto i : system.locally_owned)
      {
        change =
          std::max(change, std::abs(system.state[i] - state_at_pairing[i]));
        increment =
          std::max(increment,
                   std::abs(system.state[i] - system.state_step_start[i]));
      }
    change    = Utilities::MPI::max(change, system.mpi_communicator);
    increment = Utilities::MPI::max(increment, system.mpi_communicator);
    return increment > 0 ? change / increment : 0.;
  }


  // The pairing stays: finish the solve at 'Relative tolerance' (it was
  // handed over at @p handover > 0), unless its last step was exact
  // (linear equations at settled statuses, direct solve) and left a
  // residual above it: a further solve would only stir the round-off.
  template <int dim>
  bool
  LoadStep<dim>::finish_geometric_loop(const double  handover,
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
    if (equilibrium.statistics().n_geometric_frozen > 0)
      pcout << "    geometric loop converged with "
            << equilibrium.statistics().n_geometric_frozen
            << " point(s) frozen by the geometric loop, "
            << equilibrium.statistics().n_geometric_violated
            << " of them against the plain contact law" << std::endl;
    return true;
  }


  // The first Newton update of the step moves the Dirichlet DoFs from
  // where they are now (the predictor, with the initial multipliers of a
  // first pairing) to their values at the step's time: the constraints of
  // that update are taken from the state the Newton solve starts from, so
  // that the increment is applied once, whatever wrote the state before.
  template <int dim>
  void
  LoadStep<dim>::arm_first_update()
  {
    values_pending = false;
    const bool first_update =
      system.make_first_update_constraints(contact, system.state_step_start);
    if (first_update)
      equilibrium.impose_in_first_update(&system.constraints_first);
    else
      {
        // Already at the values (to round-off): put them on exactly.
        TrilinosWrappers::MPI::Vector owned(system.owned_system,
                                            system.mpi_communicator);
        owned = system.state;
        system.constraints_values.distribute(owned);
        system.state = owned;
        system.update_solution();
      }
  }


  // One Newton solve of the current pairing (Solver::NewtonSolver, with
  // the EquilibriumProblem as its problem).
  template <int dim>
  bool
  LoadStep<dim>::newton(unsigned int &iterations, const double tolerance)
  {
    if (values_pending)
      arm_first_update();
    Solver::NewtonSolver::Parameters p;
    p.max_iterations     = parameters.newton.max_iterations;
    p.relative_tolerance = parameters.newton.relative_tolerance;
    p.absolute_tolerance = parameters.newton.absolute_tolerance;
    // The line search damps the status changes of contact and of the
    // materials (yielding, unloading); a linear bulk alone has none.
    p.line_search_steps = contact.active() || !equilibrium.linear_bulk() ?
                            parameters.newton.line_search_steps :
                            0;
    p.quiet             = parameters.output.verbosity == Verbosity::quiet;
    const Solver::NewtonSolver solver(p, pcout, timer);
    last_newton = solver.solve(equilibrium, force_scale, tolerance);
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
  LoadStep<dim>::failure_advice() const
  {
    const std::string smaller =
      parameters.load_stepping.explicit_times ?
        "more times in 'Load stepping/Step times'" :
        "more steps ('Load stepping/Number of steps')";
    // A 'closed' start pulls every paired point onto the master in the
    // first iterate: at finite strain a curved surface pulled that far
    // distorts the body beyond what Newton recovers from (issue 62,
    // defect 6: J2 at finite strain on the rigid Hertz scene, 5 cuts).
    bool finite_strain = false;
    for (const auto &m : parameters.materials)
      finite_strain = finite_strain || m.finite_strain;
    if (none_converged && finite_strain && contact.active() &&
        parameters.contact.initial_status == InitialStatus::closed &&
        newton_failure_kind != NewtonFailure::geometric)
      return "The run starts 'Contact/Initial status = closed', whose first "
             "iterate pulls every paired point onto the master; at finite "
             "strain that distorts a curved body too far. Start from the "
             "default 'penetrating' (it closes the points that touch), "
             "unless the touching points cannot hold the body.";
    switch (newton_failure_kind)
      {
        case NewtonFailure::non_finite:
          if (newton_failure.find("is not finite at") != std::string::npos)
            return "Give a load expression that is finite over the load "
                   "path.";
          if (newton_failure.find("inverted at finite strain") !=
              std::string::npos)
            return "The step was cut where the cell named above inverts; "
                   "more steps help only if a smaller increment avoids it.";
          return "The loads are finite: the iterate diverged; try " + smaller +
                 ".";
        case NewtonFailure::stagnation:
          return "Either the load has no equilibrium (check it against what "
                 "the supports and friction can carry) or the iteration is "
                 "stuck; " +
                 smaller + " helps only in the second case.";
        case NewtonFailure::linear_solve:
          if (newton_failure.find("Krylov solve") != std::string::npos)
            return "The Krylov solver reached its iteration cap: raise "
                   "'Linear solver/Maximum iterations' (or set 'Linear "
                   "solver/Type = direct'); smaller steps do not help.";
          return "A singular tangent means that part of the model can move "
                 "at no force in that iterate: a body without supports, or a "
                 "perfectly plastic zone that has become a mechanism (give "
                 "the material some hardening, or prescribe the motion "
                 "instead of the load); " +
                 smaller + " helps when a large step reached it.";
        case NewtonFailure::geometric:
          return "Raise 'Contact/Maximum geometric iterations' or use " +
                 smaller + ".";
        default:
          return "Raise 'Newton/Maximum iterations' or use " + smaller + ".";
      }
  }


  template <int dim>
  bool
  LoadStep<dim>::solve_step(const double  time,
                            const double  start_time,
                            unsigned int &iterations)
  {
    return solve(time, start_time, iterations);
  }


  template <int dim>
  void
  LoadStep<dim>::accept_step(const double time, const double start_time)
  {
    record_increment();
    last_step_size = time - start_time;
    last_converged = system.state;
    none_converged = false;
    // The quadrature-point history of the materials follows the converged
    // (sub)steps only: a cut step, line-search trials and the Jacobian check
    // never reach it.
    system.update_solution();
    system.history.save_start();
    bulk.update_history(system.dof_handler, system.solution, system.history);
  }


  template <int dim>
  void
  LoadStep<dim>::reject_step()
  {
    // The failed iterates go to newton_history.csv now: the retry may be
    // killed, or the run stop.
    report.append_newton_history();
    system.state = last_converged;
    system.update_solution();
    equilibrium.impose_in_first_update(nullptr); // the retry starts anew
    // Back to the initial state: the retry needs the initial multipliers
    // again ('Initial status').
    if (none_converged)
      first_pairing = true;
  }


  template <int dim>
  void
  LoadStep<dim>::restore_last_converged(const double time)
  {
    report.position.time = time;
    system.make_constraints(time, boundary_conditions, contact);
    boundary_conditions.set_load_time(time);
    system.state            = last_converged;
    system.state_step_start = last_converged;
    system.update_solution();
    // The pairing is the failed attempt's (at a state that may be NaN):
    // paired again at the converged state, whose last geometric iteration
    // it reproduces, so that the written contact forces and reactions are
    // the converged sub-step's. The law is the plain one there: the
    // anti-cycling freezes of the failed attempt would hold its statuses
    // (a c_n = 1e6 scene wrote contact forces 28 % above the loads).
    if (contact.active())
      {
        contact.start_geometric_loop();
        pair(time, time);
        contact.start_newton_solve();
      }
    equilibrium.evaluate(false);
  }


  template <int dim>
  std::string
  LoadStep<dim>::failure() const
  {
    return newton_failure;
  }


  // The converged increment of the last (sub)step: the extrapolated
  // predictor of the next one.
  template <int dim>
  void
  LoadStep<dim>::record_increment()
  {
    last_increment.reinit(system.owned_system, system.mpi_communicator);
    for (const auto i : system.owned_system)
      last_increment[i] = system.state[i] - system.state_step_start[i];
    last_increment.compress(VectorOperation::insert);
  }


  template class LoadStep<2>;
  template class LoadStep<3>;
} // namespace Signorini
