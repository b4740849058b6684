#ifndef signorini_base_output_files_h
#define signorini_base_output_files_h

#include <deal.II/base/mpi.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>

/**
 * Result files that are complete whenever they are on disk, after a kill
 * or a full disk (user_guide.md, "How output is kept"):
 *  - a per-step file is written under a temporary name next to it and
 *    renamed into place after a checked close (rename is atomic on POSIX):
 *    readers and a killed run see the old complete file or the new one;
 *  - a table that grows by one step at a time (statistics.csv,
 *    newton_history.csv) is appended and flushed once per step, not
 *    rewritten: a kill costs at most the step being written, and the cost
 *    per step stays constant.
 * Every write is checked; a failure comes back as a message naming the
 * file and the reason (errno), which the caller turns into a RunError on
 * all ranks (first_failure()).
 */
namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    namespace internal
    {
      /**
       * A file buffer that keeps the errno of its first failed write, flush
       * or close: by the time the stream reports the failure, an exception
       * (deal.II's writers throw ExcIO) or later calls may have changed
       * errno, and the message must say why the write failed.
       */
      class FileBuffer : public std::filebuf
      {
      public:
        /** errno of the first failure, 0 if none. */
        int
        error() const
        {
          return first_error;
        }

      protected:
        int_type
        overflow(int_type c) override;
        std::streamsize
        xsputn(const char_type *s, std::streamsize n) override;
        int
        sync() override;

      private:
        void
        record(const bool failed);

        int first_error = 0;
      };
    } // namespace internal

    /** The temporary name of @p filename while it is being written. */
    std::string
    temporary_name(const std::string &filename);

    /**
     * Writes @p filename with @p write (given the stream) under
     * temporary_name() and renames it into place. Returns "" on success,
     * else why it failed (the temporary file is removed and an earlier
     * @p filename is left as it was). An exception of @p write is a
     * failure of the write if the stream failed (deal.II's writers throw
     * ExcIO then), else it is passed on.
     */
    std::string
    write_atomically(const std::string                         &filename,
                     const std::function<void(std::ostream &)> &write);

    /**
     * A file that grows by whole lines: created (truncated) with its
     * header, then appended and flushed after every step. After a failed
     * append the file is cut back to its last complete line where the
     * file system allows it.
     */
    class AppendFile
    {
    public:
      /** Creates @p filename with @p header (whole lines). "" or why not. */
      std::string
      open(const std::string &filename, const std::string &header);

      /** Appends @p lines (whole lines) and flushes. "" or why not. */
      std::string
      append(const std::string &lines);

      bool
      is_open() const
      {
        return buffer.is_open();
      }

    private:
      std::string
      failure();

      std::string          filename;
      internal::FileBuffer buffer;
      std::ostream         out{&buffer};
      std::uintmax_t       complete_size = 0; // up to the last full line
    };

    /**
     * Collective: the first non-empty @p local_failure over the ranks
     * (with the rank if it is not rank 0), "" if every rank succeeded.
     * Every rank gets the same answer, so that all stop together.
     */
    std::string
    first_failure(const std::string &local_failure, const MPI_Comm comm);

    /**
     * Collective: where a rank's write failed (@p local_failure not
     * empty), throws RunError with the first failure, saying that the
     * files on disk are complete and what to do about @p directory.
     */
    void
    check_written(const std::string &local_failure,
                  const std::string &directory,
                  const MPI_Comm     comm);

    /**
     * Removes the files of an earlier run from @p directory: regular files
     * named like this program's results (solution_NNNN.R.vtu,
     * solution_NNNN.pvtu, solution.pvd, the same of contact_surface,
     * contact_NNNN.csv, statistics.csv,
     * newton_history.csv, and their temporary names), nothing else.
     * Returns how many were removed; @p failure says which could not be.
     */
    unsigned int
    remove_earlier_results(const std::string &directory, std::string &failure);

    /**
     * The name of the parameter echo in @p directory: parameters.prm, or
     * parameters.echo.prm if parameters.prm there is the input file
     * @p input_file itself (the echo must not overwrite it).
     */
    std::string
    echo_filename(const std::string &directory, const std::string &input_file);
  } // namespace Postprocess
} // namespace Signorini

#endif
