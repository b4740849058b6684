#ifndef signorini_source_postprocess_parsed_function_h
#define signorini_source_postprocess_parsed_function_h

// Private to source/postprocess/: the reference expressions of subsection
// 'Reference solution' as functions of x, y(, z) and t. The expressions
// were checked when the parameters were read (core/input_checks.cc).

#include <deal.II/base/function_parser.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace Signorini
{
  namespace Postprocess
  {
    /** nullptr for no expression. */
    template <int dim>
    std::unique_ptr<dealii::FunctionParser<dim>>
    parsed(const std::vector<std::string>      &expressions,
           const std::map<std::string, double> &constants)
    {
      if (expressions.empty())
        return nullptr;
      auto f = std::make_unique<dealii::FunctionParser<dim>>(expressions.size());
      f->initialize(dim == 2 ? "x,y,t" : "x,y,z,t", expressions, constants, true);
      return f;
    }
  } // namespace Postprocess
} // namespace Signorini

#endif
