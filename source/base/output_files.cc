#include <deal.II/base/utilities.h>

#include <signorini/base/errors.h>
#include <signorini/base/output_files.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <regex>

namespace Signorini
{
  namespace Postprocess
  {
    namespace
    {
      // "cannot write 'file': No space left on device". A failure without
      // errno (a stream that failed on its own) is reported as an I/O error.
      std::string
      describe(const std::string &what,
               const std::string &filename,
               const int          error_number)
      {
        return what + " '" + filename +
               "': " + std::strerror(error_number != 0 ? error_number : EIO);
      }
    } // namespace


    namespace internal
    {
      void
      FileBuffer::record(const bool failed)
      {
        if (failed && first_error == 0)
          first_error = errno != 0 ? errno : EIO;
      }


      FileBuffer::int_type
      FileBuffer::overflow(int_type c)
      {
        errno              = 0;
        const int_type out = std::filebuf::overflow(c);
        record(traits_type::eq_int_type(out, traits_type::eof()));
        return out;
      }


      std::streamsize
      FileBuffer::xsputn(const char_type *s, std::streamsize n)
      {
        errno                   = 0;
        const std::streamsize m = std::filebuf::xsputn(s, n);
        record(m < n);
        return m;
      }


      int
      FileBuffer::sync()
      {
        errno        = 0;
        const int ok = std::filebuf::sync();
        record(ok != 0);
        return ok;
      }
    } // namespace internal


    std::string
    temporary_name(const std::string &filename)
    {
      return filename + ".tmp";
    }


    std::string
    write_atomically(const std::string                         &filename,
                     const std::function<void(std::ostream &)> &write)
    {
      // In the same directory: a rename across file systems is a copy.
      const std::string    temporary = temporary_name(filename);
      internal::FileBuffer buffer;
      errno = 0;
      if (buffer.open(temporary, std::ios::out | std::ios::trunc) == nullptr)
        return describe("cannot create", temporary, errno);
      std::ostream out(&buffer);
      try
        {
          write(out);
        }
      catch (const std::exception &)
        {
          if (!out.fail())
            {
              buffer.close(); // not a write error: no file, pass it on
              std::remove(temporary.c_str());
              throw;
            }
        }
      out.flush();
      errno               = 0;
      const bool closed   = buffer.close() != nullptr;
      const int  on_close = errno;
      if (out.fail() || !closed || buffer.error() != 0)
        {
          std::remove(temporary.c_str());
          const int error_number =
            buffer.error() != 0 ? buffer.error() : on_close;
          return "cannot write '" + filename + "' (as '" + temporary +
                 "'): " + std::strerror(error_number != 0 ? error_number : EIO);
        }
      errno = 0;
      if (std::rename(temporary.c_str(), filename.c_str()) != 0)
        {
          const int error_number = errno;
          std::remove(temporary.c_str());
          return describe("cannot rename '" + temporary + "' to",
                          filename,
                          error_number);
        }
      return "";
    }


    std::string
    AppendFile::open(const std::string &name, const std::string &header)
    {
      filename      = name;
      complete_size = 0;
      errno         = 0;
      if (buffer.open(filename, std::ios::out | std::ios::trunc) == nullptr)
        return describe("cannot create", filename, errno);
      out.clear();
      return append(header);
    }


    std::string
    AppendFile::append(const std::string &lines)
    {
      // One write per step (the text goes out at the flush, or in one
      // piece if it is larger than the buffer): a kill leaves the file
      // at a line end.
      out << lines;
      out.flush();
      if (out.fail() || buffer.error() != 0)
        return failure();
      complete_size += lines.size();
      return "";
    }


    std::string
    AppendFile::failure()
    {
      const int error_number = buffer.error();
      // What did get out of a failed append is a partial line: cut it off
      // (not possible on every file, e.g. a device: then it stays).
      out.clear();
      buffer.close();
      std::error_code ignored;
      std::filesystem::resize_file(filename, complete_size, ignored);
      return describe("cannot write", filename, error_number);
    }


    std::string
    first_failure(const std::string &local_failure, const MPI_Comm comm)
    {
      if (!Utilities::MPI::logical_or(!local_failure.empty(), comm))
        return "";
      const std::vector<std::string> all =
        Utilities::MPI::all_gather(comm, local_failure);
      for (unsigned int rank = 0; rank < all.size(); ++rank)
        if (!all[rank].empty())
          return rank == 0 ?
                   all[rank] :
                   all[rank] + " (on rank " + std::to_string(rank) + ")";
      return "";
    }


    void
    check_written(const std::string &local_failure,
                  const std::string &directory,
                  const MPI_Comm     comm)
    {
      const std::string first = first_failure(local_failure, comm);
      if (!first.empty())
        throw RunError(first +
                       ". The result files on disk are complete (up "
                       "to the last step written); make room in '" +
                       directory + "' or choose another 'Output/Directory'.");
    }


    unsigned int
    remove_earlier_results(const std::string &directory, std::string &failure)
    {
      // Exactly the names this program writes (and their temporary names
      // left by a killed run): a user's own files in the directory stay.
      static const std::regex ours(
        "((solution|contact_surface)_[0-9]+\\.[0-9]+\\.vtu|"
        "(solution|contact_surface)_[0-9]+\\.pvtu|"
        "(solution|contact_surface)\\.pvd|contact_[0-9]+\\.csv|statistics\\."
        "csv|"
        "newton_history\\.csv)(\\.tmp)?|parameters(\\.echo)?\\.prm\\.tmp");
      namespace fs                     = std::filesystem;
      unsigned int           n_removed = 0;
      std::error_code        error;
      fs::directory_iterator entry(directory, error), end;
      for (; !error && entry != end; entry.increment(error))
        {
          // Regular files only, not symbolic links: a link is the user's.
          std::error_code ignored, removal;
          if (!fs::is_regular_file(entry->symlink_status(ignored)) ||
              !std::regex_match(entry->path().filename().string(), ours))
            continue;
          if (fs::remove(entry->path(), removal))
            ++n_removed;
          else if (removal && failure.empty())
            failure = describe("cannot remove the earlier result",
                               entry->path().string(),
                               removal.value());
        }
      if (error && failure.empty())
        failure = describe("cannot list", directory, error.value());
      return n_removed;
    }


    std::string
    echo_filename(const std::string &directory, const std::string &input_file)
    {
      // equivalent(): the same file by device and inode, whatever path (or
      // link) names it; false if either does not exist.
      const std::string echo = directory + "/parameters.prm";
      std::error_code   ignored;
      if (!input_file.empty() &&
          std::filesystem::equivalent(input_file, echo, ignored))
        return directory + "/parameters.echo.prm";
      return echo;
    }
  } // namespace Postprocess
} // namespace Signorini
