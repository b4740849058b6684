#include <signorini/base/errors.h>
#include <signorini/material/interface.h>

namespace Signorini
{
  namespace Material
  {
    void
    declare_model_parameters(ParameterHandler &prm)
    {
      const auto &registry = Registry<2>::instance();
      prm.declare_entry("Model",
                        "linear elastic",
                        Patterns::Selection(registry.selection()),
                        "Constitutive model of the cells with this material "
                        "id: " +
                          registry.documentation() +
                          ". Every model takes 'Young's modulus' and "
                          "'Poisson's ratio' from this subsection and its "
                          "own parameters from a subsection named after "
                          "it, capitalised.");
      registry.declare_parameters(prm);
    }


    namespace
    {
      // The family's declaration, handed to the parameters (base/plugins.h).
      const Plugins::Declaration declaration(Plugins::Family::material,
                                             declare_model_parameters);
    } // namespace


    namespace
    {
      // 'Kinematics' of 'Material k': one the model implements.
      template <int dim>
      void
      set_kinematics(Interface<dim>           &model,
                     const MaterialParameters &m,
                     const Parameters         &parameters,
                     const unsigned int        k)
      {
        const auto kinematics   = m.finite_strain ? Kinematics::finite_strain :
                                                    Kinematics::small_strain;
        const std::string where = "subsection 'Materials/Material " +
                                  std::to_string(k) +
                                  "', parameter 'Kinematics': ";
        if (!model.supports(kinematics))
          throw InputError(
            where + "the model '" + m.model + "' has no " +
            (m.finite_strain ?
               "finite-strain form; use 'Kinematics = small strain' or a "
               "finite-strain model ('neo-Hookean')." :
               "small-strain form; set 'Kinematics = finite strain' (its "
               "small-strain limit is 'Model = linear elastic')."));
        model.set_kinematics(kinematics);
        if (parameters.plane_stress && m.finite_strain)
          throw InputError(where + "plane stress is implemented at small "
                                   "strain; set 'Kinematics = small strain' "
                                   "or 'Plane stress = false'.");
        model.set_plane_stress(parameters.plane_stress);
      }
    } // namespace


    template <int dim>
    SymmetricTensor<2, 3>
    Interface<dim>::completed_strain(
      const SymmetricTensor<2, 3>   &strain,
      const ArrayView<const double> &history) const
    {
      SymmetricTensor<2, 3> e = strain;
      if (!in_plane_stress)
        return e;
      // sigma_33(eps_33) is piecewise smooth (elastic, plastic): Newton
      // with the consistent tangent C_3333 > 0 converges in a few steps,
      // in one for an elastic model.
      SymmetricTensor<2, 3> stress;
      SymmetricTensor<4, 3> C;
      for (unsigned int it = 0; it < 50; ++it)
        {
          evaluate(e, history, stress, &C);
          const double r = stress[2][2];
          if (std::abs(r) <= 1e-14 * (stress.norm() + E * e.norm()))
            break;
          e[2][2] -= r / C[2][2][2][2];
        }
      return e;
    }


    template <int dim>
    void
    Interface<dim>::evaluate_completed(const SymmetricTensor<2, 3>   &strain,
                                       const ArrayView<const double> &history,
                                       SymmetricTensor<2, 3>         &stress,
                                       SymmetricTensor<4, 3> *tangent) const
    {
      if (!in_plane_stress)
        {
          evaluate(strain, history, stress, tangent);
          return;
        }
      SymmetricTensor<4, 3> C;
      evaluate(completed_strain(strain, history), history, stress, &C);
      stress[2][2] = 0; // the round-off of the solve
      if (!tangent)
        return;
      // d eps_33 = -(C_33kl d eps_kl) / C_3333 over the in-plane strains.
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = k; l < 3; ++l)
              (*tangent)[i][j][k][l] =
                C[i][j][k][l] - C[i][j][2][2] * C[2][2][k][l] / C[2][2][2][2];
    }


    template <int dim>
    std::map<types::material_id, std::unique_ptr<Interface<dim>>>
    make_materials(const Parameters &parameters, ParameterHandler &prm)
    {
      std::map<types::material_id, std::unique_ptr<Interface<dim>>> result;
      prm.enter_subsection("Materials");
      for (unsigned int k = 0; k < parameters.materials.size(); ++k)
        {
          const auto       &m     = parameters.materials[k];
          const std::string where = "subsection 'Materials/Material " +
                                    std::to_string(k + 1) +
                                    "', parameter 'Model'";
          auto model = Registry<dim>::instance().create(m.model, where);
          model->set_elastic_constants(m.youngs_modulus, m.poissons_ratio);
          set_kinematics(*model, m, parameters, k + 1);
          prm.enter_subsection("Material " + std::to_string(k + 1));
          try
            {
              model->parse_parameters(prm);
            }
          catch (const InputError &e)
            {
              throw InputError("subsection 'Materials/Material " +
                               std::to_string(k + 1) + "', " + e.what());
            }
          prm.leave_subsection();
          result.emplace(m.material_id, std::move(model));
        }
      prm.leave_subsection();
      return result;
    }


    template class Interface<2>;
    template class Interface<3>;
    template std::map<types::material_id, std::unique_ptr<Interface<2>>>
    make_materials<2>(const Parameters &, ParameterHandler &);
    template std::map<types::material_id, std::unique_ptr<Interface<3>>>
    make_materials<3>(const Parameters &, ParameterHandler &);
  } // namespace Material
} // namespace Signorini
