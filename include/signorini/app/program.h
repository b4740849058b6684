#ifndef signorini_app_program_h
#define signorini_app_program_h

/**
 * The program: command line, MPI start-up, exit codes and error messages,
 * in the library so that the stock `signorini` (source/main.cc) and any
 * program of a user are the same program. A user's plug-ins need no
 * program at all: the stock one loads them from the parameter file
 * ('Additional shared libraries', base/shared_libraries.h).
 *
 *   signorini <file.prm>                   run the scene
 *   signorini --check <file.prm>...        read and check, solve nothing
 *   signorini --print-parameters [file]    every parameter with its
 *                                          default and documentation; with
 *                                          a file, its plug-in libraries
 *                                          loaded first
 *   signorini -h | --help                  usage
 *
 * Exit codes: 0 done; 1 bad input or usage (one message naming the
 * parameter); 2 the run stopped (no convergence; the completed steps are
 * written); 4 the run finished but a reference check failed; 3 an
 * unexpected error (a defect: the message names the rank).
 */
namespace Signorini
{
  /** Runs the program on @p argv; returns the exit code. Starts and ends
   * MPI itself (a run needs it; --help and --print-parameters do not). */
  int
  run_program(int argc, char *argv[]);
} // namespace Signorini

#endif
