#ifndef signorini_postprocess_run_report_h
#define signorini_postprocess_run_report_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <signorini/base/output_files.h>
#include <signorini/base/parameters.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/postprocess/interface.h>

#include <array>
#include <string>
#include <vector>

namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    /** Counts of the current load step over all its sub-steps and
     * geometric iterations, filled in by the Newton solves. */
    struct StepCounts
    {
      unsigned int cycle_detections = 0; // status cycles (anti-cycling)
      unsigned int points_frozen    = 0; // frozen or frozen again
      unsigned int points_released  = 0; // released at convergence
      unsigned int line_searches    = 0;
      unsigned int step_cuts        = 0;
      // Iterative linear solver: iterations in the step, most per solve.
      unsigned int krylov_iterations = 0, krylov_max = 0;
    };

    /** The results of a written load step that its report shows. */
    template <int dim>
    struct StepResults
    {
      unsigned int step;
      double       time;
      unsigned int newton_iterations;
      double       u_max; // largest |u_i| at the nodes [m]
      // Per Dirichlet condition: the force of the supports [N], the mean
      // displacement it prescribes and which components it constrains.
      const std::vector<Tensor<1, dim>>        &reactions;
      const std::vector<Tensor<1, dim>>        &dirichlet_displacement;
      const std::vector<std::array<bool, dim>> &dirichlet_components;
      // Per contact pair (empty without contact), forces below round-off
      // set to zero.
      const std::vector<typename Contact::ContactProblem<dim>::PairSummary>
                                     &pairs;
      const StatisticsColumns        &columns; // of the postprocessors
      const std::vector<CheckResult> &checks;  // of the postprocessors
    };

    /**
     * What a run reports besides its fields: per written load step the
     * report on screen (Newton and Krylov iterations, anti-cycling,
     * reactions, contact pairs, reference checks) and the step's row of
     * statistics.csv (the run's own columns, then the postprocessors');
     * at the end the run summary (Newton iterations per step, cuts, status
     * cycles) and the count of failed checks.
     */
    template <int dim>
    class RunReport
    {
    public:
      /** @p pcout: per-step output (off when quiet); @p sout: what even a
       * quiet run prints (rank 0). */
      RunReport(const Parameters   &parameters,
                ConditionalOStream &pcout,
                ConditionalOStream &sout,
                const MPI_Comm      comm);

      /** The counts of the load step under way. */
      StepCounts counts;

      /** At the start of a load step: its counts from zero (the Krylov
       * counts restart after each report). */
      void
      start_step();

      /** Points opened early by the release extrapolation (run total). */
      void
      add_early_releases(const unsigned int n)
      {
        early_releases += n;
      }

      /** Prints the report of a written step, keeps its checks for the
       * end of a quiet run, and returns its statistics.csv lines (with the
       * header at the first step). A RunError if the postprocessors'
       * columns differ from the first step's. */
      std::string
      report_step(const StepResults<dim> &results);

      /** Appends @p lines to statistics.csv (the first call creates it);
       * collective: a failed write stops every rank. */
      void
      append_statistics(const std::string &lines);

      /** The run summary: the last step's checks (quiet runs), Newton
       * iterations per step, cuts and anti-cycling counts; @p stopped_in:
       * the load step the run stopped in (0: it finished). */
      void
      print_run_summary(const unsigned int n_written,
                        const unsigned int stopped_in);

      /** One more failed check (the Jacobian check of the run). */
      void
      count_failed_check()
      {
        ++n_failed_checks;
      }
      /** Failed checks over the run. */
      unsigned int
      failed_checks() const
      {
        return n_failed_checks;
      }

      /** Where the Newton iterates being logged belong: load step, target
       * time of the solve, geometric iteration. */
      struct IteratePosition
      {
        unsigned int step = 0, geometric = 0;
        double       time = 0;
      };
      IteratePosition position;

      /** Creates newton_history.csv in the output directory with its
       * header (rank 0; 'Write CSV'). Returns "" or why not. */
      std::string
      open_newton_history();

      /** The log of a Newton iterate: its row on screen (with contact:
       * the block residuals relative to @p force_level and the statuses of
       * @p contact; without contact (nullptr) in verbose runs only) and its
       * newton_history.csv row; its status cycles and freezes count into
       * the step. */
      void
      log_iterate(const unsigned int                iteration,
                  const std::array<double, 3>      &block,
                  const double                      force_level,
                  const Contact::ContactStatistics *contact,
                  const bool                        friction,
                  const bool                        converged);

      /** Appends the Newton rows since the last call to
       * newton_history.csv (collective: a failed write stops every rank).
       * Every iterate goes there, also those of attempts cut later. */
      void
      append_newton_history();

    private:
      void
      print_step_counts(const StepResults<dim> &results);
      void
      print_pair_report(const StepResults<dim> &results) const;
      std::vector<std::string>
      statistics_row(const StepResults<dim> &results);
      void
      add_postprocessor_columns(const StatisticsColumns  &columns,
                                const bool                header,
                                std::vector<std::string> &row);

      const Parameters   &parameters;
      ConditionalOStream &pcout;
      ConditionalOStream &sout;
      MPI_Comm            comm;

      std::vector<std::string> statistics_header;
      AppendFile               statistics_file; // rank 0, 'Write CSV'
      // newton_history.csv (rank 0, 'Write CSV') and its rows not yet
      // appended (one per iterate).
      AppendFile               history_file;
      std::vector<std::string> newton_rows;
      // The checks of the last written step, and failed checks so far.
      std::vector<std::string> last_checks;
      unsigned int             n_failed_checks   = 0;
      double                   last_written_time = 0;
      // Run totals: Newton iterations of every written step, cuts,
      // anti-cycling, line searches, early releases.
      std::vector<unsigned int> step_iterations;
      unsigned int              run_cuts = 0, run_cycles = 0, run_frozen = 0,
                   run_released = 0, run_line_searches = 0, early_releases = 0;
    };
  } // namespace Postprocess
} // namespace Signorini

#endif
