// Poisson_remesh/Geodesic/Iso_arc.h
//
// The iso-distance curves that the geodesic oracles return (paper §4.2.2, §5.1): pieces of circle,
// conic or segment, each in one face, chained into curves. Shared by every oracle of the package
// and by the available boundary.
//
// Face-local 2D frame convention (used by `Iso_arc`):
//   Let h0 = halfedge(f), v0 = source(h0), v1 = target(h0),
//   v2 = target(next(h0)).  The face is laid out isometrically in the plane
//   with v0 = (0,0), v1 = (|v0v1|, 0) and v2 = (x2, y2) with y2 > 0, so the
//   face is counter-clockwise in its frame (consistent with the mesh
//   orientation).  The barycentric coordinates of a `Face_location` use the
//   same vertex order (this is also CGAL's PMP/locate convention).

#ifndef POISSON_REMESH_GEODESIC_ISO_ARC_H
#define POISSON_REMESH_GEODESIC_ISO_ARC_H

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/locate.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace Poisson_remesh {

// ---------------------------------------------------------------------------
// Iso-distance curves (shared by all geodesic oracles of the package)
// ---------------------------------------------------------------------------

/// One piece of an iso-distance curve, contained in a single face.
/// It is either a circular arc (exact oracle, uniform density), a conic arc
/// (exact oracle, adaptive density: paper §5.1, Eq. 4-5) or a straight segment
/// (`is_segment == true`, approximate oracle).  All 2D quantities are given
/// in the face-local 2D frame described at the top of this file.
///
/// Conic arcs: the points x with |x - center| = radius + gradient . (x - center),
/// in polar form around `center` rho(theta) = radius / (1 - gradient . u(theta)),
/// u(theta) = (cos theta, sin theta): an ellipse with a focus at `center` and
/// eccentricity |gradient| < 1.  A circle is the case gradient = 0.
template <class FaceDescriptor, class Point3>
struct Iso_arc
{
  FaceDescriptor face;   ///< the face that holds the arc
  /// circle center / conic focus: the unfolded (pseudo-)source in the face frame
  std::array<double, 2> center{{0., 0.}};
  /// circle radius, i.e. `R - sigma`; for a conic its semi-latus rectum
  double radius = 0.;
  /// the gradient of the disk radius r(x) in the face (Eq. 3): zero for a circle
  std::array<double, 2> gradient{{0., 0.}};

  /// true for a conic arc (adaptive density), false for a circular one
  bool is_conic() const { return gradient[0] != 0. || gradient[1] != 0.; }
  /// distance from the center to the curve in direction theta
  double rho(double th) const
  {
    if(!is_conic()) return radius;
    return radius / (1. - gradient[0] * std::cos(th) - gradient[1] * std::sin(th));
  }
  /// < 0 inside the region the arc bounds (closer to the source than the level), > 0 outside
  double level_function(const std::array<double, 2>& x) const
  {
    const double dx = x[0] - center[0], dy = x[1] - center[1];
    return std::sqrt(dx * dx + dy * dy) - radius - gradient[0] * dx - gradient[1] * dy;
  }
  /// geodesic distance from the source to `center` (the pseudo-source)
  double sigma = 0.;
  /// counter-clockwise angular range, `theta_start <= theta_end <= theta_start + 2 pi`
  /// @{
  double theta_start = 0., theta_end = 0.;
  /// @}
  /// straight-segment pieces (approximate oracle): endpoints in the face frame
  bool is_segment = false;
  /// the endpoints of a straight piece (`is_segment`), in the face frame
  /// @{
  std::array<double, 2> segment_start{{0., 0.}}, segment_end{{0., 0.}};
  /// @}
  /// 3D positions of v0, v1, v2 of the face
  std::array<Point3, 3> corners;
  /// the 2D layout (|v0v1|, x2, y2) of the face
  std::array<double, 3> layout{{1., 0., 1.}};

  /// point of parameter `t` in [0,1] in the face frame
  std::array<double, 2> point_2(double t) const
  {
    if(is_segment)
      return {{segment_start[0] + t * (segment_end[0] - segment_start[0]),
               segment_start[1] + t * (segment_end[1] - segment_start[1])}};
    const double th = theta_start + t * (theta_end - theta_start);
    const double r = rho(th);
    return {{center[0] + r * std::cos(th), center[1] + r * std::sin(th)}};
  }
  /// barycentric coordinates (w.r.t. v0, v1, v2) of the point of parameter `t`
  std::array<double, 3> barycentric(double t) const
  {
    const std::array<double, 2> p = point_2(t);
    const double l0 = layout[0], x2 = layout[1], y2 = layout[2];
    double b2 = p[1] / y2;
    double b1 = (p[0] - b2 * x2) / l0;
    double b0 = 1. - b1 - b2;
    return {{b0, b1, b2}};
  }
  /// 3D point of parameter `t` in [0,1]
  Point3 point(double t) const
  {
    const std::array<double, 3> b = barycentric(t);
    return Point3(b[0] * corners[0].x() + b[1] * corners[1].x() + b[2] * corners[2].x(),
                  b[0] * corners[0].y() + b[1] * corners[1].y() + b[2] * corners[2].y(),
                  b[0] * corners[0].z() + b[1] * corners[1].z() + b[2] * corners[2].z());
  }
  /// length of the arc (isometric to the surface length)
  double length() const
  {
    if(is_segment)
      return std::sqrt((segment_end[0] - segment_start[0]) * (segment_end[0] - segment_start[0]) + (segment_end[1] - segment_start[1]) * (segment_end[1] - segment_start[1]));
    if(!is_conic()) return radius * (theta_end - theta_start);
    // |d/dtheta (rho u)| = sqrt(rho^2 + rho'^2), integrated by 4-point Gauss-Legendre on pieces
    // of at most pi/8 (relative error < 1e-9 for eccentricities up to 0.9)
    const double span = theta_end - theta_start;
    if(!(span > 0.)) return 0.;
    const int pieces = 1 + int(span / (3.14159265358979323846 / 8.));
    const double h = span / pieces;
    static const double xg[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    static const double wg[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    double total = 0.;
    for(int k = 0; k < pieces; ++k)
      for(int i = 0; i < 4; ++i) {
        const double th = theta_start + h * (k + 0.5 + 0.5 * xg[i]);
        const double c = std::cos(th), s = std::sin(th);
        const double den = 1. - gradient[0] * c - gradient[1] * s;
        const double r = radius / den;
        const double dr = -radius * (gradient[0] * s - gradient[1] * c) / (den * den);
        total += 0.5 * h * wg[i] * std::sqrt(r * r + dr * dr);
      }
    return total;
  }
};

/// An ordered chain of arcs.  `closed` is true when the last arc ends where the
/// first one starts; open chains end on the mesh border.  Arcs are oriented
/// counter-clockwise around their centers, i.e. the region closer than `R`
/// to the source lies on the left of the curve (seen from the outward side
/// of the consistently oriented mesh).
template <class FaceDescriptor, class Point3>
struct Iso_curve
{
  std::vector<Iso_arc<FaceDescriptor, Point3> > arcs;   ///< the arcs, in order along the curve
  bool closed = false;   ///< true when the last arc ends where the first one starts
};

} // namespace Poisson_remesh

#endif // POISSON_REMESH_GEODESIC_ISO_ARC_H
