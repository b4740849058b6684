#ifndef signorini_material_linear_elastic_h
#define signorini_material_linear_elastic_h

#include <signorini/material/interface.h>

namespace Signorini
{
  namespace Material
  {
    /**
     * Isotropic small-strain linear elasticity (model 'linear elastic'):
     * sigma = lambda tr(eps) I + 2 mu eps [Pa], with the Lame parameters of
     * 'Young's modulus' and 'Poisson's ratio'. No parameters of its own, no
     * history.
     */
    template <int dim>
    class LinearElastic : public Interface<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        (void)prm;
      }

      void
      evaluate(const SymmetricTensor<2, 3> &strain,
               const ArrayView<const double> &,
               SymmetricTensor<2, 3> &stress,
               SymmetricTensor<4, 3> *tangent) const override;

      bool
      is_linear() const override
      {
        return true;
      }
    };
  } // namespace Material
} // namespace Signorini

#endif
