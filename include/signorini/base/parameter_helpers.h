#ifndef signorini_base_parameter_helpers_h
#define signorini_base_parameter_helpers_h

// Helpers for reading parameters: the parameters of base/ and the
// parameters a plug-in declares and reads itself (numbers, points,
// components, selections).

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <signorini/base/errors.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace Signorini
{
  namespace internal
  {
    using namespace dealii;

    inline std::vector<double>
    to_doubles(const std::string &text)
    {
      return Utilities::string_to_double(
        Utilities::split_string_list(text, ','));
    }

    inline std::vector<unsigned int>
    to_unsigned(const std::string &text)
    {
      std::vector<unsigned int> result;
      for (const int v :
           Utilities::string_to_int(Utilities::split_string_list(text, ',')))
        result.push_back(static_cast<unsigned int>(v));
      return result;
    }

    // Pattern for a comma separated list of doubles: empty or 1..3 numbers.
    inline Patterns::List
    point_pattern(const unsigned int min = 0)
    {
      return Patterns::List(Patterns::Double(), min, 3, ",");
    }

    /** A point of the first dim of @p values (more are ignored); throws
     * InputError naming @p entry if there are fewer. */
    template <int dim>
    Point<dim>
    point_of(const std::vector<double> &values, const std::string &entry)
    {
      if (values.size() < dim)
        throw InputError("parameter '" + entry + "': give " +
                         std::to_string(dim) + " coordinates.");
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = values[d];
      return p;
    }

    /** point_of() of the numbers of entry @p entry of @p prm. */
    template <int dim>
    Point<dim>
    parse_point(const ParameterHandler &prm, const std::string &entry)
    {
      return point_of<dim>(to_doubles(prm.get(entry)), entry);
    }

    /** parse_point() for a direction, normalised; zero is an input error. */
    template <int dim>
    Tensor<1, dim>
    parse_direction(const ParameterHandler &prm, const std::string &entry)
    {
      const Tensor<1, dim> v = parse_point<dim>(prm, entry);
      if (v.norm() == 0.)
        throw InputError("parameter '" + entry + "': give " +
                         std::to_string(dim) +
                         " coordinates of a nonzero vector.");
      return v / v.norm();
    }

    /**
     * The names and values of one selection entry: its pattern and its
     * parsing come from the one list, so that a name cannot be accepted
     * by the pattern and then read as another value.
     */
    template <typename Enum>
    class SelectionTable
    {
    public:
      SelectionTable(
        std::initializer_list<std::pair<const char *, Enum>> entries)
          : entries(entries.begin(), entries.end())
      {
      }

      /** "a|b|c", in the order of the table. */
      Patterns::Selection
      pattern() const
      {
        std::string names;
        for (const auto &[name, value] : entries)
          names += (names.empty() ? "" : "|") + name;
        return Patterns::Selection(names);
      }

      /** The value of @p name (the pattern has accepted it). */
      Enum
      value(const std::string &name) const
      {
        for (const auto &[n, v] : entries)
          if (n == name)
            return v;
        AssertThrow(false, ExcMessage("'" + name + "' is not in the table."));
        return entries.front().second;
      }

    private:
      std::vector<std::pair<std::string, Enum>> entries;
    };

    inline unsigned int
    component_index(const std::string &name)
    {
      if (name == "x")
        return 0;
      if (name == "y")
        return 1;
      return 2;
    }
  } // namespace internal
} // namespace Signorini

#endif
