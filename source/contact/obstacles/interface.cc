#include <deal.II/base/utilities.h>

#include <signorini/contact/obstacles/interface.h>

namespace Signorini
{
  namespace Obstacles
  {
    template <int dim>
    void
    Interface<dim>::set_length_scale(const double)
    {
    }


    template <int dim>
    bool
    Interface<dim>::flat() const
    {
      return false;
    }


    template <int dim>
    std::string
    Interface<dim>::approximate_derivatives() const
    {
      return "";
    }


    template <int dim>
    void
    Interface<dim>::set_motion(const RigidMotion<dim> &m)
    {
      motion = m;
    }


    template <int dim>
    void
    Interface<dim>::set_translation(const Tensor<1, dim> &t)
    {
      motion             = RigidMotion<dim>();
      motion.translation = t;
    }


    template <int dim>
    const RigidMotion<dim> &
    Interface<dim>::get_motion() const
    {
      return motion;
    }


    template <int dim>
    Projection<dim>
    Interface<dim>::project(const Point<dim> &p) const
    {
      Projection<dim>      r = project_reference(motion.inverse(p));
      const Tensor<2, dim> R = motion.rotation;
      r.x_m                  = motion.apply(r.x_m);
      r.normal               = R * r.normal;
      r.dnormal              = R * r.dnormal * transpose(R);
      r.dclosest             = R * r.dclosest * transpose(R);
      return r;
    }


    void
    declare_master_parameters(ParameterHandler &prm)
    {
      const auto &registry = Registry<2>::instance();
      prm.declare_entry("Master",
                        "body",
                        Patterns::Selection("body|" + registry.selection()),
                        "Master surface: 'body' (the faces 'Master boundary "
                        "id' of another meshed body) or a rigid obstacle: " +
                          registry.documentation() +
                          ". An obstacle reads its parameters from the "
                          "subsection named after it, capitalised.");
      registry.declare_parameters(prm);
    }


    namespace
    {
      // The family's declaration, handed to the parameters (base/plugins.h).
      const Plugins::Declaration declaration(Plugins::Family::obstacle,
                                             declare_master_parameters);
    } // namespace


    template <int dim>
    std::vector<std::unique_ptr<Interface<dim>>>
    make_obstacles(const Parameters &parameters, ParameterHandler &prm)
    {
      std::vector<std::unique_ptr<Interface<dim>>> result;
      const auto &pairs = parameters.contact.pairs;
      prm.enter_subsection("Contact");
      for (unsigned int k = 0; k < pairs.size(); ++k)
        {
          result.emplace_back();
          if (pairs[k].master_is_body())
            continue;
          const std::string where =
            "subsection 'Contact/Pair " + std::to_string(k + 1) + "'";
          result.back() =
            Registry<dim>::instance().create(pairs[k].master,
                                             where + ", parameter 'Master'");
          prm.enter_subsection("Pair " + std::to_string(k + 1));
          try
            {
              result.back()->parse_parameters(prm);
            }
          catch (const InputError &e)
            {
              prm.leave_subsection();
              prm.leave_subsection();
              throw InputError(where + ", " + e.what());
            }
          prm.leave_subsection();
        }
      prm.leave_subsection();
      return result;
    }


#define SIGNORINI_INSTANTIATE(dim)                                           \
  template class Interface<dim>;                                             \
  template std::vector<std::unique_ptr<Interface<dim>>> make_obstacles<dim>( \
    const Parameters &, ParameterHandler &);
    SIGNORINI_INSTANTIATE(2)
    SIGNORINI_INSTANTIATE(3)
#undef SIGNORINI_INSTANTIATE
  } // namespace Obstacles
} // namespace Signorini
