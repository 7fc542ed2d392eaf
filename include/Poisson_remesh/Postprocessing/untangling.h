// Poisson_remesh/Postprocessing/untangling.h
//
// (beyond the paper) Untangling. Objective: the number of crossing face pairs. The tessellation
// and the Lloyd passes do not check for crossings (bumps finer than the spacing), and the later
// steps only refuse new ones, so crossings made early stay. Each vertex of a face that still crosses
// another tries a few positions towards its neighbours (on the input), each edge of such a face a
// flip, and a free vertex shared by two crossing faces a collapse into a neighbour; a change is kept
// when fewer crossing pairs remain and the smallest angle around stays over `min_angle` (or what it
// was), `collapse_min_angle` for a collapse. Constraints: vertices on the input; the link
// condition for collapses (no topology change).

#ifndef POISSON_REMESH_POSTPROCESSING_UNTANGLING_H
#define POISSON_REMESH_POSTPROCESSING_UNTANGLING_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/Postprocessing/internal/face_box_grid.h>
#include <Poisson_remesh/internal/memory_free_order.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// The untangling's settings.
struct Untangling_settings
{
  /// rounds of untangling at the very end; 0 disables
  unsigned int rounds = 3;
  /// the smallest angle the triangles of a move or flip keep, or what it was if smaller (degrees)
  double min_angle = 30;
  /// the smallest angle the triangles of a collapse keep (degrees; 0: no collapse)
  double collapse_min_angle = 15;
};

/// One round of untangling of `m`; with `collapses`, collapses too (counted there). Returns the
/// number of changes made. `ConcurrencyTag`: the mode of the whole-mesh intersection search (the
/// same result).
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge, class IsCorner>
std::size_t untangle(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsCorner is_fixed, const Untangling_settings& s,
                     Relaxation_statistics& stats, std::size_t* collapses = nullptr)
{
  typedef typename Context::Point_3 Point_3;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  auto pairs = Poisson_remesh::internal::intersecting_pairs<ConcurrencyTag>(m);
  if(pairs.empty() || pairs.size() > num_faces(m)) return 0;
  auto vpm = get(CGAL::vertex_point, m);
  // the faces' boxes in a grid, kept up to date by `refresh` after each change (taken back or
  // not); the crossing pairs that involve one of the faces of `fs` (sorted) are looked for among
  // the faces whose boxes meet theirs (intersecting_pairs_near would box the whole mesh each
  // time, and a scan of every face's box for each trial was most of the untangling's time)
  auto box_of = [&](face_descriptor f) { return Poisson_remesh::internal::face_box(f, m); };
  internal::Face_box_grid<Mesh> grid(faces(m), box_of);
  auto refresh = [&](const std::vector<face_descriptor>& fs) { for(face_descriptor f : fs) grid.update(f, box_of(f)); };
  // (intersecting_pairs_near's near faces, where every face's box in the grid is current)
  auto near_in_grid = [&](const CGAL::Bbox_3& b, std::vector<face_descriptor>& out) { grid.overlapping(b, out); };
  // (the pairs that involve a face of fs are those of a face of fs and a face whose box meets its
  // box, by CGAL's rule for a pair (internal/self_intersections.h): tested pair by pair, not by a
  // search of every pair among the faces near fs, most of which do not involve fs; a face of zero
  // area is the pair (f, f) and in no other, as in that search)
  std::vector<face_descriptor> near;
  auto flat = [&](face_descriptor f) {
    const auto h = halfedge(f, m);
    return CGAL::collinear(get(vpm, source(h, m)), get(vpm, target(h, m)), get(vpm, target(next(h, m), m)));
  };
  auto crossings = [&](const std::vector<face_descriptor>& fs) {   // (fs sorted)
    refresh(fs);
    std::size_t n = 0;
    for(face_descriptor f : fs) {
      if(flat(f)) { ++n; continue; }
      near.clear();
      grid.overlapping(grid.box(f), near);
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
      for(face_descriptor g : near) {
        // (a pair of two faces of fs counted once, from its smaller face)
        if(g == f || (g < f && std::binary_search(fs.begin(), fs.end(), g)) || flat(g)) continue;
        if(Poisson_remesh::internal::self_intersection_detail::faces_intersect(f, g, m, vpm)) ++n;
      }
    }
    return n;
  };
  // the crossing pairs once the faces of `changed` moved or were flipped: those of the other faces
  // stay as they were (their points and neighbours did not change), those of `changed` are
  // looked for near them -- the pairs a search of the whole mesh finds, without it
  std::vector<face_descriptor> changed;
  auto update_pairs = [&] {
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    if(changed.empty()) return;
    auto is_changed = [&](face_descriptor f) { return std::binary_search(changed.begin(), changed.end(), f); };
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const auto& fp) { return is_changed(fp.first) || is_changed(fp.second); }), pairs.end());
    // (every face's box in the grid is current here)
    for(const auto& fp : Poisson_remesh::internal::intersecting_pairs_near(m, changed, near_in_grid))
      if(is_changed(fp.first) || is_changed(fp.second)) pairs.push_back(fp);
    std::sort(pairs.begin(), pairs.end());
    changed.clear();
  };
  const double floor = s.min_angle * CGAL_PI / 180;
  std::size_t done = 0;
  std::vector<vertex_descriptor> vs;
  for(const auto& fp : pairs)
    for(face_descriptor f : {fp.first, fp.second})
      for(vertex_descriptor x : CGAL::vertices_around_face(halfedge(f, m), m)) vs.push_back(x);
  // (the vertices, edges and shared vertices below are visited in an order that does not depend on
  // memory: each change depends on those before it)
  const Poisson_remesh::internal::Memory_free_order<Mesh> order(m);
  std::sort(vs.begin(), vs.end(), order);
  vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
  // moves of the free vertices
  for(vertex_descriptor v : vs) {
    const int c_v = ctx.constraint(v, m, is_feature, is_fixed);   // 0 free, 1 on a curve, 2 fixed
    if(c_v == 2) continue;   // (a border vertex is on a curve: border edges count as features)
    const std::vector<face_descriptor> fs = Poisson_remesh::internal::faces_around(m, std::array<vertex_descriptor, 1>{{v}});
    const std::size_t before = crossings(fs);
    if(before == 0) continue;
    const Point_3 start = get(vpm, v);
    // (a triangle of zero area around v makes the angles -1: then no triangle may get worse than 0)
    const double limit = std::min(std::max(ctx.smallest_angles_around(v, m, start).first, 0.0), floor);
    double x = 0, y = 0, z = 0, mean = 0;
    std::size_t n = 0;
    for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, m), m)) {
      const Point_3& q = get(vpm, w);
      x += CGAL::to_double(q.x()); y += CGAL::to_double(q.y()); z += CGAL::to_double(q.z());
      mean += std::sqrt(CGAL::to_double(CGAL::squared_distance(q, start)));
      ++n;
    }
    if(n == 0) continue;
    mean /= double(n);
    const Point_3 c(x / double(n), y / double(n), z / double(n));
    // toward the centroid, and a third of the way toward each neighbour: the one that leaves
    // the fewest crossings
    std::vector<Point_3> tries;
    if(c_v == 0) tries = {c, CGAL::midpoint(start, c)};
    for(auto g : CGAL::halfedges_around_target(v, m))   // (a vertex on a curve slides along it)
      if(c_v == 0 || is_feature(edge(g, m)) || is_border(edge(g, m), m)) tries.push_back(start + (get(vpm, source(g, m)) - start) / 3.0);
    std::size_t best = before;
    Point_3 best_q = start;
    for(const Point_3& t : tries) {
      const Point_3 q = c_v == 0 ? ctx.project_on_surface(t, start) : ctx.project_on_features(t, start);
      if(CGAL::to_double(CGAL::squared_distance(q, t)) > CGAL::square(0.25 * mean)) continue;   // thin parts
      const double new_min = ctx.smallest_angles_around(v, m, q).first;
      if(new_min < 0 || new_min < limit) continue;
      put(vpm, v, q);
      const std::size_t after = crossings(fs);
      if(after < best) { best = after; best_q = q; }
      put(vpm, v, start);
      refresh(fs);
      if(best == 0) break;
    }
    if(best < before) {
      put(vpm, v, best_q);
      refresh(fs);
      changed.insert(changed.end(), fs.begin(), fs.end());
      ++done;
      ++stats.untangle_changes;
    }
  }
  // flips of the edges of the faces still crossing
  update_pairs();
  const double cos_max = std::cos(60 * CGAL_PI / 180);
  std::vector<typename boost::graph_traits<Mesh>::edge_descriptor> es;
  for(const auto& fp : pairs)
    for(face_descriptor f : {fp.first, fp.second})
      for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m)) es.push_back(edge(h, m));
  std::sort(es.begin(), es.end(), order);
  es.erase(std::unique(es.begin(), es.end()), es.end());
  for(auto e : es) {
    if(is_feature(e) || is_border(e, m)) continue;
    const auto h = halfedge(e, m);
    const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
    if(degree(p, m) <= 3 || degree(q, m) <= 3 || r == t || halfedge(r, t, m).second) continue;
    if(!ctx.flip_is_safe(h, m, cos_max)) continue;
    std::vector<face_descriptor> fs = {face(h, m), face(opposite(h, m), m)};
    std::sort(fs.begin(), fs.end());
    const std::size_t before = crossings(fs);
    if(before == 0) continue;
    if(ctx.min_angle_after_flip(h, m) < std::min(ctx.min_angle_of_faces(h, m), floor)) continue;
    CGAL::Euler::flip_edge(h, m);
    std::vector<face_descriptor> gs = {face(h, m), face(opposite(h, m), m)};
    std::sort(gs.begin(), gs.end());
    // (a flip taken back may leave the two triangles each in the other's face: both changed)
    changed.insert(changed.end(), gs.begin(), gs.end());
    if(crossings(gs) < before) { ++done; ++stats.untangle_changes; }
    else {
      CGAL::Euler::flip_edge(h, m);
      std::vector<face_descriptor> back = {face(h, m), face(opposite(h, m), m)};
      refresh(back);
    }
  }
  // (with `collapses`) a free vertex shared by two faces still crossing -- its fan folded over on
  // a part thinner than the triangles, a claw -- goes into a free neighbour, which keeps
  // its place, when the triangles around it cross fewer others and keep untangle_collapse_min_angle;
  // tried on a copy of the faces near the edge (the whole mesh when those faces do not make a
  // mesh on their own); the caller optimizes the angles there again
  if(collapses != nullptr) {
    typedef typename boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
    update_pairs();
    std::vector<vertex_descriptor> shared;
    for(const auto& fp : pairs)
      for(vertex_descriptor x : CGAL::vertices_around_face(halfedge(fp.first, m), m))
        for(vertex_descriptor y : CGAL::vertices_around_face(halfedge(fp.second, m), m))
          if(x == y) shared.push_back(x);
    std::sort(shared.begin(), shared.end(), order);
    shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
    const double collapse_floor = s.collapse_min_angle * CGAL_PI / 180;
    std::set<vertex_descriptor> gone;
    // (at most 64 trials per pass: a large input folded in many places would spend its time there)
    std::size_t trials = 0;
    const std::size_t max_trials = 64;
    // the crossings of the faces around the vertices `around` (in m, or in a copy of it); the
    // faces near them in m from the grid (kept current below after each collapse)
    auto crossings_near = [](const Mesh& g, const std::vector<vertex_descriptor>& around, const auto& near_faces) {
      const auto fs = Poisson_remesh::internal::faces_around(g, around);
      std::size_t n = 0;
      for(const auto& fp : Poisson_remesh::internal::intersecting_pairs_near(g, fs, near_faces))
        if(std::binary_search(fs.begin(), fs.end(), fp.first) || std::binary_search(fs.begin(), fs.end(), fp.second)) ++n;
      return n;
    };
    // copies into `copy` the faces whose boxes meet the box of the stars of h's ends -- every face
    // that a triangle around the vertex h collapses into can meet, each with its neighbours there,
    // so that the crossings counted around it are those of a whole copy -- or the whole mesh when
    // those faces do not make a mesh on their own; returns h's halfedge in the copy
    auto copy_near = [&](halfedge_descriptor h, Mesh& copy) {
      CGAL::Bbox_3 around;
      for(vertex_descriptor v : {source(h, m), target(h, m)})
        for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, m), m)) around += get(vpm, v).bbox() + get(vpm, w).bbox();
      std::map<vertex_descriptor, vertex_descriptor> v2v;
      auto copy_vpm = get(CGAL::vertex_point, copy);
      bool valid = true;
      for(face_descriptor f : faces(m)) {
        if(!CGAL::do_overlap(box_of(f), around)) continue;
        std::array<vertex_descriptor, 3> corners;
        int k = 0;
        for(vertex_descriptor w : CGAL::vertices_around_face(halfedge(f, m), m)) {
          auto it = v2v.find(w);
          if(it == v2v.end()) {
            it = v2v.emplace(w, add_vertex(copy)).first;
            put(copy_vpm, it->second, get(vpm, w));
          }
          corners[k++] = it->second;
        }
        if(CGAL::Euler::add_face(corners, copy) == boost::graph_traits<Mesh>::null_face()) { valid = false; break; }
      }
      if(valid) {
        const auto found = halfedge(v2v[source(h, m)], v2v[target(h, m)], copy);
        if(found.second) return found.first;
      }
      clear(copy);
      std::map<halfedge_descriptor, halfedge_descriptor> h2h;
      CGAL::copy_face_graph(m, copy, CGAL::parameters::halfedge_to_halfedge_output_iterator(std::inserter(h2h, h2h.end())));
      return h2h[h];
    };
    for(vertex_descriptor x : shared) {
      if(gone.count(x) || ctx.constraint(x, m, is_feature, is_fixed) != 0) continue;
      halfedge_descriptor best_h = boost::graph_traits<Mesh>::null_halfedge();
      std::size_t best_gain = 0;
      for(halfedge_descriptor h : CGAL::halfedges_around_target(x, m)) {   // h: y -> x
        const vertex_descriptor y = source(h, m);
        if(gone.count(y) || ctx.constraint(y, m, is_feature, is_fixed) != 0 || !CGAL::Euler::does_satisfy_link_condition(edge(h, m), m)) continue;
        std::vector<vertex_descriptor> xy = {x, y};
        std::sort(xy.begin(), xy.end());
        const std::size_t before = crossings_near(m, xy, near_in_grid);
        if(before == 0 || trials >= max_trials) continue;
        ++trials;
        Mesh copy;
        const halfedge_descriptor hc = copy_near(h, copy);
        const Point_3 at = get(vpm, y);
        const auto z = CGAL::Euler::collapse_edge(edge(hc, copy), copy);
        put(get(CGAL::vertex_point, copy), z, at);
        if(!(ctx.smallest_angles_around(z, copy, at).first >= collapse_floor)) continue;
        const std::size_t after = crossings_near(copy, std::vector<vertex_descriptor>(1, z), Poisson_remesh::internal::All_faces());
        if(after < before && before - after > best_gain) { best_gain = before - after; best_h = h; }
      }
      if(best_h == boost::graph_traits<Mesh>::null_halfedge()) continue;
      const vertex_descriptor y = source(best_h, m);
      const Point_3 at = get(vpm, y);
      const std::vector<face_descriptor> were = Poisson_remesh::internal::faces_around(m, std::array<vertex_descriptor, 2>{{x, y}});
      const vertex_descriptor z = CGAL::Euler::collapse_edge(edge(best_h, m), m);
      put(vpm, z, at);
      // (the grid: the two faces gone removed, those around z filed where they are now)
      const std::vector<face_descriptor> now = Poisson_remesh::internal::faces_around(m, std::array<vertex_descriptor, 1>{{z}});
      for(face_descriptor f : were)
        if(!std::binary_search(now.begin(), now.end(), f)) grid.remove(f);
      refresh(now);
      gone.insert(z == x ? y : x);
      ++done;
      ++*collapses;
      ++stats.untangle_changes;
    }
  }
  return done;
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_UNTANGLING_H
