#ifndef signorini_geometry_shapes_interface_h
#define signorini_geometry_shapes_interface_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/manifold.h>
#include <deal.II/grid/tria.h>

#include <signorini/base/parameter_helpers.h>
#include <signorini/base/parameters.h>
#include <signorini/base/plugins.h>

#include <memory>
#include <string>
#include <vector>

/**
 * Body shapes: how the coarse mesh of one body is made ('Geometry/Body
 * k/Shape' names the shape). A plug-in family (base/plugins.h), as the
 * obstacles are: each shape is a class derived from
 * Geometry::Shapes::Interface<dim>, registered from its own source file with
 *
 *   SIGNORINI_REGISTER_SHAPE(Class, "name", "description")
 *
 * and reads its own parameters from a subsection of 'Body k' named after
 * it, capitalised ('ball segment': 'Ball segment'; doc/extending.md). The
 * library registers 'block', 'ball segment', 'cylinder segment' and 'file'.
 *
 * A shape builds its mesh in its own coordinates. The scene (scene.cc)
 * then does what every body shares: it renames a generated shape's face
 * groups to the user's boundary ids ('Boundary ids', or 10 k + group),
 * moves the body ('Shift', then 'Rotation angle' about 'Rotation axis'
 * through 'Rotation centre'), sets its material id, attaches the manifold
 * of its curved faces and joins the bodies into one mesh.
 */
namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      using namespace dealii;

      /** Where a body goes: its 'Shift', then its rotation. */
      template <int dim>
      class Placement
      {
      public:
        /** No move. */
        Placement() = default;

        /** @p shift [m]; @p rotation the rotation matrix about @p centre. */
        Placement(const Tensor<1, dim> &shift,
                  const Tensor<2, dim> &rotation,
                  const Point<dim>     &centre);

        /** A point of the shape's coordinates, placed. */
        Point<dim>
        operator()(const Point<dim> &p) const;

        /** A direction of the shape's coordinates, placed. */
        Tensor<1, dim>
        direction(const Tensor<1, dim> &v) const;

      private:
        Tensor<1, dim> shift;
        Tensor<2, dim> rotation = unit_symmetric_tensor<dim>();
        Point<dim>     centre;
        bool           rotates = false;
      };


      /** The curved faces of a body and the exact surface they lie on. */
      template <int dim>
      struct CurvedSurface
      {
        /** The curved faces: face groups of a generated shape (see
         * Interface::n_face_groups()), the mesh's own boundary ids
         * otherwise. */
        std::vector<types::boundary_id> faces;

        /** Their surface, for the placed body; null: no curved faces. */
        std::unique_ptr<Manifold<dim>> manifold;

        /** True if the body's cells follow the surface by transfinite
         * interpolation (a few large generated cells; a file mesh's cells
         * stay flat: the chart fails on irregular cells). */
        bool cells_follow = false;
      };


      /** The shape of one body. */
      template <int dim>
      class Interface
      {
      public:
        virtual ~Interface() = default;

        /**
         * Reads the shape's parameters; @p prm is in the subsection
         * 'Geometry/Body k' (the shape enters its own subsection).
         * @p input_directory is the parameter file's directory (for files
         * the shape reads). Throws InputError naming the parameter (not
         * the body: the scene adds it) on a value it cannot use.
         */
        virtual void
        parse_parameters(ParameterHandler  &prm,
                         const std::string &input_directory) = 0;

        /**
         * The number of cells build() will make, known before it is made,
         * so that the scene refuses a body beyond 'Maximum number of
         * cells' instead of allocating it; 0 if unknown (a file is read).
         * @p entry: the parameter that sets it, for the message.
         */
        virtual double
        n_cells(std::string &entry) const;

        /**
         * Makes the coarse mesh in the shape's coordinates. A generated
         * shape numbers its boundary faces 0 .. n_face_groups() - 1; a
         * shape with n_face_groups() = 0 gives them their final ids.
         */
        virtual void
        build(Triangulation<dim> &tria) const = 0;

        /**
         * The number of face groups of a generated shape, which the scene
         * renames to the body's boundary ids; 0 if the mesh carries its
         * own boundary and material ids (a file), which the scene keeps.
         */
        virtual unsigned int
        n_face_groups() const = 0;

        /** The curved faces of the body placed by @p placement (default:
         * none). */
        virtual CurvedSurface<dim>
        curved_surface(const Triangulation<dim> &tria,
                       const Placement<dim>     &placement) const;
      };


      template <int dim>
      using Registry = Plugins::Registry<Interface<dim>>;

      /** A point of dim coordinates from an entry, and a direction
       * (normalised, nonzero): base/parameter_helpers.h. */
      using internal::parse_direction;
      using internal::parse_point;

      /**
       * Declares 'Shape' (the name of a registered shape) and every
       * shape's subsection, in the current subsection 'Body k'.
       */
      void
      declare_shape_parameters(ParameterHandler &prm);

      /** "subsection 'Geometry/Body k/Name'" of the shape @p shape of body
       * @p b (0-based), for messages: a shape's subsection is its name,
       * capitalised. */
      std::string
      subsection_of(const unsigned int b, const std::string &shape);

      /**
       * The shape of every body, created from the registry and given its
       * parameters from 'Geometry/Body k'.
       */
      template <int dim>
      std::vector<std::unique_ptr<Interface<dim>>>
      make_shapes(const Parameters &parameters, ParameterHandler &prm);
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini


/**
 * Registers the shape class template @p classname (derived from
 * Geometry::Shapes::Interface<dim>, default constructible, with a static
 * declare_parameters(ParameterHandler &)) under @p name for 2D and 3D.
 */
#define SIGNORINI_REGISTER_SHAPE(classname, name, description)                \
  namespace                                                                   \
  {                                                                           \
    const ::Signorini::Plugins::                                              \
      Registration<::Signorini::Geometry::Shapes::Interface<2>, classname<2>> \
        SIGNORINI_PLUGIN_NAME(signorini_shape_2_)(name, description);         \
    const ::Signorini::Plugins::                                              \
      Registration<::Signorini::Geometry::Shapes::Interface<3>, classname<3>> \
        SIGNORINI_PLUGIN_NAME(signorini_shape_3_)(name, description);         \
  }

#endif
