// The generalised Newton method on a NonlinearProblem: the iteration, its
// convergence rules, the line search and the reason of a failure.
#include <deal.II/base/utilities.h>

#include <signorini/base/errors.h>
#include <signorini/base/format.h>
#include <signorini/solver/newton_solver.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace Signorini
{
  namespace Solver
  {
    namespace
    {
      constexpr const char *stagnated_why = "no longer decreases";
      constexpr const char *exact_why =
        "after an exact step of linear equations";

      // The log line of a residual accepted at the round-off floor:
      // @p relative over the force level, @p why the rule.
      std::string
      floor_line(const double relative, const double floor, const char *why)
      {
        std::ostringstream s;
        s << "    residual " << std::scientific << std::setprecision(2)
          << relative << " " << why << " (round-off floor "
          << std::setprecision(1) << floor << "): accepted";
        return s.str();
      }

      // The residual norm from its three block norms (u, lambda, Lambda).
      double
      norm_of(const std::array<double, 3> &block)
      {
        return std::sqrt(block[0] * block[0] + block[1] * block[1] +
                         block[2] * block[2]);
      }

      // Why a Newton solve used up its iterations, from its residuals over
      // the force level, the status changes of the last iterate and the
      // rigid motions nothing held at the last solve.
      std::pair<NewtonFailure, std::string>
      failure_reason(const std::vector<double> &r,
                     const unsigned int         n_changed,
                     const std::string         &free_motions,
                     const unsigned int         max_iterations)
      {
        std::ostringstream s;
        s << std::scientific << std::setprecision(2);
        const double last = r.empty() ? 0. : r.back();
        // Stagnation: the last residual is not below half the smallest of
        // the few iterates before it.
        const std::size_t n = r.size(), k = std::max<std::size_t>(3, n / 4);
        const bool        stalled =
          n > k && last > 0.5 * *std::min_element(r.end() - k - 1, r.end() - 1);
        NewtonFailure kind = NewtonFailure::iteration_limit;
        if (n_changed > 0)
          {
            kind = NewtonFailure::statuses;
            s << "the contact statuses still change at the last Newton "
                 "iterate ("
              << n_changed << " changed, |R|/|F| = " << last << ")";
          }
        else if (stalled)
          {
            kind = NewtonFailure::stagnation;
            s << "the residual stagnates at |R|/|F| = " << last
              << " with settled contact statuses";
          }
        else
          s << "'Newton/Maximum iterations' (" << max_iterations
            << ") was reached while the residual still decreased (|R|/|F| "
               "= "
            << last << ")";
        if (!free_motions.empty())
          s << "; at the last iterate nothing held " << free_motions
            << " (no Dirichlet condition along it and no closed point "
               "sticking: under force control a tangential load above mu "
               "times the normal force has no equilibrium)";
        return {kind, s.str()};
      }
    } // namespace


    std::string
    NewtonSolver::Result::exact_floor_line() const
    {
      return floor_line(residual_at_end, floor_at_end, exact_why);
    }


    NewtonSolver::NewtonSolver(const Parameters         &parameters,
                               const ConditionalOStream &out,
                               TimerOutput              &timer)
        : parameters(parameters)
        , out(out)
        , timer(timer)
    {
    }


    // The evaluation of the full update is its trial, so an accepted full
    // step costs no extra assembly.
    Evaluation
    NewtonSolver::evaluate_trial(NonlinearProblem &problem,
                                 SearchTrial      &trial,
                                 bool             &step_exact,
                                 Result           &result) const
    {
      const bool search     = trial.pending;
      trial.pending         = false;
      const auto saved      = search ? problem.save() : nullptr;
      Evaluation evaluation = problem.evaluate(false);
      if (!search)
        return evaluation;
      const double r_full = norm_of(evaluation.block);
      // A non-finite trial (at finite strain: an element turned inside out
      // by the full update) is backtracked too.
      if (std::isfinite(r_full) && r_full <= (1 - 1e-4) * trial.residual)
        return evaluation;
      problem.restore(*saved);
      const double alpha = line_search(
        problem, trial.base, trial.update, trial.residual, r_full, result);
      if (alpha < 1)
        step_exact = false;
      TrilinosWrappers::MPI::Vector owned = trial.base;
      owned.add(alpha, trial.update);
      problem.set_iterate(owned);
      return problem.evaluate(false);
    }


    // The iteration: evaluate (the trial of the last full update first,
    // with the line search if it made the residual grow), judge, then
    // release frozen statuses or solve and update.
    NewtonSolver::Result
    NewtonSolver::solve(NonlinearProblem &problem,
                        double           &force_level,
                        const double      tolerance) const
    {
      Result result;
      double residual_before = 0;
      bool   settled_before  = false;
      // The iterate is the result of an exact Newton step: a direct solve,
      // the full update, with the statuses of its evaluation.
      bool                step_exact = false;
      SearchTrial         search; // the line search of the last update
      std::string         held_motions;
      std::vector<double> residuals; // relative, per iterate
      Evaluation          evaluation;
      for (unsigned int it = 0; it <= parameters.max_iterations; ++it)
        {
          result.iterations = it;
          if (it == 0)
            problem.start_solve();
          evaluation = evaluate_trial(problem, search, step_exact, result);
          const double residual = norm_of(evaluation.block);
          force_level           = std::max(force_level, evaluation.force);
          const Verdict verdict = judge(evaluation,
                                        residual,
                                        force_level,
                                        tolerance,
                                        it,
                                        step_exact,
                                        settled_before,
                                        residual_before);
          problem.record_iterate(it,
                                 evaluation,
                                 force_level,
                                 verdict.converged);
          if (!std::isfinite(residual))
            {
              result.failure = NewtonFailure::non_finite;
              result.why     = "the residual is not finite (" +
                           Postprocess::format(residual, 2) +
                           ") at Newton iterate " + std::to_string(it) +
                           problem.non_finite_cause();
              return result;
            }
          const auto relative = [&](const double r) {
            return force_level > 0 ? r / force_level : 0.;
          };
          residuals.push_back(relative(residual));
          problem.check_iterate();
          if (verdict.converged)
            {
              result.converged       = true;
              result.exact_at_end    = verdict.at_exact_floor;
              result.residual_at_end = relative(residual);
              result.floor_at_end    = relative(verdict.floor);
              return result;
            }
          if (it == parameters.max_iterations)
            break;
          step_exact = false;
          if (verdict.release)
            {
              problem.release_contradicted();
              continue; // evaluate the same iterate again
            }
          LinearisedStep step;
          try
            {
              step = problem.solve_linearised(it);
            }
          catch (const LinearSolveError &e)
            {
              result.failure = NewtonFailure::linear_solve;
              result.why =
                "Newton iterate " + std::to_string(it) + ": " + e.what();
              return result;
            }
          held_motions                        = step.held_motions;
          TrilinosWrappers::MPI::Vector owned = problem.iterate();
          if (parameters.line_search_steps > 0 && !step.prescribes_values)
            search = {true, owned, step.update, residual};
          owned.add(1., step.update);
          problem.set_iterate(owned);
          step_exact = step.exact;
        }
      std::tie(result.failure, result.why) =
        failure_reason(residuals,
                       evaluation.n_changed,
                       held_motions,
                       parameters.max_iterations);
      return result;
    }


    // Converged: every block small against the force level (or at the
    // round-off floor once Newton can do no more) and no status changed.
    NewtonSolver::Verdict
    NewtonSolver::judge(const Evaluation  &evaluation,
                        const double       residual,
                        const double       force_level,
                        const double       tolerance,
                        const unsigned int iteration,
                        const bool         step_exact,
                        bool              &settled_before,
                        double            &residual_before) const
    {
      const auto  &block = evaluation.block;
      const double relative_tolerance =
        tolerance > 0 ? std::max(tolerance, parameters.relative_tolerance) :
                        parameters.relative_tolerance;
      const auto small = [&](const double r) {
        return r <= parameters.absolute_tolerance ||
               r <= relative_tolerance * force_level;
      };
      // Round-off floor (doc/robustness.md, "Round-off floor computed"):
      // the residual cannot go below the round-off of its terms, eps times
      // the problem's round-off scales of the bulk and contact terms. An
      // iterate at or below 10 eps times that scale is accepted once the
      // statuses have settled and Newton can do no more: its last step no
      // longer halved the residual (stagnation), or it was an exact step of
      // equations linear at fixed statuses, after which what is left is
      // round-off. A Newton that still contracts, or one that stalls above
      // round-off (a Jacobian that is not the derivative of the residual),
      // is never accepted here.
      constexpr double floor_factor =
        10 * std::numeric_limits<double>::epsilon();
      const double bulk_floor    = floor_factor * evaluation.bulk_roundoff;
      const double contact_floor = floor_factor * evaluation.contact_roundoff;
      Verdict      verdict;
      verdict.floor               = std::hypot(bulk_floor, contact_floor);
      const bool statuses_settled = evaluation.n_changed == 0;
      const bool stagnated        = iteration >= 1 && statuses_settled &&
                             settled_before && residual > 0.5 * residual_before;
      settled_before  = statuses_settled;
      residual_before = residual;
      const bool exact_step =
        step_exact && statuses_settled && evaluation.linear_at_fixed_statuses;
      // A floor above 1e-6 of the force level is not round-off of an
      // answer: the iterate has run away (its round-off grows with it; a
      // perfectly plastic body pushed off its contact reached |u| = 1e13
      // and was accepted at a floor of 1.7 times the force level).
      constexpr double largest_floor = 1e-6;
      const bool       floor_of_an_answer =
        verdict.floor <= largest_floor * force_level;
      const bool at_floor = residual <= verdict.floor && floor_of_an_answer &&
                            (stagnated || exact_step);
      verdict.at_exact_floor = at_floor && exact_step;
      // A force level near zero (a body moving rigidly without touching
      // anything): the displacement rows at the round-off of the internal
      // force are as small as they get.
      const bool below_tolerance =
        (small(block[0]) || block[0] <= bulk_floor) && small(block[1]) &&
        small(block[2]);
      if (residual <= verdict.floor && !floor_of_an_answer &&
          (stagnated || exact_step) && !below_tolerance && !parameters.quiet)
        out << "    round-off floor " << std::scientific << std::setprecision(1)
            << verdict.floor / force_level
            << " of the force level: the iterate has run away "
               "(not accepted)"
            << std::defaultfloat << std::endl;
      const bool residual_small = below_tolerance || at_floor;
      if (below_tolerance && !small(block[0]) && !parameters.quiet)
        out << "    displacement residual at the round-off of the internal "
               "force (a rigid motion, or a finite-strain stress at a small "
               "strain): accepted"
            << std::endl;
      if (at_floor && !below_tolerance)
        out << floor_line(residual / force_level,
                          verdict.floor / force_level,
                          exact_step ? exact_why : stagnated_why)
            << std::endl;
      // A frozen status (anti-cycling) that the plain law contradicts at
      // the converged iterate is released; Newton goes on from there.
      verdict.release = residual_small && evaluation.frozen_contradicted;
      verdict.converged =
        residual_small && !verdict.release && !evaluation.values_pending;
      return verdict;
    }


    // Backtracking on the residual norm: try 1/2, 1/4, ... of the update
    // and take the first fraction that decreases the residual, else the
    // one with the smallest residual (1 if no fraction beats the full
    // update; a full update with a non-finite residual is beaten by every
    // finite one). Each trial is an evaluation outside the status history; the
    // problem is left as it was on entry.
    double
    NewtonSolver::line_search(NonlinearProblem                    &problem,
                              const TrilinosWrappers::MPI::Vector &base,
                              const TrilinosWrappers::MPI::Vector &update,
                              const double                         residual_now,
                              const double residual_full,
                              Result      &result) const
    {
      TimerOutput::Scope t(timer, "line search");
      const auto         saved      = problem.save();
      double             best       = std::isfinite(residual_full) ?
                                        residual_full :
                                        std::numeric_limits<double>::infinity();
      double             best_alpha = 1, alpha = 1;
      // A trial whose residual is not finite (an element turned inside out
      // at finite strain) is no admissible state: it is halved again
      // without counting as a step, down to 2^-20 of the update.
      unsigned int counted = 0;
      for (unsigned int k = 1;
           k <= 20 && counted < parameters.line_search_steps;
           ++k)
        {
          alpha *= 0.5;
          TrilinosWrappers::MPI::Vector trial = base;
          trial.add(alpha, update);
          problem.set_iterate(trial);
          const double r = norm_of(problem.evaluate(true).block);
          if (!std::isfinite(r))
            continue;
          ++counted;
          if (r < best)
            {
              best       = r;
              best_alpha = alpha;
            }
          if (r <= (1 - 1e-4 * alpha) * residual_now)
            break;
        }
      problem.restore(*saved);
      if (best_alpha < 1)
        {
          ++result.line_searches;
          if (!parameters.quiet)
            out << "    line search: " << best_alpha
                << " of the update (residual " << std::scientific
                << std::setprecision(2) << residual_full / residual_now
                << " -> " << best / residual_now << " of the current)"
                << std::defaultfloat << std::endl;
        }
      return best_alpha;
    }
  } // namespace Solver
} // namespace Signorini
