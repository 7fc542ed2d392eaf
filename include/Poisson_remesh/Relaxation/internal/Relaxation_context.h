// Poisson_remesh/Relaxation/internal/Relaxation_context.h
//
// What the relaxation's steps share (internal): the input surface and its features, the
// projections onto them (CGAL AABB tree; internal/feature_curves.h), the bounding-box diagonal,
// the input's own crossings, and the small geometric and combinatorial predicates the steps use
// (angles, flip guards, a vertex's constraint, self-intersection checks scoped to the changed
// faces). Every step of Relaxation/ and Postprocessing/ takes a `Relaxation_context` as its first
// argument; a `Lloyd_relaxer` owns one.

#ifndef POISSON_REMESH_RELAXATION_INTERNAL_RELAXATION_CONTEXT_H
#define POISSON_REMESH_RELAXATION_INTERNAL_RELAXATION_CONTEXT_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/internal/closest_point.h>
#include <Poisson_remesh/internal/feature_curves.h>
#include <Poisson_remesh/internal/parallel.h>
#include <Poisson_remesh/internal/self_intersections.h>
#include <Poisson_remesh/internal/vector_angle.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/Bbox_3.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace Poisson_remesh {

namespace internal {

template <class Mesh>
using Face_pairs = std::vector<std::pair<typename boost::graph_traits<Mesh>::face_descriptor, typename boost::graph_traits<Mesh>::face_descriptor>>;

// the intersecting face pairs among the faces of `range` (all of m's by default), each (smaller,
// larger), sorted (internal/self_intersections.h: CGAL's pairs, found with fewer exact tests); the
// search stops past twice the face count (a mesh that cuts itself everywhere: folded input). The
// pairs never depend on the number of threads.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Mesh, class FaceRange>
Face_pairs<Mesh> intersecting_pairs(const Mesh& m, const FaceRange& range)
{
  return intersecting_face_pairs<ConcurrencyTag>(m, range, get(CGAL::vertex_point, m), 2 * num_faces(m) + 1);
}
template <class ConcurrencyTag = CGAL::Sequential_tag, class Mesh>
Face_pairs<Mesh> intersecting_pairs(const Mesh& m) { return intersecting_pairs<ConcurrencyTag>(m, faces(m)); }

// Where intersecting_pairs_near looks for the faces near the changed ones: every face of the mesh.
struct All_faces {};

// the bounding box of face f of m (of its corners' points)
template <class Mesh>
CGAL::Bbox_3 face_box(typename boost::graph_traits<Mesh>::face_descriptor f, const Mesh& m)
{
  const auto vpm = get(CGAL::vertex_point, m);
  const auto h = halfedge(f, m);
  return get(vpm, source(h, m)).bbox() + get(vpm, target(h, m)).bbox() + get(vpm, target(next(h, m), m)).bbox();
}

// the intersecting face pairs (as above) that involve a face of `changed` or a face whose box
// meets the box of one: all the pairs that can differ from an earlier check when only the faces
// of `changed` moved or are new. A box search of the changed faces against all faces, then
// CGAL's exact test on that neighbourhood alone (a whole-mesh check per undo round would test
// again every pair that no move touched); when most faces changed, the whole mesh's pairs (a superset: the box
// search would only repeat self_intersections' own). `near_faces(box, out)`, when given, appends
// to `out` every face whose box (as it is now) meets `box`, or more (the box search then looks at
// those alone): a scan of every face per call is what the operators that check after each small
// trial cannot afford (Postprocessing/internal/face_box_grid.h). The pairs are the same.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Mesh, class FaceRange, class NearFaces = All_faces>
Face_pairs<Mesh> intersecting_pairs_near(const Mesh& m, const FaceRange& changed, const NearFaces& near_faces = NearFaces())
{
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  typedef CGAL::Box_intersection_d::Box_with_info_d<double, 3, face_descriptor> Box;
  auto box_of = [&](face_descriptor f) { return Box(face_box(f, m), f); };
  const auto n = std::size_t(std::distance(std::begin(changed), std::end(changed)));
  if(n == 0) return {};
  if(2 * n > num_faces(m)) return intersecting_pairs<ConcurrencyTag>(m);
  std::vector<Box> mine;
  for(face_descriptor f : changed) mine.push_back(box_of(f));
  // (each changed face meets its own box, so it is in `near` too)
  std::vector<face_descriptor> near;
  {
    // the changed boxes in a grid of cells as large as the largest of them (each box in 8 cells
    // at most), each face's box against those of the cells it meets (the same closed-box test as
    // box_intersection_d's, without its sweep sorting every face's box at each call)
    CGAL::Bbox_3 all_mine;
    double cell = 0;
    for(const Box& b : mine) {
      all_mine += b.bbox();
      for(int i = 0; i < 3; ++i) cell = (std::max)(cell, b.bbox().max(i) - b.bbox().min(i));
    }
    for(int i = 0; i < 3; ++i) cell = (std::max)(cell, 1e-9 * (all_mine.max(i) - all_mine.min(i)));
    if(!(cell > 0)) cell = 1;
    auto index = [&](double x, int i) { return std::int64_t(std::floor((x - all_mine.min(i)) / cell)); };
    auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) { return (std::uint64_t(x) << 42) ^ (std::uint64_t(y) << 21) ^ std::uint64_t(z); };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
    for(std::size_t k = 0; k < mine.size(); ++k) {
      const CGAL::Bbox_3& b = mine[k].bbox();
      for(std::int64_t x = index(b.xmin(), 0); x <= index(b.xmax(), 0); ++x)
        for(std::int64_t y = index(b.ymin(), 1); y <= index(b.ymax(), 1); ++y)
          for(std::int64_t z = index(b.zmin(), 2); z <= index(b.zmax(), 2); ++z) grid[key(x, y, z)].push_back(k);
    }
    const std::int64_t last[3] = {index(all_mine.xmax(), 0), index(all_mine.ymax(), 1), index(all_mine.zmax(), 2)};
    // (each face at once with CGAL::Parallel_tag, the grid only read; taken in in the faces' order)
    std::vector<face_descriptor> all;
    if constexpr(std::is_same<NearFaces, All_faces>::value) all.assign(faces(m).begin(), faces(m).end());
    else {   // (the candidates, each once, in the descriptors' order)
      near_faces(all_mine, all);
      std::sort(all.begin(), all.end());
      all.erase(std::unique(all.begin(), all.end()), all.end());
    }
    std::vector<std::int8_t> is_near(all.size(), 0);
    for_each_index<ConcurrencyTag>(all.size(), [&](std::size_t i) {
      const face_descriptor f = all[i];
      const CGAL::Bbox_3 b = box_of(f).bbox();
      if(!CGAL::do_overlap(b, all_mine)) return;
      std::int64_t lo[3], hi[3], cells = 1;
      for(int d = 0; d < 3; ++d) {
        lo[d] = (std::max)(std::int64_t(0), index(b.min(d), d));
        hi[d] = (std::min)(last[d], index(b.max(d), d));
        cells *= hi[d] - lo[d] + 1;
      }
      bool meets = false;
      if(cells > 64) {   // (a face much larger than the changed ones: against each of them)
        for(const Box& c : mine) if((meets = CGAL::do_overlap(b, c.bbox()))) break;
      } else {
        for(std::int64_t x = lo[0]; x <= hi[0] && !meets; ++x)
          for(std::int64_t y = lo[1]; y <= hi[1] && !meets; ++y)
            for(std::int64_t z = lo[2]; z <= hi[2] && !meets; ++z) {
              const auto it = grid.find(key(x, y, z));
              if(it == grid.end()) continue;
              for(std::size_t k : it->second) if((meets = CGAL::do_overlap(b, mine[k].bbox()))) break;
            }
      }
      is_near[i] = meets ? 1 : 0;
    });
    for(std::size_t i = 0; i < all.size(); ++i) if(is_near[i]) near.push_back(all[i]);
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  return intersecting_pairs<ConcurrencyTag>(m, near);
}

// the faces around the vertices of a range, sorted, each once
template <class Mesh, class VertexRange>
std::vector<typename boost::graph_traits<Mesh>::face_descriptor> faces_around(const Mesh& m, const VertexRange& vs)
{
  std::vector<typename boost::graph_traits<Mesh>::face_descriptor> out;
  for(auto v : vs)
    for(auto h : CGAL::halfedges_around_target(halfedge(v, m), m))
      if(!is_border(h, m)) out.push_back(face(h, m));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

} // namespace internal

namespace internal {

/// The input surface, its features and the shared predicates of the relaxation's steps.
/// `GeomTraits`: the kernel of the input's points.
template <class InputMesh, class GeomTraits>
class Relaxation_context
{
public:
  typedef InputMesh Input_mesh;
  typedef GeomTraits Geom_traits;
  typedef typename GeomTraits::Point_3 Point_3;
  typedef typename GeomTraits::Vector_3 Vector_3;

private:
  // (each triangle kept in its primitive: the input does not change, and a projection then reads
  // no halfedge and no vertex point of the input)
  typedef CGAL::AABB_face_graph_triangle_primitive<InputMesh, CGAL::Default, CGAL::Tag_true, CGAL::Tag_true> Face_primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GeomTraits, Face_primitive>> Face_tree;

public:
  /// `features`: the input's features (their edges are where feature vertices may slide).
  Relaxation_context(const InputMesh& input, const Feature_set<InputMesh>& features)
    : input_(input), faces_(faces(input).first, faces(input).second, input), curves_(input, features)
  {
    faces_.do_not_accelerate_distance_queries();   // (internal/closest_point.h needs no k-d tree)
    if(!faces_.empty()) faces_.build();
    const auto& pts = get(CGAL::vertex_point, input);
    if(!vertices(input).empty()) {
      CGAL::Bbox_3 box;
      for(auto v : vertices(input)) box += get(pts, v).bbox();
      diagonal_ = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) + CGAL::square(box.zmax() - box.zmin()));
    }
  }

  /// the input mesh
  const InputMesh& input() const { return input_; }
  /// the input's bounding-box diagonal
  double diagonal() const { return diagonal_; }

  /// the point of the input surface closest to `p`
  Point_3 project_on_surface(const Point_3& p) const { return internal::closest_point(faces_, p); }
  /// the point of the input's feature edges closest to `p` (of the surface, without features)
  Point_3 project_on_features(const Point_3& p) const { return curves_.empty() ? project_on_surface(p) : curves_.closest_point(p); }
  /// The same with `hint`, a point known to lie on the input surface (on a feature curve for
  /// project_on_features), near p: the search starts with its distance as the bound, which makes
  /// projections of moving vertices cheaper (the result is the same closest point). With any
  /// other hint, the closest point when it is closer to p than the hint, else the hint.
  /// @{
  Point_3 project_on_surface(const Point_3& p, const Point_3& hint) const { return internal::closest_point(faces_, p, hint); }
  Point_3 project_on_features(const Point_3& p, const Point_3& hint) const
  {
    return curves_.empty() ? project_on_surface(p, hint) : curves_.closest_point(p, hint);
  }
  /// @}

  static double angle(const Point_3& a, const Point_3& o, const Point_3& b)
  {
    const Vector_3 u = a - o, v = b - o;
    return internal::vector_angle(std::sqrt(CGAL::to_double(CGAL::cross_product(u, v).squared_length())), CGAL::to_double(u * v));
  }
  // the smallest angle lies opposite the shortest edge: one atan2 instead of three (the relaxer's
  // angle searches spend most of their time here)
  static double min_angle(const Point_3& a, const Point_3& b, const Point_3& c)
  {
    const double ab = CGAL::to_double(CGAL::squared_distance(a, b));
    const double bc = CGAL::to_double(CGAL::squared_distance(b, c));
    const double ca = CGAL::to_double(CGAL::squared_distance(c, a));
    if(bc <= ab && bc <= ca) return angle(b, a, c);
    if(ca <= ab) return angle(a, b, c);
    return angle(a, c, b);
  }
  static Vector_3 normal(const Point_3& a, const Point_3& b, const Point_3& c) { return CGAL::cross_product(b - a, c - a); }
  static double cos_between(const Vector_3& a, const Vector_3& b)
  {
    const double la = std::sqrt(CGAL::to_double(a.squared_length())), lb = std::sqrt(CGAL::to_double(b.squared_length()));
    return (la > 0 && lb > 0) ? CGAL::to_double(a * b) / (la * lb) : -1;
  }

  template <class Mesh, class IsFeatureEdge>
  std::size_t feature_degree(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, IsFeatureEdge is_feature) const
  {
    std::size_t d = 0;
    for(auto h : CGAL::halfedges_around_target(v, m)) if(is_feature(edge(h, m)) || is_border(edge(h, m), m)) ++d;
    return d;
  }

  template <class Mesh>
  bool folds(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, const Point_3& to) const
  {
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      if(is_border(h, m)) continue;
      const Point_3& a = get(get(CGAL::vertex_point, m), source(h, m));
      const Point_3& b = get(get(CGAL::vertex_point, m), target(next(h, m), m));
      // triangle (a, v, b) in this order around the face
      const Vector_3 before = normal(a, get(get(CGAL::vertex_point, m), v), b), after = normal(a, to, b);
      if(cos_between(before, after) < 0.5) return true;
    }
    return false;
  }

  // the two new triangles of a flip stay close to the old ones
  template <class Mesh>
  bool flip_is_safe(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m, double cos_max) const
  {
    const auto p = source(h, m), q = target(h, m);
    const auto r = target(next(h, m), m), s = target(next(opposite(h, m), m), m);
    if(r == s || halfedge(r, s, m).second) return false;
    if(degree(p, m) <= 3 || degree(q, m) <= 3) return false;
    const Point_3 &P = get(get(CGAL::vertex_point, m), p), &Q = get(get(CGAL::vertex_point, m), q), &R = get(get(CGAL::vertex_point, m), r), &S = get(get(CGAL::vertex_point, m), s);
    const Vector_3 n1 = normal(P, Q, R), n2 = normal(Q, P, S);
    const Vector_3 m1 = normal(R, S, Q), m2 = normal(S, R, P);   // new triangles (r, s, q), (s, r, p)
    // (area-weighted: the normal of a nearly flat triangle is noise)
    const Vector_3 avg = n1 + n2;
    return cos_between(m1, avg) > cos_max && cos_between(m2, avg) > cos_max && cos_between(m1, m2) > cos_max;
  }

  // how many more of its four vertices a flip of h makes irregular (valence not 6, not 4 on a
  // border): negative when fewer
  template <class Mesh>
  static int irregular_change(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m)
  {
    // (each vertex's degree and border test once: both walk around it)
    auto shift = [&](auto v, int change) {
      const int d = int(degree(v, m)), regular = is_border(v, m) ? 4 : 6;
      return int(d + change != regular) - int(d != regular);
    };
    const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
    return shift(p, -1) + shift(q, -1) + shift(r, 1) + shift(t, 1);
  }
  // the smallest angle of the two triangles of h, and of the two a flip of h would make
  template <class Mesh>
  static double min_angle_of_faces(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m)
  {
    auto vpm = get(CGAL::vertex_point, m);
    const Point_3 &P = get(vpm, source(h, m)), &Q = get(vpm, target(h, m));
    const Point_3 &R = get(vpm, target(next(h, m), m)), &T = get(vpm, target(next(opposite(h, m), m), m));
    return std::min(min_angle(P, Q, R), min_angle(Q, P, T));
  }
  template <class Mesh>
  static double min_angle_after_flip(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m)
  {
    auto vpm = get(CGAL::vertex_point, m);
    const Point_3 &P = get(vpm, source(h, m)), &Q = get(vpm, target(h, m));
    const Point_3 &R = get(vpm, target(next(h, m), m)), &T = get(vpm, target(next(opposite(h, m), m), m));
    return std::min(min_angle(R, T, Q), min_angle(T, R, P));
  }

  // calls f(x) for each vertex of the faces that intersect now but not in `before` (sorted pairs),
  // where only the faces of `changed` moved or are new since `before` was taken
  template <class Mesh, class Pairs, class FaceRange, class F>
  void for_vertices_of_new_intersections(const Mesh& m, const Pairs& before, const FaceRange& changed, F f) const
  {
    for_vertices_of_pairs_not_in(m, internal::intersecting_pairs_near(m, changed), before, f);
  }

  // The same when only vertices moved since the earlier state: `moved` lists (vertex, where it
  // was) pairs, sorted by vertex. Which of the pairs that intersect now also did then is asked of
  // those pairs alone, with the vertices put back for a moment: no check of the whole earlier
  // state (most often nothing intersects now and nothing more is asked). Returns the number of
  // pairs that intersect now near `changed`.
  // (`ConcurrencyTag`: the searches' mode, see intersecting_pairs)
  // (`near_faces`: see intersecting_pairs_near)
  template <class ConcurrencyTag = CGAL::Sequential_tag, class Mesh, class Moved, class FaceRange, class F, class NearFaces = All_faces>
  std::size_t for_vertices_of_new_intersections_after_moves(Mesh& m, const Moved& moved, const FaceRange& changed, F f,
                                                            const NearFaces& near_faces = NearFaces()) const
  {
    typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
    const auto now = internal::intersecting_pairs_near<ConcurrencyTag>(m, changed, near_faces);
    if(now.empty()) return 0;
    std::vector<face_descriptor> involved;
    for(const auto& fp : now) { involved.push_back(fp.first); involved.push_back(fp.second); }
    std::sort(involved.begin(), involved.end());
    involved.erase(std::unique(involved.begin(), involved.end()), involved.end());
    auto vpm = get(CGAL::vertex_point, m);
    std::vector<Point_3> current;
    current.reserve(moved.size());
    for(const auto& x : moved) { current.push_back(get(vpm, x.first)); put(vpm, x.first, x.second); }
    const auto before = internal::intersecting_pairs<ConcurrencyTag>(m, involved);
    for(std::size_t i = 0; i < moved.size(); ++i) put(vpm, moved[i].first, current[i]);
    for_vertices_of_pairs_not_in(m, now, before, f);
    return now.size();
  }

  // calls f(x) for each vertex of the pairs of `now` that are not in `before` (sorted) and not
  // near the input's own crossings
  template <class Mesh, class Pairs, class F>
  void for_vertices_of_pairs_not_in(const Mesh& m, const Pairs& now, const Pairs& before, F f) const
  {
    for(const auto& fp : now) {
      if(std::binary_search(before.begin(), before.end(), fp)) continue;
      if(near_input_crossing(fp.first, m) && near_input_crossing(fp.second, m)) continue;
      for(auto face : {fp.first, fp.second})
        for(auto x : CGAL::vertices_around_face(halfedge(face, m), m)) f(x);
    }
  }

  // whether the centroid of face f of m lies within two of f's longest edge's lengths of the
  // centroid of a face of the input that cuts the input (one part of it runs through another): the
  // mesh follows the input there, and a crossing of it is the input's own (the quality report
  // leaves out such crossings too, by its own measure: two mean edge lengths of tm to the face)
  template <class Mesh>
  bool near_input_crossing(typename boost::graph_traits<Mesh>::face_descriptor f, const Mesh& m) const
  {
    if(!input_crossings_known_) {
      input_crossings_known_ = true;
      const auto pairs = internal::intersecting_pairs(input_);
      const auto vpm = get(CGAL::vertex_point, input_);
      std::vector<typename boost::graph_traits<InputMesh>::face_descriptor> crossing;
      for(const auto& fp : pairs) { crossing.push_back(fp.first); crossing.push_back(fp.second); }
      std::sort(crossing.begin(), crossing.end());
      crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
      for(auto g : crossing) {
        const auto h = halfedge(g, input_);
        input_crossings_.push_back(CGAL::centroid(get(vpm, source(h, input_)), get(vpm, target(h, input_)), get(vpm, target(next(h, input_), input_))));
      }
    }
    if(input_crossings_.empty()) return false;
    const auto vpm = get(CGAL::vertex_point, m);
    const auto h = halfedge(f, m);
    const Point_3 &a = get(vpm, source(h, m)), &b = get(vpm, target(h, m)), &c = get(vpm, target(next(h, m), m));
    const double reach2 = 4 * std::max({CGAL::to_double(CGAL::squared_distance(a, b)), CGAL::to_double(CGAL::squared_distance(b, c)),
                                        CGAL::to_double(CGAL::squared_distance(c, a))});
    const Point_3 x = CGAL::centroid(a, b, c);
    for(const Point_3& p : input_crossings_)
      if(CGAL::to_double(CGAL::squared_distance(p, x)) <= reach2) return true;
    return false;
  }

  // the smallest angle of the triangles around v with v at `at`, and the sum of their smallest
  // angles; (-1, -1) when one of them would turn over (its normal more than 60 degrees away from
  // the current one)
  template <class Mesh>
  std::pair<double, double> smallest_angles_around(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m,
                                                   const Point_3& at) const
  {
    return smallest_angles_around(v, m, at, [](typename boost::graph_traits<Mesh>::vertex_descriptor) { return 1.0; });
  }
  // the same with the angles at each other vertex x of the triangles scaled by tip_scale(x)
  template <class Mesh, class TipScale>
  std::pair<double, double> smallest_angles_around(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m,
                                                   const Point_3& at, TipScale tip_scale) const
  {
    auto vpm = get(CGAL::vertex_point, m);
    double worst = CGAL_PI, sum = 0;
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      if(is_border(h, m)) continue;
      const Point_3& a = get(vpm, source(h, m));
      const Point_3& b = get(vpm, target(next(h, m), m));
      const Vector_3 n = normal(a, get(vpm, v), b);
      const double x = star_triangle_angle(a, at, b, n, std::sqrt(CGAL::to_double(n.squared_length())),
                                           tip_scale(source(h, m)), tip_scale(target(next(h, m), m)));
      if(x < 0) return {-1, -1};
      worst = std::min(worst, x);
      sum += x;
    }
    return {worst, sum};
  }
  // the smallest angle of the star triangle (a, at, b), its angles at a and b scaled by sa and
  // sb; -1 when it turns over: its normal more than 60 degrees away from `n` (the triangle's
  // current normal, of length `ln`)
  static double star_triangle_angle(const Point_3& a, const Point_3& at, const Point_3& b, const Vector_3& n, double ln,
                                    double sa, double sb)
  {
    const Vector_3 now = normal(a, at, b);
    const double lnow = std::sqrt(CGAL::to_double(now.squared_length()));
    if(!(ln > 0 && lnow > 0) || CGAL::to_double(n * now) < 0.5 * ln * lnow) return -1;
    // (the angle searches spend most of their time here: each angle is atan2 of twice the area,
    // lnow, the same at every corner, over the dot product of the corner's edges)
    auto angle_at = [lnow](const Point_3& o, const Point_3& x, const Point_3& y) { return internal::vector_angle(lnow, CGAL::to_double((x - o) * (y - o))); };
    if(sa == 1 && sb == 1) {   // (the smallest angle lies opposite the shortest edge)
      const double l_a = CGAL::to_double(CGAL::squared_distance(at, b)), l_at = CGAL::to_double(CGAL::squared_distance(a, b));
      const double l_b = CGAL::to_double(CGAL::squared_distance(a, at));
      if(l_at <= l_a && l_at <= l_b) return angle_at(at, a, b);
      if(l_a <= l_b) return angle_at(a, at, b);
      return angle_at(b, a, at);
    }
    return std::min({angle_at(a, at, b) * sa, angle_at(at, a, b), angle_at(b, a, at) * sb});
  }

  // what a vertex may do: 2 fixed (a corner, or where features meet), 1 slide on a feature, 0 free
  template <class Mesh, class IsFeatureEdge, class IsCorner>
  int constraint(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner) const
  {
    if(is_corner(v)) return 2;
    const std::size_t fd = feature_degree(v, m, is_feature);
    return fd == 0 ? 0 : fd == 2 ? 1 : 2;
  }

  // splits the edge of h at `at` and its (one or two) triangles: the new vertex, of degree 3 or 4
  template <class Mesh>
  static typename boost::graph_traits<Mesh>::vertex_descriptor
  insert_vertex_on_edge(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Point_3& at, Mesh& m)
  {
    const auto g0 = opposite(h, m);
    const auto hnew = CGAL::Euler::split_edge(h, m);   // hnew points to the new vertex, followed by h
    const auto v = target(hnew, m);
    put(get(CGAL::vertex_point, m), v, at);
    for(auto g : {hnew, g0})
      if(!is_border(g, m)) CGAL::Euler::split_face(g, next(next(g, m), m), m);
    return v;
  }

  // the inverse of insert_vertex_on_edge for the edge (a, b): v's four triangles become two (its
  // two become one on a border)
  template <class Mesh>
  static void remove_vertex_on_edge(typename boost::graph_traits<Mesh>::vertex_descriptor v,
                                    typename boost::graph_traits<Mesh>::vertex_descriptor a,
                                    typename boost::graph_traits<Mesh>::vertex_descriptor b, Mesh& m)
  {
    if(is_border(v, m)) {   // (a border edge split: one triangle on each side of v's inner edge)
      auto inner = boost::graph_traits<Mesh>::null_halfedge(), to_a = inner;
      for(auto h : CGAL::halfedges_around_source(v, m)) {
        if(target(h, m) == a) to_a = h;
        else if(target(h, m) != b) inner = h;
      }
      CGAL::Euler::join_face(inner, m);
      CGAL::Euler::join_vertex(to_a, m);   // (v goes, a stays)
      return;
    }
    const auto g = CGAL::Euler::remove_center_vertex(halfedge(v, m), m);
    auto to_a = boost::graph_traits<Mesh>::null_halfedge(), to_b = boost::graph_traits<Mesh>::null_halfedge();
    for(auto x : CGAL::halfedges_around_face(g, m)) {
      if(target(x, m) == a) to_a = x;
      if(target(x, m) == b) to_b = x;
    }
    CGAL::Euler::split_face(to_a, to_b, m);
  }

private:
  const InputMesh& input_;
  double diagonal_ = 0;
  Face_tree faces_;
  // the centroids of the input's faces that cut another of its faces, found the first time a new
  // crossing of the mesh is met (see near_input_crossing)
  mutable bool input_crossings_known_ = false;
  mutable std::vector<Point_3> input_crossings_;
  internal::Feature_curves<GeomTraits> curves_;
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_INTERNAL_RELAXATION_CONTEXT_H
