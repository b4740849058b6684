#include <signorini/material/linear_elastic.h>

namespace Signorini
{
  namespace Material
  {
    template <int dim>
    void
    LinearElastic<dim>::evaluate(const SymmetricTensor<2, 3> &strain,
                                 const ArrayView<const double> &,
                                 SymmetricTensor<2, 3> &stress,
                                 SymmetricTensor<4, 3> *tangent) const
    {
      const double lambda = this->lambda, mu = this->mu;
      stress =
        lambda * trace(strain) * unit_symmetric_tensor<3>() + 2 * mu * strain;
      if (tangent)
        *tangent = lambda * outer_product(unit_symmetric_tensor<3>(),
                                          unit_symmetric_tensor<3>()) +
                   2 * mu * identity_tensor<3>();
    }

    template class LinearElastic<2>;
    template class LinearElastic<3>;
  } // namespace Material
} // namespace Signorini

SIGNORINI_REGISTER_MATERIAL(Signorini::Material::LinearElastic,
                            "linear elastic",
                            "isotropic small-strain linear elasticity, sigma "
                            "= lambda tr(eps) I + 2 mu eps")
