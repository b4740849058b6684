// A constitutive model defined outside the library, built as a module
// that the stock `signorini` loads ('Additional shared libraries'; doc/
// extending.md, B.3): 'scaled elastic' is linear elasticity with its stress
// multiplied by its own parameter 'Stiffness factor', which it delegates to
// the library's 'linear elastic'. No main(): tests/material_plugin.prm.in
// runs it.
#include <signorini/material/linear_elastic.h>

namespace Example
{
  using namespace dealii;

  template <int dim>
  class ScaledElastic : public Signorini::Material::Interface<dim>
  {
  public:
    // Its own parameters, in subsection 'Material k/Scaled elastic'.
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Scaled elastic");
      prm.declare_entry("Stiffness factor",
                        "1",
                        Patterns::Double(0),
                        "The stress of linear elasticity times this factor.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm) override
    {
      prm.enter_subsection("Scaled elastic");
      factor = prm.get_double("Stiffness factor");
      prm.leave_subsection();
      elastic.set_elastic_constants(this->youngs_modulus(),
                                    this->poissons_ratio());
    }

    void
    evaluate(const SymmetricTensor<2, 3>   &strain,
             const ArrayView<const double> &history,
             SymmetricTensor<2, 3>         &stress,
             SymmetricTensor<4, 3>         *tangent) const override
    {
      elastic.evaluate(strain, history, stress, tangent);
      stress *= factor;
      if (tangent)
        *tangent *= factor;
    }

    bool
    is_linear() const override
    {
      return true;
    }

    double
    representative_modulus() const override
    {
      return factor * this->youngs_modulus();
    }

  private:
    double                                  factor = 1;
    Signorini::Material::LinearElastic<dim> elastic;
  };
} // namespace Example

SIGNORINI_REGISTER_MATERIAL(Example::ScaledElastic,
                            "scaled elastic",
                            "linear elasticity times 'Stiffness factor' "
                            "(tests/plugins/scaled_elastic.cc)")
