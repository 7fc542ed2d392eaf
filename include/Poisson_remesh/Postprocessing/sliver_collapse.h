// Poisson_remesh/Postprocessing/sliver_collapse.h
//
// (beyond the paper) Sliver collapse. Objective: the smallest angle in the vertex stars around a
// sliver whose short edge no vertex move can lengthen (pinned between corners and feature samples).
// A triangle under `sliver_angle` whose shortest edge is under `edge_ratio` of its longest loses
// that edge by a collapse onto its more constrained end (corner > feature vertex > free vertex;
// two corners closer than the sampling allows are merged), when the link condition holds, no
// triangle folds and the smallest angle around improves. Constraints: the link condition (no
// topology change); a feature vertex leaves only along its curve; the kept vertex keeps its place
// on the input.

#ifndef POISSON_REMESH_POSTPROCESSING_SLIVER_COLLAPSE_H
#define POISSON_REMESH_POSTPROCESSING_SLIVER_COLLAPSE_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <algorithm>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// The sliver collapse's settings.
struct Sliver_collapse_settings
{
  bool enabled = true;   ///< false disables the collapses
  /// a sliver's shortest edge must be under this share of its longest to be collapsed (a triangle
  /// of three corners closer than the spacing has about half)
  double edge_ratio = 0.5;
  /// the collapses may also merge two corners joined by the sliver's short edge
  bool merge_close_corners = true;
};

/// Collapses the short edges of the triangles of `m` sharper than `sliver_angle` (degrees).
/// Returns the number of collapses.
template <class Context, class Mesh, class IsFeatureEdge, class IsCorner>
std::size_t collapse_slivers(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, const Sliver_collapse_settings& s,
                             double sliver_angle, Relaxation_statistics& stats)
{
  typedef typename Context::Point_3 Point_3;
  typedef boost::graph_traits<Mesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  auto vpm = get(CGAL::vertex_point, m);
  const double sliver = sliver_angle * CGAL_PI / 180;
  // the short edges of the slivers, shortest first
  std::vector<std::pair<double, std::pair<vertex_descriptor, vertex_descriptor>>> candidates;
  for(auto f : faces(m)) {
    const auto h = halfedge(f, m);
    const vertex_descriptor v[3] = {source(h, m), target(h, m), target(next(h, m), m)};
    const Point_3 p[3] = {get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2])};
    if(ctx.min_angle(p[0], p[1], p[2]) >= sliver) continue;
    double l[3];
    for(int i = 0; i < 3; ++i) l[i] = std::sqrt(CGAL::to_double(CGAL::squared_distance(p[i], p[(i + 1) % 3])));
    const int k = int(std::min_element(l, l + 3) - l);
    if(l[k] < s.edge_ratio * std::max({l[0], l[1], l[2]})) candidates.push_back({l[k], {v[k], v[(k + 1) % 3]}});
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<vertex_descriptor> removed;
  std::size_t done = 0;
  for(const auto& c : candidates) {
    vertex_descriptor a = c.second.first, b = c.second.second;
    if(std::find(removed.begin(), removed.end(), a) != removed.end() || std::find(removed.begin(), removed.end(), b) != removed.end()) continue;
    const auto ab = halfedge(a, b, m);
    if(!ab.second) continue;
    const auto e = edge(ab.first, m);
    const int ca = ctx.constraint(a, m, is_feature, is_corner), cb = ctx.constraint(b, m, is_feature, is_corner);
    if(ca < cb) std::swap(a, b);   // a is kept, b goes
    const int cr = std::min(ca, cb);
    // two fixed ends: two corners closer than the sampling allows are merged (the junction of
    // more curves stays; the merged one moves by less than the sliver's short edge)
    if(cr == 2) {
      if(!s.merge_close_corners) continue;
      if(ctx.feature_degree(b, m, is_feature) > ctx.feature_degree(a, m, is_feature)) std::swap(a, b);
    }
    if(cr == 1 && !is_feature(e) && !is_border(e, m)) continue;   // a feature vertex leaves only along its curve
    if(!CGAL::Euler::does_satisfy_link_condition(e, m)) continue;
    const auto hba = halfedge(b, a, m).first;
    bool ok = true;
    for(auto g : {hba, opposite(hba, m)})
      if(!is_border(g, m) && degree(target(next(g, m), m), m) <= 3) ok = false;
    if(!ok) continue;
    // the faces around b take a's place: no fold, and a better smallest angle around
    const Point_3 pa = get(vpm, a);
    double before = CGAL_PI, after = CGAL_PI;
    for(vertex_descriptor x : {a, b})
      for(auto g : CGAL::halfedges_around_target(x, m)) {
        if(is_border(g, m)) continue;
        before = std::min(before, ctx.min_angle(get(vpm, source(g, m)), get(vpm, x), get(vpm, target(next(g, m), m))));
      }
    for(auto g : CGAL::halfedges_around_target(b, m)) {
      if(is_border(g, m)) continue;
      const vertex_descriptor x = source(g, m), y = target(next(g, m), m);
      if(x == a || y == a) continue;   // one of the two faces that go
      const Point_3 px = get(vpm, x), py = get(vpm, y);
      if(ctx.cos_between(ctx.normal(px, get(vpm, b), py), ctx.normal(px, pa, py)) < 0.5) { ok = false; break; }
      after = std::min(after, ctx.min_angle(px, pa, py));
    }
    if(!ok) continue;
    for(auto g : CGAL::halfedges_around_target(a, m)) {
      if(is_border(g, m)) continue;
      const vertex_descriptor x = source(g, m), y = target(next(g, m), m);
      if(x == b || y == b) continue;
      after = std::min(after, ctx.min_angle(get(vpm, x), pa, get(vpm, y)));
    }
    if(!(after > before)) continue;
    // collapse_edge(e) keeps target(halfedge(e)): a must be that vertex
    if(target(halfedge(edge(hba, m), m), m) != a) continue;
    const vertex_descriptor kept = CGAL::Euler::collapse_edge(edge(hba, m), m);
    put(vpm, kept, pa);
    removed.push_back(b);
    ++done;
  }
  stats.collapses += done;
  return done;
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_SLIVER_COLLAPSE_H
