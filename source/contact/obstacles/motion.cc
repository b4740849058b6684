#include <deal.II/base/utilities.h>
#include <deal.II/physics/transformations.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameters.h>
#include <signorini/contact/obstacles/motion.h>

namespace Signorini
{
  namespace Obstacles
  {


    template <int dim>
    Motion<dim>::Motion(const std::vector<std::string>      &translation_in,
                        const std::vector<std::string>      &rotation_in,
                        const std::vector<double>           &centre_in,
                        const std::map<std::string, double> &constants,
                        const std::string                   &where)
    {
      if (translation_in.size() < dim)
        throw InputError(where + ", parameter 'Obstacle motion': give " +
                         std::to_string(dim) +
                         " expressions separated by ';'.");
      translation =
        parse_function<dim>(std::vector<std::string>(translation_in.begin(),
                                                     translation_in.begin() +
                                                       dim),
                            constants,
                            where + ", parameter 'Obstacle motion'");
      const unsigned int n_rotation = dim == 2 ? 1 : 3;
      const bool         none =
        rotation_in.size() == 1 && Utilities::trim(rotation_in[0]) == "0";
      if (!none && rotation_in.size() != n_rotation)
        throw InputError(
          where + ", parameter 'Obstacle rotation': give " +
          (dim == 2 ? std::string("the angle [rad] as one expression of t") :
                      std::string("the rotation vector (axis times angle "
                                  "[rad]) as 3 expressions of t separated "
                                  "by ';'")) +
          ", or 0.");
      if (!none)
        rotation =
          parse_function<dim>(rotation_in,
                              constants,
                              where + ", parameter 'Obstacle rotation'");
      if (centre_in.size() < dim)
        throw InputError(where + ", parameter 'Rotation centre': give " +
                         std::to_string(dim) + " coordinates.");
      for (unsigned int d = 0; d < dim; ++d)
        centre[d] = centre_in[d];
    }


    template <int dim>
    RigidMotion<dim>
    Motion<dim>::at(const double t) const
    {
      RigidMotion<dim> motion;
      motion.centre = centre;
      translation->set_time(t);
      for (unsigned int c = 0; c < dim; ++c)
        motion.translation[c] = translation->value(Point<dim>(), c);
      if (rotation)
        {
          rotation->set_time(t);
          if constexpr (dim == 2)
            motion.rotation =
              Physics::Transformations::Rotations::rotation_matrix_2d(
                rotation->value(Point<dim>(), 0));
          else
            {
              Tensor<1, 3> axis;
              for (unsigned int c = 0; c < 3; ++c)
                axis[c] = rotation->value(Point<dim>(), c);
              const double angle = axis.norm();
              if (angle > 0)
                motion.rotation =
                  Physics::Transformations::Rotations::rotation_matrix_3d(
                    Point<3>(axis / angle), angle);
            }
        }
      return motion;
    }

    template class Motion<2>;
    template class Motion<3>;
  } // namespace Obstacles
} // namespace Signorini
