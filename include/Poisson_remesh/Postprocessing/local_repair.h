// Poisson_remesh/Postprocessing/local_repair.h
//
// (beyond the paper) Local repair. Objective: the sharpest triangles of the region around each
// triangle still sharper than `sliver_angle` after every other step (the region: its vertices'
// rings, `rings` deep). The other steps change one thing at a time and keep it only when it wins
// at once: a flip or a split judged with the vertices where they are, a vertex moved with its
// neighbours fixed. Where the last sharp triangles sit between vertices that would all have to
// move, or move after a change of connectivity, each of them finds nothing. Here each candidate --
// no change, a flip of one of the triangle's edges, a split of one of them at the point of the
// input (of its curve, for a feature or border edge) nearest its midpoint -- is made on the mesh
// and followed by the pattern search of the angle optimization over the region's movable
// vertices (free ones in their tangent plane, projected onto the input at the end); the region's
// angles under `sliver_angle`, sorted, are then compared with what they were, and the best
// candidate that wins by `min_gain` is kept (made again), the others taken back (positions
// restored, flip flipped back, split vertex removed). Constraints: vertices on the input
// (feature vertices on their curves); no topology change; a change that adds a crossing face pair
// near the region is taken back (the search takes back its own moves that would).

#ifndef POISSON_REMESH_POSTPROCESSING_LOCAL_REPAIR_H
#define POISSON_REMESH_POSTPROCESSING_LOCAL_REPAIR_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/Postprocessing/internal/face_box_grid.h>
#include <Poisson_remesh/Postprocessing/internal/vertex_angle_search.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// The local repair's settings.
struct Local_repair_settings
{
  /// rounds over the triangles still sharper than `sliver_angle` at the very end; 0 disables
  unsigned int rounds = 1;
  /// rings of vertices around a sharp triangle whose movable vertices are searched after a change
  /// (the region whose angles judge it)
  unsigned int rings = 2;
  /// pattern search rounds over the region after a change (they stop when one moves nothing)
  unsigned int search_rounds = 3;
  /// the region's vertices at a triangle sharper than this are searched (degrees)
  double searched_angle = 45;
  /// times a triangle is treated in a round: again when a kept change leaves its region sharp
  unsigned int max_tries = 3;
  /// a candidate must raise the region's sharpest angle under `sliver_angle` that it changes by
  /// this much (degrees)
  double min_gain = 0.5;
};

namespace internal {

// the sorted smallest angles (radians) under `sliver` of the faces around the vertices of `region`
template <class Context, class Mesh, class VertexRange>
std::vector<double> sharp_angles_around(const Context& ctx, const Mesh& m, const VertexRange& region, double sliver)
{
  auto vpm = get(CGAL::vertex_point, m);
  std::vector<double> out;
  for(auto f : Poisson_remesh::internal::faces_around(m, region)) {
    const auto h = halfedge(f, m);
    const double a = ctx.min_angle(get(vpm, source(h, m)), get(vpm, target(h, m)), get(vpm, target(next(h, m), m)));
    if(a < sliver) out.push_back(a);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// `after` beats `before` (sorted angles under `sliver`): at the first place where they differ (a
// missing angle counts as `sliver`), after's angle is larger by `gain` at least
inline bool sharp_angles_better(const std::vector<double>& after, const std::vector<double>& before, double sliver, double gain)
{
  for(std::size_t i = 0; i < std::max(after.size(), before.size()); ++i) {
    const double x = i < after.size() ? after[i] : sliver, y = i < before.size() ? before[i] : sliver;
    if(std::abs(x - y) < 1e-9) continue;
    return x > y + gain;
  }
  return false;
}

} // namespace internal

/// One round of local repair of `m` at the triangles sharper than `sliver_angle` (degrees);
/// `is_fixed`: the vertices that may not move (corners, pinned vertices). `new_vertex(v,
/// on_feature)` is told each vertex a split adds, a trial's too (the trials' vertices are removed
/// again). Returns the number of candidates kept.
template <class Context, class Mesh, class IsFeatureEdge, class IsFixed, class NewVertex>
std::size_t repair_sharp_triangles(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsFixed is_fixed, NewVertex new_vertex,
                                   const Local_repair_settings& s, double sliver_angle, Relaxation_statistics& stats)
{
  typedef typename Context::Point_3 Point_3;
  typedef boost::graph_traits<Mesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  auto vpm = get(CGAL::vertex_point, m);
  const double sliver = sliver_angle * CGAL_PI / 180, gain = s.min_gain * CGAL_PI / 180;
  const double cos_flip = 0.5;   // (the refinement's guard on the normals of a flip: 60 degrees)

  // the sharp triangles, by their vertices (a change made for one may remove another), sharpest first
  std::vector<std::pair<double, std::array<vertex_descriptor, 3>>> sharp;
  auto queue_if_sharp = [&](face_descriptor f) {
    const halfedge_descriptor h = halfedge(f, m);
    const std::array<vertex_descriptor, 3> v = {source(h, m), target(h, m), target(next(h, m), m)};
    const double a = ctx.min_angle(get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2]));
    if(a < sliver) sharp.push_back({a, v});
  };
  for(face_descriptor f : faces(m)) queue_if_sharp(f);
  if(sharp.empty()) return 0;
  std::stable_sort(sharp.begin(), sharp.end(), [](const auto& x, const auto& y) { return x.first < y.first; });

  // the crossing checks after each step of a trial look for the faces near the region in a grid
  // of the other faces' boxes, not in a scan of every face (most of the repair's time on an input
  // of many parts when it was one scan per step): the same pairs
  auto box_of = [&](face_descriptor f) { return Poisson_remesh::internal::face_box(f, m); };
  internal::Region_near_faces<Mesh, decltype(box_of)> near_faces(m, box_of);

  auto no_pin = [](vertex_descriptor) -> const Point_3* { return nullptr; };
  // the candidates for one triangle: none, a flip or a split of the edge (v[k], v[k+1])
  enum class Operation { none, flip, split };
  struct Candidate { Operation op; vertex_descriptor a, b; };
  // what a trial did, to take it back
  struct Made { bool valid = false; halfedge_descriptor flipped; vertex_descriptor added; };
  std::size_t kept = 0;
  // a triangle of a region that a kept change leaves (or makes) sharp is treated again, after the
  // others, up to `max_tries` times in all
  std::map<std::array<vertex_descriptor, 3>, unsigned int> tries;
  auto key_of = [](std::array<vertex_descriptor, 3> v) { std::sort(v.begin(), v.end()); return v; };

  for(std::size_t next_entry = 0; next_entry < sharp.size(); ++next_entry) {
    const auto entry = sharp[next_entry];
    const auto& v = entry.second;
    if(++tries[key_of(v)] > s.max_tries) continue;
    // the triangle is still there (with this orientation)
    const auto [h01, found] = halfedge(v[0], v[1], m);
    if(!found || is_border(h01, m) || target(next(h01, m), m) != v[2]) continue;
    {
      const double a = ctx.min_angle(get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2]));
      if(!(a < sliver)) continue;
    }
    // the region: the triangle's vertices and their rings, in the order they are met from the
    // triangle (the order of the search: not that of the descriptors, a Polyhedron_3's are addresses)
    std::vector<vertex_descriptor> region(v.begin(), v.end());
    {
      std::set<vertex_descriptor> in_region(v.begin(), v.end());
      std::size_t ring_begin = 0;
      for(unsigned int ring = 0; ring < s.rings; ++ring) {
        const std::size_t ring_end = region.size();
        for(std::size_t i = ring_begin; i < ring_end; ++i)
          for(halfedge_descriptor g : CGAL::halfedges_around_target(region[i], m))
            if(in_region.insert(source(g, m)).second) region.push_back(source(g, m));
        ring_begin = ring_end;
      }
    }
    // (the region's faces are about to change: the grid answers for the others only, until its
    // faces are filed again when this triangle's treatment ends, however it ends)
    near_faces.begin(region);
    struct Region_done { decltype(near_faces)& near; ~Region_done() { near.end(); } } region_done{near_faces};
    const std::vector<double> before = internal::sharp_angles_around(ctx, m, region, sliver);
    const std::size_t crossings_before =
      Poisson_remesh::internal::intersecting_pairs_near(m, Poisson_remesh::internal::faces_around(m, region), near_faces).size();
    std::vector<std::pair<vertex_descriptor, Point_3>> positions;
    for(vertex_descriptor x : region) positions.push_back({x, get(vpm, x)});

    std::vector<Candidate> candidates{{Operation::none, GT::null_vertex(), GT::null_vertex()}};
    for(int k = 0; k < 3; ++k) {
      candidates.push_back({Operation::flip, v[k], v[(k + 1) % 3]});
      candidates.push_back({Operation::split, v[k], v[(k + 1) % 3]});
    }
    // makes candidate c (with the search after it); the result's sharp angles, or nothing when it
    // cannot be made or adds a crossing (then it is taken back already)
    Relaxation_statistics scratch;
    auto take_back = [&](const Made& made, const Candidate& c) {
      for(const auto& [x, p] : positions) put(vpm, x, p);
      if(c.op == Operation::flip) CGAL::Euler::flip_edge(made.flipped, m);
      if(c.op == Operation::split) ctx.remove_vertex_on_edge(made.added, c.a, c.b, m);
    };
    auto make = [&](const Candidate& c, Made& made, std::vector<double>& result) {
      made = Made();
      std::vector<vertex_descriptor> searched = region;
      if(c.op != Operation::none) {
        const auto [h, exists] = halfedge(c.a, c.b, m);
        if(!exists) return;
        const bool on_curve = is_feature(edge(h, m)) || is_border(edge(h, m), m);
        if(c.op == Operation::flip) {
          if(on_curve || !ctx.flip_is_safe(h, m, cos_flip)) return;
          CGAL::Euler::flip_edge(h, m);
          made.flipped = h;
        } else {
          const Point_3 &A = get(vpm, c.a), &B = get(vpm, c.b);
          const Point_3 mid = CGAL::midpoint(A, B);
          const Point_3 q = on_curve ? ctx.project_on_features(mid) : ctx.project_on_surface(mid);
          if(CGAL::to_double(CGAL::squared_distance(q, mid)) > 0.0625 * CGAL::to_double(CGAL::squared_distance(A, B))) return;   // thin parts
          made.added = ctx.insert_vertex_on_edge(h, q, m);
          // (told at once, a trial's vertex too: it may take the descriptor of a vertex removed
          // before it, whose kind, pin or density the caller's maps must forget before the search)
          new_vertex(made.added, on_curve);
          searched.push_back(made.added);
        }
        // a change that crosses the mesh is taken back
        if(Poisson_remesh::internal::intersecting_pairs_near(m, Poisson_remesh::internal::faces_around(m, searched), near_faces).size() > crossings_before) {
          take_back(made, c);
          return;
        }
      }
      for(unsigned int round = 0; round < s.search_rounds; ++round)
        if(Postprocessing::internal::vertex_angle_search<CGAL::Sequential_tag>(ctx, m, is_feature, is_fixed, Angle_goal::smallest, s.searched_angle,
                                                                              sliver_angle, 0 /* (no pinned_only moves) */, scratch, no_pin, false, nullptr, &searched,
                                                                              near_faces) == 0)
          break;
      made.valid = true;
      result = internal::sharp_angles_around(ctx, m, searched, sliver);
    };
    std::vector<double> best = before;
    int winner = -1;
    for(std::size_t i = 0; i < candidates.size(); ++i) {
      Made made;
      std::vector<double> result;
      make(candidates[i], made, result);
      if(!made.valid) continue;
      if(internal::sharp_angles_better(result, best, sliver, winner < 0 ? gain : 1e-9)) { best = result; winner = int(i); }
      take_back(made, candidates[i]);
      if(winner >= 0 && best.empty()) break;   // (no sharp angle left in the region: none can do better)
    }
    if(winner < 0) continue;
    Made made;
    std::vector<double> result;
    make(candidates[std::size_t(winner)], made, result);   // (the same steps: the same result)
    if(!made.valid) continue;
    ++kept;
    std::vector<vertex_descriptor> searched = region;
    if(made.added != GT::null_vertex()) searched.push_back(made.added);
    // (queued in the order they are met from the region, not in that of the descriptors: a
    // Polyhedron_3's are addresses, and the queue's order decides what is treated first)
    std::set<face_descriptor> queued;
    for(vertex_descriptor x : searched)
      for(halfedge_descriptor hx : CGAL::halfedges_around_target(x, m))
        if(!is_border(hx, m) && queued.insert(face(hx, m)).second) queue_if_sharp(face(hx, m));
  }
  stats.repair_changes += kept;
  return kept;
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_LOCAL_REPAIR_H
