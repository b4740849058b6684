// The shapes 'ball segment' and 'cylinder segment' (shapes/segment.h).
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <signorini/base/parameter_helpers.h>
#include <signorini/geometry/shapes/segment.h>

namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      namespace
      {
        const internal::SelectionTable<int> cuts{{"full", 0},
                                                 {"half", 1},
                                                 {"quarter", 2}};
      } // namespace


      template <int dim>
      void
      SegmentBase<dim>::declare_segment_entries(ParameterHandler &prm)
      {
        prm.declare_entry("Centre",
                          "0, 0, 0",
                          internal::point_pattern(),
                          "Centre of the disc or ball [m] (for a cylinder the "
                          "z coordinate is the start of its axis).");
        prm.declare_entry("Radius",
                          "1",
                          Patterns::Double(1e-300),
                          "Radius [m].");
        prm.declare_entry("Inner radius",
                          "0",
                          Patterns::Double(0),
                          "Inner radius of a hollow segment [m] (a shell or "
                          "tube), below 'Radius'; 0: solid. The inner curved "
                          "face is the last face group.");
        prm.declare_entry("Segment",
                          "half",
                          cuts.pattern(),
                          "Part of the disc/ball kept: full, the half below "
                          "the centre, or the quarter below the centre with "
                          "x >= centre (for symmetric models).");
      }


      template <int dim>
      void
      SegmentBase<dim>::parse_parameters(ParameterHandler &prm,
                                         const std::string &)
      {
        prm.enter_subsection(subsection());
        try
          {
            centre       = internal::parse_point<dim>(prm, "Centre");
            radius       = prm.get_double("Radius");
            inner_radius = prm.get_double("Inner radius");
            cut          = Cut(cuts.value(prm.get("Segment")));
            parse_more(prm);
          }
        catch (...)
          {
            prm.leave_subsection();
            throw;
          }
        prm.leave_subsection();
        if (inner_radius >= radius)
          throw InputError("parameter 'Inner radius': it must be below "
                           "'Radius' (0 for a solid body).");
      }


      template <int dim>
      void
      SegmentBase<dim>::parse_more(ParameterHandler &)
      {
      }


      template <int dim>
      template <int d>
      unsigned int
      SegmentBase<dim>::n_disc_face_groups() const
      {
        const unsigned int flat = cut == Cut::full ? 0 :
                                  cut == Cut::half ? 1 :
                                                     d;
        return 1 + flat + (inner_radius > 0);
      }


      template <int dim>
      template <int d>
      void
      SegmentBase<dim>::make_disc_segment(Triangulation<d> &tria) const
      {
        // deal.II's segments: halves cut at x = 0 (kept x > 0), quarters in
        // the positive quadrant/octant; turned by -90 degrees about z (+x
        // becomes -y) to put the curved side down.
        const Point<d> o;
        if (inner_radius == 0)
          {
            if (cut == Cut::full)
              GridGenerator::hyper_ball(tria, o, radius);
            else if (cut == Cut::half)
              GridGenerator::half_hyper_ball(tria, o, radius);
            else
              GridGenerator::quarter_hyper_ball(tria, o, radius);
          }
        else if (cut == Cut::full)
          GridGenerator::hyper_shell(tria, o, inner_radius, radius);
        else if (cut == Cut::half)
          GridGenerator::half_hyper_shell(tria, o, inner_radius, radius);
        else
          GridGenerator::quarter_hyper_shell(tria, o, inner_radius, radius);
        if constexpr (d == 2)
          GridTools::rotate(-numbers::PI / 2, tria);
        else
          GridTools::rotate(Tensor<1, 3>({0., 0., 1.}), -numbers::PI / 2, tria);

        const unsigned int inner = n_disc_face_groups<d>() - 1;
        const double       tol   = 1e-10 * radius;
        // On the sphere of radius r: every vertex of the face is.
        const auto on_sphere = [tol](const auto &face, const double r) {
          for (const auto v : face->vertex_indices())
            if (std::abs(face->vertex(v).norm() - r) > tol)
              return false;
          return true;
        };
        for (const auto &face : tria.active_face_iterators())
          if (face->at_boundary())
            {
              const Point<d> c = face->center();
              if (on_sphere(face, radius))
                face->set_boundary_id(0);
              else if (inner_radius > 0 && on_sphere(face, inner_radius))
                face->set_boundary_id(inner);
              else if (std::abs(c[1]) < tol)
                face->set_boundary_id(1);
              else if (std::abs(c[0]) < tol)
                face->set_boundary_id(2);
              else if (d == 3 && std::abs(c[d - 1]) < tol)
                face->set_boundary_id(3);
            }
      }


      template <int dim>
      CurvedSurface<dim>
      SegmentBase<dim>::curved_surface(const Triangulation<dim> &,
                                       const Placement<dim> &placement) const
      {
        CurvedSurface<dim> curved;
        curved.faces.push_back(0);
        if (inner_radius > 0)
          curved.faces.push_back(this->n_face_groups() - 1);
        curved.cells_follow  = true;
        const Point<dim> c   = placement(centre);
        const bool       cyl = dim == 3 && cylindrical();
        if (cyl)
          {
            Tensor<1, dim> axis;
            axis[dim - 1]   = 1;
            curved.manifold = std::make_unique<CylindricalManifold<dim>>(
              placement.direction(axis), c);
          }
        else
          curved.manifold = std::make_unique<SphericalManifold<dim>>(c);
        return curved;
      }


      // ------------------------------------------------------ ball segment
      template <int dim>
      void
      BallSegment<dim>::declare_parameters(ParameterHandler &prm)
      {
        prm.enter_subsection("Ball segment");
        SegmentBase<dim>::declare_segment_entries(prm);
        prm.leave_subsection();
      }


      template <int dim>
      void
      BallSegment<dim>::build(Triangulation<dim> &tria) const
      {
        this->template make_disc_segment<dim>(tria);
        GridTools::shift(this->centre, tria);
      }


      template <int dim>
      unsigned int
      BallSegment<dim>::n_face_groups() const
      {
        return this->template n_disc_face_groups<dim>();
      }


      template <int dim>
      std::string
      BallSegment<dim>::subsection() const
      {
        return "Ball segment";
      }


      template <int dim>
      bool
      BallSegment<dim>::cylindrical() const
      {
        return false;
      }


      // -------------------------------------------------- cylinder segment
      template <int dim>
      void
      CylinderSegment<dim>::declare_parameters(ParameterHandler &prm)
      {
        prm.enter_subsection("Cylinder segment");
        SegmentBase<dim>::declare_segment_entries(prm);
        prm.declare_entry("Length",
                          "1",
                          Patterns::Double(1e-300),
                          "Axial length [m] (3D).");
        prm.declare_entry("Axial subdivisions",
                          "1",
                          Patterns::Integer(1, 10000),
                          "Number of layers of cells along the axis [-] (3D).");
        prm.leave_subsection();
      }


      template <int dim>
      void
      CylinderSegment<dim>::parse_more(ParameterHandler &prm)
      {
        length = prm.get_double("Length");
        layers = prm.get_integer("Axial subdivisions");
      }


      template <int dim>
      void
      CylinderSegment<dim>::build(Triangulation<dim> &tria) const
      {
        if constexpr (dim == 2)
          this->template make_disc_segment<2>(tria);
        else
          {
            Triangulation<2> disc;
            this->template make_disc_segment<2>(disc);
            // Side walls keep 0/1/2 (and the inner face); put the end caps
            // on 3 and 4 and the inner face on 5.
            const unsigned int inner =
              this->template n_disc_face_groups<2>() - 1;
            GridGenerator::extrude_triangulation(disc,
                                                 layers + 1,
                                                 length,
                                                 tria);
            for (const auto &face : tria.active_face_iterators())
              if (face->at_boundary())
                {
                  const double z = face->center()[2];
                  if (std::abs(z) < 1e-12 * length)
                    face->set_boundary_id(3);
                  else if (std::abs(z - length) < 1e-12 * length)
                    face->set_boundary_id(4);
                  else if (this->inner_radius > 0 &&
                           face->boundary_id() == inner)
                    face->set_boundary_id(5);
                }
          }
        GridTools::shift(this->centre, tria);
      }


      template <int dim>
      unsigned int
      CylinderSegment<dim>::n_face_groups() const
      {
        return dim == 2 ? this->template n_disc_face_groups<2>() :
                          (this->inner_radius > 0 ? 6 : 5);
      }


      template <int dim>
      std::string
      CylinderSegment<dim>::subsection() const
      {
        return "Cylinder segment";
      }


      template <int dim>
      bool
      CylinderSegment<dim>::cylindrical() const
      {
        return true;
      }

      template class SegmentBase<2>;
      template class SegmentBase<3>;
      template class BallSegment<2>;
      template class BallSegment<3>;
      template class CylinderSegment<2>;
      template class CylinderSegment<3>;
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini

SIGNORINI_REGISTER_SHAPE(
  Signorini::Geometry::Shapes::BallSegment,
  "ball segment",
  "disc (2D) or ball (3D) of 'Radius' about 'Centre', solid or hollow, cut "
  "to the 'Segment' below the centre (flat face on top, curved face down); "
  "face groups 0 curved, 1 flat top (y = centre), for a quarter 2 the side "
  "x = centre and (3D) 3 the side z = centre, then the inner curved face")
SIGNORINI_REGISTER_SHAPE(
  Signorini::Geometry::Shapes::CylinderSegment,
  "cylinder segment",
  "the disc segment extruded along z over 'Length' (3D; the disc segment in "
  "2D); face groups 0 curved, 1 top, 2 side x = centre (quarter), 3 z-, 4 "
  "z+, 5 the inner curved face of a tube")
