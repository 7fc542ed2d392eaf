// Poisson_remesh/Relaxation/lloyd_step.h
//
// The Lloyd step of paper §6.2 (Eq. 6). The one-ring of a free vertex is laid out in the plane
// (the exponential-map layout of §6.1: radial lengths kept, angles scaled to sum to 2 pi); the
// vertex moves to the density-weighted mean of its triangles' centroids (uniform density: their
// mean), mapped back through the ring triangle that contains it, then projected onto the INPUT
// surface (closest point, CGAL AABB tree), so vertices always lie on the input. A feature vertex
// (two incident feature edges) slides along its curve to the midpoint of its two feature
// neighbours, projected onto the input's feature edges; corners and vertices where features meet
// do not move. A move that would fold an incident triangle is refused. With CGAL::Parallel_tag the
// vertices whose earlier neighbours have moved move at once, with the sequential pass's result.

#ifndef POISSON_REMESH_RELAXATION_LLOYD_STEP_H
#define POISSON_REMESH_RELAXATION_LLOYD_STEP_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/internal/parallel.h>
#include <boost/container/small_vector.hpp>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {

namespace Relaxation {

/// Uniform density for the Lloyd centroids.
struct Unit_density
{
  /// 1 at every vertex
  template <class V> double operator()(V) const { return 1.0; }
};

/// Eq. 6 in the exponential-map layout of the one-ring of `v`, mapped back to 3D: the centroid of
/// the ring's triangles' centroids, weighted by their area (`area_weighted`; else alike) times their
/// mean density (`vertex_density(x)` > 0 at the vertices). False when the ring is degenerate.
template <class Context, class Mesh, class VertexDensity>
bool lloyd_target(const Context& ctx, typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m,
                  typename Context::Point_3& target, VertexDensity vertex_density, bool area_weighted = true)
{
  typedef typename Context::Point_3 Point_3;
  constexpr bool uniform = std::is_same<VertexDensity, Unit_density>::value;
  // (rings rarely have more than 16 vertices: no allocation per vertex)
  boost::container::small_vector<Point_3, 16> ring;
  boost::container::small_vector<double, 16> ring_density;
  for(auto h : CGAL::halfedges_around_target(v, m)) {
    ring.push_back(get(get(CGAL::vertex_point, m), source(h, m)));
    if constexpr(!uniform) ring_density.push_back(vertex_density(source(h, m)));
  }
  std::reverse(ring.begin(), ring.end());  // counter-clockwise around v
  std::reverse(ring_density.begin(), ring_density.end());
  double own_density = 1;
  if constexpr(!uniform) own_density = vertex_density(v);
  const std::size_t n = ring.size();
  if(n < 3) return false;
  const Point_3& p = get(get(CGAL::vertex_point, m), v);
  boost::container::small_vector<double, 16> theta(n), len(n);
  double total = 0;
  for(std::size_t i = 0; i < n; ++i) {
    theta[i] = ctx.angle(ring[i], p, ring[(i + 1) % n]);
    len[i] = std::sqrt(CGAL::to_double(CGAL::squared_distance(ring[i], p)));
    total += theta[i];
  }
  if(!(total > 0)) return false;
  boost::container::small_vector<std::array<double, 2>, 16> q(n);
  double phi = 0;
  for(std::size_t i = 0; i < n; ++i) {
    q[i] = {{len[i] * std::cos(phi), len[i] * std::sin(phi)}};
    phi += 2 * CGAL_PI * theta[i] / total;
  }
  double cx = 0, cy = 0, wsum = 0;
  for(std::size_t i = 0; i < n; ++i) {
    const auto& a = q[i];
    const auto& b = q[(i + 1) % n];
    double w = area_weighted ? 0.5 * std::abs(a[0] * b[1] - a[1] * b[0]) : 1.0;
    if constexpr(!uniform) w *= (own_density + ring_density[i] + ring_density[(i + 1) % n]) / 3.0;
    cx += w * (a[0] + b[0]) / 3.0;
    cy += w * (a[1] + b[1]) / 3.0;
    wsum += w;
  }
  if(!(wsum > 0)) return false;
  cx /= wsum;
  cy /= wsum;
  // the ring triangle (0, q_i, q_i+1) that contains (cx, cy)
  for(int shrink = 0; shrink < 8; ++shrink) {
    for(std::size_t i = 0; i < n; ++i) {
      const auto& a = q[i];
      const auto& b = q[(i + 1) % n];
      const double det = a[0] * b[1] - a[1] * b[0];
      if(!(std::abs(det) > 0)) continue;
      const double u = (cx * b[1] - cy * b[0]) / det, w = (a[0] * cy - a[1] * cx) / det;
      if(u >= -1e-12 && w >= -1e-12 && u + w <= 1 + 1e-12) {
        const Point_3& A = ring[i];
        const Point_3& B = ring[(i + 1) % n];
        target = p + u * (A - p) + w * (B - p);
        return true;
      }
    }
    cx *= 0.5;  // concave ring: pull towards the vertex until inside
    cy *= 0.5;
  }
  return false;
}

/// One Lloyd pass over the vertices of `m`: each movable vertex moves to its Lloyd target (a free
/// vertex, projected onto the input; a feature vertex, along its curve), unless the move folds a
/// triangle or `guard(v, m, feature_degree, max_jump, target)` refuses it (it may also shorten it).
/// The vertices move in the order of vertices(m), one by one; with `ConcurrencyTag` =
/// CGAL::Parallel_tag, in rounds of vertices whose earlier neighbours have moved
/// (internal/parallel.h), each round at once: the same result for any number of threads, and in
/// both modes. `is_feature`, `is_corner`, `vertex_density` and `guard` are then called from several
/// threads; they must only read.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge, class IsCorner, class VertexDensity, class Guard>
void lloyd_pass(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, Relaxation_statistics& stats,
                VertexDensity vertex_density, bool area_weighted, Guard guard)
{
  typedef typename Context::Point_3 Point_3;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  constexpr bool uniform = std::is_same<VertexDensity, Unit_density>::value;
  // (the density read before the moves, in the order in which the moves below read it: a
  // caller's density may fill itself in lazily, in that order, which several threads may not do
  // at once; it depends on the connectivity alone, which the moves keep)
  auto density_map = get(CGAL::dynamic_vertex_property_t<double>(), m);
  if constexpr(!uniform)
    for(vertex_descriptor v : vertices(m)) {
      if(is_corner(v) || ctx.feature_degree(v, m, is_feature) != 0) continue;
      for(auto h : CGAL::halfedges_around_target(v, m)) put(density_map, source(h, m), vertex_density(source(h, m)));
      put(density_map, v, vertex_density(v));
    }
  auto density = [&](vertex_descriptor v) { return get(density_map, v); };
  enum Outcome : char { unmoved, moved, refused };
  auto move = [&](vertex_descriptor v) -> Outcome {
    if(is_corner(v)) return unmoved;
    const std::size_t fd = ctx.feature_degree(v, m, is_feature);
    Point_3 target;
    double max_jump = 0;   // (a free vertex: how far its projection onto the input may jump)
    if(fd == 0) {
      bool found;
      if constexpr(uniform) found = lloyd_target(ctx, v, m, target, vertex_density, area_weighted);
      else found = lloyd_target(ctx, v, m, target, density, area_weighted);
      if(!found) return unmoved;
      // the closest point of the input must be the local one: in thin parts (horns, legs, tails)
      // the other side can be closer; a projection farther than a fraction of the ring's size
      // is refused (the paper projects through a local parameterization for the same reason)
      const Point_3 projected = ctx.project_on_surface(target, get(get(CGAL::vertex_point, m), v));
      double ring = 0;
      std::size_t nr = 0;
      for(auto h : CGAL::halfedges_around_target(v, m)) {
        ring += std::sqrt(CGAL::to_double(CGAL::squared_distance(get(get(CGAL::vertex_point, m), source(h, m)), get(get(CGAL::vertex_point, m), v))));
        ++nr;
      }
      if(nr > 0) max_jump = 0.25 * ring / double(nr);
      if(nr == 0 || CGAL::to_double(CGAL::squared_distance(projected, target)) > CGAL::square(max_jump)) return refused;
      target = projected;
    } else if(fd == 2) {
      boost::container::small_vector<Point_3, 4> ends;
      for(auto h : CGAL::halfedges_around_target(v, m))
        if(is_feature(edge(h, m)) || is_border(edge(h, m), m)) ends.push_back(get(get(CGAL::vertex_point, m), source(h, m)));
      target = ctx.project_on_features(CGAL::midpoint(ends[0], ends[1]), get(get(CGAL::vertex_point, m), v));
    } else {
      return unmoved;
    }
    if(ctx.folds(v, m, target)) return refused;
    // (beyond the paper: Postprocessing/lloyd_guard.h)
    if(!guard(v, m, fd, max_jump, target)) return refused;
    // (no other vertex of this round reads v's point: it is in none of their rings)
    put(get(CGAL::vertex_point, m), v, target);
    return moved;
  };
  std::vector<Outcome> outcome;
  std::vector<vertex_descriptor> movable;
  for(vertex_descriptor v : vertices(m)) if(!is_corner(v)) movable.push_back(v);
  for(const auto& round : internal::dependency_rounds(m, movable)) {
    outcome.assign(round.size(), unmoved);
    internal::for_each_index<ConcurrencyTag>(round.size(), [&](std::size_t i) { outcome[i] = move(round[i]); });
    for(Outcome o : outcome) {
      if(o == moved) ++stats.moves;
      if(o == refused) ++stats.refused_moves;
    }
  }
}

} // namespace Relaxation

} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_LLOYD_STEP_H
