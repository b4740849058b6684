// A body shape defined outside the library, built as a module that the
// stock `signorini` loads ('Additional shared libraries'; doc/extending.md,
// B.1): 'graded block', a block whose cells shrink geometrically towards
// its top face (y+), where contact usually is. No main():
// tests/shape_plugin.prm.in runs it in the B1 contact patch test (exact
// solution), and the invariant row shape_plugin_graded_block_block checks
// that with 'Growth = 1' it gives the library's 'block' to round-off.
#include <deal.II/grid/grid_generator.h>

#include <signorini/geometry/shapes/interface.h>

#include <cmath>

namespace Example
{
  using namespace dealii;

  template <int dim>
  class GradedBlock : public Signorini::Geometry::Shapes::Interface<dim>
  {
  public:
    // Its own parameters, in subsection 'Body k/Graded block'.
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Graded block");
      prm.declare_entry("Lower corner",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "Lower corner [m].");
      prm.declare_entry("Upper corner",
                        "1, 1, 1",
                        Patterns::List(Patterns::Double(), 0, 3, ","),
                        "Upper corner [m].");
      prm.declare_entry("Subdivisions",
                        "1, 1, 1",
                        Patterns::List(Patterns::Integer(1, 1000), 1, 3, ","),
                        "Cells per coordinate direction.");
      prm.declare_entry("Growth",
                        "1",
                        Patterns::Double(1, 10),
                        "Size ratio of neighbouring cells along y, growing "
                        "away from the top face (1: uniform).");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm, const std::string &) override
    {
      prm.enter_subsection("Graded block");
      lower =
        Signorini::Geometry::Shapes::parse_point<dim>(prm, "Lower corner");
      upper =
        Signorini::Geometry::Shapes::parse_point<dim>(prm, "Upper corner");
      const auto n = Utilities::string_to_int(
        Utilities::split_string_list(prm.get("Subdivisions"), ','));
      growth = prm.get_double("Growth");
      prm.leave_subsection();
      if (n.size() < dim)
        throw Signorini::InputError("parameter 'Subdivisions': give " +
                                    std::to_string(dim) + " numbers.");
      for (unsigned int d = 0; d < dim; ++d)
        {
          if (!(upper[d] > lower[d]))
            throw Signorini::InputError(
              "parameter 'Upper corner': it must exceed 'Lower corner' in "
              "every coordinate.");
          cells[d] = n[d];
        }
    }

    double
    n_cells(std::string &entry) const override
    {
      entry        = "Subdivisions";
      double total = 1;
      for (unsigned int d = 0; d < dim; ++d)
        total *= cells[d];
      return total;
    }

    // Cell sizes per direction: uniform, and along y a geometric series
    // from the top face down (the top cell the smallest).
    void
    build(Triangulation<dim> &tria) const override
    {
      std::vector<std::vector<double>> steps(dim);
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double length = upper[d] - lower[d];
          for (unsigned int i = 0; i < cells[d]; ++i)
            steps[d].push_back(d != 1 ?
                                 length / cells[d] :
                                 std::pow(growth, double(cells[d] - 1 - i)));
        }
      double sum = 0;
      for (const double h : steps[1])
        sum += h;
      for (double &h : steps[1])
        h *= (upper[1] - lower[1]) / sum;
      // colorize: the faces x-, x+, y-, y+ (, z-, z+) are groups 0, 1, ...
      GridGenerator::subdivided_hyper_rectangle(
        tria, steps, lower, upper, true);
    }

    unsigned int
    n_face_groups() const override
    {
      return 2 * dim;
    }

  private:
    Point<dim>   lower, upper;
    unsigned int cells[dim] = {};
    double       growth     = 1;
  };
} // namespace Example

SIGNORINI_REGISTER_SHAPE(Example::GradedBlock,
                         "graded block",
                         "block with cells shrinking geometrically towards "
                         "its top face (tests/plugins/graded_block.cc)")
