// Parallel VTU time series written through temporary names.
#include <deal.II/base/utilities.h>

#include <signorini/base/output_files.h>
#include <signorini/postprocess/vtu_series.h>

#include <algorithm>

namespace Signorini
{
  namespace Postprocess
  {
    VtuSeries::VtuSeries(const std::string &directory, const std::string &stem)
        : directory(directory)
        , stem(stem)
    {
    }


    template <int dim, int spacedim>
    void
    VtuSeries::write(DataOutInterface<dim, spacedim> &out,
                     const unsigned int               step,
                     const double                     time,
                     const MPI_Comm                   comm)
    {
      DataOutBase::VtkFlags flags;
      flags.compression_level = DataOutBase::VtkFlags::best_speed;
      out.set_flags(flags);
      const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int digits =
        Utilities::needed_digits(std::max(0, static_cast<int>(n_ranks) - 1));
      const std::string name  = stem + "_" + Utilities::int_to_string(step, 4);
      const std::string path  = directory + "/";
      const auto        piece = [&](const unsigned int r) {
        return name + "." + Utilities::int_to_string(r, digits) + ".vtu";
      };
      check_written(write_atomically(path + piece(rank),
                                     [&](std::ostream &stream) {
                                       out.write_vtu(stream);
                                     }),
                    directory,
                    comm);
      std::string failure;
      if (rank == 0)
        {
          std::vector<std::string> pieces;
          for (unsigned int r = 0; r < n_ranks; ++r)
            pieces.push_back(piece(r));
          failure =
            write_atomically(path + name + ".pvtu", [&](std::ostream &stream) {
              out.write_pvtu_record(stream, pieces);
            });
          if (failure.empty())
            {
              records.emplace_back(time, name + ".pvtu");
              failure = write_atomically(
                path + stem + ".pvd", [&](std::ostream &stream) {
                  DataOutBase::write_pvd_record(stream, records);
                });
            }
        }
      check_written(failure, directory, comm);
    }


    template void
    VtuSeries::write(DataOutInterface<1, 2> &,
                     const unsigned int,
                     const double,
                     const MPI_Comm);
    template void
    VtuSeries::write(DataOutInterface<2, 2> &,
                     const unsigned int,
                     const double,
                     const MPI_Comm);
    template void
    VtuSeries::write(DataOutInterface<2, 3> &,
                     const unsigned int,
                     const double,
                     const MPI_Comm);
    template void
    VtuSeries::write(DataOutInterface<3, 3> &,
                     const unsigned int,
                     const double,
                     const MPI_Comm);
  } // namespace Postprocess
} // namespace Signorini
