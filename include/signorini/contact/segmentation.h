#ifndef signorini_contact_segmentation_h
#define signorini_contact_segmentation_h

#include <deal.II/base/point.h>

#include <vector>

/**
 * Segment-based ("mortar") integration on one slave face (doc/theory.md
 * section 6). The slave face is cut into pieces by the master faces it
 * overlaps, so that the coupling integrands (psi x N^m, the gap) are smooth
 * on every piece; Gauss points are placed on each piece.
 *
 * Everything is done in the reference coordinates xi of the slave face
 * (its FE_Q<dim-1> parametrisation, the unit interval or square): the
 * vertices of each master face are carried onto the slave face along the
 * slave normal at the face centre, which is the slave face's own plane for
 * a flat face. In that plane
 *  - 2D: each master face covers an interval of [0,1]; the union of their
 *    end points cuts [0,1] into sub-intervals, each with QGauss<1>(n);
 *  - 3D: each master face covers a polygon; the unit square is partitioned
 *    into convex pieces covered by exactly one master face (or by none) by
 *    clipping (Sutherland-Hodgman) the uncovered pieces against each master
 *    polygon in turn; every piece is fanned into triangles, each with the
 *    Witherden-Vincent rule of n points per direction (exact to degree
 *    2n - 1).
 * For flat faces the maps between slave xi, the plane and master xi are
 * affine on every piece, so a rule exact to the polynomial degree of
 * psi x N^m integrates the coupling terms exactly; curved faces are
 * followed through their maps (the master edges are straight between the
 * carried vertices).
 *
 * Pieces not covered by any master face keep their points (master -1):
 * every slave node keeps its multiplier equations.
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    template <int dim>
    struct Segmentation
    {
      std::vector<Point<dim - 1>> points;  // on the unit slave face
      std::vector<double>         weights; // sum to 1 (unit face measure)
      std::vector<int>            master;  // index into the candidates, or -1
      unsigned int                n_pieces = 0;
    };

    /**
     * @param slave      current positions of the slave face nodes
     *                   (FE_Q<dim-1> order, as project_onto_face)
     * @param candidates current node positions of the master faces that may
     *                   overlap the slave face
     * @param n_points   points per direction on each piece (>= 1)
     */
    template <int dim>
    Segmentation<dim>
    segment_slave_face(
      const std::vector<Point<dim>>                      &slave,
      const std::vector<const std::vector<Point<dim>> *> &candidates,
      const unsigned int                                  n_points);

    template <>
    Segmentation<2>
    segment_slave_face<2>(const std::vector<Point<2>> &,
                          const std::vector<const std::vector<Point<2>> *> &,
                          const unsigned int);
    template <>
    Segmentation<3>
    segment_slave_face<3>(const std::vector<Point<3>> &,
                          const std::vector<const std::vector<Point<3>> *> &,
                          const unsigned int);

    /** The smallest points-per-direction for which segment_slave_face
     * integrates psi x N^m exactly on flat faces of degree @p fe_degree:
     * degree 2p in 2D (p + 1 Gauss points), total degree 4p in 3D. */
    template <int dim>
    unsigned int
    exact_segment_order(const unsigned int fe_degree)
    {
      return dim == 2 ? fe_degree + 1 : 2 * fe_degree + 1;
    }
  } // namespace Contact
} // namespace Signorini

#endif
