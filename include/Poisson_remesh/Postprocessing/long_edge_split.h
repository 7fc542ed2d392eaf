// Poisson_remesh/Postprocessing/long_edge_split.h
//
// (beyond the paper) Long feature edges split. Objective: the distance to the input along the
// features, and the smallest angle of the triangles beside a feature edge much longer than its
// neighbours (where a feature sample was refused, too close to another curve's). Such an edge is
// split at its midpoint projected onto the input's features, unless the curve bends away from the
// edge or a new triangle would turn. Constraints: the new vertex is on the input's features; no
// topology change (an edge split).

#ifndef POISSON_REMESH_POSTPROCESSING_LONG_EDGE_SPLIT_H
#define POISSON_REMESH_POSTPROCESSING_LONG_EDGE_SPLIT_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// The long-edge split's settings.
struct Long_edge_split_settings
{
  /// a feature or border edge longer than this times the mean length of the other edges at its
  /// ends is split; 0 disables
  double ratio = 1.6;
};

/// Splits the long feature and border edges of `m`; `new_vertex(v, on_feature)` is told each new
/// vertex. Returns the number of splits.
template <class Context, class Mesh, class IsFeatureEdge, class NewVertex>
std::size_t split_long_feature_edges(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, NewVertex new_vertex,
                                     const Long_edge_split_settings& s, Relaxation_statistics& stats)
{
  typedef typename Context::Point_3 Point_3;
  typedef typename Context::Vector_3 Vector_3;
  typedef boost::graph_traits<Mesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  auto vpm = get(CGAL::vertex_point, m);
  auto length = [&](vertex_descriptor a, vertex_descriptor b) { return std::sqrt(CGAL::to_double(CGAL::squared_distance(get(vpm, a), get(vpm, b)))); };
  std::vector<std::pair<vertex_descriptor, vertex_descriptor>> long_edges;
  for(auto e : edges(m)) {
    if(!is_feature(e) && !is_border(e, m)) continue;   // (free edges: the Lloyd rounds even them out)
    const vertex_descriptor a = source(halfedge(e, m), m), b = target(halfedge(e, m), m);
    double sum = 0;
    std::size_t n = 0;
    for(vertex_descriptor x : {a, b})
      for(auto h : CGAL::halfedges_around_target(x, m))
        if(edge(h, m) != e && !is_feature(edge(h, m)) && !is_border(edge(h, m), m)) { sum += length(source(h, m), x); ++n; }
    if(n > 0 && length(a, b) > s.ratio * sum / double(n)) long_edges.push_back({a, b});
  }
  std::size_t done = 0;
  for(const auto& ab : long_edges) {
    const auto h = halfedge(ab.first, ab.second, m);
    if(!h.second) continue;
    const bool on_feature = is_feature(edge(h.first, m)) || is_border(edge(h.first, m), m);
    const Point_3 chord_mid = CGAL::midpoint(get(vpm, ab.first), get(vpm, ab.second));
    const Point_3 mid = on_feature ? ctx.project_on_features(chord_mid) : ctx.project_on_surface(chord_mid);
    // the feature must run along the edge: a curve that bends away (the projection lands far
    // from the chord) would fold the new triangles
    if(CGAL::to_double(CGAL::squared_distance(mid, chord_mid)) > CGAL::square(0.1 * length(ab.first, ab.second))) continue;
    // and the four new triangles stay close to the two old ones (no fold on thin parts)
    bool folds = false;
    for(halfedge_descriptor g : {h.first, opposite(h.first, m)}) {
      if(is_border(g, m)) continue;
      const Point_3 &P = get(vpm, source(g, m)), &Q = get(vpm, target(g, m)), &R = get(vpm, target(next(g, m), m));
      const Vector_3 n = ctx.normal(P, Q, R);
      if(ctx.cos_between(ctx.normal(P, mid, R), n) < 0.8 || ctx.cos_between(ctx.normal(mid, Q, R), n) < 0.8) folds = true;
    }
    if(folds) continue;
    const vertex_descriptor v = ctx.insert_vertex_on_edge(h.first, mid, m);
    new_vertex(v, on_feature);
    ++done;
  }
  stats.splits += done;
  return done;
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_LONG_EDGE_SPLIT_H
