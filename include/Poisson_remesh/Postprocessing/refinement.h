// Poisson_remesh/Postprocessing/refinement.h
//
// (beyond the paper) Refinement. Objective: the smallest angle in the stars of the triangles still
// sharper than `sliver_angle` (their vertices could not move enough: corners, feature samples).
// Each gets the best of three local changes that beats the old triangles' smallest angle by
// `min_gain`: a flip of one of its edges; the removal of a vertex of degree 3 off the features,
// free or pinned by the fidelity insertions (when the vertex is within half of the fidelity
// tolerance of the new triangle: a tip is not cut off); or a new vertex on one of the two edges at
// its smallest angle, placed on the input (on the features for a feature edge) where the four new
// triangles have the largest smallest angle -- the small angle's wedge is shared with the
// neighbour's angle, as Ruppert's refinement does. Constraints: vertices on the input; no topology
// change (flips, degree-3 removals, edge splits); a change that makes the mesh cut itself anew is
// taken back.

#ifndef POISSON_REMESH_POSTPROCESSING_REFINEMENT_H
#define POISSON_REMESH_POSTPROCESSING_REFINEMENT_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <algorithm>
#include <set>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// The refinement's settings.
struct Refinement_settings
{
  /// rounds of refinement (each followed by Delaunay flips and angle optimization); 0 disables
  unsigned int rounds = 3;
  /// a change must raise the smallest angle of the triangles it replaces by this much (degrees)
  double min_gain = 1;
};

/// One round of refinement of `m` at the triangles sharper than `sliver_angle` (degrees);
/// `max_deviation`: the fidelity tolerance (times the diagonal; 0: a removal may cut 0.002 of it);
/// `pinned`: the vertices of the fidelity insertions (sorted; kept up to date). `new_vertex(v,
/// on_feature)` is told each new vertex. Returns the number of changes.
template <class Context, class Mesh, class IsFeatureEdge, class IsCorner, class NewVertex>
std::size_t refine_sharp_triangles(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, NewVertex new_vertex,
                                   const Refinement_settings& s, double sliver_angle, double max_deviation, Relaxation_statistics& stats,
                                   std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>& pinned)
{
  typedef typename Context::Point_3 Point_3;
  typedef typename Context::Vector_3 Vector_3;
  typedef typename Context::Geom_traits GeomTraits;
  typedef boost::graph_traits<Mesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  auto vpm = get(CGAL::vertex_point, m);
  const double sliver = sliver_angle * CGAL_PI / 180, gain = s.min_gain * CGAL_PI / 180;
  // a new vertex on the edge of h, a flip of that edge, or the removal of the free vertex
  // target(h) of degree 3
  enum class Operation { split, flip, remove };
  struct Candidate
  {
    double gain;
    halfedge_descriptor h;
    Point_3 at;
    bool on_feature;
    Operation op;
    std::vector<face_descriptor> faces;   // the faces the change replaces (checked before h is used)
  };
  const double cos_refine = 0.5;
  std::vector<Candidate> candidates;
  for(face_descriptor f : faces(m)) {
    const halfedge_descriptor hf = halfedge(f, m);
    const vertex_descriptor v[3] = {source(hf, m), target(hf, m), target(next(hf, m), m)};
    const Point_3 p[3] = {get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2])};
    const double old_f = ctx.min_angle(p[0], p[1], p[2]);
    if(!(old_f < sliver)) continue;
    // the vertex of the smallest angle, and the two edges there
    const double a[3] = {ctx.angle(p[1], p[0], p[2]), ctx.angle(p[0], p[1], p[2]), ctx.angle(p[0], p[2], p[1])};
    const int k = int(std::min_element(a, a + 3) - a);
    Candidate best{0, GT::null_halfedge(), Point_3(), false, Operation::split, {}};
    for(halfedge_descriptor h : CGAL::halfedges_around_face(hf, m)) {
      // flip: the two new triangles beat the two old ones
      if(!is_feature(edge(h, m)) && !is_border(edge(h, m), m)) {
        const Point_3 &A = get(vpm, source(h, m)), &B = get(vpm, target(h, m));
        const Point_3 &C = get(vpm, target(next(h, m), m)), &D = get(vpm, target(next(opposite(h, m), m), m));
        // (the guards of the Delaunay flips, with the looser normal change of the tessellation's
        // removals, 60 degrees: the triangles here are the worst of the mesh, their normals noisy)
        if(ctx.flip_is_safe(h, m, cos_refine)) {
          const double old = std::min(old_f, ctx.min_angle(B, A, D));
          const double value = std::min(ctx.min_angle(C, A, D), ctx.min_angle(D, B, C));
          if(value > old + gain && value - old > best.gain) best = {value - old, h, Point_3(), false, Operation::flip, {f, face(opposite(h, m), m)}};
        }
      }
      // removal of target(h), a vertex of degree 3 off the features: its three triangles become
      // one (a pinned vertex of the fidelity pass too: the new triangle passes near it, see below)
      const vertex_descriptor x = target(h, m);
      // (constraint 0: no corner, no feature or border edge)
      if(degree(x, m) == 3 && ctx.constraint(x, m, is_feature, is_corner) == 0) {
        double old = CGAL_PI;
        Vector_3 n(0, 0, 0);
        std::vector<face_descriptor> star;
        bool closed = false;   // the three neighbours bound a face already (four faces closed on themselves)
        for(halfedge_descriptor g : CGAL::halfedges_around_target(x, m)) {
          const Point_3 &P = get(vpm, source(g, m)), &Q = get(vpm, target(next(g, m), m));
          old = std::min(old, ctx.min_angle(P, get(vpm, x), Q));
          n = n + ctx.normal(P, get(vpm, x), Q);
          star.push_back(face(g, m));
          // the link edge (b, a) of face (a, x, b): the face across it must not be (a, b, c)
          const halfedge_descriptor across = opposite(next(next(g, m), m), m);
          if(!is_border(across, m)) {
            const vertex_descriptor w = target(next(across, m), m);
            for(halfedge_descriptor k : CGAL::halfedges_around_target(x, m))
              if(source(k, m) == w && w != source(g, m) && w != target(next(g, m), m)) closed = true;
          }
        }
        // the new triangle runs along the link edges next(next(g)) = (b, a) of the faces (a, x, b)
        const halfedge_descriptor link = next(next(halfedge(x, m), m), m);
        // (the next link edge, from target(link), is in the face across the edge (x, target(link)))
        const Point_3 &P = get(vpm, source(link, m)), &Q = get(vpm, target(link, m));
        const Point_3& third = get(vpm, target(next(opposite(next(link, m), m), m), m));
        if(closed) continue;
        // (and the removed vertex is close to the new triangle, within half the fidelity tolerance:
        // a tip is not cut off)
        const double tol = (max_deviation > 0 ? 0.5 * max_deviation : 0.002) * ctx.diagonal();
        if(ctx.cos_between(ctx.normal(P, Q, third), n) > 0.5 &&
           CGAL::to_double(CGAL::squared_distance(get(vpm, x), typename GeomTraits::Triangle_3(P, Q, third))) <= tol * tol) {
          const double value = ctx.min_angle(P, Q, third);
          if(value > old + gain && value - old > best.gain) best = {value - old, h, Point_3(), false, Operation::remove, star};
        }
      }
    }
    for(halfedge_descriptor h : CGAL::halfedges_around_face(hf, m)) {
      if(source(h, m) != v[k] && target(h, m) != v[k]) continue;
      if(is_border(opposite(h, m), m)) continue;
      const Point_3 &A = get(vpm, source(h, m)), &B = get(vpm, target(h, m));
      const Point_3 &C = get(vpm, target(next(h, m), m)), &D = get(vpm, target(next(opposite(h, m), m), m));
      const double old = std::min(old_f, ctx.min_angle(B, A, D));
      const bool on_feature = is_feature(edge(h, m));
      const Vector_3 n1 = ctx.normal(A, B, C), n2 = ctx.normal(B, A, D);
      // the four triangles (A, q, C), (q, B, C), (B, q, D), (q, A, D): the smallest angle, or -1
      // when one turns over
      auto objective = [&](const Point_3& q) {
        if(ctx.cos_between(ctx.normal(A, q, C), n1) < 0.5 || ctx.cos_between(ctx.normal(q, B, C), n1) < 0.5 ||
           ctx.cos_between(ctx.normal(B, q, D), n2) < 0.5 || ctx.cos_between(ctx.normal(q, A, D), n2) < 0.5) return -1.0;
        return std::min({ctx.min_angle(A, q, C), ctx.min_angle(q, B, C), ctx.min_angle(B, q, D), ctx.min_angle(q, A, D)});
      };
      const Point_3 mid = CGAL::midpoint(A, B);
      const double length = std::sqrt(CGAL::to_double(CGAL::squared_distance(A, B)));
      Point_3 q = on_feature ? ctx.project_on_features(mid) : ctx.project_on_surface(mid);
      if(CGAL::to_double(CGAL::squared_distance(q, mid)) > CGAL::square(0.25 * length)) continue;   // thin parts
      double value = objective(q);
      if(value < 0) continue;
      // pattern search: along the edge for a feature edge, else in the plane of the two faces
      std::vector<Vector_3> dirs;
      const Vector_3 ab = (B - A) / length;
      dirs.push_back(ab);
      dirs.push_back(-ab);
      if(!on_feature) {
        Vector_3 nn = n1 / std::sqrt(CGAL::to_double(n1.squared_length())) + n2 / std::sqrt(CGAL::to_double(n2.squared_length()));
        const Vector_3 w = CGAL::cross_product(nn, ab);
        const double lw = std::sqrt(CGAL::to_double(w.squared_length()));
        if(!(lw > 0)) continue;
        for(int sign : {1, -1}) {
          dirs.push_back(double(sign) * w / lw);
          dirs.push_back(std::sqrt(0.5) * (ab + double(sign) * w / lw));
          dirs.push_back(std::sqrt(0.5) * (-ab + double(sign) * w / lw));
        }
      }
      double step = 0.2 * length;
      for(int iteration = 0; iteration < 30 && step > 0.01 * length; ++iteration) {
        Point_3 best_q = q;
        double best_here = value;
        for(const Vector_3& d : dirs) {
          const Point_3 t = q + step * d;
          const Point_3 r = on_feature ? ctx.project_on_features(t, q) : ctx.project_on_surface(t, q);
          if(CGAL::to_double(CGAL::squared_distance(r, t)) > CGAL::square(0.25 * length)) continue;
          const double x = objective(r);
          if(x > best_here + 1e-9) { best_here = x; best_q = r; }
        }
        if(best_here > value + 1e-6) { value = best_here; q = best_q; }
        else step *= 0.5;
      }
      if(value > old + gain && value - old > best.gain) best = {value - old, h, q, on_feature, Operation::split, {f, face(opposite(h, m), m)}};
    }
    if(best.h != GT::null_halfedge()) candidates.push_back(best);
  }
  if(candidates.empty()) return 0;
  const auto before = Poisson_remesh::internal::intersecting_pairs(m);
  if(before.size() > num_faces(m)) return 0;   // (folded everywhere: see angle_pass)
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) { return x.gain > y.gain; });
  std::set<face_descriptor> touched;
  struct Inserted { vertex_descriptor v; bool on_feature; vertex_descriptor a, b; };   // on the old edge (a, b)
  std::vector<Inserted> mine;
  std::vector<halfedge_descriptor> flipped;
  struct Removed { halfedge_descriptor h; Point_3 at; bool pinned; };   // a halfedge of the new triangle, where the vertex was, pinned
  std::vector<Removed> removed;
  // (the removals last: the faces they free are not reused by a split of this pass, which would
  // pair them with the old faces' intersections in `before`)
  std::stable_partition(candidates.begin(), candidates.end(), [](const Candidate& c) { return c.op != Operation::remove; });
  for(const Candidate& c : candidates) {
    // the faces changed and their neighbours take one change at most; a candidate whose faces
    // are untouched still has valid descriptors
    if(std::any_of(c.faces.begin(), c.faces.end(), [&](face_descriptor f) { return touched.count(f) > 0; })) continue;
    if(c.op == Operation::flip && !ctx.flip_is_safe(c.h, m, cos_refine)) continue;
    for(face_descriptor f : c.faces) {
      touched.insert(f);
      for(halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(f, m), m))
        if(!is_border(opposite(g, m), m)) touched.insert(face(opposite(g, m), m));
    }
    if(c.op == Operation::flip) {
      CGAL::Euler::flip_edge(c.h, m);
      flipped.push_back(c.h);
      continue;
    }
    if(c.op == Operation::remove) {
      const vertex_descriptor x = target(c.h, m);
      const Point_3 at = get(vpm, x);
      const auto it = std::lower_bound(pinned.begin(), pinned.end(), x);
      const bool was_pinned = it != pinned.end() && *it == x;
      if(was_pinned) pinned.erase(it);
      removed.push_back({CGAL::Euler::remove_center_vertex(halfedge(x, m), m), at, was_pinned});
      continue;
    }
    const vertex_descriptor a = source(c.h, m), b = target(c.h, m);
    mine.push_back({ctx.insert_vertex_on_edge(c.h, c.at, m), c.on_feature, a, b});
  }
  // a change that makes the mesh cut itself is taken back: an inserted vertex's four triangles
  // become the two old ones, a flip is flipped back, a removed vertex comes back
  std::vector<face_descriptor> cut;   // the faces of the new intersections
  std::vector<vertex_descriptor> inserted;
  for(const Inserted& x : mine) inserted.push_back(x.v);
  std::vector<face_descriptor> new_faces = Poisson_remesh::internal::faces_around(m, inserted);   // the faces that are new
  for(halfedge_descriptor h : flipped)
    for(halfedge_descriptor g : {h, opposite(h, m)}) if(!is_border(g, m)) new_faces.push_back(face(g, m));
  for(const Removed& r : removed) new_faces.push_back(face(r.h, m));
  std::sort(new_faces.begin(), new_faces.end());
  new_faces.erase(std::unique(new_faces.begin(), new_faces.end()), new_faces.end());
  for(const auto& fp : Poisson_remesh::internal::intersecting_pairs_near(m, new_faces))
    if(!std::binary_search(before.begin(), before.end(), fp)) { cut.push_back(fp.first); cut.push_back(fp.second); }
  std::sort(cut.begin(), cut.end());
  auto is_cut = [&](face_descriptor f) { return std::binary_search(cut.begin(), cut.end(), f); };
  std::size_t changed = 0;
  for(halfedge_descriptor h : flipped) {
    if(is_cut(face(h, m)) || is_cut(face(opposite(h, m), m))) { CGAL::Euler::flip_edge(h, m); ++stats.refused_moves; }
    else { ++changed; ++stats.refinement_flips; }
  }
  for(const Removed& r : removed) {
    if(is_cut(face(r.h, m))) {
      const vertex_descriptor v = target(CGAL::Euler::add_center_vertex(r.h, m), m);   // a new descriptor
      put(vpm, v, r.at);
      new_vertex(v, false);
      if(r.pinned) pinned.insert(std::lower_bound(pinned.begin(), pinned.end(), v), v);
      ++stats.refused_moves;
    } else {
      ++changed;
      ++stats.refinement_removals;
    }
  }
  std::vector<Inserted> undo;
  for(const Inserted& x : mine)
    for(halfedge_descriptor g : CGAL::halfedges_around_target(x.v, m))
      if(is_cut(face(g, m))) { undo.push_back(x); break; }
  auto by_vertex = [](const Inserted& x, const Inserted& y) { return x.v < y.v; };
  std::sort(undo.begin(), undo.end(), by_vertex);
  for(const Inserted& u : undo) {
    ctx.remove_vertex_on_edge(u.v, u.a, u.b, m);
    ++stats.refused_moves;
  }
  std::size_t done = 0;
  for(const Inserted& x : mine)
    if(!std::binary_search(undo.begin(), undo.end(), x, by_vertex)) { new_vertex(x.v, x.on_feature); ++done; }
  stats.refinement_insertions += done;
  return done + changed;
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_REFINEMENT_H
