#include <signorini/material/neo_hookean.h>

namespace Signorini
{
  namespace Material
  {
    template <int dim>
    void
    NeoHookean<dim>::evaluate_finite_strain(
      const Tensor<2, 3> &F,
      const ArrayView<const double> &,
      SymmetricTensor<2, 3> &tau,
      SymmetricTensor<4, 3> *tangent) const
    {
      const double J = determinant(F);
      Assert(J > 0, ExcMessage("det F <= 0: the element is inverted"));
      const double                mu    = this->mu;
      const double                kappa = bulk_modulus();
      const SymmetricTensor<2, 3> I     = unit_symmetric_tensor<3>();
      const SymmetricTensor<2, 3> b_bar =
        std::pow(J, -2. / 3.) * symmetrize(F * transpose(F));
      const SymmetricTensor<2, 3> tau_iso = mu * deviator(b_bar);
      tau = tau_iso + 0.5 * kappa * (J * J - 1) * I;
      if (tangent)
        {
          const SymmetricTensor<4, 3> IxI = outer_product(I, I);
          const SymmetricTensor<4, 3> Is  = identity_tensor<3>();
          *tangent =
            2. / 3. * mu * trace(b_bar) * (Is - IxI / 3.) -
            2. / 3. * (outer_product(tau_iso, I) + outer_product(I, tau_iso)) +
            kappa * J * J * IxI - kappa * (J * J - 1) * Is;
        }
    }


    template class NeoHookean<2>;
    template class NeoHookean<3>;
  } // namespace Material
} // namespace Signorini

SIGNORINI_REGISTER_MATERIAL(Signorini::Material::NeoHookean,
                            "neo-Hookean",
                            "compressible neo-Hookean hyperelasticity "
                            "(finite strain), tau = mu dev(b_bar) + kappa/2 "
                            "(J^2 - 1) I")
