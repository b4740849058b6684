// The family of body shapes (shapes/interface.h): placement, defaults,
// the 'Shape' entry and the creation of every body's shape.
#include <signorini/geometry/shapes/interface.h>

#include <cctype>

namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      template <int dim>
      Placement<dim>::Placement(const Tensor<1, dim> &shift,
                                const Tensor<2, dim> &rotation,
                                const Point<dim>     &centre)
          : shift(shift)
          , rotation(rotation)
          , centre(centre)
          , rotates(rotation != Tensor<2, dim>(unit_symmetric_tensor<dim>()))
      {
      }


      template <int dim>
      Point<dim>
      Placement<dim>::operator()(const Point<dim> &p) const
      {
        if (!rotates)
          return p + shift;
        return centre + rotation * (p + shift - centre);
      }


      template <int dim>
      Tensor<1, dim>
      Placement<dim>::direction(const Tensor<1, dim> &v) const
      {
        return rotation * v;
      }


      template <int dim>
      double
      Interface<dim>::n_cells(std::string &) const
      {
        return 0;
      }


      template <int dim>
      CurvedSurface<dim>
      Interface<dim>::curved_surface(const Triangulation<dim> &,
                                     const Placement<dim> &) const
      {
        return {};
      }


      void
      declare_shape_parameters(ParameterHandler &prm)
      {
        const auto &registry = Registry<2>::instance();
        prm.declare_entry("Shape",
                          "block",
                          Patterns::Selection(registry.selection()),
                          "How this body's mesh is made: " +
                            registry.documentation() +
                            ". A shape reads its parameters from the "
                            "subsection named after it, capitalised.");
        registry.declare_parameters(prm);
      }


      std::string
      subsection_of(const unsigned int b, const std::string &shape)
      {
        std::string name = shape;
        if (!name.empty())
          name[0] = std::toupper(name[0]);
        return "subsection 'Geometry/Body " + std::to_string(b + 1) + "/" +
               name + "'";
      }


      namespace
      {
        // The family's declaration, handed to the parameters
        // (base/plugins.h).
        const Plugins::Declaration declaration(Plugins::Family::shape,
                                               declare_shape_parameters);
      } // namespace


      template <int dim>
      std::vector<std::unique_ptr<Interface<dim>>>
      make_shapes(const Parameters &parameters, ParameterHandler &prm)
      {
        std::vector<std::unique_ptr<Interface<dim>>> result;
        const auto &bodies = parameters.geometry.bodies;
        prm.enter_subsection("Geometry");
        for (unsigned int b = 0; b < bodies.size(); ++b)
          {
            const std::string body = "Body " + std::to_string(b + 1);
            result.push_back(
              Registry<dim>::instance().create(bodies[b].shape,
                                               "subsection 'Geometry/" + body +
                                                 "', parameter 'Shape'"));
            prm.enter_subsection(body);
            try
              {
                result.back()->parse_parameters(prm,
                                                parameters.input_directory);
              }
            catch (const InputError &e)
              {
                prm.leave_subsection();
                prm.leave_subsection();
                throw InputError(subsection_of(b, bodies[b].shape) + ", " +
                                 e.what());
              }
            prm.leave_subsection();
          }
        prm.leave_subsection();
        return result;
      }


#define SIGNORINI_INSTANTIATE(dim)                                        \
  template class Placement<dim>;                                          \
  template class Interface<dim>;                                          \
  template std::vector<std::unique_ptr<Interface<dim>>> make_shapes<dim>( \
    const Parameters &, ParameterHandler &);
      SIGNORINI_INSTANTIATE(2)
      SIGNORINI_INSTANTIATE(3)
#undef SIGNORINI_INSTANTIATE
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini
