// Poisson_remesh/Postprocessing/internal/vertex_angle_search.h
//
// The searches of the angle smoothing and the angle optimization (internal): vertices move on the
// input (feature vertices along their curves) to raise the angles of their triangles.

#ifndef POISSON_REMESH_POSTPROCESSING_INTERNAL_VERTEX_ANGLE_SEARCH_H
#define POISSON_REMESH_POSTPROCESSING_INTERNAL_VERTEX_ANGLE_SEARCH_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/internal/parallel.h>
#include <Poisson_remesh/internal/vector_angle.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// What the vertex search raises.
enum class Angle_goal { smallest, sum_of_smallest };

namespace internal {

namespace vertex_angle_search_detail {

// a triangle (a, v, b) of the star of the vertex v that searches: its other corners, its normal
// n (length ln) at the search's start, and the scales of its angles at a and b (tips)
template <class Point_3, class Vector_3>
struct Ring_triangle { Point_3 a, b; Vector_3 n; double ln, sa, sb; };

// the gradient steps of a free vertex's smoothing search, at most (each step moves the vertex or
// halves the step size, which starts at a tenth of its mean edge length and ends under a hundredth)
constexpr int gradient_steps = 16;

// At q (the searching vertex's trial point), the directions in the tangent space (unit normal nn)
// in which the sum of the ring triangles' smallest angles rises fastest (d_sum), and the bisector
// of it and the direction in which the least of those angles rises fastest (d_both): the unit
// projections of their gradients. With e = q - a and f = b - a, the angle at a changes as q moves
// across e, by the move over |e|: its gradient is minus the part of f across e over |e x f|,
// twice the area; at b alike; the angle at q is pi minus the two. A corner's tip scale scales its
// gradient. Where the sum has no gradient -- its terms cancel to rounding, as on a flat star whose
// triangles all have their smallest angle at q (they sum to 2 pi), or where the smallest angles of
// the two triangles beside an edge qa are both at a (they sum to the angle between a's other two
// neighbours) -- no move in the plane raises it (a triangle's smallest angle can only fall below
// the corner that was its smallest): both directions are the null vector. Where the two directions
// are opposite, no direction raises both: d_both is the null vector.
template <class Ring, class Point_3, class Vector_3>
void ascent_directions(const Ring& ring, const Point_3& q, const Vector_3& nn, Vector_3& d_sum, Vector_3& d_both)
{
  Vector_3 g_sum = CGAL::NULL_VECTOR, g_least = CGAL::NULL_VECTOR;
  double least = std::numeric_limits<double>::infinity(), terms = 0;   // (terms: the sum of the gradients' lengths)
  for(const auto& t : ring) {
    const Vector_3 ea = q - t.a, eb = q - t.b, ab = t.b - t.a;
    const double area2 = std::sqrt(CGAL::to_double(CGAL::cross_product(ea, ab).squared_length()));
    const double la = CGAL::to_double(ea.squared_length()), lb = CGAL::to_double(eb.squared_length());
    if(!(area2 > 0 && la > 0 && lb > 0)) continue;
    // the smallest (scaled) corner: with unit scales it lies opposite the shortest edge (the
    // angle at a faces qb, at b faces qa, at q faces ab), and only its angle is computed; where
    // two of those lengths are within a relative 1e-9 -- angles that close may compare either way
    // once rounded -- all three angles are compared as with tip scales, for the same choice
    const double lab = CGAL::to_double(ab.squared_length());
    int corner;   // (0: a, 1: b, 2: q)
    double x;
    auto angle_a = [&] { return t.sa * Poisson_remesh::internal::vector_angle(area2, CGAL::to_double(ea * ab)); };
    auto angle_b = [&] { return t.sb * Poisson_remesh::internal::vector_angle(area2, -CGAL::to_double(eb * ab)); };
    auto angle_q = [&] { return Poisson_remesh::internal::vector_angle(area2, CGAL::to_double((t.a - q) * (t.b - q))); };
    auto apart = [](double u, double w) { return std::abs(u - w) > 1e-9 * (std::max)(u, w); };
    if(t.sa == 1 && t.sb == 1 && apart(la, lb) && apart(la, lab) && apart(lb, lab)) {
      corner = lb < la && lb < lab ? 0 : la < lab ? 1 : 2;
      x = corner == 0 ? angle_a() : corner == 1 ? angle_b() : angle_q();
    } else {
      const double xa = angle_a(), xb = angle_b(), xq = angle_q();
      corner = xa <= xb && xa <= xq ? 0 : xb <= xq ? 1 : 2;
      x = corner == 0 ? xa : corner == 1 ? xb : xq;
    }
    const Vector_3 ga = (CGAL::to_double(ab * ea) / la * ea - ab) / area2;
    const Vector_3 gb = (ab - CGAL::to_double(ab * eb) / lb * eb) / area2;
    const Vector_3 g = corner == 0 ? t.sa * ga : corner == 1 ? t.sb * gb : -(ga + gb);
    g_sum = g_sum + g;
    terms += std::sqrt(CGAL::to_double(g.squared_length()));
    if(x < least) { least = x; g_least = g; }
  }
  // (the null vector when the part in the plane is no longer than `cancelled`)
  auto unit_in_plane = [&](Vector_3 g, double cancelled) {
    g = g - CGAL::to_double(g * nn) * nn;
    const double l = std::sqrt(CGAL::to_double(g.squared_length()));
    return l > cancelled ? g / l : CGAL::NULL_VECTOR;
  };
  const double rounding = 1e-9;   // (relative to the terms: far above the rounding of their sum)
  d_sum = unit_in_plane(g_sum, rounding * terms);
  const Vector_3 u_least = unit_in_plane(g_least, 0);
  d_both = d_sum == CGAL::NULL_VECTOR || u_least == CGAL::NULL_VECTOR ? CGAL::NULL_VECTOR : unit_in_plane(d_sum + u_least, 2 * rounding);
}

} // namespace vertex_angle_search_detail

/// Moves vertices by a search on the input (feature vertices along their curves; a compass search,
/// but gradient steps for the smoothing's free vertices, vertex_angle_search_detail): with
/// Angle_goal::smallest, the movable vertices of the triangles sharper than `optimized_angle`
/// (degrees), to raise the smallest angle around them; with Angle_goal::sum_of_smallest, every
/// movable vertex, to raise the sum of its triangles' smallest angles without lowering the smallest
/// (free vertices search in their tangent space and are projected once: it is a smoothing of
/// vertices already well placed, with a shorter search). With `pinned_only` (Angle_goal::smallest),
/// only the vertices of the fidelity insertions (fixed for is_corner) at a triangle sharper than
/// `sliver_angle` move, by a quarter of the fidelity tolerance (`max_deviation` times the diagonal)
/// at most from where they were put, `pin_position(x)` (nullptr for the others): they still hold the
/// mesh near the input. With Angle_goal::smallest and `max_deviation` > 0, a trial point wins only
/// if each edge of the moving vertex stays within `max_deviation` times the diagonal of the input
/// (at its midpoint), or no farther than it was (not checked again when a neighbour is taken back
/// below). A move that makes the mesh cut itself anew is taken back. With `unmoved`
/// (not null), the digest of each vertex's star -- its point, its ring's points, border and
/// feature flags and tip scales, its movability -- is kept when its search moves nothing, and a
/// vertex whose star has the same digest at the next call is not searched again: its search
/// would find the same nothing (repeated smoothing rounds). With `ConcurrencyTag` =
/// CGAL::Parallel_tag the vertices search in rounds of vertices whose earlier neighbours have
/// searched (internal/parallel.h), each round at once: the same result as in sequence, for any
/// number of threads (`is_feature` and `is_corner` are then called from several threads). Returns
/// the number of vertices moved. With `only` (not null; Angle_goal::smallest), the vertices searched
/// are those of `only`, in its order, at a triangle sharper than `optimized_angle`, the free ones
/// in their tangent space, projected once (the local repair's searches). `near_faces`: where the
/// check for new crossings looks for the faces near the moved ones (Relaxation_context.h's
/// intersecting_pairs_near; by default every face).
template <class ConcurrencyTag, class Context, class Mesh, class IsFeatureEdge, class IsCorner, class PinPosition,
          class NearFaces = Poisson_remesh::internal::All_faces>
std::size_t vertex_angle_search(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, Angle_goal goal,
                                double optimized_angle, double sliver_angle, double max_deviation, Relaxation_statistics& stats,
                                PinPosition pin_position, bool pinned_only,
                                std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, std::uint64_t>* unmoved = nullptr,
                                const std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>* only = nullptr,
                                const NearFaces& near_faces = NearFaces())
{
  typedef typename Context::Point_3 Point_3;
  typedef typename Context::Vector_3 Vector_3;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  auto vpm = get(CGAL::vertex_point, m);
  const bool smoothing = goal == Angle_goal::sum_of_smallest;
  const double sharp = optimized_angle * CGAL_PI / 180;   // (Angle_goal::smallest only)
  std::vector<vertex_descriptor> todo;
  // a feature vertex with one feature edge (the output's edge along its curve is a chord too far
  // from the curve to count) slides along the curve too when it is at a sliver
  const double pin_reach = 0.25 * max_deviation * ctx.diagonal(), sliver = sliver_angle * CGAL_PI / 180;
  auto movability = [&](vertex_descriptor x) {
    if(pinned_only)
      return pin_reach > 0 && pin_position(x) != nullptr && ctx.feature_degree(x, m, is_feature) == 0 && !is_border(x, m) &&
             ctx.smallest_angles_around(x, m, get(vpm, x)).first < sliver ? 0 : 2;
    const int c = ctx.constraint(x, m, is_feature, is_corner);
    return !smoothing && c == 2 && !is_corner(x) && ctx.feature_degree(x, m, is_feature) == 1 ? 1 : c;
  };
  std::vector<vertex_descriptor> candidates;   // (those whose movability decides whether they search)
  if(only != nullptr) {   // (Angle_goal::smallest: those of `only` at a triangle sharper than optimized_angle)
    for(vertex_descriptor x : *only) {
      bool at_sharp = false;
      for(auto h : CGAL::halfedges_around_target(x, m))
        if(!is_border(h, m) && ctx.min_angle(get(vpm, source(h, m)), get(vpm, x), get(vpm, target(next(h, m), m))) < sharp) { at_sharp = true; break; }
      if(at_sharp) candidates.push_back(x);
    }
  } else if(smoothing) {
    candidates.assign(vertices(m).begin(), vertices(m).end());
  } else {   // (in the order of vertices(m), not of the descriptors: a Polyhedron_3's are addresses)
    auto at_sharp = get(CGAL::dynamic_vertex_property_t<bool>(), m);
    for(vertex_descriptor x : vertices(m)) put(at_sharp, x, false);
    for(auto f : faces(m)) {
      const auto h = halfedge(f, m);
      const vertex_descriptor v[3] = {source(h, m), target(h, m), target(next(h, m), m)};
      if(ctx.min_angle(get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2])) >= sharp) continue;
      for(vertex_descriptor x : v) put(at_sharp, x, true);
    }
    for(vertex_descriptor x : vertices(m)) if(get(at_sharp, x)) candidates.push_back(x);
  }
  // the candidates that may move (their movabilities on TBB's threads with Parallel_tag: nothing
  // moves meanwhile; with `pinned_only` in order, as pin_position may remember the pin)
  {
    std::vector<int> movabilities(candidates.size());
    if(pinned_only)
      for(std::size_t i = 0; i < candidates.size(); ++i) movabilities[i] = movability(candidates[i]);
    else
      Poisson_remesh::internal::for_each_index<ConcurrencyTag>(candidates.size(), [&](std::size_t i) { movabilities[i] = movability(candidates[i]); });
    for(std::size_t i = 0; i < candidates.size(); ++i)
      if(movabilities[i] < 2) todo.push_back(candidates[i]);
  }
  // a tip -- a fixed vertex on no feature curve whose angles sum to less than 90 degrees -- has
  // triangles sharper than 30 degrees whatever its neighbours do: its angles count times 90
  // degrees over its angle sum (a third of the sum counts as 30), so that the neighbours raise
  // their own angles (at a tip whose angles sum to s, k triangles have apex angles of s / k at
  // most; their other two angles then depend on the neighbours)
  std::map<vertex_descriptor, double> tips;
  std::set<vertex_descriptor> checked;
  for(vertex_descriptor x : todo)
    for(auto h : CGAL::halfedges_around_target(x, m)) {
      const vertex_descriptor t = source(h, m);
      if(!is_corner(t) || !checked.insert(t).second || is_border(t, m) || ctx.feature_degree(t, m, is_feature) != 0) continue;
      double sum = 0;
      for(auto g : CGAL::halfedges_around_target(t, m))
        sum += ctx.angle(get(vpm, source(g, m)), get(vpm, t), get(vpm, target(next(g, m), m)));
      if(sum > 0 && sum < CGAL_PI / 2) tips[t] = CGAL_PI / 2 / sum;
    }
  auto tip_scale = [&](vertex_descriptor x) {
    if(tips.empty()) return 1.0;
    const auto it = tips.find(x);
    return it == tips.end() ? 1.0 : it->second;
  };
  std::size_t moved = 0;
  std::vector<std::pair<vertex_descriptor, Point_3>> from;   // where the moved vertices were
  auto mix = [](std::uint64_t h, double x) {   // (splitmix64 of the bits, folded into h)
    std::uint64_t z;
    std::memcpy(&z, &x, sizeof z);
    z += 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return h ^ (z ^ (z >> 31));
  };
  auto digest_of_star = [&](vertex_descriptor v, int c) {
    const Point_3& o = get(vpm, v);
    std::uint64_t h = mix(mix(mix(mix(0, double(c)), CGAL::to_double(o.x())), CGAL::to_double(o.y())), CGAL::to_double(o.z()));
    for(auto g : CGAL::halfedges_around_target(v, m)) {
      const Point_3& a = get(vpm, source(g, m));
      h = mix(mix(mix(h, CGAL::to_double(a.x())), CGAL::to_double(a.y())), CGAL::to_double(a.z()));
      h = mix(h, double(int(is_border(g, m)) + 2 * int(is_feature(edge(g, m)) || is_border(edge(g, m), m))));
      h = mix(h, tip_scale(source(g, m)));
    }
    return h | 1;
  };
  // the search from v's point: where v should go (its point when nowhere better); `c` its
  // movability, `pin` where it is pinned (pinned_only). It reads v's star alone, so that vertices that are
  // not neighbours can search at the same time with the same results.
  auto search = [&](vertex_descriptor v, int c, const Point_3* pin) -> Point_3 {
    const Point_3 start = get(vpm, v);
    Point_3 p = start;
    // the triangles around the vertex being moved, read once for its whole search (its
    // neighbours stay where they are meanwhile): Context::smallest_angles_around() without
    // walking the mesh for each trial point, the same figures
    typedef vertex_angle_search_detail::Ring_triangle<Point_3, Vector_3> Ring_triangle;
    thread_local std::vector<Ring_triangle> ring;
    ring.clear();
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      if(is_border(h, m)) continue;
      Ring_triangle t{get(vpm, source(h, m)), get(vpm, target(next(h, m), m)), Vector_3(), 0, tip_scale(source(h, m)), tip_scale(target(next(h, m), m))};
      t.n = ctx.normal(t.a, start, t.b);
      t.ln = std::sqrt(CGAL::to_double(t.n.squared_length()));
      ring.push_back(t);
    }
    // (a triangle under `cut` ends the count with -1: the trial point it belongs to cannot win)
    auto smallest_angles_around = [&](const Point_3& at, double cut) -> std::pair<double, double> {
      double worst = CGAL_PI, sum = 0;
      for(const Ring_triangle& t : ring) {
        const double x = ctx.star_triangle_angle(t.a, at, t.b, t.n, t.ln, t.sa, t.sb);
        if(x < 0 || x < cut) return {-1, -1};
        worst = std::min(worst, x);
        sum += x;
      }
      return {worst, sum};
    };
    const double floor = smallest_angles_around(p, 0).first;
    // the goal at q; `beaten`: a value q must exceed to be taken (a smallest angle at or under it
    // ends the count early; with Angle_goal::sum_of_smallest one under the floor does)
    auto objective = [&](const Point_3& q, double beaten = -1) {
      const auto [smallest, sum] = smallest_angles_around(q, smoothing ? floor : std::nextafter(beaten, 2 * CGAL_PI));
      if(!smoothing || smallest < 0) return smallest;
      return smallest < floor ? -1.0 : sum;
    };
    double best = objective(p);
    if(best < 0) return start;
    // (Angle_goal::smallest with a tolerance) a trial point wins only if each of v's edges stays
    // within the tolerance of the input, or no farther than it was: the angle moves come after
    // the fidelity insertions, and a move that stretches an edge across a groove or around a
    // bend would undo them (each edge's midpoint measured; the limits read at the first check)
    const double edge_reach = !smoothing && max_deviation > 0 ? max_deviation * ctx.diagonal() : 0;
    thread_local std::vector<std::pair<Point_3, double>> edge_limits;   // (each neighbour, and its edge's largest squared distance)
    edge_limits.clear();
    auto keeps_edges_near = [&](const Point_3& q) {
      if(!(edge_reach > 0)) return true;
      auto squared_distance_of_midpoint = [&](const Point_3& a, const Point_3& x) {
        const Point_3 mid = CGAL::midpoint(a, x);
        return CGAL::to_double(CGAL::squared_distance(mid, ctx.project_on_surface(mid, a)));
      };
      if(edge_limits.empty())
        for(auto h : CGAL::halfedges_around_target(v, m)) {
          const Point_3& a = get(vpm, source(h, m));
          edge_limits.push_back({a, (std::max)(squared_distance_of_midpoint(a, start), edge_reach * edge_reach)});
        }
      for(const auto& [a, limit] : edge_limits)
        if(squared_distance_of_midpoint(a, q) > limit) return false;
      return true;
    };
    // directions: the tangent space (8 of them; the smoothing climbs the gradient there instead),
    // or along the feature curve (2)
    std::vector<Vector_3> dirs;
    double mean = 0;
    std::size_t n = 0;
    Vector_3 nv(0, 0, 0);
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      const Point_3& a = get(vpm, source(h, m));
      mean += std::sqrt(CGAL::to_double(CGAL::squared_distance(a, p)));
      ++n;
      if(c == 1 && (is_feature(edge(h, m)) || is_border(edge(h, m), m))) {
        const Vector_3 d = a - p;
        dirs.push_back(d / std::sqrt(CGAL::to_double(d.squared_length())));
      }
      if(!is_border(h, m)) nv = nv + ctx.normal(a, p, get(vpm, target(next(h, m), m)));
    }
    if(n == 0) return start;
    mean /= double(n);
    // (one feature edge: the vertex may be the loose end of a curve at a tip, it moves little)
    const bool loose_end = c == 1 && dirs.size() == 1;
    if(loose_end) dirs.push_back(-dirs[0]);
    Vector_3 nn(0, 0, 0);   // (c == 0: the unit normal of the tangent space)
    if(c == 0) {
      const double ln = std::sqrt(CGAL::to_double(nv.squared_length()));
      if(!(ln > 0)) return start;
      nn = nv / ln;
      if(!smoothing) {   // (the smoothing climbs the gradient instead: no compass)
        Vector_3 u = CGAL::cross_product(nn, Vector_3(1, 0, 0));
        if(CGAL::to_double(u.squared_length()) < 0.1) u = CGAL::cross_product(nn, Vector_3(0, 1, 0));
        u = u / std::sqrt(CGAL::to_double(u.squared_length()));
        const Vector_3 w = CGAL::cross_product(nn, u);
        // (8 directions in the tangent space, 45 degrees apart: their cosines and sines once)
        static const std::array<std::array<double, 2>, 8> compass = [] {
          std::array<std::array<double, 2>, 8> cs{};
          for(int k = 0; k < 8; ++k) cs[std::size_t(k)] = {std::cos(k * CGAL_PI / 4), std::sin(k * CGAL_PI / 4)};
          return cs;
        }();
        for(const auto& cs : compass) dirs.push_back(cs[0] * u + cs[1] * w);
      }
    }
    if(dirs.empty() && !(smoothing && c == 0)) return start;
    // (a bounded number of steps: where gains never stop, however small -- a flat sheet folded
    // onto itself -- the step would never shrink)
    // (the local repair's searches, `only`, too: each of its candidates searches its region again,
    // and a projection per trial point costs most where the input's triangles are long and thin)
    const bool in_plane = (smoothing || only != nullptr) && c == 0;
    double step = (smoothing ? 0.1 : 0.2) * mean;
    if(smoothing && c == 0) {
      // a free vertex's smoothing climbs the gradient of the sum (smooth between the changes of
      // which corner is a triangle's smallest): a step along the gradient, or, when that does not
      // gain (most often: it would lower the least angle under the floor), along the bisector of
      // it and the least triangle's gradient (an ascent direction of both), the step size halved
      // while neither gains; it stops where the sum has no gradient. A compass poll of the
      // tangent space pays 8 trials for each halving, most of them in directions that lose;
      // this pays one or two, and a gradient where the vertex moved.
      Vector_3 d[2];
      bool current = false;   // (d holds the directions at p)
      for(int iteration = 0; iteration < vertex_angle_search_detail::gradient_steps && step > 0.01 * mean; ++iteration) {
        if(!current) {
          vertex_angle_search_detail::ascent_directions(ring, p, nn, d[0], d[1]);
          current = true;
          if(d[0] == CGAL::NULL_VECTOR) break;   // (no move in the plane raises the sum)
        }
        bool gained = false;
        for(const Vector_3& dk : d) {
          if(dk == CGAL::NULL_VECTOR) continue;
          const Point_3 q = p + step * dk;
          const double a = objective(q);
          if(a > best + 1e-6) { best = a; p = q; gained = true; current = false; break; }
        }
        if(!gained) step *= 0.5;
      }
    } else {
      // the smoothing of a feature vertex polls opportunistically along its curve (a compass
      // search): it takes the first direction that gains, starting with the last one that did,
      // within the trials that polling every direction at each of its 10 steps would make; the
      // angle optimization, whose smallest angle is not smooth, takes the best of all directions
      // at each step
      const std::size_t nd = dirs.size();
      std::size_t trials = smoothing ? 10 * nd : 0, first = 0;
      for(int iteration = 0; iteration < (smoothing ? int(10 * nd) : 40) && step > 0.01 * mean; ++iteration) {
        Point_3 best_q = p;
        double best_here = best;
        for(std::size_t k = 0; k < nd; ++k) {
          const std::size_t i = (first + k) % nd;
          const Vector_3& d = dirs[i];
          const Point_3 t = p + step * d;
          const Point_3 q = in_plane ? t : c == 0 ? ctx.project_on_surface(t, p) : ctx.project_on_features(t, p);
          if(CGAL::to_double(CGAL::squared_distance(q, t)) > CGAL::square(0.25 * mean)) continue;   // thin parts
          if(loose_end && CGAL::to_double(CGAL::squared_distance(q, start)) > CGAL::square(0.25 * mean)) continue;
          if(pin != nullptr && CGAL::to_double(CGAL::squared_distance(q, *pin)) > pin_reach * pin_reach) continue;
          if(smoothing) {
            if(trials == 0) break;
            --trials;
          }
          const double a = objective(q, best_here + 1e-9);
          if(a > best_here + 1e-9 && keeps_edges_near(q)) {
            best_here = a;
            best_q = q;
            if(smoothing && a > best + 1e-6) { first = i; break; }
          }
        }
        if(best_here > best + 1e-6) { best = best_here; p = best_q; }
        else step *= 0.5;
        if(smoothing && trials == 0) break;
      }
    }
    if(in_plane && p != start) {   // onto the input; kept if still better there
      const Point_3 t = p;
      p = ctx.project_on_surface(t, start);
      // (a repair's search may go farther in the plane: not to the other side of a thin part)
      if(only != nullptr && CGAL::to_double(CGAL::squared_distance(p, t)) > CGAL::square(0.25 * mean)) p = start;
      else if(!(objective(p) > objective(start))) p = start;
    }
    return p;
  };
  // in the order of `todo`; with CGAL::Parallel_tag, in rounds of vertices whose earlier
  // neighbours have searched (internal/parallel.h), each round at once, what they found taken in
  // in order after it: the sequential search's result
  struct Found { vertex_descriptor v; int c; const Point_3* pin; std::uint64_t digest; bool unchanged; Point_3 start, p; };
  std::vector<Found> found;
  for(const auto& round : Poisson_remesh::internal::dependency_rounds(m, todo)) {
    found.clear();
    // each vertex's movability read again: is_feature may read the points, which the rounds
    // before moved (on TBB's threads with Parallel_tag: no vertex of this round has moved yet;
    // with `pinned_only` in order, as pin_position may remember the pin)
    for(vertex_descriptor v : round) {
      const int c = pinned_only ? movability(v) : 0;
      found.push_back(Found{v, c, pinned_only ? pin_position(v) : nullptr, 0, false, get(vpm, v), get(vpm, v)});
    }
    if(!pinned_only)
      Poisson_remesh::internal::for_each_index<ConcurrencyTag>(found.size(), [&](std::size_t i) { found[i].c = movability(found[i].v); });
    Poisson_remesh::internal::for_each_index<ConcurrencyTag>(found.size(), [&](std::size_t i) {
      Found& x = found[i];
      if(unmoved != nullptr) {
        x.digest = digest_of_star(x.v, x.c);
        const auto it = unmoved->find(x.v);
        if(it != unmoved->end() && it->second == x.digest) { x.unchanged = true; return; }
      }
      x.p = search(x.v, x.c, x.pin);
      // (no other vertex of this round reads v's point: it is in none of their rings)
      if(x.p != x.start) put(vpm, x.v, x.p);
    }, 8);   // (a search takes tens of microseconds: blocks of 8 share a round of a few dozen too)
    for(const Found& x : found) {
      if(x.unchanged) { ++stats.unchanged_stars; continue; }
      if(x.p != x.start) {
        from.push_back({x.v, x.start});
        ++moved;
        if(unmoved != nullptr) unmoved->erase(x.v);   // (taken back below or not: searched again)
      } else if(unmoved != nullptr) {
        (*unmoved)[x.v] = x.digest;   // (its search moved nothing: not searched again while its star stays)
      }
    }
  }
  // a move may not make the mesh cut itself (thin parts): the moved vertices of triangles
  // that intersect anew go back, until no new intersection is left
  if(moved > 0) {
    std::sort(from.begin(), from.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<vertex_descriptor> movers;
    for(const auto& x : from) movers.push_back(x.first);
    // (the first round checks the faces around every moved vertex; a later one those around the
    // vertices the round before took back: a new crossing of the faces that did not change since
    // was found then, and each of its moved vertices taken back)
    auto changed = Poisson_remesh::internal::faces_around(m, movers);
    std::vector<vertex_descriptor> taken_back;
    for(int round = 0; round < 8; ++round) {
      std::size_t back = 0;
      taken_back.clear();
      const std::size_t crossing = ctx.template for_vertices_of_new_intersections_after_moves<ConcurrencyTag>(m, from, changed, [&](vertex_descriptor x) {
        auto it = std::lower_bound(from.begin(), from.end(), x, [](const auto& y, vertex_descriptor z) { return y.first < z; });
        if(it != from.end() && it->first == x && get(vpm, x) != it->second) { put(vpm, x, it->second); ++back; taken_back.push_back(x); }
      }, near_faces);
      // (a mesh that cuts itself everywhere -- folded input -- is left as it was: not worth the checks)
      if(round == 0 && crossing > num_faces(m)) {
        for(const auto& x : from) put(vpm, x.first, x.second);
        stats.refused_moves += moved;
        return 0;
      }
      if(back == 0) break;
      moved -= std::min(moved, back);
      stats.refused_moves += back;
      changed = Poisson_remesh::internal::faces_around(m, taken_back);
    }
  }
  stats.angle_moves += moved;
  return moved;
}

/// The same without pinned vertices.
template <class ConcurrencyTag, class Context, class Mesh, class IsFeatureEdge, class IsCorner>
std::size_t vertex_angle_search(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, Angle_goal goal,
                                double optimized_angle, double sliver_angle, double max_deviation, Relaxation_statistics& stats,
                                std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, std::uint64_t>* unmoved = nullptr)
{
  return vertex_angle_search<ConcurrencyTag>(ctx, m, is_feature, is_corner, goal, optimized_angle, sliver_angle, max_deviation, stats,
                             [](typename boost::graph_traits<Mesh>::vertex_descriptor) -> const typename Context::Point_3* { return nullptr; }, false,
                             unmoved);
}

} // namespace internal
} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_INTERNAL_VERTEX_ANGLE_SEARCH_H
