// Poisson_remesh/Postprocessing/fidelity_insertion.h
//
// (beyond the paper) Fidelity insertions. Objective: the distance to the input. Input points
// (vertices, edge midpoints, triangle centroids) farther than `max_deviation` (times the input's
// bounding-box diagonal) from the mesh -- rims and crests finer than the spacing, cut across by the
// triangles -- are inserted where they are (the nearest triangle split there), at most one per
// triangle and its neighbours; the other way, a triangle or an edge that far from the input takes
// the input point nearest to it, and an edge along a border or a feature curve whose midpoint is
// that far from its curve is split at the curve's point nearest the midpoint (a border or crest
// turning tighter than the spacing). At most `max_insertions_share` of the vertex count per pass,
// farthest first. Constraints: the new vertices are on the input (on the curve for a curve's
// edge); an insertion that would make the mesh cut itself anew is taken back (and tried as an
// edge split instead); no topology change.

#ifndef POISSON_REMESH_POSTPROCESSING_FIDELITY_INSERTION_H
#define POISSON_REMESH_POSTPROCESSING_FIDELITY_INSERTION_H

#include <Poisson_remesh/Postprocessing/internal/near_surface.h>
#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/internal/closest_point.h>
#include <Poisson_remesh/internal/memory_free_order.h>
#include <Poisson_remesh/internal/near_points.h>
#include <Poisson_remesh/internal/parallel.h>
#include <Poisson_remesh/internal/self_intersections.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>
#include <set>
#include <tuple>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {

namespace Postprocessing {

/// The fidelity insertions' settings.
struct Fidelity_settings
{
  /// the tolerance, times the input's bounding-box diagonal; 0 disables the insertions (named
  /// parameter `fidelity_tolerance`)
  double max_deviation = 0.008;
  /// at most this share of the vertex count is inserted in one pass, and as many far edges split (a
  /// mesh much too coarse for its input everywhere is not mended by pinned vertices)
  double max_insertions_share = 0.01;
  /// one more pass after the angle optimization, whose moves may cut a crest again
  bool final_pass = true;
};

/// The input's points that the fidelity insertions measure -- its vertices (those on a face), edge
/// midpoints and face centroids, with the vertices each is made of (by their place among the
/// vertices) -- in a grid of cells of the tolerance, and its triangles around each vertex in a grid
/// of the vertices (together they tell most points of the mesh near the input). The same for every
/// pass on one input and tolerance: built by the first.
template <class InputMesh, class Point_3>
struct Fidelity_input_points
{
  std::vector<Point_3> vertex_points;   ///< the input's vertices on a face
  std::vector<std::pair<Point_3, std::array<std::size_t, 2>>> midpoints;   ///< each edge's midpoint, and its ends among vertex_points
  std::vector<std::pair<Point_3, std::array<std::size_t, 3>>> centroids;   ///< each face's centroid, and its corners among vertex_points
  std::optional<Poisson_remesh::internal::Near_points<Point_3>> near;   ///< all of them, in cells of `tolerance`
  std::optional<internal::Near_surface<Point_3>> near_triangles;   ///< the input's triangles around its vertices
  double tolerance = -1;   ///< the tolerance they were read for (-1: not yet read)

  /** reads them from `input` for the tolerance `tol`, unless they were read for it (their grid
      built on TBB's threads with `ConcurrencyTag` = CGAL::Parallel_tag) */
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  void build(const InputMesh& input, double tol)
  {
    if(near && tolerance == tol) return;
    near.reset();
    near_triangles.reset();   // (valid again only once all of it is read: `tolerance` is set last)
    vertex_points.clear();
    midpoints.clear();
    centroids.clear();
    auto in_vpm = get(CGAL::vertex_point, input);
    auto place = get(CGAL::dynamic_vertex_property_t<std::size_t>(), input);
    for(auto v : vertices(input))
      if(halfedge(v, input) != boost::graph_traits<InputMesh>::null_halfedge()) {
        put(place, v, vertex_points.size());
        vertex_points.push_back(get(in_vpm, v));
      }
    for(auto e : edges(input)) {
      const auto a = source(e, input), b = target(e, input);
      midpoints.push_back({CGAL::midpoint(get(in_vpm, a), get(in_vpm, b)), {{get(place, a), get(place, b)}}});
    }
    for(auto f : faces(input)) {
      const auto h = halfedge(f, input);
      const auto a = source(h, input), b = target(h, input), c = target(next(h, input), input);
      centroids.push_back({CGAL::centroid(get(in_vpm, a), get(in_vpm, b), get(in_vpm, c)), {{get(place, a), get(place, b), get(place, c)}}});
    }
    std::vector<Point_3> all = vertex_points;
    for(const auto& x : midpoints) all.push_back(x.first);
    for(const auto& x : centroids) all.push_back(x.first);
    near.emplace(all, tol, ConcurrencyTag());
    // (the vertices' grid's cell: twice the mean edge length, or the tolerance if larger, so that a
    // point on the input finds its nearest vertex)
    double length = 0;
    for(const auto& x : midpoints) length += std::sqrt(CGAL::to_double(CGAL::squared_distance(vertex_points[x.second[0]], vertex_points[x.second[1]])));
    std::vector<std::array<std::size_t, 3>> triangles;
    for(const auto& x : centroids) triangles.push_back(x.second);
    near_triangles.emplace(vertex_points, std::move(triangles), (std::max)(tol, midpoints.empty() ? 0. : 2 * length / double(midpoints.size())), ConcurrencyTag());
    tolerance = tol;
  }
};

/// One pass of fidelity insertions in `m`; `new_vertex(v, on_curve)` is told each new vertex (true
/// for a split of a border or feature curve's edge); the others are also added to `added` (kept
/// sorted: the caller pins these vertices). The distance queries run on
/// TBB's threads with `ConcurrencyTag` = CGAL::Parallel_tag (`is_feature` is called from one thread;
/// the result is the same in both modes). `input_cache`, when given, keeps the input's points (and
/// their grid) from one pass to the next: the input does not change. Returns the number of
/// vertices inserted.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge, class NewVertex>
std::size_t insert_far_input_points(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, NewVertex new_vertex, const Fidelity_settings& s,
                                    Relaxation_statistics& stats, std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>& added,
                                    Fidelity_input_points<typename Context::Input_mesh, typename Context::Point_3>* input_cache = nullptr)
{
  typedef typename Context::Point_3 Point_3;
  typedef typename Context::Vector_3 Vector_3;
  typedef typename Context::Geom_traits GeomTraits;
  typedef typename Context::Input_mesh InputMesh;
  typedef boost::graph_traits<Mesh> GT;
  typedef typename GT::face_descriptor face_descriptor;
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GeomTraits, Primitive>> Tree;
  auto vpm = get(CGAL::vertex_point, m);
  const double tol = s.max_deviation * ctx.diagonal();
  if(!(tol > 0) || faces(m).empty()) return 0;
  // the mesh's tree, built on first use and before the mesh changes (on a mesh that follows its
  // input, the triangles around the nearest vertex below answer most queries, and often all of them)
  std::optional<Tree> tree_storage;
  auto tree = [&]() -> const Tree& {
    if(!tree_storage) {
      tree_storage.emplace(faces(m).first, faces(m).second, m);
      tree_storage->do_not_accelerate_distance_queries();   // (internal/closest_point.h needs no k-d tree)
      tree_storage->build();
    }
    return *tree_storage;
  };
  // the input's vertices, edge midpoints and face centroids (all on the input: the distance
  // from the input to the mesh peaks inside the input's triangles as often as at its vertices)
  // (the distance queries run in parallel with CGAL::Parallel_tag; their results are taken in
  // in the same order in both modes)
  std::vector<std::pair<double, Point_3>> far;
  std::vector<Point_3> queries;
  std::vector<double> d2s;
  // (a point within the tolerance of a vertex of the mesh, or of a triangle around the vertex
  // nearest to it, is near the mesh: that squared distance is given, a bound at most tol^2, and the
  // tree is not asked; the far points, and their distances, are the same)
  // (the vertices' points, each face's vertices by their places and its centroid, computed on
  // TBB's threads with CGAL::Parallel_tag; the vertices' grid's cell is twice the mean edge length,
  // or the tolerance if larger)
  typedef typename GT::vertex_descriptor vertex_descriptor;
  const std::vector<vertex_descriptor> mesh_vertices(vertices(m).begin(), vertices(m).end());
  const std::vector<face_descriptor> mesh_faces(faces(m).begin(), faces(m).end());
  const std::size_t nv = mesh_vertices.size(), nf = mesh_faces.size();
  auto place = get(CGAL::dynamic_vertex_property_t<std::size_t>(), m);
  std::vector<Point_3> vertex_points(nv), centroids(nf);
  for(std::size_t i = 0; i < nv; ++i) {   // (in sequence: a Polyhedron_3's property map is a hash map)
    put(place, mesh_vertices[i], i);
    vertex_points[i] = get(vpm, mesh_vertices[i]);
  }
  std::vector<std::array<std::size_t, 3>> triangles(nf);
  std::vector<double> perimeters(nf);
  Poisson_remesh::internal::for_each_index<ConcurrencyTag>(nf, [&](std::size_t i) {
    const auto h = halfedge(mesh_faces[i], m);
    const vertex_descriptor a = source(h, m), b = target(h, m), c = target(next(h, m), m);
    triangles[i] = {{get(place, a), get(place, b), get(place, c)}};
    const Point_3 &pa = get(vpm, a), &pb = get(vpm, b), &pc = get(vpm, c);
    centroids[i] = CGAL::centroid(pa, pb, pc);
    perimeters[i] = std::sqrt(CGAL::to_double(CGAL::squared_distance(pa, pb))) + std::sqrt(CGAL::to_double(CGAL::squared_distance(pb, pc))) +
                    std::sqrt(CGAL::to_double(CGAL::squared_distance(pc, pa)));
  }, 1024);
  double mean_edge = 0;
  for(double x : perimeters) mean_edge += x;
  mean_edge /= 3. * double((std::max)(nf, std::size_t(1)));
  const internal::Near_surface<Point_3> near_mesh(std::move(vertex_points), std::move(triangles), (std::max)(tol, 2 * mean_edge), ConcurrencyTag());
  auto distances = [&] {   // (the squared distance from each query point to the mesh, or a bound of it up to tol^2)
    d2s.assign(queries.size(), -1);
    std::atomic<bool> far_from_points(false);
    Poisson_remesh::internal::for_each_index<ConcurrencyTag>(queries.size(), [&](std::size_t i) {
      const double d2 = near_mesh.squared_distance_bound(queries[i], tol * tol);
      if(d2 <= tol * tol) d2s[i] = d2;
      else far_from_points = true;
    });
    if(!far_from_points) return;
    const Tree& t = tree();   // (built here, by this thread)
    Poisson_remesh::internal::for_each_index<ConcurrencyTag>(queries.size(), [&](std::size_t i) {
      if(d2s[i] < 0) d2s[i] = Poisson_remesh::internal::squared_distance_to(t, queries[i]);
    });
  };
  auto take_far = [&] {
    for(std::size_t i = 0; i < queries.size(); ++i)
      if(d2s[i] > tol * tol) far.push_back({d2s[i], queries[i]});
  };
  // the input's points, read once for all the passes of a relaxation (`input_cache`)
  Fidelity_input_points<InputMesh, Point_3> own_points;
  Fidelity_input_points<InputMesh, Point_3>& on_input = input_cache != nullptr ? *input_cache : own_points;
  on_input.template build<ConcurrencyTag>(ctx.input(), tol);
  // (the distance is 1-Lipschitz: a midpoint or centroid within tol of the mesh by way of one
  // of its vertices is not queried)
  std::vector<double> vertex_distance(on_input.vertex_points.size());
  queries = on_input.vertex_points;
  distances();
  take_far();
  for(std::size_t i = 0; i < vertex_distance.size(); ++i) vertex_distance[i] = std::sqrt(d2s[i]);
  auto near_by_way_of = [&](const Point_3& x, std::size_t i) {
    return vertex_distance[i] + std::sqrt(CGAL::to_double(CGAL::squared_distance(x, on_input.vertex_points[i]))) <= tol;
  };
  queries.clear();
  for(const auto& [x, ends] : on_input.midpoints)
    if(!near_by_way_of(x, ends[0]) && !near_by_way_of(x, ends[1])) queries.push_back(x);
  distances();
  take_far();
  queries.clear();
  for(const auto& [x, corners] : on_input.centroids)
    if(!near_by_way_of(x, corners[0]) && !near_by_way_of(x, corners[1]) && !near_by_way_of(x, corners[2])) queries.push_back(x);
  distances();
  take_far();
  // and the other way: a triangle of the mesh whose centroid is far from the input (it spans a
  // groove) takes the input's point nearest to it; an edge whose midpoint is, is split there
  // (for each (c, hint) of `points`, the input point nearest c and its squared distance to c,
  // in the order of `points`, in parallel with CGAL::Parallel_tag; the search starts from `hint`,
  // a vertex of the mesh: on the input, and near c)
  // (a point within the tolerance of a point of the input -- one of its vertices, edge midpoints
  // and triangle centroids listed above, queried or not -- or of a triangle of the input around the
  // input's vertex nearest to it (Near_surface) is near the input: its squared distance is given as
  // tol^2, a bound, and it is not projected)
  const Poisson_remesh::internal::Near_points<Point_3>& near_input = *on_input.near;
  const internal::Near_surface<Point_3>& near_input_triangles = *on_input.near_triangles;
  auto nearest_on_input = [&](const std::vector<std::pair<Point_3, Point_3>>& points) {
    std::vector<std::pair<double, Point_3>> nearest(points.size());
    Poisson_remesh::internal::for_each_index<ConcurrencyTag>(points.size(), [&](std::size_t i) {
      if(near_input_triangles.squared_distance_bound(points[i].first, tol * tol) <= tol * tol || near_input.within(points[i].first, tol)) { nearest[i] = {tol * tol, points[i].second}; return; }
      const Point_3 p = ctx.project_on_surface(points[i].first, points[i].second);
      nearest[i] = {CGAL::to_double(CGAL::squared_distance(points[i].first, p)), p};
    });
    return nearest;
  };
  // (the mesh's vertices are on the input, and the distance is 1-Lipschitz: a centroid or
  // midpoint within the tolerance of one of its vertices, with a margin for the vertices' own
  // rounding, is not queried)
  const double near_vertex = 0.999 * tol;
  std::vector<std::pair<Point_3, Point_3>> points;   // (the point, and a vertex of the mesh near it)
  {
    // (whether each face's centroid is far from its three vertices, on TBB's threads)
    std::vector<std::int8_t> far_from_corners(mesh_faces.size());
    Poisson_remesh::internal::for_each_index<ConcurrencyTag>(mesh_faces.size(), [&](std::size_t i) {
      const auto h = halfedge(mesh_faces[i], m);
      const Point_3 &a = get(vpm, source(h, m)), &b = get(vpm, target(h, m)), &c = get(vpm, target(next(h, m), m));
      const Point_3& x = centroids[i];
      const double d2 = std::min({CGAL::to_double(CGAL::squared_distance(x, a)), CGAL::to_double(CGAL::squared_distance(x, b)),
                                  CGAL::to_double(CGAL::squared_distance(x, c))});
      far_from_corners[i] = d2 > near_vertex * near_vertex ? 1 : 0;
    }, 1024);
    for(std::size_t i = 0; i < mesh_faces.size(); ++i)
      if(far_from_corners[i]) points.push_back({centroids[i], get(vpm, source(halfedge(mesh_faces[i], m), m))});
  }
  for(const auto& [d2, p] : nearest_on_input(points))
    // (not when that input point is near the mesh elsewhere: the other side of a thin part)
    if(d2 > tol * tol && Poisson_remesh::internal::squared_distance_to(tree(), p) > tol * tol) far.push_back({d2, p});
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  // (the split point, the edge's ends, and whether the edge follows a feature curve or a border)
  std::vector<std::tuple<double, Point_3, vertex_descriptor, vertex_descriptor, bool>> far_edges;
  std::vector<halfedge_descriptor> hs;
  points.clear();
  for(auto e : edges(m)) {
    halfedge_descriptor h = halfedge(e, m);
    const Point_3 x = CGAL::midpoint(get(vpm, source(h, m)), get(vpm, target(h, m)));
    if(CGAL::to_double(CGAL::squared_distance(x, get(vpm, source(h, m)))) <= near_vertex * near_vertex) continue;
    if(is_border_edge(h, m) || is_feature(e)) {
      // an edge along a border or a feature curve is a chord of that curve: where the chord is
      // farther than the tolerance from the curve (a border or crest that turns tighter than the
      // spacing), the edge is split at the curve's point nearest its midpoint, which stays on
      // the curve (within half the edge's length of the midpoint, and not within a quarter of it
      // of either end: a point past an end belongs to the next chord, or to another curve)
      const double max_offset = 0.5, min_end_distance = 0.25;   // (times the edge's length)
      if(is_border(h, m)) h = opposite(h, m);   // (the halfedge in a triangle)
      const Point_3 q = ctx.project_on_features(x, get(vpm, source(h, m)));
      const double d2 = CGAL::to_double(CGAL::squared_distance(x, q));
      const double l2 = CGAL::to_double(CGAL::squared_distance(get(vpm, source(h, m)), get(vpm, target(h, m))));
      const double end2 = CGAL::square(min_end_distance) * l2;
      if(d2 > tol * tol && d2 <= CGAL::square(max_offset) * l2 && CGAL::to_double(CGAL::squared_distance(q, get(vpm, source(h, m)))) >= end2 &&
         CGAL::to_double(CGAL::squared_distance(q, get(vpm, target(h, m)))) >= end2)
        far_edges.push_back({d2, q, source(h, m), target(h, m), true});
      continue;
    }
    hs.push_back(h);
    points.push_back({x, get(vpm, source(h, m))});
  }
  const auto nearest = nearest_on_input(points);
  for(std::size_t i = 0; i < hs.size(); ++i)
    if(nearest[i].first > tol * tol) far_edges.push_back({nearest[i].first, nearest[i].second, source(hs[i], m), target(hs[i], m), false});
  if(far.empty() && far_edges.empty()) return 0;
  std::sort(far.begin(), far.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if(!far.empty()) tree();   // (the tree of the mesh as it is now: the insertions below change it)
  std::set<face_descriptor> touched;
  std::vector<vertex_descriptor> mine;
  std::size_t done = 0;
  const std::size_t cap = std::max<std::size_t>(1, std::size_t(s.max_insertions_share * double(num_vertices(m))));
  // the intersections there already that the check after the insertions asks about, found before
  // each insertion: the pairs of the triangle it splits, as it is, with the faces whose boxes meet
  // that triangle's box grown to hold its point (the box of the three triangles it becomes). The
  // faces the insertions before it split are left out (the tree still holds them, reading their
  // new triangles; such a pair was found when the first of the two was split), and the faces they
  // made are not in the tree. The check takes a pair for new unless it is here, but only takes back
  // the new vertices of its faces: a pair that holds one holds a split triangle, whose pairs from
  // before the insertions are all here (no search of the whole mesh). The rule of
  // internal/self_intersections.h: a flat triangle is a pair with itself and meets no other; two
  // others whose boxes meet, by the exact test.
  typedef std::decay_t<decltype(Poisson_remesh::internal::intersecting_pairs(m))> Pairs;
  Pairs before;
  std::vector<face_descriptor> split, around;
  auto flat = [&](face_descriptor g) {
    const auto h = halfedge(g, m);
    return CGAL::collinear(get(vpm, source(h, m)), get(vpm, target(h, m)), get(vpm, target(next(h, m), m)));
  };
  for(const auto& fp : far) {
    if(mine.size() >= cap) break;
    const face_descriptor f = Poisson_remesh::internal::closest_point_and_primitive(tree(), fp.second).second;
    if(touched.count(f)) continue;
    // the triangle and its neighbours take one new vertex at most
    touched.insert(f);
    for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m))
      if(!is_border(opposite(h, m), m)) touched.insert(face(opposite(h, m), m));
    if(flat(f)) before.emplace_back(f, f);
    else {
      const CGAL::Bbox_3 box = Poisson_remesh::internal::face_box(f, m);
      around.clear();
      Poisson_remesh::internal::primitives_meeting_box(tree(), box + fp.second.bbox(), std::back_inserter(around));
      for(face_descriptor g : around)
        if(g != f && !std::binary_search(split.begin(), split.end(), g) && !flat(g) && CGAL::do_overlap(box, Poisson_remesh::internal::face_box(g, m)) &&
           Poisson_remesh::internal::self_intersection_detail::faces_intersect(f, g, m, vpm))
          before.emplace_back((std::min)(f, g), (std::max)(f, g));
    }
    split.insert(std::upper_bound(split.begin(), split.end(), f), f);
    const auto hnew = CGAL::Euler::add_center_vertex(halfedge(f, m), m);
    const auto v = target(hnew, m);
    put(vpm, v, fp.second);
    mine.push_back(v);
  }
  std::sort(before.begin(), before.end());
  before.erase(std::unique(before.begin(), before.end()), before.end());
  // an insertion that makes the mesh cut itself is taken back (its vertex still has degree 3)
  std::sort(mine.begin(), mine.end());
  std::vector<vertex_descriptor> undo;
  const auto now = Poisson_remesh::internal::intersecting_pairs_near(m, Poisson_remesh::internal::faces_around(m, mine));
  // (a mesh that cuts itself everywhere there is left as it was: the search stops at twice the
  // face count and could miss a new intersection)
  if(now.size() > num_faces(m)) {
    for(vertex_descriptor v : mine) CGAL::Euler::remove_center_vertex(halfedge(v, m), m);
    return 0;
  }
  ctx.for_vertices_of_pairs_not_in(m, now, before, [&](vertex_descriptor x) {
    if(std::binary_search(mine.begin(), mine.end(), x)) undo.push_back(x);
  });
  // (the retries below split edges one after the other, each seeing the splits before it: they
  // run in an order that does not depend on where the vertices lie in memory)
  const Poisson_remesh::internal::Memory_free_order<Mesh> order(m);
  std::sort(undo.begin(), undo.end(), order);
  undo.erase(std::unique(undo.begin(), undo.end()), undo.end());
  std::vector<std::pair<Point_3, typename GT::halfedge_descriptor>> retry;   // (a halfedge of the triangle it was in)
  for(vertex_descriptor v : undo) {
    const Point_3 p = get(vpm, v);
    retry.push_back({p, CGAL::Euler::remove_center_vertex(halfedge(v, m), m)});
  }
  std::sort(undo.begin(), undo.end());   // (removed: compared as descriptors alone from here)
  for(vertex_descriptor v : mine)
    if(!std::binary_search(undo.begin(), undo.end(), v)) {
      new_vertex(v, false);
      added.push_back(v);
      ++done;
    }
  // a split of an edge of `order` at p (the first that works) is kept if it makes the mesh cut
  // itself nowhere new and turns no triangle by more than acos(min_cos) from both old ones
  // (`on_curve`: the edge follows a border or a feature curve, and so does the new vertex; x is
  // then the edge's halfedge in a triangle)
  const double flat_angle = 1e-6;   // radians: a face with no larger angle is a segment to rounding
  auto try_split = [&](const Point_3& p, const std::vector<std::pair<double, halfedge_descriptor>>& order, double min_cos, bool on_curve) {
    for(const auto& candidate : order) {
      const auto x = candidate.second;
      const vertex_descriptor a = source(x, m), b = target(x, m);
      const bool one_side = is_border(opposite(x, m), m);
      const Vector_3 n1 = ctx.normal(get(vpm, a), get(vpm, b), get(vpm, target(next(x, m), m)));
      const Vector_3 n2 = one_side ? n1 : ctx.normal(get(vpm, b), get(vpm, a), get(vpm, target(next(opposite(x, m), m), m)));
      const vertex_descriptor v = ctx.insert_vertex_on_edge(x, p, m);
      bool ok = true;
      for(auto h : CGAL::halfedges_around_target(v, m)) {
        if(is_border(h, m)) continue;
        const Vector_3 n = ctx.normal(get(vpm, source(h, m)), p, get(vpm, target(next(h, m), m)));
        ok = ok && (ctx.cos_between(n, n1) >= min_cos || ctx.cos_between(n, n2) >= min_cos);
        // nor a flat face: the new point on the line of a face's other two vertices (a curve's
        // point on the straight input edge between an end of the edge and the opposite vertex),
        // which no later move along the curve can open (the rounding of the normal's direction
        // let it through the test above)
        ok = ok && ctx.min_angle(get(vpm, source(h, m)), p, get(vpm, target(next(h, m), m))) > flat_angle;
      }
      // (every crossing of a triangle at v is new; `before` is not used here: its face indices
      // may have been recycled by the removals above)
      if(ok)
        ctx.for_vertices_of_new_intersections(m, decltype(before)(), Poisson_remesh::internal::faces_around(m, std::vector<vertex_descriptor>(1, v)),
                                          [&](vertex_descriptor y) { if(y == v) ok = false; });
      if(!ok) { ctx.remove_vertex_on_edge(v, a, b, m); continue; }
      new_vertex(v, on_curve);
      // (a vertex on a curve is not pinned: it slides along the curve like the feature samples,
      // and stays on it)
      if(!on_curve) added.push_back(v);
      ++done;
      return true;
    }
    return false;
  };
  // one taken back splits an edge of that triangle instead, the nearest edge first (not a
  // feature edge: it would lose its feature), turning a triangle by 75 degrees at most: it
  // follows the input there (a protrusion thinner than the spacing turns that much)
  for(const auto& [p, g] : retry) {
    std::vector<std::pair<double, halfedge_descriptor>> order;
    for(auto x : CGAL::halfedges_around_face(g, m)) {
      if(is_border(opposite(x, m), m) || is_feature(edge(x, m))) continue;
      order.push_back({CGAL::to_double(CGAL::squared_distance(p, typename GeomTraits::Segment_3(get(vpm, source(x, m)), get(vpm, target(x, m))))), x});
    }
    std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    try_split(p, order, 0.26, false);
  }
  // the edges far from the input (those still in the mesh), each triangle split once at most,
  // turning a triangle by 60 degrees at most (the limit of ctx.folds())
  std::sort(far_edges.begin(), far_edges.end(), [](const auto& x, const auto& y) { return std::get<0>(x) > std::get<0>(y); });
  std::set<vertex_descriptor> split_near;
  std::size_t edge_splits = 0;
  for(const auto& [d2, p, a, b, on_curve] : far_edges) {
    if(edge_splits >= cap) break;
    const auto [h, exists] = halfedge(a, b, m);
    if(!exists || split_near.count(a) || split_near.count(b)) continue;
    for(auto x : {h, opposite(h, m)})
      if(!is_border(x, m))
        for(vertex_descriptor y : CGAL::vertices_around_face(x, m)) split_near.insert(y);
    if(try_split(p, std::vector<std::pair<double, halfedge_descriptor>>(1, {d2, h}), 0.5, on_curve)) ++edge_splits;
  }
  std::sort(added.begin(), added.end());   // (the caller looks its pinned vertices up)
  stats.fidelity_insertions += done;
  return done;
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_FIDELITY_INSERTION_H
