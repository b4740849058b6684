#ifndef signorini_postprocess_interface_h
#define signorini_postprocess_interface_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>

#include <signorini/base/parameters.h>
#include <signorini/base/plugins.h>
#include <signorini/material/history.h>
#include <signorini/material/interface.h>

#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    template <int dim>
    class ContactProblem;
  }

  /**
   * Postprocessors: what runs after every written load step (the plug-in
   * family of 'Output/Postprocessors', after ASPECT's postprocessors). A
   * postprocessor sees the converged state of the step (StepData) and
   * returns its checks: each is printed as a "reference check:" line, and
   * a failed one makes the run exit with a non-zero code. It may also write
   * files of its own (through write_atomically(), output_files.h).
   *
   * A new postprocessor: a class derived from Interface<dim> with a static
   * declare_parameters(ParameterHandler &) (its own subsection inside
   * 'Output', named after it, capitalised), registered in its source file
   * with SIGNORINI_REGISTER_POSTPROCESSOR(Class, "name", "description"),
   * and listed by name in 'Output/Postprocessors' (doc/extending.md). The
   * library registers 'reference checks': the checks of its subsection
   * 'Output/Reference checks' against exact solutions and closed forms.
   */
  namespace Postprocess
  {
    using namespace dealii;

    /** One check: what was compared, the numbers, the verdict, and the
     * line printed after "reference check: ". */
    struct CheckResult
    {
      static constexpr double none = std::numeric_limits<double>::quiet_NaN();
      std::string             what;             // the quantity checked
      double                  value     = none; // where one number is compared
      double                  reference = none; // with its reference
      double                  error = none; // the measure against the tolerance
      double                  tolerance = none;
      bool        checked = true; // false: does not apply at this step
      bool        pass    = true;
      std::string text;
    };

    /**
     * Columns a postprocessor adds to the step's row of statistics.csv,
     * after the run's own (step, Newton iterations, reactions, contact
     * forces, ...): named values, the same names at every step (the header
     * is written with the first step; a row whose names differ stops the
     * run).
     */
    class StatisticsColumns
    {
    public:
      /** Adds the column @p name (unique within the row) with @p value. */
      void
      add(const std::string &name, const double value)
      {
        for (const auto &column : entries)
          if (column.name == name)
            throw RunError("postprocessor '" + owner +
                           "': the statistics column '" + name +
                           "' was added twice in one step; give each "
                           "column its own name.");
        entries.push_back({name, value, owner});
      }

      struct Column
      {
        std::string name;
        double      value;
        std::string owner; // the postprocessor that added it
      };

      const std::vector<Column> &
      columns() const
      {
        return entries;
      }

      /** Called by the run: clear() for the row of a new step,
       * set_owner() before each postprocessor's execute(). */
      void
      clear()
      {
        entries.clear();
      }

      void
      set_owner(const std::string &name)
      {
        owner = name;
      }

    private:
      std::vector<Column> entries;
      std::string         owner;
    };

    /** The converged state of a written load step. Vectors are ghosted;
     * functions taking a point are collective (every rank calls them). */
    template <int dim>
    struct StepData
    {
      unsigned int                         step;
      double                               time;
      MPI_Comm                             mpi_communicator;
      const Parameters                    &parameters;
      const Mapping<dim>                  &mapping;
      const DoFHandler<dim>               &dof_handler; // displacement
      const TrilinosWrappers::MPI::Vector &displacement;
      // The displacement at the start of the (sub)step, from which the
      // contact law measures slip increments.
      const TrilinosWrappers::MPI::Vector &displacement_step_start;
      const std::map<types::material_id,
                     std::unique_ptr<Material::Interface<dim>>> &materials;
      // The materials' committed history at the bulk quadrature points.
      const Material::History<dim> &history;
      // nullptr without contact pairs; else with the system vector
      // (u | lambda | Lambda) of its multipliers.
      const Contact::ContactProblem<dim>  *contact;
      const TrilinosWrappers::MPI::Vector &state;
      // The force level of the step: the largest internal or external
      // force norm, the scale of a force that is zero up to round-off.
      double force_level;
      // The displacement component c at point p (lowest rank's cell).
      std::function<double(const Point<dim> &, const unsigned int)>
        displacement_at;
      // Where the postprocessors add their columns of statistics.csv.
      StatisticsColumns &statistics;
    };

    template <int dim>
    class Interface
    {
    public:
      virtual ~Interface() = default;

      /** Reads the postprocessor's own subsection of 'Output' (the current
       * subsection of @p prm is 'Output'); @p parameters are the run's. */
      virtual void
      parse_parameters(const Parameters &parameters, ParameterHandler &prm)
      {
        (void)parameters;
        (void)prm;
      }

      /** Before the first load step is solved, on every rank, with the
       * initial state (step 0): where the postprocessor checks its
       * parameters against the scene (a point in a body, a quantity some
       * material has), so that a wrong one stops the run before a step is
       * solved. */
      virtual void
      initialize(const StepData<dim> &data)
      {
        (void)data;
      }

      /** After each written load step, on every rank. */
      virtual std::vector<CheckResult>
      execute(const StepData<dim> &data) = 0;
    };

    /** The registry of the family (dim 2 and 3 share the names). */
    template <int dim>
    using Registry = Plugins::Registry<Interface<dim>>;

    /** Declares 'Postprocessors' and the postprocessors' own subsections
     * in the current subsection ('Output'). */
    void
    declare_parameters(ParameterHandler &prm);

    /** The postprocessors listed in 'Output/Postprocessors', in that
     * order, with their parameters read. Throws InputError where subsection
     * 'Output/Reference checks' gives references but 'reference checks' is
     * not listed. */
    template <int dim>
    std::vector<std::unique_ptr<Interface<dim>>>
    make_postprocessors(const Parameters &parameters, ParameterHandler &prm);
  } // namespace Postprocess
} // namespace Signorini

/**
 * Registers the postprocessor class template @p classname (derived from
 * Postprocess::Interface<dim>, default constructible, with a static
 * declare_parameters(ParameterHandler &)) under @p name for 2D and 3D.
 */
#define SIGNORINI_REGISTER_POSTPROCESSOR(classname, name, description)      \
  namespace                                                                 \
  {                                                                         \
    const ::Signorini::Plugins::                                            \
      Registration<::Signorini::Postprocess::Interface<2>, classname<2>>    \
        SIGNORINI_PLUGIN_NAME(signorini_postprocess_2_)(name, description); \
    const ::Signorini::Plugins::                                            \
      Registration<::Signorini::Postprocess::Interface<3>, classname<3>>    \
        SIGNORINI_PLUGIN_NAME(signorini_postprocess_3_)(name, description); \
  }

#endif
