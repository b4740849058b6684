#ifndef signorini_base_input_checks_h
#define signorini_base_input_checks_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>

#include <signorini/base/parameters.h>

#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

/**
 * Checks of the input that ParameterHandler's patterns cannot express, run
 * before any expensive work so that a mistake stops the run with one
 * InputError naming subsection, parameter and what to change (and never
 * later with a crash or a silent default):
 *
 * - the raw text of the parameter file (empty, byte-order mark, NUL byte),
 * - numbered subsections that a 'Number of ...' entry asks for but the file
 *   never enters (ParameterHandler would silently use the defaults),
 * - 'Function constants' (names muparser or deal.II's FunctionParser would
 *   refuse with an uncaught exception, or silently shadow),
 * - every component of every expression (parsed and evaluated once),
 * - the output directory (on rank 0, the verdict broadcast).
 */
namespace Signorini
{
  /**
   * Captures std::cerr while it lives. deal.II prints muparser's and the
   * mesh readers' diagnostics to std::cerr, on every rank, before it
   * throws; a check wraps such calls and puts the reason into its one
   * InputError instead.
   */
  class CerrCapture
  {
  public:
    CerrCapture()
        : old(std::cerr.rdbuf(sink.rdbuf()))
    {
    }
    ~CerrCapture()
    {
      std::cerr.rdbuf(old);
    }
    CerrCapture(const CerrCapture &) = delete;
    CerrCapture &
    operator=(const CerrCapture &) = delete;

    std::string
    text() const
    {
      return sink.str();
    }

  private:
    std::ostringstream sink;
    std::streambuf    *old;
  };

  /**
   * Refuses a parameter text that is empty (no 'set' or 'subsection' line),
   * holds a UTF-8 byte-order mark or a NUL byte; @p source names the file.
   */
  void
  check_parameter_text(const std::string &text, const std::string &source);

  /**
   * Refuses a numbered subsection (Body k, Material k, Dirichlet k,
   * Neumann k, Pair k) that @p counts asks for but @p text never enters.
   */
  void
  check_numbered_subsections(const std::string &text,
                             const Counts      &counts,
                             const std::string &source);

  /**
   * Parses 'Function constants' ("name: value, name: value"), refusing empty
   * entries, missing or non-numeric values, duplicate names and names that
   * muparser cannot define or that clash with a variable or a built-in
   * function. @p where starts the message ("subsection '...', parameter
   * '...': ").
   */
  std::map<std::string, double>
  parse_function_constants(
    const std::string &text,
    const std::string &where =
      "subsection 'Boundary conditions', parameter 'Function constants': ");

  /**
   * Parses and evaluates every component of every expression of the input
   * once, at the origin and t = 0 (a non-finite value is not an error: a
   * load may be 1/t).
   */
  void
  check_expressions(const Parameters &parameters);

  /** One expression entry of a parameter file: where it is (subsection
   * and parameter, for the message), its components and their names. */
  struct ExpressionInput
  {
    std::string              where;
    std::vector<std::string> expressions;
    std::vector<std::string> labels;
    // The variable after x, y(, z): the time t, the refinement cycle of
    // 'Refinement region', or none ("").
    std::string time_variable = "t";
  };

  /** Component names x, y, z (then numbers) for @p n expressions. */
  std::vector<std::string>
  axis_labels(const unsigned int n);

  /** check_expressions() for the entries @p inputs of a plug-in's own
   * parameters, with the 'Function constants' of @p parameters. */
  void
  check_expressions(const std::vector<ExpressionInput> &inputs,
                    const Parameters                   &parameters);

  /**
   * Refuses an output directory that is empty, exists as something other
   * than a directory, cannot be created or is not writable. Checked (and
   * created) on rank 0 of @p mpi_communicator; every rank throws the same
   * InputError.
   */
  void
  check_output_directory(const std::string &directory,
                         const MPI_Comm     mpi_communicator);

  /**
   * A FunctionParser of x, y(, z) and t with the 'Function constants'
   * @p constants, one component per entry of @p expressions. The
   * expressions were checked when the parameters were read
   * (check_expressions()); one that still does not parse is an InputError
   * naming @p where (a subsection and parameter).
   */
  template <int dim>
  std::unique_ptr<FunctionParser<dim>>
  parse_function(const std::vector<std::string>      &expressions,
                 const std::map<std::string, double> &constants,
                 const std::string                   &where);
} // namespace Signorini

#endif
