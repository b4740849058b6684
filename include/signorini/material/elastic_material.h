#ifndef signorini_material_elastic_material_h
#define signorini_material_elastic_material_h

#include <deal.II/base/symmetric_tensor.h>

#include <signorini/core/parameters.h>

#include <map>

/**
 * Isotropic small-strain linear elasticity, sigma = lambda tr(eps) I + 2 mu
 * eps [Pa]. In 2D the strain normal to the plane is 0 (plane strain) or the
 * hoop strain u_r / r (axisymmetric); it enters the trace, and the stress
 * normal to the plane enters the von Mises stress.
 */
namespace Signorini
{
  namespace Material
  {
    using namespace dealii;

    template <int dim>
    class ElasticMaterial
    {
    public:
      ElasticMaterial() = default;
      ElasticMaterial(const double youngs_modulus, const double poissons_ratio)
        : E(youngs_modulus)
        , nu(poissons_ratio)
        , lambda(E * nu / ((1 + nu) * (1 - 2 * nu)))
        , mu(E / (2 * (1 + nu)))
      {}

      double
      youngs_modulus() const
      {
        return E;
      }

      /** In-plane (or 3D) stress. In 2D, @p strain_33 is the strain normal
       * to the plane: 0 in plane strain, the hoop strain u_r / r in an
       * axisymmetric model; it enters through the trace. */
      SymmetricTensor<2, dim>
      stress(const SymmetricTensor<2, dim> &strain,
             const double                   strain_33 = 0) const
      {
        return stress_from_volumetric(strain, trace(strain) + strain_33);
      }

      /** 2D: the stress normal to the plane (sigma_zz of plane strain, the
       * hoop stress of an axisymmetric model). */
      double
      stress_33(const SymmetricTensor<2, dim> &strain,
                const double                   strain_33 = 0) const
      {
        return stress_33_from_volumetric(strain_33, trace(strain) + strain_33);
      }

      /** stress() with the volumetric strain @p volumetric in place of
       * tr(eps) + strain_33 (B-bar: the volumetric strain projected per
       * cell, Material::ProjectedVolumetricStrain). */
      SymmetricTensor<2, dim>
      stress_from_volumetric(const SymmetricTensor<2, dim> &strain,
                             const double                   volumetric) const
      {
        return lambda * volumetric * unit_symmetric_tensor<dim>() +
               2 * mu * strain;
      }

      /** stress_33() with the volumetric strain @p volumetric. */
      double
      stress_33_from_volumetric(const double strain_33,
                                const double volumetric) const
      {
        return lambda * volumetric + 2 * mu * strain_33;
      }

      /** von Mises stress, in 2D including the stress normal to the plane
       * (independent of the volumetric strain: lambda tr(eps) shifts the
       * three normal stresses alike). */
      double
      von_mises(const SymmetricTensor<2, dim> &strain,
                const double                   strain_33 = 0) const
      {
        const SymmetricTensor<2, dim> s = stress(strain, strain_33);
        double sxx = s[0][0], syy = s[1][1];
        double sz  = dim == 3 ? s[dim - 1][dim - 1] :
                                stress_33(strain, strain_33);
        double shear2 = s[0][1] * s[0][1];
        if constexpr (dim == 3)
          shear2 += s[0][2] * s[0][2] + s[1][2] * s[1][2];
        return std::sqrt(0.5 * ((sxx - syy) * (sxx - syy) +
                                (syy - sz) * (syy - sz) +
                                (sz - sxx) * (sz - sxx)) +
                         3 * shear2);
      }

      double E = 0, nu = 0, lambda = 0, mu = 0;
    };

    /** Materials by material id, built from the Materials subsection. */
    template <int dim>
    std::map<types::material_id, ElasticMaterial<dim>>
    make_materials(const Parameters &parameters)
    {
      std::map<types::material_id, ElasticMaterial<dim>> result;
      for (const auto &m : parameters.materials)
        result.emplace(m.material_id,
                       ElasticMaterial<dim>(m.youngs_modulus, m.poissons_ratio));
      return result;
    }
  } // namespace Material
} // namespace Signorini

#endif
