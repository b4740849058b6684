#ifndef signorini_source_postprocess_parsed_function_h
#define signorini_source_postprocess_parsed_function_h

// Private to source/postprocess/: the reference expressions of subsection
// 'Output/Reference checks' as functions of x, y(, z) and t. The expressions
// were checked when the parameters were read (base/input_checks.cc).

#include <deal.II/base/function_parser.h>

#include <signorini/base/input_checks.h>

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
      return parse_function<dim>(expressions,
                                 constants,
                                 "subsection 'Output/Reference checks'");
    }
  } // namespace Postprocess
} // namespace Signorini

#endif
