// An element inverted at a vertex while its Gauss points are not
// (Bulk::Assembler::deformation_valid). One unit cell, 'Kinematics =
// finite strain', neo-Hookean; the vertex opposite the origin is moved to
// (a, ..., a), the others stay. The map's Jacobian at that vertex is
// 2a - 1 in 2D and 3a - 2 in 3D (the 2D one is affine, 1 + (a - 1)(xi +
// eta)); at the Gauss points of the cell (degree + 1 per direction) it
// stays positive for the a used below. Facts checked:
//  * the Gauss points are positive (computed here with FEValues), the
//    vertex is not: the assembler must count the cell as inverted, with
//    its smallest det F the vertex value and its centre, and the residual
//    must be NaN (Newton then rejects the iterate);
//  * with a a little larger every point is positive: the residual is
//    finite and no cell is counted.
// Q1 and Q2 (the same bilinear field at the Q2 nodes) in 2D, Q1 in 3D.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/assembler.h>
#include <signorini/material/history.h>

#include "bulk_helpers.h"

#include <cmath>
#include <fstream>
#include <iomanip>

using namespace dealii;

namespace
{
  std::string
  parameter_text(const unsigned int dim, const unsigned int degree)
  {
    return "set Dimension = " + std::to_string(dim) +
           "\nsubsection Finite element\n set Degree = " +
           std::to_string(degree) +
           "\nend\n"
           "subsection Geometry\n subsection Body 1\n  set Shape = block\n"
           " end\nend\n"
           "subsection Materials\n subsection Material 1\n"
           "  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
           "  set Model = neo-Hookean\n  set Kinematics = finite strain\n"
           " end\nend\n"
           "subsection Boundary conditions\n"
           " set Number of Dirichlet conditions = 1\n"
           " subsection Dirichlet 1\n  set Boundary id = 0\n end\nend\n";
  }


  // u(X) = (a - 1) X_0 X_1 (X_2) along every component: the vertex at
  // (1, ..., 1) moves to (a, ..., a), the others stay.
  template <int dim>
  class CornerPush : public Function<dim>
  {
  public:
    explicit CornerPush(const double a)
        : Function<dim>(dim)
        , a(a)
    {
    }
    double
    value(const Point<dim> &p, const unsigned int) const override
    {
      double product = a - 1;
      for (unsigned int d = 0; d < dim; ++d)
        product *= p[d];
      return product;
    }

  private:
    const double a;
  };


  template <int dim>
  void
  check(std::ofstream     &out,
        const unsigned int degree,
        const double       a,
        const bool         inverted)
  {
    ParameterHandler            prm;
    const Signorini::Parameters parameters =
      Signorini::read_parameters_from_string(parameter_text(dim, degree), prm);
    Triangulation<dim> tria;
    GridGenerator::hyper_cube(tria, 0, 1);
    tria.begin_active()->set_material_id(1);
    const test_helpers::BulkSpace<dim> space(tria, degree, parameters, prm);
    const auto &[fe, dof_handler, mapping, materials] = space;
    std::vector<std::unique_ptr<FunctionParser<dim>>> neumann;
    const auto body_force = test_helpers::zero_body_forces<dim>(materials);
    const Signorini::Bulk::Assembler<dim> assembler(
      parameters, mapping, fe, materials, neumann, body_force);
    Signorini::Material::History<dim> history;

    const IndexSet                owned = dof_handler.locally_owned_dofs();
    TrilinosWrappers::MPI::Vector u(owned, MPI_COMM_WORLD), rhs(u), f_int(u),
      f_ext(u);
    VectorTools::interpolate(mapping, dof_handler, CornerPush<dim>(a), u);

    // det F at the bulk Gauss points (the assembler's rule: degree + 1).
    FEValues<dim> gauss(mapping, fe, QGauss<dim>(degree + 1), update_gradients);
    gauss.reinit(dof_handler.begin_active());
    std::vector<Tensor<2, dim>> grad(gauss.n_quadrature_points);
    gauss[FEValuesExtractors::Vector(0)].get_function_gradients(u, grad);
    double gauss_J = 1e300;
    for (const auto &g : grad)
      gauss_J =
        std::min(gauss_J, determinant(unit_symmetric_tensor<dim>() + g));

    AffineConstraints<double> constraints;
    constraints.close();
    assembler.assemble(
      dof_handler, u, history, constraints, nullptr, rhs, f_int, f_ext);
    const auto  &inversion = assembler.inversion();
    const double vertex_J  = dim == 2 ? 2 * a - 1 : 3 * a - 2;
    Point<dim>   centre;
    for (unsigned int d = 0; d < dim; ++d)
      centre[d] = 0.5;
    const bool pass =
      gauss_J > 0 && std::isfinite(rhs.l2_norm()) == !inverted &&
      inversion.n_cells == (inverted ? 1u : 0u) &&
      (!inverted || (std::abs(inversion.smallest_J - vertex_J) < 1e-12 &&
                     inversion.where.distance(centre) < 1e-12));
    out << dim << "D Q" << degree << ", a = " << a
        << ": smallest det F at the Gauss points " << std::setprecision(3)
        << gauss_J << ", at the vertex " << vertex_J << "; residual "
        << (std::isfinite(rhs.l2_norm()) ? "finite" : "NaN") << ", "
        << inversion.n_cells << " inverted cell(s)";
    if (inverted)
      out << ", smallest det F " << inversion.smallest_J << " at ("
          << inversion.where << ")";
    out << ": " << (pass ? "PASS" : "FAIL") << std::endl;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ofstream                    out("output");
  check<2>(out, 1, 0.4, true);
  check<2>(out, 1, 0.55, false);
  check<2>(out, 2, 0.45, true);
  check<3>(out, 1, 0.6, true);
  check<3>(out, 1, 0.7, false);
}
