// Poisson_remesh/Geodesic/internal/window_geometry.h
//
// The one-dimensional geometry of window propagation (Surazhsky et al. 2005, §3): snapping of
// source locations, a window's distance function along its edge, where two of them are equal,
// and the intervals of an edge that a window keeps.

#ifndef POISSON_REMESH_GEODESIC_INTERNAL_WINDOW_GEOMETRY_H
#define POISSON_REMESH_GEODESIC_INTERNAL_WINDOW_GEOMETRY_H

#include <Poisson_remesh/Geodesic/internal/Indexed_triangle_mesh.h>

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
namespace internal {

/// Snaps a barycentric triple: negative or tiny values are set to zero and the
/// triple is renormalised.  Returns the number of non-zero coordinates.
/// The threshold, 1e-12, moves a point by at most 1e-12 x (edge length); a source a
/// few 1e-15 off a vertex, not snapped, produces degenerate windows that lose
/// whole regions (a feature sample at a crease vertex).
inline int snap_barycentric(std::array<double, 3>& b)
{
  for(double& x : b)
    if(!(x > 1e-12)) x = 0.;
  const double s = b[0] + b[1] + b[2];
  if(!(s > 0.)) b = {{1., 0., 0.}};
  else
    for(double& x : b) x /= s;
  return int(b[0] > 0.) + int(b[1] > 0.) + int(b[2] > 0.);
}

/// Distance function of a window along its edge: D(x) = sigma + sqrt((x-sx)^2 + sy^2).
struct Edge_distance_function
{
  double sx, sy2, sigma;
  double operator()(double x) const { return sigma + std::sqrt((x - sx) * (x - sx) + sy2); }
};

/// Roots in the open interval (lo, hi) of D1(x) = D2(x), candidate values
/// from the squared equation (spurious roots are harmless: callers classify
/// the sub-intervals by evaluation).  Returns the number of roots written.
inline int equal_distance_points(const Edge_distance_function& f1, const Edge_distance_function& f2,
                                 double lo, double hi, double* roots)
{
  // shift the origin for conditioning
  const double a = f1.sx - lo, b = f2.sx - lo, A = f1.sy2, B = f2.sy2;
  const double alpha = f2.sigma - f1.sigma;
  // m x + c = 2 alpha sqrt((x-b)^2 + B)
  const double m = 2. * (b - a);
  const double c = a * a + A - b * b - B - alpha * alpha;
  const double qa = m * m - 4. * alpha * alpha;
  const double qb = 2. * m * c + 8. * alpha * alpha * b;
  const double qc = c * c - 4. * alpha * alpha * (b * b + B);
  double r[2];
  int n = 0;
  const double scale = (std::max)({std::abs(qb), std::abs(qc), 1e-300});
  if(std::abs(qa) <= 1e-14 * scale)
  {
    if(qb != 0.) r[n++] = -qc / qb;
  }
  else
  {
    double disc = qb * qb - 4. * qa * qc;
    if(disc < 0.) disc = (disc > -1e-12 * qb * qb) ? 0. : -1.;
    if(disc >= 0.)
    {
      const double sq = std::sqrt(disc);
      const double q = -0.5 * (qb + (qb >= 0. ? sq : -sq));
      r[n++] = q / qa;
      if(q != 0.) r[n++] = qc / q;
    }
  }
  int out = 0;
  const double w = hi - lo;
  for(int i = 0; i < n; ++i)
    if(r[i] > 0. && r[i] < w && std::isfinite(r[i])) roots[out++] = r[i] + lo;
  if(out == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  return out;
}

/// Small sorted set of disjoint closed intervals.
struct Interval_set
{
  std::vector<std::pair<double, double> > v;
  void subtract(double a, double b)
  {
    if(!(b > a)) return;
    std::size_t n = v.size();
    for(std::size_t i = 0; i < n; ++i)
    {
      std::pair<double, double>& I = v[i];
      if(I.second <= a || I.first >= b) continue;
      if(I.first < a && I.second > b)
      {
        const double e = I.second;
        I.second = a;
        v.push_back({b, e});
      }
      else if(I.first < a)
        I.second = a;
      else if(I.second > b)
        I.first = b;
      else
        I.second = I.first;  // emptied
    }
    v.erase(std::remove_if(v.begin(), v.end(), [](const std::pair<double, double>& I) { return !(I.second > I.first); }),
            v.end());
  }
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_GEODESIC_INTERNAL_WINDOW_GEOMETRY_H
