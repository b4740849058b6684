#ifndef signorini_source_core_simulation_helpers_h
#define signorini_source_core_simulation_helpers_h

// Helpers shared by the source files of Simulation (private to
// source/core/).

#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>

#include <signorini/core/parameters.h>
#include <signorini/core/simulation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace Signorini
{
  namespace internal
  {
    using namespace dealii;

    // FunctionParser with x, y(, z), t and the user's constants.
    template <int dim>
    std::unique_ptr<FunctionParser<dim>>
    make_function(const std::vector<std::string> &expressions,
                  const std::map<std::string, double> &constants,
                  const std::string &                  where)
    {
      auto f = std::make_unique<FunctionParser<dim>>(expressions.size());
      const std::string variables = dim == 2 ? "x,y,t" : "x,y,z,t";
      try
        {
          f->initialize(variables, expressions, constants, true);
          // muparser reports some errors only on evaluation.
          f->value(Point<dim>(), 0);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream info;
          e.print_info(info);
          std::string text = info.str();
          for (auto &c : text)
            if (c == '\n')
              c = ' ';
          throw InputError(where + ": cannot parse the expression(s) '" +
                           Utilities::trim(
                             [&] {
                               std::string s;
                               for (const auto &e : expressions)
                                 s += (s.empty() ? "" : "; ") + e;
                               return s;
                             }()) +
                           "' (variables: " + variables +
                           ", plus 'Function constants'). " +
                           Utilities::trim(text));
        }
      return f;
    }

    // The log line of a residual accepted at the round-off floor (Newton
    // loop): @p relative over the force level, @p why the rule.
    inline std::string
    floor_line(const double relative, const double floor, const char *why)
    {
      std::ostringstream s;
      s << "    residual " << std::scientific << std::setprecision(2)
        << relative << " " << why << " (round-off floor "
        << std::setprecision(1) << floor << "): accepted";
      return s.str();
    }
    inline constexpr const char *stagnated_why = "no longer decreases";
    inline constexpr const char *exact_why =
      "after an exact step of linear equations";

    // The residual norm from its three block norms (u, lambda, Lambda).
    inline double
    norm_of(const std::array<double, 3> &block)
    {
      return std::sqrt(block[0] * block[0] + block[1] * block[1] +
                       block[2] * block[2]);
    }

    // Why a Newton solve used up its iterations, from its residuals over
    // the force level, the status changes of the last iterate and the
    // rigid motions nothing held at the last solve.
    inline std::pair<NewtonFailure, std::string>
    newton_failure_reason(const std::vector<double> &r,
                          const unsigned int         n_changed,
                          const std::string &        free_motions,
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
          << ") was reached while the residual still decreased (|R|/|F| = "
          << last << ")";
      if (!free_motions.empty())
        s << "; at the last iterate nothing held " << free_motions
          << " (no Dirichlet condition along it and no closed point "
             "sticking: under force control a tangential load above mu "
             "times the normal force has no equilibrium)";
      return {kind, s.str()};
    }
  } // namespace internal
} // namespace Signorini

#endif
