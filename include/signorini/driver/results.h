#ifndef signorini_driver_results_h
#define signorini_driver_results_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/boundary_conditions.h>
#include <signorini/contact/contact_problem.h>
#include <signorini/driver/discrete_system.h>
#include <signorini/postprocess/interface.h>
#include <signorini/postprocess/run_report.h>

#include <memory>
#include <string>
#include <vector>

namespace Signorini
{
  namespace Postprocess
  {
    using namespace dealii;

    /**
     * The results of a run (the "postprocess" step of the data path): the
     * output directory, and at each load step the reactions of the
     * supports, the postprocessors of 'Output/Postprocessors' (plug-ins,
     * interface.h) with their checks, the contact CSV, the step's report
     * on screen and its rows of statistics.csv and newton_history.csv.
     */
    template <int dim>
    class Results
    {
    public:
      /** @p prm: the parameters read (the postprocessors read their own
       * subsections, and the run's are echoed to the output directory). */
      Results(const Parameters                    &parameters,
              ParameterHandler                    &prm,
              const DiscreteSystem<dim>           &system,
              const Bulk::Materials<dim>          &materials,
              const Bulk::BoundaryConditions<dim> &boundary_conditions,
              const Contact::ContactProblem<dim>  &contact,
              RunReport<dim>                      &report,
              TimerOutput                         &timer,
              ConditionalOStream                  &sout);

      /** The output directory: earlier results removed, parameters
       * echoed, newton_history.csv started; then each postprocessor's
       * initialize() with the initial state. */
      void
      prepare_output();

      /** Reactions, postprocessors, VTU and contact CSV, the report of
       * load step @p step at @p time (@p force_level: of the step), the
       * statistics row last (a step listed there has all its files). */
      void
      write(const unsigned int step,
            const double       time,
            const unsigned int iterations,
            const double       force_level);

      /** The checks of the postprocessors at the last written step. */
      const std::vector<CheckResult> &
      checks() const
      {
        return step_checks;
      }

    private:
      void
      compute_reactions();
      /** The balance of each body (a connected part of the mesh): the
       * reactions of its supports, its loads and the contact forces on it
       * cancel (its internal forces sum to zero; in an axisymmetric model
       * along the axis only). A FAIL check naming the body if they do
       * not, to 1e-6 of the force level; nothing printed if they do. */
      void
      check_force_balance();
      /** Displacement component at a point of a body; an InputError
       * naming the point if no cell holds it. */
      double
      point_value(const Point<dim> &p, const unsigned int component) const;
      /** What the postprocessors see of step @p step at @p time, the
       * displacement at the step's start @p start (ghosted). */
      StepData<dim>
      step_data(const unsigned int                   step,
                const double                         time,
                const TrilinosWrappers::MPI::Vector &start);
      void
      run_postprocessors(const unsigned int step, const double time);
      /** The step's report on screen; returns its statistics.csv lines. */
      std::string
      report_step(const unsigned int step,
                  const double       time,
                  const unsigned int iterations);
      /** Collective: a failed write on any rank (@p failure, "" if none
       * here) stops every rank with a RunError naming the file. */
      void
      check_output(const std::string &failure) const;

      const Parameters                    &parameters;
      const ParameterHandler              &prm;
      const DiscreteSystem<dim>           &system;
      const Bulk::Materials<dim>          &materials;
      const Bulk::BoundaryConditions<dim> &boundary_conditions;
      const Contact::ContactProblem<dim>  &contact;
      RunReport<dim>                      &report;
      TimerOutput                         &timer;
      ConditionalOStream                  &sout;

      // The postprocessors (some keep history across steps) and their
      // checks and statistics columns of the last step.
      std::vector<std::unique_ptr<Interface<dim>>> postprocessors;
      std::vector<CheckResult>                     step_checks;
      StatisticsColumns                            postprocessor_columns;
      // Reactions and displacements of the supports, and the force level,
      // of the step being written.
      Bulk::Supports<dim> supports;
      double              force_scale = 0;
    };
  } // namespace Postprocess
} // namespace Signorini

#endif
