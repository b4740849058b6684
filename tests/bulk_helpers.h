// Helpers of the bulk-assembler unit tests (tests/finite_strain_jacobian.cc,
// tests/finite_strain_inverted_vertex.cc).
#ifndef signorini_tests_bulk_helpers_h
#define signorini_tests_bulk_helpers_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>

#include <signorini/base/parameters.h>
#include <signorini/bulk/assembler.h>
#include <signorini/material/interface.h>

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


  /** What a bulk-assembler test builds on a mesh: the FE_Q(degree)^dim
   * space with its DoFs, a linear mapping, the materials of the input. */
  template <int dim>
  struct BulkSpace
  {
    BulkSpace(const dealii::Triangulation<dim> &tria,
              const unsigned int                degree,
              const Signorini::Parameters      &parameters,
              dealii::ParameterHandler         &prm)
        : fe(dealii::FE_Q<dim>(degree), dim)
        , dof_handler(tria)
        , mapping(1)
        , materials(Signorini::Material::make_materials<dim>(parameters, prm))
    {
      dof_handler.distribute_dofs(fe);
    }

    const dealii::FESystem<dim>           fe;
    dealii::DoFHandler<dim>               dof_handler;
    const dealii::MappingQ<dim>           mapping;
    const Signorini::Bulk::Materials<dim> materials;
  };
} // namespace test_helpers

#endif
