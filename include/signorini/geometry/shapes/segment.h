#ifndef signorini_geometry_shapes_segment_h
#define signorini_geometry_shapes_segment_h

#include <signorini/geometry/shapes/interface.h>

namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      /**
       * What the ball and cylinder segments share: the disc (2D) or ball
       * (3D) of 'Radius' about 'Centre', solid or hollow ('Inner radius'),
       * cut to the 'Segment' below the centre: its curved side down, its
       * flat face on top.
       */
      template <int dim>
      class SegmentBase : public Interface<dim>
      {
      public:
        /** Declares the shared entries in the current subsection. */
        static void
        declare_segment_entries(ParameterHandler &prm);

        void
        parse_parameters(ParameterHandler  &prm,
                         const std::string &input_directory) override;

        CurvedSurface<dim>
        curved_surface(const Triangulation<dim> &tria,
                       const Placement<dim>     &placement) const override;

      protected:
        /** The subsection of the shape's entries. */
        virtual std::string
        subsection() const = 0;

        /** Reads the entries of the derived shape (in its subsection). */
        virtual void
        parse_more(ParameterHandler &prm);

        /** The number of face groups of the disc or ball segment: 1 full,
         * 2 half, 3 (2D) or 4 (3D) quarter, one more if hollow. */
        template <int d>
        unsigned int
        n_disc_face_groups() const;

        /** The disc (d = 2) or ball (d = 3) segment about the origin with
         * its face groups: 0 the outer curved face, 1 the top (y = 0), 2
         * the side x = 0, 3 the side z = 0, then the inner curved face. */
        template <int d>
        void
        make_disc_segment(Triangulation<d> &tria) const;

        /** True for a cylinder along z through 'Centre' (else a sphere
         * about it). */
        virtual bool
        cylindrical() const = 0;

        enum class Cut
        {
          full,
          half,
          quarter
        };

        Point<dim> centre;
        double     radius       = 1;
        double     inner_radius = 0; // 0: solid
        Cut        cut          = Cut::half;
      };


      /**
       * A ball segment: a disc (2D) or ball (3D). Face groups: 0 the
       * curved face, 1 the flat top (y = centre), for a quarter 2 the side
       * x = centre and (3D) 3 the side z = centre, then the inner curved
       * face of a hollow one. Parameters: subsection 'Ball segment'.
       */
      template <int dim>
      class BallSegment : public SegmentBase<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm);

        void
        build(Triangulation<dim> &tria) const override;

        unsigned int
        n_face_groups() const override;

      protected:
        std::string
        subsection() const override;

        bool
        cylindrical() const override;
      };


      /**
       * A cylinder segment (3D): the disc segment extruded along z over
       * 'Length' from 'Centre', with 'Axial subdivisions' layers of cells.
       * Face groups: 0 curved, 1 top, 2 the side x = centre (quarter), 3
       * z-, 4 z+, 5 the inner curved face of a tube. In 2D it is the disc
       * segment. Parameters: subsection 'Cylinder segment'.
       */
      template <int dim>
      class CylinderSegment : public SegmentBase<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm);

        void
        build(Triangulation<dim> &tria) const override;

        unsigned int
        n_face_groups() const override;

      protected:
        std::string
        subsection() const override;

        bool
        cylindrical() const override;

        void
        parse_more(ParameterHandler &prm) override;

      private:
        double       length = 1;
        unsigned int layers = 1;
      };
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini

#endif
