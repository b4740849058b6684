// Helpers of the bulk-assembler unit tests (tests/finite_strain_jacobian.cc,
// tests/finite_strain_inverted_vertex.cc).
#ifndef signorini_tests_bulk_helpers_h
#define signorini_tests_bulk_helpers_h

#include <deal.II/base/function_parser.h>

#include <signorini/bulk/assembler.h>

#include <memory>
#include <string>

namespace test_helpers
{
  /** A zero body force for each material of @p materials. */
  template <int dim>
  Signorini::Bulk::BodyForces<dim>
  zero_body_forces(const Signorini::Bulk::Materials<dim> &materials)
  {
    Signorini::Bulk::BodyForces<dim> body_force;
    for (const auto &[id, material] : materials)
      {
        body_force[id] = std::make_unique<dealii::FunctionParser<dim>>(dim);
        body_force[id]->initialize(
          dealii::FunctionParser<dim>::default_variable_names(),
          dim == 2 ? "0; 0" : "0; 0; 0",
          {});
      }
    return body_force;
  }
} // namespace test_helpers

#endif
