// The program (app/program.h): command line, MPI start-up, exit codes and
// error messages. The stock executable (source/main.cc) is this function.
#include <deal.II/base/mpi.h>

#include <signorini/app/program.h>
#include <signorini/base/errors.h>
#include <signorini/base/parameters.h>
#include <signorini/driver/simulation.h>

#include <dlfcn.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
  void
  print_usage(std::ostream &out)
  {
    out << "Usage: signorini [options] <file.prm>\n"
           "Quasi-static elasticity and frictional contact with deal.II.\n\n"
           "Options:\n"
           "  -h, --help            print this message\n"
           "  --print-parameters [file.prm]\n"
           "                        print every parameter with its default "
           "value\n"
           "                        and documentation (prm format); with a "
           "file, the\n"
           "                        plug-ins of its 'Additional shared "
           "libraries' too\n"
           "  --check <file.prm>... read each file, build its mesh and "
           "unknowns and\n"
           "                        check the input against them, without "
           "solving\n\n"
           "Run in parallel with: mpirun -np N signorini file.prm\n";
  }


  // The rank under mpirun before MPI is started (OpenMPI, MPICH/PMI):
  // only rank 0 prints the help.
  bool
  first_rank()
  {
    for (const char *name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK"})
      if (const char *rank = std::getenv(name))
        return std::string(rank) == "0";
    return true;
  }


  // A run started without a launcher is an MPI singleton: one process, no
  // messages to other processes. OpenMPI's start-up of a singleton probes
  // every transport (UCX looks for network devices: 0.20 s of the 0.23 s of
  // MPI_Init on this machine) and starts a helper daemon (0.05 s at exit).
  // Neither serves one process: its defaults are the plain point-to-point
  // layer and no daemon, unless the user set them. Under a launcher nothing
  // is changed (a cluster's transport is the user's choice).
  void
  singleton_defaults()
  {
    for (const char *launched :
         {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
      if (std::getenv(launched))
        return;
    setenv("OMPI_MCA_pml", "ob1", 0);
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  }


  // OpenBLAS chooses its kernels from the CPU model when it is loaded,
  // before main(). A model it does not know (Debian 12 ships 0.3.21; recent
  // Xeons) gets the generic 'Prescott' kernels: MUMPS's dense fronts then
  // run 2.4 times slower than with the AVX-512 ones (3D Hertz, 62k DoFs,
  // doc/performance.md). The choice cannot be changed once loaded, so the
  // run (and --help, on standard error) says how to change it;
  // scripts/blas-coretype reads that and sets it.
  std::string
  blas_kernel_note()
  {
    using Name = char *(*)();
    const auto name =
      reinterpret_cast<Name>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
    if (name == nullptr || std::getenv("OPENBLAS_CORETYPE") != nullptr ||
        std::string(name()) != "Prescott")
      return "";
    __builtin_cpu_init();
    const char *better = __builtin_cpu_supports("avx512f") ? "SkylakeX" :
                         __builtin_cpu_supports("avx2")    ? "Haswell" :
                                                             nullptr;
    if (better == nullptr)
      return "";
    return std::string("signorini: note: OpenBLAS does not know this CPU and "
                       "runs its generic 'Prescott' kernels; the direct "
                       "solver runs faster with\n  export "
                       "OPENBLAS_CORETYPE=") +
           better + "\n(scripts/run and scripts/benchmark set it).\n";
  }


  // signorini --check: each file read and checked against its mesh and
  // unknowns, nothing solved; one line per file, exit code 1 if any input
  // is refused.
  int
  check_files(const std::vector<std::string> &files, const bool root)
  {
    int code = 0;
    for (const auto &file : files)
      try
        {
          Signorini::run_from_file(file, MPI_COMM_WORLD, true);
          if (root)
            std::cout << "\nsignorini: the input of " << file
                      << " is complete and consistent with its mesh "
                         "(--check: nothing solved)."
                      << std::endl;
        }
      catch (const Signorini::InputError &e)
        {
          if (root)
            std::cerr << "\nsignorini: input error in " << file << ": "
                      << e.what() << std::endl;
          code = 1;
        }
    return code;
  }


  // signorini --print-parameters [file.prm]: every parameter, one
  // subsection of each numbered kind (Counts::listing()); with a file, its
  // plug-in libraries loaded first (the file is read and checked), so that
  // their names and subsections are listed too.
  int
  print_parameters(const std::vector<std::string> &files)
  {
    using namespace dealii;
    if (files.size() > 1)
      {
        if (first_rank())
          print_usage(std::cerr);
        return 1;
      }
    try
      {
        if (!files.empty())
          {
            ParameterHandler file_prm;
            Signorini::read_parameters(files[0], file_prm);
          }
      }
    catch (const Signorini::InputError &e)
      {
        if (first_rank())
          std::cerr << "\nsignorini: input error: " << e.what() << std::endl;
        return 1;
      }
    ParameterHandler prm;
    Signorini::Parameters::declare_parameters(prm,
                                              Signorini::Counts::listing());
    if (first_rank())
      prm.print_parameters(std::cout, ParameterHandler::PRM);
    return 0;
  }


  // A run or --check, under MPI: the errors each get one message (on rank
  // 0) and their exit code.
  int
  run_under_mpi(int argc, char *argv[], const std::vector<std::string> &args)
  {
    using namespace dealii;
    singleton_defaults();
    Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    if (root)
      std::cout << blas_kernel_note() << std::flush;
    try
      {
        if (args[0] == "--check")
          return check_files({args.begin() + 1, args.end()}, root);
        // A run whose reference checks failed kept its results but did not
        // reproduce its reference: exit code 4 for scripts and CI.
        if (Signorini::run_from_file(args[0], MPI_COMM_WORLD) > 0)
          return 4;
      }
    catch (const Signorini::InputError &e)
      {
        if (root)
          std::cerr << "\nsignorini: input error: " << e.what() << std::endl;
        return 1;
      }
    catch (const Signorini::RunError &e)
      {
        if (root)
          std::cerr << "\nsignorini: run stopped: " << e.what() << std::endl;
        return 2;
      }
    catch (const std::exception &e)
      {
        std::cerr << "\nsignorini: unexpected error on rank "
                  << Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) << ":\n"
                  << e.what() << std::endl;
        MPI_Abort(MPI_COMM_WORLD, 3);
      }
    return 0;
  }
} // namespace


namespace Signorini
{
  int
  run_program(int argc, char *argv[])
  {
    // Usage and the parameter list need no MPI: answered before MPI starts
    // (its start-up was 0.3 of the 0.56 s of 'signorini --help').
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "-h" || args[0] == "--help")
      {
        if (first_rank())
          {
            print_usage(args.empty() ? std::cerr : std::cout);
            std::cerr << blas_kernel_note();
          }
        return args.empty() ? 1 : 0;
      }
    if (args[0] == "--print-parameters")
      return print_parameters({args.begin() + 1, args.end()});
    // --check takes one or more files (a directory of scenes in one start).
    const bool check_only = args.size() >= 2 && args[0] == "--check";
    if (!check_only && (args.size() != 1 || args[0][0] == '-'))
      {
        if (first_rank())
          print_usage(std::cerr);
        return 1;
      }
    return run_under_mpi(argc, argv, args);
  }
} // namespace Signorini
