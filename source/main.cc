// signorini: the stock executable. The program is in the library
// (app/program.h); a user's plug-ins are loaded by it from the parameter
// file ('Additional shared libraries'), so they need no main() of their own.
#include <signorini/app/program.h>

int
main(int argc, char *argv[])
{
  return Signorini::run_program(argc, argv);
}
