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

  } // namespace internal
} // namespace Signorini

#endif
