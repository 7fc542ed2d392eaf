// Poisson_remesh/Postprocessing/regularity_flips.h
//
// (beyond the paper) Regularity flips. Objective: the valence deviation (the number of vertices of
// valence other than 6, 4 on a border). Eq. 7-8 aims at the ideal valence of the angle sum, which
// is not 6 on curved parts, and its flips stop at about a quarter of irregular vertices. A flip is
// made when fewer of its four vertices are irregular after it and both new triangles keep their
// smallest angle over `min_angle`; with `lookahead`, a flip that only moves an irregular vertex is
// kept when a second flip beside it then removes one (irregular vertices stuck next to each other
// meet this way). A last round (`final_min_angle`) keeps 30 degrees and is taken back whole if it
// makes the mesh cut itself anew. Constraints: flips only (no topology change, vertices stay);
// feature and border edges are never flipped; the normal guard of the Delaunay flips.

#ifndef POISSON_REMESH_POSTPROCESSING_REGULARITY_FLIPS_H
#define POISSON_REMESH_POSTPROCESSING_REGULARITY_FLIPS_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// The regularity flips' settings.
struct Regularity_settings
{
  /// rounds of regularity flips after the angle smoothing (each followed by a smoothing round);
  /// they stop when a round flips nothing; 0 disables
  unsigned int rounds = 4;
  /// the smallest angle a regularity flip's triangles keep (degrees): a degree under the 30 degree
  /// floor, which the angle optimization and the refinement that follow lift back
  double min_angle = 29;
  /// a flip that leaves as many irregular vertices (it moves one: a 5-7 pair glides) is made when a
  /// flip of an edge at one of its four vertices then makes fewer; both flips under the same guards
  bool lookahead = true;
  /// after the regularity flips, a Delaunay flip that would make more irregular vertices is made
  /// only at a triangle sharper than the sliver angle whose smallest angle it raises (else the
  /// Delaunay flips of the angle optimization undo most regularity flips)
  bool keep_regularity = true;
  /// after the refinement, one more round of flips (no look-ahead) whose new triangles keep this
  /// smallest angle, or the mesh's smallest angle if larger (up to the angle optimization's
  /// optimized_angle); taken back whole if it makes the mesh cut itself anew; 0 disables
  double final_min_angle = 30;
};

/// One round of regularity flips of `m`; their triangles keep `min_angle_degrees` (< 0:
/// s.min_angle); `max_normal_change`: the flips' normal guard (degrees). With `flipped`, the
/// flipped edges are put there and no look-ahead flip is made (single flips can be undone in
/// reverse order). Returns the number of flips.
template <class Context, class Mesh, class IsFeatureEdge>
std::size_t regularity_flips(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, const Regularity_settings& s, double max_normal_change,
                             Relaxation_statistics& stats, double min_angle_degrees = -1,
                             std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor>* flipped = nullptr)
{
  const double cos_max = std::cos(max_normal_change * CGAL_PI / 180);
  const double floor = (min_angle_degrees < 0 ? s.min_angle : min_angle_degrees) * CGAL_PI / 180;
  typedef typename boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
  const int no = 99;
  // each vertex's degree and regular degree (6, or 4 on a border), read for the four vertices of
  // every edge looked at and kept up to date by the flips below (walking around the vertices each
  // time was most of the round's time)
  auto deg = get(CGAL::dynamic_vertex_property_t<int>(), m);
  auto regular = get(CGAL::dynamic_vertex_property_t<int>(), m);
  for(auto v : vertices(m)) {
    put(deg, v, int(degree(v, m)));
    put(regular, v, is_border(v, m) ? 4 : 6);
  }
  auto flip = [&](halfedge_descriptor h) {
    const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
    CGAL::Euler::flip_edge(h, m);
    put(deg, p, get(deg, p) - 1);
    put(deg, q, get(deg, q) - 1);
    put(deg, r, get(deg, r) + 1);
    put(deg, t, get(deg, t) + 1);
  };
  // (the change in the number of irregular vertices when v's degree changes by `change`)
  auto shift = [&](auto v, int change) {
    const int d = get(deg, v), reg = get(regular, v);
    return int(d + change != reg) - int(d != reg);
  };
  // the change of the number of irregular vertices a flip of h makes, or `no` when it may not be made
  auto gain = [&](halfedge_descriptor h) {
    if(is_feature(edge(h, m)) || is_border(edge(h, m), m)) return no;
    const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
    if(get(deg, p) <= 3 || get(deg, q) <= 3 || halfedge(r, t, m).second) return no;
    const int change = shift(p, -1) + shift(q, -1) + shift(r, 1) + shift(t, 1);
    if(change > 0) return no;
    if(ctx.min_angle_after_flip(h, m) < floor) return no;
    if(!ctx.flip_is_safe(h, m, cos_max)) return no;
    return change;
  };
  const bool lookahead = s.lookahead;
  std::size_t flips = 0;
  std::vector<halfedge_descriptor> around;
  for(auto e : edges(m)) {
    auto h = halfedge(e, m);
    const int g = gain(h);
    if(g == no || g > 0) continue;
    if(g < 0) { flip(h); ++flips; if(flipped) flipped->push_back(h); continue; }
    if(!lookahead || flipped) continue;
    // a flip that only moves an irregular vertex, when a second flip next to it then removes one
    const auto p = source(h, m), q = target(h, m);
    flip(h);
    around.clear();
    for(auto x : {p, q, source(h, m), target(h, m)})
      for(auto k : CGAL::halfedges_around_target(x, m))
        if(edge(k, m) != edge(h, m)) around.push_back(k);
    bool done = false;
    for(auto k : around)
      if(gain(k) < 0) { flip(k); flips += 2; done = true; break; }
    if(!done) flip(h);
  }
  stats.valence_flips += flips;
  return flips;
}

/// The last round of regularity flips (Regularity_settings::final_min_angle), taken back whole if it
/// makes the mesh cut itself anew; `optimized_angle`: the angle optimization's (degrees).
/// `ConcurrencyTag`: the mode of the whole-mesh intersection search (the same result).
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge>
void final_regularity_flips(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, const Regularity_settings& s, double max_normal_change,
                            double optimized_angle, Relaxation_statistics& stats)
{
  if(!(s.final_min_angle > 0)) return;
  const auto before = Poisson_remesh::internal::intersecting_pairs<ConcurrencyTag>(m);
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> flipped;
  // (nor under the mesh's smallest angle, up to optimized_angle: these flips trade little
  // regularity for the smallest angle)
  const auto vpm = get(CGAL::vertex_point, m);
  double smallest = CGAL_PI;
  for(auto f : faces(m)) {
    const auto h = halfedge(f, m);
    smallest = std::min(smallest, ctx.min_angle(get(vpm, source(h, m)), get(vpm, target(h, m)), get(vpm, target(next(h, m), m))));
  }
  const double floor_degrees = std::max(s.final_min_angle, std::min(smallest * 180 / CGAL_PI, optimized_angle));
  if(before.size() <= num_faces(m) && regularity_flips(ctx, m, is_feature, s, max_normal_change, stats, floor_degrees, &flipped) > 0) {
    std::vector<typename boost::graph_traits<Mesh>::face_descriptor> changed;
    for(auto h : flipped) { changed.push_back(face(h, m)); changed.push_back(face(opposite(h, m), m)); }
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    bool cut = false;
    ctx.for_vertices_of_new_intersections(m, before, changed, [&](typename boost::graph_traits<Mesh>::vertex_descriptor) { cut = true; });
    if(cut) {
      for(auto it = flipped.rbegin(); it != flipped.rend(); ++it) CGAL::Euler::flip_edge(*it, m);
      stats.valence_flips -= std::min(stats.valence_flips, flipped.size());
    }
  }
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_REGULARITY_FLIPS_H
