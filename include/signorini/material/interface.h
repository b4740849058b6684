#ifndef signorini_material_interface_h
#define signorini_material_interface_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <signorini/base/parameters.h>
#include <signorini/base/plugins.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

/**
 * Constitutive models of the bodies (the plug-in family of subsection
 * 'Materials/Material k', entry 'Model'), after step-42's ConstitutiveLaw:
 * stress and tangent from the strain at a quadrature point.
 *
 * Every model works with 3D tensors: in 2D the component (2, 2) of the
 * strain is the strain normal to the plane, 0 in plane strain and the hoop
 * strain u_r / r in an axisymmetric model, and the stress normal to the
 * plane comes back in the same component. In plane stress the caller
 * evaluates through evaluate_completed(), which finds the eps_33 of
 * sigma_33 = 0 with the model's own stress and tangent. A model is written once
 * for plane strain, axisymmetry and 3D, and models with an inelastic strain
 * (plasticity) keep all its components.
 *
 * Every solid model of this family has an elastic part: 'Young's modulus'
 * and 'Poisson's ratio' are entries of 'Material k' itself, shared by the
 * models; a model declares the parameters of its own in a subsection of
 * 'Material k' named after it, capitalised (declare_parameters()), and
 * reads them in parse_parameters().
 *
 * A model with history (plasticity) declares how many values each
 * quadrature point keeps (n_history_values(); they start at 0). evaluate()
 * reads the values committed at the end of the last converged load step and
 * never changes them; update_history() computes the new values from the
 * converged strain, and the bulk assembler stores them only when a load
 * step (or sub-step) has converged (Bulk::Assembler::update_history()).
 * Line-search trials, the Jacobian check and cut steps therefore never
 * reach the history.
 *
 * Kinematics ('Material k/Kinematics', per material): with small strain a
 * model maps the strain eps = sym H to the Cauchy stress (evaluate());
 * with finite strain it maps the deformation gradient F = I + H to the
 * Kirchhoff stress tau = J sigma and its spatial tangent
 * (evaluate_finite_strain()). H is the 3D displacement gradient of the
 * point, in 2D with H_33 = 0 (plane strain) or u_r / R (axisymmetric:
 * F_33 = r / R, the hoop stretch). A model says which kinematics it
 * implements (supports()); make_materials() refuses the others.
 *
 * A new model: a class derived from Interface<dim> with a static
 * declare_parameters(ParameterHandler &), registered in its source file
 * with SIGNORINI_REGISTER_MATERIAL(Class, "name", "description")
 * (doc/extending.md).
 */
namespace Signorini
{
  namespace Material
  {
    using namespace dealii;

    /** The 3D strain of a point: @p strain in the plane (or in 3D) and,
     * in 2D, @p strain_33 normal to it. */
    template <int dim>
    SymmetricTensor<2, 3>
    to_3d(const SymmetricTensor<2, dim> &strain, const double strain_33 = 0.)
    {
      SymmetricTensor<2, 3> e;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          e[i][j] = strain[i][j];
      if (dim == 2)
        e[2][2] = strain_33;
      return e;
    }

    /** The 3D displacement gradient of a point: @p grad in the plane (or
     * in 3D) and, in 2D, @p h_33 normal to it (0 in plane strain, u_r / R
     * axisymmetric). */
    template <int dim>
    Tensor<2, 3>
    to_3d(const Tensor<2, dim> &grad, const double h_33 = 0.)
    {
      Tensor<2, 3> h;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          h[i][j] = grad[i][j];
      if (dim == 2)
        h[2][2] = h_33;
      return h;
    }

    /** Small strain, B-bar: @p strain with its volumetric part tr(eps)
     * replaced by the projected @p theta_bar. */
    inline SymmetricTensor<2, 3>
    with_volumetric(const SymmetricTensor<2, 3> &strain, const double theta_bar)
    {
      return strain +
             (theta_bar - trace(strain)) / 3. * unit_symmetric_tensor<3>();
    }

    /** Finite strain, F-bar: F_bar = exp((theta_bar - ln J) / 3) F, whose
     * ln det is the projected @p theta_bar; @p log_J = ln det F. */
    inline Tensor<2, 3>
    with_volumetric(const Tensor<2, 3> &F,
                    const double        theta_bar,
                    const double        log_J)
    {
      return std::exp((theta_bar - log_J) / 3.) * F;
    }

    /** The kinematics of a material ('Material k/Kinematics'). */
    enum class Kinematics
    {
      small_strain,
      finite_strain
    };

    /** The in-plane (or 3D) part of a 3D tensor. */
    template <int dim>
    SymmetricTensor<2, dim>
    from_3d(const SymmetricTensor<2, 3> &t)
    {
      SymmetricTensor<2, dim> r;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          r[i][j] = t[i][j];
      return r;
    }

    /** von Mises equivalent stress of a 3D stress [Pa]. */
    inline double
    von_mises(const SymmetricTensor<2, 3> &stress)
    {
      const SymmetricTensor<2, 3> s = deviator(stress);
      return std::sqrt(1.5 * (s * s));
    }

    template <int dim>
    class Interface
    {
    public:
      virtual ~Interface() = default;

      /** The elastic constants of 'Material k', set before
       * parse_parameters(). */
      void
      set_elastic_constants(const double youngs_modulus,
                            const double poissons_ratio)
      {
        E      = youngs_modulus;
        nu     = poissons_ratio;
        lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
        mu     = E / (2 * (1 + nu));
      }

      /** Reads the model's own parameters; @p prm is in subsection
       * 'Material k'. Default: the model has none. */
      virtual void
      parse_parameters(ParameterHandler &prm)
      {
        (void)prm;
      }

      /** True if the model implements @p kinematics. Default: small
       * strain only. */
      virtual bool
      supports(const Kinematics kinematics) const
      {
        return kinematics == Kinematics::small_strain;
      }

      /** The kinematics this material runs with (set by make_materials()
       * from 'Material k/Kinematics'). */
      Kinematics
      kinematics() const
      {
        return used_kinematics;
      }

      void
      set_kinematics(const Kinematics kinematics)
      {
        used_kinematics = kinematics;
      }

      /** Plane stress (2D, the top-level 'Plane stress'; set by
       * make_materials()): the stress normal to the plane is zero and the
       * strain normal to it follows (small strain). */
      void
      set_plane_stress(const bool on)
      {
        in_plane_stress = on;
      }

      bool
      plane_stress() const
      {
        return in_plane_stress;
      }

      /**
       * The 3D small strain of a point, completed: in plane stress
       * @p strain with the component (2, 2) at which the model's stress
       * sigma_33 is zero (Newton on sigma_33 with the model's tangent from
       * the given eps_33), otherwise @p strain itself. Any small-strain
       * model, with history (plasticity) too, is so run in plane stress.
       */
      SymmetricTensor<2, 3>
      completed_strain(const SymmetricTensor<2, 3>   &strain,
                       const ArrayView<const double> &history) const;

      /**
       * evaluate() at the completed strain of a point; in plane stress the
       * tangent is condensed to the in-plane strains at sigma_33 = 0:
       * C - (C : E_33) (E_33 : C) / C_3333, E_33 = e_3 e_3.
       */
      void
      evaluate_completed(const SymmetricTensor<2, 3>   &strain,
                         const ArrayView<const double> &history,
                         SymmetricTensor<2, 3>         &stress,
                         SymmetricTensor<4, 3>         *tangent) const;

      /**
       * Small strain: the Cauchy stress at a point for the 3D small strain
       * @p strain [Pa], and if @p tangent is given its derivative
       * d sigma / d eps (the consistent tangent of a model with history).
       * @p history: the point's committed values (n_history_values() of
       * them; empty for a model without history). Default: not
       * implemented (supports() says false).
       */
      virtual void
      evaluate(const SymmetricTensor<2, 3>   &strain,
               const ArrayView<const double> &history,
               SymmetricTensor<2, 3>         &stress,
               SymmetricTensor<4, 3>         *tangent) const
      {
        (void)strain;
        (void)history;
        (void)stress;
        (void)tangent;
        AssertThrow(false, ExcInternalError());
      }

      /**
       * Finite strain: the Kirchhoff stress tau = J sigma [Pa] at the 3D
       * deformation gradient @p F, and if @p tangent is given the spatial
       * tangent c of the Lie derivative of tau (step-44's J c):
       *   d tau = c : sym(l) + l tau + tau l^T,  l = dF F^-1.
       * Default: not implemented (supports() says false).
       */
      virtual void
      evaluate_finite_strain(const Tensor<2, 3>            &F,
                             const ArrayView<const double> &history,
                             SymmetricTensor<2, 3>         &tau,
                             SymmetricTensor<4, 3>         *tangent) const
      {
        (void)F;
        (void)history;
        (void)tau;
        (void)tangent;
        AssertThrow(false, ExcInternalError());
      }

      /** The Cauchy stress [Pa] at the 3D displacement gradient @p H with
       * the material's kinematics. With @p theta_bar (the cell's projected
       * volumetric strain, 'Volumetric strain = projected') the volumetric
       * part is replaced: small strain eps_bar = sym H + (theta_bar -
       * tr H) / 3 I (B-bar), finite strain F_bar = exp((theta_bar - ln J)
       * / 3) F (F-bar), sigma = tau(F_bar) / det F_bar. */
      SymmetricTensor<2, 3>
      cauchy_stress(const Tensor<2, 3>            &H,
                    const ArrayView<const double> &history,
                    const double                  *theta_bar = nullptr) const
      {
        SymmetricTensor<2, 3> stress;
        if (used_kinematics == Kinematics::small_strain)
          {
            const SymmetricTensor<2, 3> strain = symmetrize(H);
            evaluate_completed(theta_bar ? with_volumetric(strain, *theta_bar) :
                                           strain,
                               history,
                               stress,
                               nullptr);
          }
        else
          {
            Tensor<2, 3> F = unit_symmetric_tensor<3>() + H;
            if (theta_bar)
              F = with_volumetric(F, *theta_bar, std::log(determinant(F)));
            evaluate_finite_strain(F, history, stress, nullptr);
            stress /= determinant(F);
          }
        return stress;
      }

      /** Number of history values per quadrature point. Default: 0. */
      virtual unsigned int
      n_history_values() const
      {
        return 0;
      }

      /** The history after the converged strain @p strain: @p history
       * holds the committed values on entry and the new ones on return.
       * Default (no history): nothing. */
      virtual void
      update_history(const SymmetricTensor<2, 3> &strain,
                     const ArrayView<double>     &history) const
      {
        (void)strain;
        (void)history;
      }

      /** update_history() at finite strain, from the converged
       * deformation gradient @p F. Default (no history): nothing. */
      virtual void
      update_history_finite_strain(const Tensor<2, 3>      &F,
                                   const ArrayView<double> &history) const
      {
        (void)F;
        (void)history;
      }

      /** Scalar quantities of the history, by name, for output (cell means
       * in the VTU files) and for 'Output/Reference checks/History quantity'.
       * Default: none. */
      virtual std::vector<std::string>
      history_output_names() const
      {
        return {};
      }

      /** The quantities of history_output_names() at a point whose history
       * is @p history, in that order. */
      virtual std::vector<double>
      history_output(const ArrayView<const double> &history) const
      {
        (void)history;
        return {};
      }

      /** True if the stress is a linear function of the strain without
       * history: Newton's step at fixed contact statuses is then exact. */
      virtual bool
      is_linear() const = 0;

      /** A stiffness for scaling the contact coefficients (rho_n = c_n
       * E / h) and the error indicator [Pa]. Default: Young's modulus. */
      virtual double
      representative_modulus() const
      {
        return E;
      }

      double
      youngs_modulus() const
      {
        return E;
      }
      double
      poissons_ratio() const
      {
        return nu;
      }
      /** Lame's first parameter and the shear modulus [Pa]. */
      double
      lame_lambda() const
      {
        return lambda;
      }
      double
      shear_modulus() const
      {
        return mu;
      }

    protected:
      double     E = 0, nu = 0, lambda = 0, mu = 0;
      Kinematics used_kinematics = Kinematics::small_strain;
      bool       in_plane_stress = false;
    };

    /** The registry of the family (dim 2 and 3 share the names). */
    template <int dim>
    using Registry = Plugins::Registry<Interface<dim>>;

    /** Materials by material id, built from subsection 'Materials': each
     * 'Material k' gives its model, elastic constants and own parameters.
     * Throws InputError for an unknown model. */
    template <int dim>
    std::map<types::material_id, std::unique_ptr<Interface<dim>>>
    make_materials(const Parameters &parameters, ParameterHandler &prm);

    /** Declares 'Model' and the models' own parameters in the current
     * subsection ('Material k'). */
    void
    declare_model_parameters(ParameterHandler &prm);
  } // namespace Material
} // namespace Signorini

/**
 * Registers a constitutive model for dim = 2 and 3 under @p name (the value
 * of 'Material k/Model') with a one-line @p description. Use once, in the
 * model's source file, at namespace scope.
 */
#define SIGNORINI_REGISTER_MATERIAL(classname, name, description)        \
  namespace                                                              \
  {                                                                      \
    const ::Signorini::Plugins::                                         \
      Registration<::Signorini::Material::Interface<2>, classname<2>>    \
        SIGNORINI_PLUGIN_NAME(signorini_material_2_)(name, description); \
    const ::Signorini::Plugins::                                         \
      Registration<::Signorini::Material::Interface<3>, classname<3>>    \
        SIGNORINI_PLUGIN_NAME(signorini_material_3_)(name, description); \
  }

#endif
