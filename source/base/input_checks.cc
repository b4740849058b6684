#include <deal.II/base/exceptions.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/mu_parser_internal.h>
#include <deal.II/base/utilities.h>

#include <signorini/base/input_checks.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>
#include <unistd.h>

namespace Signorini
{
  namespace
  {
    // ------------------------------------------------------ parameter text
    // Removes a '#' comment and the surrounding white space, as
    // ParameterHandler does before it reads a line.
    std::string
    strip_line(const std::string &line)
    {
      std::string l = line.substr(0, line.find('#'));
      std::replace(l.begin(), l.end(), '\t', ' ');
      return Utilities::trim(l);
    }

    // The full paths ("Geometry/Body 2") of the subsections that @p text
    // enters, read the way ParameterHandler reads them (a line ending in a
    // backslash continues on the next one).
    std::set<std::string>
    entered_subsections(const std::string &text)
    {
      std::set<std::string>    entered;
      std::vector<std::string> stack;
      std::istringstream       in(text);
      std::string              raw, joined;
      while (std::getline(in, raw))
        {
          raw = Utilities::trim(raw);
          if (!raw.empty() && raw.back() == '\\')
            {
              joined += raw.substr(0, raw.size() - 1);
              continue;
            }
          const std::string line = strip_line(joined + raw);
          joined.clear();
          if (line.rfind("subsection ", 0) == 0 ||
              line.rfind("SUBSECTION ", 0) == 0)
            {
              stack.push_back(Utilities::trim(line.substr(11)));
              std::string path;
              for (const auto &s : stack)
                path += (path.empty() ? "" : "/") + s;
              entered.insert(path);
            }
          else if ((line == "end" || line == "END") && !stack.empty())
            stack.pop_back();
        }
      return entered;
    }


    // ------------------------------------------------- function constants
    // Every function name muparser and deal.II's FunctionParser define:
    // muparser's own (mu::Parser::InitFun) and those deal.II adds. A constant
    // with one of these names is accepted by muparser but shadows or is
    // shadowed by the function, depending on where it is used.
    const std::set<std::string> &
    builtin_function_names()
    {
      static const std::set<std::string> names = [] {
        std::set<std::string> n = {"sin",   "cos",   "tan",   "asin", "acos",
                                   "atan",  "atan2", "sinh",  "cosh", "tanh",
                                   "asinh", "acosh", "atanh", "log2", "log10",
                                   "log",   "ln",    "exp",   "sqrt", "sign",
                                   "rint",  "abs",   "sum",   "avg",  "min",
                                   "max"};
        for (const auto &f : internal::FunctionParser::get_function_names())
          n.insert(f);
        return n;
      }();
      return names;
    }

    std::string
    constant_name_rule()
    {
      std::string list;
      for (const auto &f : builtin_function_names())
        list += (list.empty() ? "" : ", ") + f;
      return "A constant's name starts with a letter, followed by letters, "
             "digits or underscores (at most 100 characters, muparser's "
             "limit), and is neither one of the variables x, y, z, t nor a "
             "built-in function (" +
             list + "). Rename the constant and its uses in the expressions.";
    }

    // Why muparser (through FunctionParser) cannot use @p name as a constant
    // or would silently mix it up; empty if it can. muparser refuses names
    // that are empty, start with a digit or hold other characters than
    // letters, digits and '_' (ParserBase::CheckName), longer than 100
    // characters, or that a variable defined afterwards redefines (deal.II
    // defines the constants first, then x, y, z, t: ecNAME_CONFLICT). A
    // leading '_' (muparser's own _pi, _e) is refused too, and z also in 2D
    // (the same file may serve both dimensions).
    std::string
    constant_name_problem(const std::string &name)
    {
      const auto is_letter = [](const char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
      };
      if (name.empty())
        return "an entry has no name (': value')";
      if (!is_letter(name[0]))
        return "the name '" + name + "' does not start with a letter";
      for (const char c : name)
        if (!is_letter(c) && !(c >= '0' && c <= '9') && c != '_')
          return "the name '" + name + "' has the character '" +
                 std::string(1, c) + "'";
      if (name.size() > 100)
        return "the name '" + name.substr(0, 20) +
               "...' is longer than 100 characters";
      if (name == "x" || name == "y" || name == "z" || name == "t")
        return "'" + name +
               "' is a variable of the expressions (x, y, z and the load "
               "time t)";
      if (builtin_function_names().count(name))
        return "'" + name + "' is the name of a built-in function";
      return "";
    }


    // ------------------------------------------------------- expressions
    // muparser's message from deal.II's ExcParseError, whose "Column" is
    // muparser's error code, not a column: the text after "The parser
    // said:" (it gives the position).
    std::string
    parser_message(const ExceptionBase &e)
    {
      std::ostringstream info;
      e.print_info(info);
      std::string text = Utilities::trim(
        std::regex_replace(info.str(), std::regex("\\s+"), " "));
      const std::string said = "The parser said: ";
      const auto        pos  = text.find(said);
      text = pos == std::string::npos ? text : text.substr(pos + said.size());
      while (!text.empty() && text.back() == '.')
        text.pop_back();
      return text;
    }

    // Why @p expression cannot be used (empty if it can): parsed and
    // evaluated once, as muparser parses on the first evaluation.
    template <int dim>
    std::string
    expression_problem(const std::string                   &expression,
                       const std::map<std::string, double> &constants,
                       const std::string                   &time_variable)
    {
      if (Utilities::trim(expression).empty())
        return "the expression is empty (two ';' in a row?)";
      std::string variables = dim == 2 ? "x,y" : "x,y,z";
      if (!time_variable.empty())
        variables += "," + time_variable;
      CerrCapture silence; // the reason goes into the InputError
      try
        {
          FunctionParser<dim> f(1);
          f.initialize(variables,
                       std::vector<std::string>{expression},
                       constants,
                       !time_variable.empty());
          f.value(Point<dim>(), 0);
        }
      catch (const ExceptionBase &e)
        {
          return "muparser: " + parser_message(e);
        }
      catch (...)
        {
          // muparser's own ParserError escapes deal.II from some paths.
          return "muparser refused it";
        }
      return "";
    }

    template <int dim>
    void
    check_expression_input(const ExpressionInput               &input,
                           const std::map<std::string, double> &constants)
    {
      const unsigned int n = input.expressions.size();
      for (unsigned int i = 0; i < n; ++i)
        {
          const std::string problem =
            expression_problem<dim>(input.expressions[i],
                                    constants,
                                    input.time_variable);
          if (problem.empty())
            continue;
          const std::string label =
            i < input.labels.size() ? input.labels[i] : std::to_string(i + 1);
          const std::string component =
            n > 1 ? ", component " + label + " (expression " +
                      std::to_string(i + 1) + " of " + std::to_string(n) + ")" :
                    "";
          const std::string variables =
            std::string(dim == 2 ? "x, y" : "x, y, z") +
            (input.time_variable.empty() ? "" : ", " + input.time_variable);
          throw InputError(input.where + component + ": cannot evaluate '" +
                           input.expressions[i] + "': " + problem +
                           ". Expressions are in the variables " + variables +
                           " and the 'Function constants', with muparser's "
                           "functions and operators (e.g. 'sin(x)', 'x^2', "
                           "'t < 1 ? 0 : t - 1'). Correct the expression.");
        }
    }

    // Every expression entry of the input, each with all its components
    // (also the ones a Dimension ignores: a typo there is still a typo).
    template <int dim>
    std::vector<ExpressionInput>
    expression_inputs(const Parameters &parameters)
    {
      std::vector<ExpressionInput> inputs;
      const auto                  &bc = parameters.boundary_conditions;
      for (unsigned int k = 0; k < bc.dirichlet.size(); ++k)
        {
          ExpressionInput input;
          input.where = "subsection 'Boundary conditions/Dirichlet " +
                        std::to_string(k + 1) + "', parameter 'Values'";
          input.expressions = bc.dirichlet[k].values;
          for (const unsigned int c : bc.dirichlet[k].components)
            input.labels.emplace_back(1, "xyz"[c]);
          inputs.push_back(input);
        }
      for (unsigned int k = 0; k < bc.neumann.size(); ++k)
        inputs.push_back({"subsection 'Boundary conditions/Neumann " +
                            std::to_string(k + 1) + "', parameter 'Values'",
                          bc.neumann[k].values,
                          axis_labels(bc.neumann[k].values.size())});
      for (unsigned int k = 0; k < parameters.materials.size(); ++k)
        inputs.push_back(
          {"subsection 'Materials/Material " + std::to_string(k + 1) +
             "', parameter 'Body force'",
           parameters.materials[k].body_force,
           axis_labels(parameters.materials[k].body_force.size())});
      const auto &pairs = parameters.contact.pairs;
      for (unsigned int k = 0; k < pairs.size(); ++k)
        {
          const std::string where =
            "subsection 'Contact/Pair " + std::to_string(k + 1) + "'";
          inputs.push_back({where + ", parameter 'Obstacle motion'",
                            pairs[k].obstacle_motion,
                            axis_labels(pairs[k].obstacle_motion.size())});
          inputs.push_back({where + ", parameter 'Obstacle rotation'",
                            pairs[k].obstacle_rotation,
                            axis_labels(pairs[k].obstacle_rotation.size())});
        }
      inputs.push_back({"subsection 'Geometry', parameter 'Refinement region'",
                        {parameters.geometry.refinement_region},
                        {""},
                        "cycle"});
      return inputs;
    }


    // --------------------------------------------------- output directory
    // Why @p directory cannot take the results (empty if it can); creates
    // it when missing.
    std::string
    output_directory_problem(const std::string &directory)
    {
      namespace fs = std::filesystem;
      if (Utilities::trim(directory).empty())
        return "it is empty. Give the directory for the results, e.g. "
               "'results'.";
      const fs::path  path(directory);
      std::error_code error;
      if (fs::exists(path, error) && !fs::is_directory(path, error))
        return "'" + directory +
               "' exists and is not a directory. Give another name, or move "
               "that file away.";
      if (!fs::exists(path, error))
        {
          fs::create_directories(path, error);
          if (error)
            return "cannot create '" + directory + "' (" + error.message() +
                   "). Give a directory that can be created: its parent "
                   "must be a writable directory.";
        }
      // Permissions alone do not tell (root, read-only file systems): try.
      const fs::path probe =
        path / (".signorini_write_test_" + std::to_string(getpid()));
      bool written = false;
      {
        std::ofstream out(probe);
        out << "test\n";
        out.close();
        written = static_cast<bool>(out);
      }
      fs::remove(probe, error);
      if (!written)
        return "'" + directory +
               "' is not writable (no file can be created in it). Give a "
               "writable directory.";
      return "";
    }
  } // namespace


  void
  check_parameter_text(const std::string &text, const std::string &source)
  {
    unsigned int line = 1;
    for (std::size_t i = 0; i < text.size(); ++i)
      {
        if (text[i] == '\0')
          throw InputError(source + ", line " + std::to_string(line) +
                           ": the file contains a NUL byte (a binary file, or "
                           "text saved as UTF-16?). Save the parameter file "
                           "as plain text (ASCII or UTF-8).");
        if (text.compare(i, 3, "\xEF\xBB\xBF") == 0)
          throw InputError(source + ", line " + std::to_string(line) +
                           ": the file contains a UTF-8 byte-order mark "
                           "(bytes EF BB BF), which ParameterHandler reads "
                           "as part of the line. Save the file as UTF-8 "
                           "without BOM (or plain ASCII).");
        if (text[i] == '\n')
          ++line;
      }
    std::istringstream in(text);
    std::string        l;
    while (std::getline(in, l))
      if (!strip_line(l).empty())
        return;
    throw InputError(source +
                     " is empty (no 'set' or 'subsection' line, only blank "
                     "lines and comments). Give the parameters of the run; "
                     "'signorini --print-parameters' lists them all.");
  }


  void
  check_numbered_subsections(const std::string &text,
                             const Counts      &counts,
                             const std::string &source)
  {
    struct Numbered
    {
      const char  *section, *item, *count_entry;
      unsigned int count;
    };
    const Numbered numbered[] = {
      {"Geometry", "Body", "Number of bodies", counts.n_bodies},
      {"Materials", "Material", "Number of materials", counts.n_materials},
      {"Boundary conditions",
       "Dirichlet",
       "Number of Dirichlet conditions",
       counts.n_dirichlet},
      {"Boundary conditions",
       "Neumann",
       "Number of Neumann conditions",
       counts.n_neumann},
      {"Contact", "Pair", "Number of contact pairs", counts.n_pairs}};
    const std::set<std::string> entered = entered_subsections(text);
    for (const auto &n : numbered)
      for (unsigned int k = 1; k <= n.count; ++k)
        {
          const std::string item =
            std::string(n.item) + " " + std::to_string(k);
          if (entered.count(std::string(n.section) + "/" + item))
            continue;
          const std::string range =
            n.count == 1 ? "'" + item + "'" :
                           "'" + std::string(n.item) + " 1' to '" + n.item +
                             " " + std::to_string(n.count) + "'";
          throw InputError(
            "subsection '" + std::string(n.section) + "/" + item +
            "': missing from " + source + ". '" + n.count_entry +
            "' = " + std::to_string(n.count) + " in subsection '" + n.section +
            "' asks for " + range +
            ", and a missing one would silently get the default values. Add "
            "'subsection " +
            item + "' inside 'subsection " + n.section + "', or change '" +
            n.count_entry + "'.");
        }
  }


  std::map<std::string, double>
  parse_function_constants(const std::string &text, const std::string &where)
  {
    const std::string format =
      " Write 'name: value' entries separated by commas, e.g. 'p0: 1e5, R: "
      "0.1'.";
    std::map<std::string, double> constants;
    if (Utilities::trim(text).empty())
      return constants;
    for (const auto &entry : Utilities::split_string_list(text, ','))
      {
        if (entry.empty())
          throw InputError(where + "'" + text +
                           "' has an empty entry (two commas in a row?)." +
                           format);
        const auto colon = entry.find(':');
        if (colon == std::string::npos)
          throw InputError(where + "the entry '" + entry +
                           "' has no ':' and value." + format);
        const std::string name    = Utilities::trim(entry.substr(0, colon));
        const std::string value   = Utilities::trim(entry.substr(colon + 1));
        const std::string problem = constant_name_problem(name);
        if (!problem.empty())
          throw InputError(where + problem + ". " + constant_name_rule());
        if (value.empty())
          throw InputError(where + "'" + name + "' has no value." + format);
        char        *end = nullptr;
        const double v   = std::strtod(value.c_str(), &end);
        if (*end != '\0' || !std::isfinite(v))
          throw InputError(where + "the value '" + value + "' of '" + name +
                           "' is not a finite number (expressions are not "
                           "allowed here). Give a number, e.g. '" +
                           name + ": 1e5'.");
        if (!constants.emplace(name, v).second)
          throw InputError(where + "'" + name +
                           "' is defined twice. Give each constant once.");
      }
    return constants;
  }


  std::vector<std::string>
  axis_labels(const unsigned int n)
  {
    std::vector<std::string> labels;
    for (unsigned int i = 0; i < n; ++i)
      labels.push_back(i < 3 ? std::string(1, "xyz"[i]) :
                               std::to_string(i + 1));
    return labels;
  }


  void
  check_expressions(const std::vector<ExpressionInput> &inputs,
                    const Parameters                   &parameters)
  {
    const auto &constants = parameters.boundary_conditions.constants;
    for (const auto &input : inputs)
      if (parameters.dimension == 2)
        check_expression_input<2>(input, constants);
      else
        check_expression_input<3>(input, constants);
  }


  void
  check_expressions(const Parameters &parameters)
  {
    check_expressions(parameters.dimension == 2 ?
                        expression_inputs<2>(parameters) :
                        expression_inputs<3>(parameters),
                      parameters);
  }


  void
  check_output_directory(const std::string &directory,
                         const MPI_Comm     mpi_communicator)
  {
    std::string problem;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      problem = output_directory_problem(directory);
    problem = Utilities::MPI::broadcast(mpi_communicator, problem, 0);
    if (!problem.empty())
      throw InputError("subsection 'Output', parameter 'Directory': " +
                       problem);
  }


  template <int dim>
  std::unique_ptr<FunctionParser<dim>>
  parse_function(const std::vector<std::string>      &expressions,
                 const std::map<std::string, double> &constants,
                 const std::string                   &where)
  {
    auto f = std::make_unique<FunctionParser<dim>>(expressions.size());
    const std::string variables = dim == 2 ? "x,y,t" : "x,y,z,t";
    std::string       problem;
    {
      CerrCapture silence; // the reason goes into the InputError
      try
        {
          f->initialize(variables, expressions, constants, true);
          // muparser parses on the first evaluation.
          f->value(Point<dim>(), 0);
        }
      catch (const ExceptionBase &e)
        {
          problem = "muparser: " + parser_message(e);
        }
      catch (...)
        {
          problem = "muparser refused it";
        }
    }
    if (problem.empty())
      return f;
    std::string all;
    for (const auto &expression : expressions)
      all += (all.empty() ? "" : "; ") + expression;
    throw InputError(where + ": cannot parse the expression(s) '" +
                     Utilities::trim(all) + "' (variables: " + variables +
                     ", plus 'Function constants'); " + problem);
  }


  template std::unique_ptr<FunctionParser<2>>
  parse_function<2>(const std::vector<std::string> &,
                    const std::map<std::string, double> &,
                    const std::string &);
  template std::unique_ptr<FunctionParser<3>>
  parse_function<3>(const std::vector<std::string> &,
                    const std::map<std::string, double> &,
                    const std::string &);
} // namespace Signorini
