#ifndef signorini_base_errors_h
#define signorini_base_errors_h

#include <stdexcept>

namespace Signorini
{
  /**
   * Everything a user can get wrong in the input ends in this exception; its
   * message names the subsection/parameter and what to change. main() prints
   * it once and exits non-zero.
   */
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** A run that must stop (not a user input problem): says where and why.
   * main() prints it once and exits non-zero. */
  class RunError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** The linearised system of a Newton iterate could not be solved (a
   * factorisation that met a singular tangent, a Krylov solve that did not
   * converge). Newton reports the iterate as failed, so the load step is
   * cut like any other failed step; the message says what failed. */
  class LinearSolveError : public RunError
  {
  public:
    using RunError::RunError;
  };
} // namespace Signorini

#endif
