// Poisson_remesh/Relaxation/valence_flips.h
//
// The connectivity flips of paper §6.3 (Eq. 7-8): a non-feature edge is flipped when that lowers
// sum (d(v) - o(v))^2 over its four vertices, d the valence and o(v) = (angle sum at v) / 60
// degrees (+1 on a border) the angle-based ideal valence, under the Delaunay flips' normal guard
// and without making the smallest angle of the two triangles worse than `min_angle_ratio` of it.

#ifndef POISSON_REMESH_RELAXATION_VALENCE_FLIPS_H
#define POISSON_REMESH_RELAXATION_VALENCE_FLIPS_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/internal/parallel.h>
#include <cmath>
#include <vector>

namespace Poisson_remesh {

namespace Relaxation {

/// The ideal valence of Eq. 7: the angle sum at `v` over 60 degrees, +1 on a border.
template <class Context, class Mesh>
double ideal_valence(const Context& ctx, typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m)
{
  double sum = 0;
  bool border = false;   // (a border vertex has a border halfedge around it: the walk tells)
  for(auto h : CGAL::halfedges_around_target(v, m)) {
    if(is_border(h, m)) { border = true; continue; }
    sum += ctx.angle(get(get(CGAL::vertex_point, m), source(h, m)), get(get(CGAL::vertex_point, m), v), get(get(CGAL::vertex_point, m), target(next(h, m), m)));
  }
  return sum * 180 / CGAL_PI / 60 + (border ? 1 : 0);
}

/// One pass of valence flips over the edges of `m` (Eq. 8). `ConcurrencyTag`: the ideal valences
/// are first computed on TBB's threads (each reads only its vertex's star; the same result).
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge>
void valence_flips(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, double max_normal_change, double min_angle_ratio,
                   Relaxation_statistics& stats)
{
  const double cos_max = std::cos(max_normal_change * CGAL_PI / 180);
  // the ideal valences, computed once per vertex and again only after a flip at the vertex (a
  // flip changes the triangles of its four vertices alone: the others' angle sums stay)
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  auto cache = get(CGAL::dynamic_vertex_property_t<double>(), m);
  // (and the degrees, kept up to date at each flip: a flip takes an edge from p and q and gives
  // one to r and t)
  auto degrees = get(CGAL::dynamic_vertex_property_t<int>(), m);
  {
    const std::vector<vertex_descriptor> vs(vertices(m).begin(), vertices(m).end());
    std::vector<double> first(vs.size());
    internal::for_each_index<ConcurrencyTag>(vs.size(), [&](std::size_t i) { first[i] = ideal_valence(ctx, vs[i], m); });
    for(std::size_t i = 0; i < vs.size(); ++i) { put(cache, vs[i], first[i]); put(degrees, vs[i], int(degree(vs[i], m))); }
  }
  auto ideal = [&](vertex_descriptor v) {
    double o = get(cache, v);
    if(o < 0) { o = ideal_valence(ctx, v, m); put(cache, v, o); }
    return o;
  };
  for(auto e : edges(m)) {
    if(is_feature(e) || is_border(e, m)) continue;
    auto h = halfedge(e, m);
    const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
    const double dp = get(degrees, p), dq = get(degrees, q), dr = get(degrees, r), dt = get(degrees, t);
    const double op = ideal(p), oq = ideal(q), orr = ideal(r), ot = ideal(t);
    auto sq = [](double x) { return x * x; };
    const double before = sq(dp - op) + sq(dq - oq) + sq(dr - orr) + sq(dt - ot);
    const double after = sq(dp - 1 - op) + sq(dq - 1 - oq) + sq(dr + 1 - orr) + sq(dt + 1 - ot);
    if(after >= before - 1e-9) continue;
    if(ctx.min_angle_after_flip(h, m) < min_angle_ratio * ctx.min_angle_of_faces(h, m)) continue;
    if(!ctx.flip_is_safe(h, m, cos_max)) continue;
    CGAL::Euler::flip_edge(h, m);
    for(auto x : {p, q, r, t}) put(cache, x, -1.0);
    put(degrees, p, get(degrees, p) - 1);
    put(degrees, q, get(degrees, q) - 1);
    put(degrees, r, get(degrees, r) + 1);
    put(degrees, t, get(degrees, t) + 1);
    ++stats.valence_flips;
  }
}

} // namespace Relaxation

} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_VALENCE_FLIPS_H
