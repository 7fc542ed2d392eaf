// The relaxation's operators beyond the paper (include/Poisson_remesh/Postprocessing/), one test
// each on a small constructed mesh that shows what the operator is for: the flaw is built in, the
// operator is run alone (directly, or through Lloyd_relaxer::relax() with every other step off),
// and its objective must improve under the shared constraints (topology kept, every vertex on the
// input, no fold). The same run with the operator switched off leaves the flaw, so each test fails
// without its operator. The judge (angles, valences, distances) is computed here, apart from the
// library's own predicates.
#include "analytic_meshes.h"
#include "test_support.h"

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Postprocessing/internal/near_surface.h>
#include <Poisson_remesh/Relaxation/Lloyd_relaxer.h>
#include <Poisson_remesh/internal/closest_point.h>
#include <Poisson_remesh/internal/near_points.h>
#include <Poisson_remesh/internal/radix_sort.h>
#include <Poisson_remesh/internal/vector_angle.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index V;
namespace PR = Poisson_remesh;
namespace P = Poisson_remesh::Postprocessing;
typedef PR::internal::Relaxation_context<Mesh, K> Context;

namespace {

// ---- the judge --------------------------------------------------------------------------------

double angle_deg(const Point& o, const Point& a, const Point& b)
{
  const double ux = a.x() - o.x(), uy = a.y() - o.y(), uz = a.z() - o.z();
  const double wx = b.x() - o.x(), wy = b.y() - o.y(), wz = b.z() - o.z();
  const double dot = ux * wx + uy * wy + uz * wz;
  const double lu = std::sqrt(ux * ux + uy * uy + uz * uz), lw = std::sqrt(wx * wx + wy * wy + wz * wz);
  return std::acos(std::max(-1.0, std::min(1.0, dot / (lu * lw)))) * 180 / CGAL_PI;
}

std::array<Point, 3> corners(Mesh::Face_index f, const Mesh& m)
{
  const auto h = halfedge(f, m);
  return {m.point(source(h, m)), m.point(target(h, m)), m.point(target(next(h, m), m))};
}

double smallest_angle(Mesh::Face_index f, const Mesh& m)
{
  const auto p = corners(f, m);
  return std::min({angle_deg(p[0], p[1], p[2]), angle_deg(p[1], p[2], p[0]), angle_deg(p[2], p[0], p[1])});
}

double min_angle(const Mesh& m)
{
  double a = 180;
  for(auto f : faces(m)) a = std::min(a, smallest_angle(f, m));
  return a;
}

std::size_t count_below(const Mesh& m, double degrees)
{
  std::size_t n = 0;
  for(auto f : faces(m)) if(smallest_angle(f, m) < degrees) ++n;
  return n;
}

std::size_t irregular(const Mesh& m)
{
  std::size_t n = 0;
  for(auto v : vertices(m)) if(degree(v, m) != (is_border(v, m) ? 4u : 6u)) ++n;
  return n;
}

// V - E + F and the number of border edges: what the operators may not change (a plane patch
// keeps one border; its length in edges may grow by splits)
long euler_characteristic(const Mesh& m)
{
  return long(std::distance(vertices(m).begin(), vertices(m).end())) - long(std::distance(edges(m).begin(), edges(m).end())) +
         long(std::distance(faces(m).begin(), faces(m).end()));
}

std::size_t border_cycles(const Mesh& m)
{
  std::vector<Mesh::Halfedge_index> cycles;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(cycles));
  return cycles.size();
}

// every face of a mesh of the plane z = 0 keeps its upward orientation (no fold)
bool no_fold_in_plane(const Mesh& m)
{
  for(auto f : faces(m)) {
    const auto p = corners(f, m);
    const double nz = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
    if(!(nz > 0)) return false;
  }
  return true;
}

// the largest distance from a point of `points` to the surface of `m`
double farthest(const std::vector<Point>& points, const Mesh& m)
{
  CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> tree(faces(m).first, faces(m).second, m);
  double d = 0;
  for(const Point& p : points) d = std::max(d, std::sqrt(tree.squared_distance(p)));
  return d;
}

// ---- the constructions -------------------------------------------------------------------------

// a regular grid of the unit square (right triangles, interior valence 6 on a grid split one way)
Mesh square(std::size_t n)
{
  analytic::Soup s;
  for(std::size_t j = 0; j <= n; ++j)
    for(std::size_t i = 0; i <= n; ++i) s.points.push_back({double(i) / double(n), double(j) / double(n), 0});
  auto id = [&](std::size_t i, std::size_t j) { return j * (n + 1) + i; };
  for(std::size_t j = 0; j < n; ++j)
    for(std::size_t i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s.to_mesh<Mesh>();
}

// the input of the tests that relax a piece of the plane: a square of n x n cells, its features
// and the relaxer on them (which keeps references to both: not copied)
struct Square_input
{
  Mesh in;
  PR::Feature_set<Mesh> features;
  PR::Lloyd_relaxer<Mesh, K> relaxer;
  explicit Square_input(std::size_t n) : in(square(n)), features(PR::detect_features(in)), relaxer(in, features) {}
  Square_input(const Square_input&) = delete;
  Square_input& operator=(const Square_input&) = delete;
};

V vertex_at(const Mesh& m, double x, double y)
{
  V best = *vertices(m).begin();
  for(V v : vertices(m))
    if(CGAL::squared_distance(m.point(v), Point(x, y, 0)) < CGAL::squared_distance(m.point(best), Point(x, y, 0))) best = v;
  return best;
}

auto no_feature = [](Mesh::Edge_index) { return false; };

// relax() with the paper's rounds and every operator off (each test turns its own on)
PR::Relaxation_settings nothing_but_the_last_lloyd_pass()
{
  PR::Relaxation_settings s;
  s.iterations = 0;
  s.delaunay_flips = s.valence_flips = false;
  s.lloyd_guard.min_angle = 0;
  s.sliver_collapse.enabled = false;
  s.fidelity.max_deviation = 0;
  s.angle_smoothing.rounds = 0;
  s.regularity.rounds = 0;
  s.regularity.final_min_angle = 0;
  s.angle_optimization.rounds = 0;
  s.refinement.rounds = 0;
  s.untangling.rounds = 0;
  s.local_repair.rounds = 0;
  return s;
}

// relax() with the fidelity insertions alone (`on`; no final pass), at most `share` of the vertex
// count inserted per pass, or with nothing
PR::Relaxation_settings fidelity_alone(bool on, double share)
{
  PR::Relaxation_settings s = nothing_but_the_last_lloyd_pass();
  if(on) {
    s.fidelity.max_deviation = 0.008;
    s.fidelity.max_insertions_share = share;
    s.fidelity.final_pass = false;
  }
  return s;
}

struct Counting_new_vertex
{
  std::vector<std::pair<V, bool>>* added;
  void operator()(V v, bool on_feature) const { added->push_back({v, on_feature}); }
};

// the fidelity tests' input: a square with a narrow ridge along x = 1/2, a Gaussian 0.1 high and
// 0.03 wide (its height at x), and a mesh's points lifted onto it
double ridge(double x) { return 0.1 * std::exp(-(x - 0.5) * (x - 0.5) / (2 * 0.03 * 0.03)); }
Mesh on_ridge(Mesh x)
{
  for(V v : vertices(x)) x.point(v) = Point(x.point(v).x(), x.point(v).y(), ridge(x.point(v).x()));
  return x;
}

} // namespace

TEST_CASE("sliver collapse: a sliver between two pinned vertices closer than the spacing goes", "[operators][collapse]")
{
  const Square_input plane(20);
  for(bool on : {false, true}) {
    INFO("sliver collapse " << (on ? "on" : "off"));
    Mesh m = square(6);
    // an interior vertex pushed next to its neighbour: slivers and a crowded star; every vertex
    // is pinned (a corner), so that no move can mend them
    const V v = vertex_at(m, 3.0 / 6, 3.0 / 6), u = vertex_at(m, 4.0 / 6, 3.0 / 6);
    m.point(v) = Point(m.point(u).x() - 0.01, m.point(u).y() + 0.002, 0);
    const std::size_t slivers = count_below(m, 30);
    const double worst = min_angle(m);
    REQUIRE(slivers >= 2);
    const long chi = euler_characteristic(m);
    PR::Relaxation_settings s = nothing_but_the_last_lloyd_pass();
    s.sliver_collapse.enabled = on;
    REQUIRE(no_fold_in_plane(m));
    const auto stats = plane.relaxer.relax(m, no_feature, [](V) { return true; }, s);
    m.collect_garbage();
    CHECK(euler_characteristic(m) == chi);
    CHECK(border_cycles(m) == 1);
    CHECK(no_fold_in_plane(m));
    for(V x : vertices(m)) CHECK(std::abs(m.point(x).z()) < 1e-12);
    if(on) {
      CHECK(stats.collapses >= 1);
      CHECK(count_below(m, 30) < slivers);
      CHECK(min_angle(m) > worst + 10);
    } else {
      CHECK(stats.collapses == 0);
      CHECK(count_below(m, 30) == slivers);
    }
  }
}

TEST_CASE("Lloyd guard: a Lloyd move that would make a triangle sharper than the guard's angle goes half the way", "[operators][guard]")
{
  // a free vertex whose ring is lopsided (two neighbours pushed towards it, all else fixed): its
  // Lloyd target -- the area-weighted centroid of its triangles' centroids -- lies where one of its
  // triangles would have a smallest angle of 19.2 degrees, against 30.0 now; half the way, 25.1
  const Square_input plane(24);
  for(bool on : {false, true}) {
    INFO("Lloyd guard " << (on ? "on" : "off"));
    Mesh m = square(6);
    const V v = vertex_at(m, 3.0 / 6, 3.0 / 6);
    m.point(vertex_at(m, 4.0 / 6, 3.0 / 6)) = Point(3.92 / 6, 3.13 / 6, 0);
    m.point(vertex_at(m, 4.0 / 6, 4.0 / 6)) = Point(4.15 / 6, 3.63 / 6, 0);
    m.point(v) = Point(3.21 / 6, 3.31 / 6, 0);
    REQUIRE(no_fold_in_plane(m));
    auto star_min = [&] {
      double worst = 180;
      for(auto h : CGAL::halfedges_around_target(v, m)) worst = std::min(worst, smallest_angle(face(h, m), m));
      return worst;
    };
    const Point start = m.point(v);
    REQUIRE(star_min() > 29.9);
    PR::Relaxation_settings s = nothing_but_the_last_lloyd_pass();
    if(on) s.lloyd_guard = P::Lloyd_guard_settings();
    REQUIRE((!on || s.lloyd_guard.min_angle == 25));
    plane.relaxer.relax(m, no_feature, [&](V x) { return x != v; }, s);
    CHECK(m.point(v) != start);
    CHECK(std::abs(m.point(v).z()) < 1e-12);
    CHECK(no_fold_in_plane(m));
    if(on) CHECK(star_min() >= 25);
    else CHECK(star_min() < 20);
  }
}

TEST_CASE("fidelity insertions: a crest finer than the spacing, cut across by the mesh, is put back", "[operators][fidelity]")
{
  // the input: a square with a narrow ridge along x = 1/2; the mesh: a coarse grid of points of
  // the input whose grid lines miss the ridge, so that its triangles cut across it
  const std::size_t fine = 42, coarse = 7;
  const Mesh in = on_ridge(square(fine));
  std::vector<Point> input_points;
  for(V v : vertices(in)) input_points.push_back(in.point(v));
  const auto features = PR::detect_features(in, PR::parameters::feature_policy(PR::Feature_policy::none));
  PR::Lloyd_relaxer<Mesh, K> relaxer(in, features);
  for(bool on : {false, true}) {
    INFO("fidelity insertions " << (on ? "on" : "off"));
    Mesh m = on_ridge(square(coarse));
    const double before = farthest(input_points, m);
    REQUIRE(before > 0.05);   // the crest is missed by about its height
    const long chi = euler_characteristic(m);
    const PR::Relaxation_settings s = fidelity_alone(on, 0.25);
    std::vector<std::pair<V, bool>> added;
    std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> crossings;
    relaxer.relax(m, no_feature, [](V) { return true; }, s, Counting_new_vertex{&added});
    m.collect_garbage();
    CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(crossings));
    CHECK(crossings.empty());
    CHECK(euler_characteristic(m) == chi);
    CHECK(border_cycles(m) == 1);
    const double after = farthest(input_points, m);
    if(on) {
      CHECK(!added.empty());
      // the inserted points are the input's own
      CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> input_tree(faces(in).first, faces(in).second, in);
      for(V x : vertices(m)) CHECK(std::sqrt(input_tree.squared_distance(m.point(x))) < 1e-9);
      CHECK(after < 0.5 * before);
    } else {
      CHECK(added.empty());
      CHECK(after == Approx(before));
    }
  }
}

// The fidelity insertions look for the crossings already there near each insertion only, not in
// the whole mesh: a crossing next to an insertion -- in a face beside the one it splits -- is
// there before and after, and must take back nothing. The mesh of the crest test above, once as
// it is and once with a small triangle standing through a face beside one that an insertion
// splits: an insertion into that face kept, and no crossing but the standing triangle's.
TEST_CASE("fidelity insertions: a crossing already there beside an insertion takes nothing back", "[operators][fidelity][intersections]")
{
  const std::size_t fine = 42, coarse = 7;
  const Mesh in = on_ridge(square(fine));
  const auto features = PR::detect_features(in, PR::parameters::feature_policy(PR::Feature_policy::none));
  const Context ctx(in, features);
  P::Fidelity_settings s;
  s.max_insertions_share = 0.25;
  auto insert = [&](Mesh& m) {   // (one pass: the points inserted, sorted)
    std::vector<V> added;
    PR::Relaxation_statistics stats;
    P::insert_far_input_points(ctx, m, no_feature, [](V, bool) {}, s, stats, added);
    std::vector<Point> points;
    for(V x : added) points.push_back(m.point(x));
    std::sort(points.begin(), points.end());
    return points;
  };
  Mesh plain = on_ridge(square(coarse));
  const std::vector<Point> alone = insert(plain);
  REQUIRE(alone.size() >= 4);
  // the face of the coarse mesh under a point inserted on the crest (the least of them in the
  // points' order), and a face beside it away from the crest
  Mesh m = on_ridge(square(coarse));
  const auto on_crest = std::find_if(alone.begin(), alone.end(), [](const Point& p) { return p.z() > 0.09; });
  REQUIRE(on_crest != alone.end());
  const Point p = *on_crest;
  auto corners = [&](Mesh::Face_index f) {
    std::vector<Point> c;
    for(V v : vertices_around_face(halfedge(f, m), m)) c.push_back(m.point(v));
    return c;
  };
  auto over = [&](Mesh::Face_index f, const Point& q) {   // (q's projection on z = 0 lies in f's)
    const auto c = corners(f);
    auto side = [&](const Point& a, const Point& b) { return (b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x()); };
    return side(c[0], c[1]) >= 0 && side(c[1], c[2]) >= 0 && side(c[2], c[0]) >= 0;
  };
  Mesh::Face_index under = Mesh::null_face();
  for(auto f : faces(m))
    if(over(f, p)) under = f;
  REQUIRE(under != Mesh::null_face());
  std::vector<Point> under_corners = corners(under);
  std::sort(under_corners.begin(), under_corners.end());
  // the face beside it across its edge parallel to the crest (at x = ex; beside it, z depends on x alone)
  Mesh::Face_index beside = Mesh::null_face();
  double ex = 0, yc = 0, sx = 0;
  for(auto h : halfedges_around_face(halfedge(under, m), m)) {
    const Point &s0 = m.point(source(h, m)), &t0 = m.point(target(h, m));
    if(is_border(opposite(h, m), m) || s0.x() != t0.x()) continue;
    beside = face(opposite(h, m), m);
    ex = s0.x();
    yc = 0.5 * (s0.y() + t0.y());
    sx = m.point(target(next(opposite(h, m), m), m)).x() > ex ? 1 : -1;
  }
  REQUIRE(beside != Mesh::null_face());
  // the standing triangle: through the face beside, 0.02 from the edge, and leaning over the face
  // under the insertion without meeting it (at a height of 0.024 over the edge, which is at 0.006):
  // its box meets that face's, so the check after the insertions meets it too
  const double t = 0.02 * double(coarse), zb = (1 - t) * ridge(ex) + t * ridge(ex + sx / double(coarse));
  const V a = m.add_vertex(Point(ex + sx * 0.02, yc, zb - 0.004));
  const V b = m.add_vertex(Point(ex + sx * 0.02, yc + 0.005, zb + 0.004));
  const V c = m.add_vertex(Point(ex - sx * 0.005, yc, 0.03));
  const Mesh::Face_index standing = m.add_face(a, b, c);
  REQUIRE(standing != Mesh::null_face());
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> crossings;
  CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(crossings));
  REQUIRE(crossings.size() == 1);
  REQUIRE((crossings[0].first == beside || crossings[0].second == beside));
  const std::vector<Point> with_crossing = insert(m);
  // an insertion on the crest into the face beside it is kept: a new vertex of degree 3 joined to
  // that face's three vertices (which of the crest's equally far points it is may change: their
  // distances to the mesh, read in a tree that holds one more triangle, may differ in the last bit,
  // and so their order; the test takes it that one of them still goes to that face, the one
  // nearest below it, rather than to a face beside it, which one insertion per face and neighbours
  // would then bar)
  bool kept = false;
  for(V v : vertices(m)) {
    if(!(m.point(v).z() > 0.09) || std::find(with_crossing.begin(), with_crossing.end(), m.point(v)) == with_crossing.end()) continue;
    std::vector<Point> around;
    for(V w : vertices_around_target(halfedge(v, m), m)) around.push_back(m.point(w));
    std::sort(around.begin(), around.end());
    kept = kept || around == under_corners;
  }
  CHECK(kept);
  crossings.clear();
  CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(crossings));
  CHECK(crossings.size() == 1);
  for(const auto& [f, g] : crossings) CHECK((f == standing || g == standing));
}

TEST_CASE("fidelity insertions: a border that turns tighter than the spacing gets vertices on its curve", "[operators][fidelity]")
{
  // the input: a flat disk whose border is a fine polygon (96 sides); the mesh: a hexagon fan of
  // points of that border, whose border edges are chords 0.13 radii inside the input's border
  const std::size_t sides = 96, rings = 8;
  analytic::Soup fine;
  fine.points.push_back({0, 0, 0});
  for(std::size_t r = 1; r <= rings; ++r)
    for(std::size_t k = 0; k < sides; ++k) {
      const double t = 2 * CGAL_PI * double(k) / double(sides), rho = double(r) / double(rings);
      fine.points.push_back({rho * std::cos(t), rho * std::sin(t), 0});
    }
  auto id = [&](std::size_t r, std::size_t k) { return r == 0 ? std::size_t(0) : 1 + (r - 1) * sides + k % sides; };
  for(std::size_t k = 0; k < sides; ++k) fine.triangles.push_back({id(0, 0), id(1, k), id(1, k + 1)});
  for(std::size_t r = 1; r < rings; ++r)
    for(std::size_t k = 0; k < sides; ++k) fine.quad(id(r, k), id(r + 1, k), id(r + 1, k + 1), id(r, k + 1));
  const Mesh in = fine.to_mesh<Mesh>();
  REQUIRE(border_cycles(in) == 1);
  std::vector<Point> rim;   // the input's border vertices
  for(std::size_t k = 0; k < sides; ++k) rim.push_back(Point(fine.points[id(rings, k)][0], fine.points[id(rings, k)][1], 0));
  // the distance from p to the input's border polygon (the judge's own segment distance)
  auto to_rim = [&](const Point& p) {
    double d = std::numeric_limits<double>::infinity();
    for(std::size_t k = 0; k < sides; ++k) d = std::min(d, std::sqrt(CGAL::squared_distance(p, K::Segment_3(rim[k], rim[(k + 1) % sides]))));
    return d;
  };
  const auto features = PR::detect_features(in);
  PR::Lloyd_relaxer<Mesh, K> relaxer(in, features);
  for(bool on : {false, true}) {
    INFO("fidelity insertions " << (on ? "on" : "off"));
    analytic::Soup coarse;
    coarse.points.push_back({0, 0, 0});
    for(std::size_t k = 0; k < 6; ++k) coarse.points.push_back(fine.points[id(rings, k * sides / 6)]);
    for(std::size_t k = 0; k < 6; ++k) coarse.triangles.push_back({0, 1 + k, 1 + (k + 1) % 6});
    Mesh m = coarse.to_mesh<Mesh>();
    const double before = farthest(rim, m);
    REQUIRE(before > 0.12);   // 1 - cos(30 degrees) at the chords' middles
    const long chi = euler_characteristic(m);
    const PR::Relaxation_settings s = fidelity_alone(on, 1);
    std::vector<std::pair<V, bool>> added;
    relaxer.relax(m, no_feature, [](V) { return true; }, s, Counting_new_vertex{&added});
    m.collect_garbage();
    CHECK(euler_characteristic(m) == chi);
    CHECK(border_cycles(m) == 1);
    CHECK(no_fold_in_plane(m));
    const double after = farthest(rim, m);
    if(on) {
      // new border vertices, on the input's border, and the border follows it more closely
      REQUIRE(!added.empty());
      std::size_t on_rim = 0;
      for(const auto& [v, on_feature] : added) {
        CHECK(on_feature);
        CHECK(bool(is_border(v, m)));
        CHECK(to_rim(m.point(v)) < 1e-9);
        on_rim += is_border(v, m) ? 1 : 0;
      }
      CHECK(on_rim >= 3);
      CHECK(after < 0.5 * before);
    } else {
      CHECK(added.empty());
      CHECK(after == Approx(before));
    }
  }
}

TEST_CASE("an edge split is taken back whole, on a border too", "[operators][fidelity]")
{
  // the fidelity insertions split an edge, check the new triangles, and may take the split back
  for(bool border : {false, true}) {
    INFO((border ? "a border edge" : "an interior edge"));
    Mesh m = square(4);
    const V a = vertex_at(m, border ? 0.25 : 0.5, border ? 0.0 : 0.5), b = vertex_at(m, border ? 0.5 : 0.75, border ? 0.0 : 0.75);
    // the halfedge from a to b, or none
    auto between = [&](V x, V y) {
      for(auto g : CGAL::halfedges_around_target(y, m)) if(source(g, m) == x) return g;
      return Mesh::null_halfedge();
    };
    auto h = between(a, b);
    REQUIRE(h != Mesh::null_halfedge());
    if(is_border(h, m)) h = opposite(h, m);
    REQUIRE(is_border(opposite(h, m), m) == border);
    const std::size_t nv = num_vertices(m), nf = num_faces(m);
    const long chi = euler_characteristic(m);
    const V v = Context::insert_vertex_on_edge(h, CGAL::midpoint(m.point(a), m.point(b)), m);
    CHECK(degree(v, m) == (border ? 3u : 4u));
    CHECK(num_faces(m) == nf + (border ? 1 : 2));
    Context::remove_vertex_on_edge(v, a, b, m);
    CHECK(between(a, b) != Mesh::null_halfedge());   // (the edge is back; before the garbage goes, a and b are theirs)
    m.collect_garbage();
    CHECK(CGAL::is_valid_polygon_mesh(m));
    CHECK(num_vertices(m) == nv);
    CHECK(num_faces(m) == nf);
    CHECK(euler_characteristic(m) == chi);
    CHECK(border_cycles(m) == 1);
    CHECK(no_fold_in_plane(m));
  }
}

TEST_CASE("angle optimization and smoothing: a free vertex pushed off its place moves back to better angles", "[operators][angles]")
{
  const Mesh in = square(24);
  const auto features = PR::detect_features(in);
  const Context context(in, features);
  auto make = [] {
    Mesh m = square(6);
    const V v = vertex_at(m, 3.0 / 6, 3.0 / 6);
    m.point(v) = Point(3.0 / 6 + 0.7 / 6, 3.0 / 6 + 0.05 / 6, 0);   // near its right neighbour: sharp triangles
    return std::make_pair(m, v);
  };
  REQUIRE(no_fold_in_plane(make().first));
  SECTION("optimization raises the smallest angle around the vertex")
  {
    auto [m, v] = make();
    const double worst = min_angle(m);
    REQUIRE(worst < 20);
    PR::Relaxation_statistics stats;
    std::size_t moved = 0;
    for(int round = 0; round < 4; ++round)
      moved += P::optimize_angles(context, m, no_feature, [&](V x) { return x != v; }, P::Angle_optimization_settings(), 30, 0.008, stats);
    CHECK(moved > 0);
    CHECK(min_angle(m) > 40);
    CHECK(std::abs(m.point(v).z()) < 1e-12);
    CHECK(no_fold_in_plane(m));
  }
  SECTION("smoothing raises the sum of the smallest angles without lowering the smallest")
  {
    auto [m, v] = make();
    auto sum_around = [&](const Mesh& x) {
      double s = 0;
      for(auto h : CGAL::halfedges_around_target(v, x)) if(!is_border(h, x)) s += smallest_angle(face(h, x), x);
      return s;
    };
    const double worst = min_angle(m), sum = sum_around(m);
    PR::Relaxation_statistics stats;
    const std::size_t moved = P::smooth_angles(context, m, no_feature, [&](V x) { return x != v; }, stats);
    CHECK(moved == 1);
    CHECK(sum_around(m) > sum + 10);
    CHECK(min_angle(m) >= worst);
    CHECK(no_fold_in_plane(m));
  }
  SECTION("rounds with a memory search only where something changed, and end where rounds without one end")
  {
    // every interior vertex of a 6 x 6 grid free, three of them pushed off their places
    Mesh with = square(6);
    for(auto [x, y, dx, dy] : {std::array<double, 4>{2, 2, 0.3, 0.1}, {4, 3, -0.2, 0.25}, {3, 4, 0.1, -0.3}})
      with.point(vertex_at(with, x / 6, y / 6)) = Point((x + dx) / 6, (y + dy) / 6, 0);
    Mesh without = with;
    auto free = [](const Mesh& m) { return [&m](V x) { return is_border(x, m); }; };
    PR::Relaxation_statistics with_stats, without_stats;
    P::Angle_smoothing_memory<Mesh> memory;
    std::size_t rounds = 0, moved_with = 1, moved_without = 1;
    for(; rounds < 12 && (moved_with > 0 || moved_without > 0); ++rounds) {
      moved_with = P::smooth_angles(context, with, no_feature, free(with), with_stats, &memory);
      moved_without = P::smooth_angles(context, without, no_feature, free(without), without_stats);
      CHECK(moved_with == moved_without);
    }
    INFO(rounds << " rounds, " << with_stats.unchanged_stars << " searches not made again");
    CHECK(rounds >= 2);
    CHECK(with_stats.unchanged_stars > 0);
    CHECK(without_stats.unchanged_stars == 0);
    for(V x : vertices(with)) CHECK(with.point(x) == without.point(x));
    // a last round with the memory searches no vertex: every star is as its search left it
    const std::size_t before = with_stats.unchanged_stars;
    CHECK(P::smooth_angles(context, with, no_feature, free(with), with_stats, &memory) == 0);
    CHECK(with_stats.unchanged_stars - before == 25);
  }
}

TEST_CASE("angle optimization: a move does not take an edge of the moving vertex farther than the tolerance from the input", "[operators][angles][fidelity]")
{
  // a coarse sphere's vertices pushed off their places along the input (a finer sphere), which
  // leaves triangles under 30 degrees: the searches move them, each trial point judged by the
  // smallest angle around it; an edge of the moving vertex may not end farther from the input
  // than the tolerance unless it was already (then no farther than it was). With a tolerance of 0
  // (the check off) the same searches stretch edges past it. (A tolerance of 0.4% of the diagonal:
  // some edges start beyond it, and stay no farther than they were.)
  const Mesh in = analytic::sphere(96, 48).to_mesh<Mesh>();
  const auto features = PR::detect_features(in);
  const Context context(in, features);
  CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> tree(faces(in).first, faces(in).second, in);
  Mesh start = analytic::sphere(24, 12).to_mesh<Mesh>();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> push(-0.05, 0.05);
  for(V v : vertices(start)) {
    const Point p = start.point(v);
    const double dx = push(rng), dy = push(rng), dz = push(rng);
    start.point(v) = tree.closest_point(Point(p.x() + dx, p.y() + dy, p.z() + dz));
  }
  const double tolerance = 0.004, reach = tolerance * context.diagonal();
  auto midpoint_distances = [&](const Mesh& m) {
    std::vector<double> d;
    for(auto e : edges(m)) d.push_back(std::sqrt(tree.squared_distance(CGAL::midpoint(m.point(source(e, m)), m.point(target(e, m))))));
    return d;
  };
  const std::vector<double> before = midpoint_distances(start);
  const double worst = min_angle(start);
  REQUIRE(worst < 30);
  REQUIRE(*std::max_element(before.begin(), before.end()) > reach);
  // (the largest excess of an edge over the tolerance, beyond what it had before)
  auto stretched = [&](double max_deviation, std::size_t& moved, double& smallest) {
    Mesh m = start;
    PR::Relaxation_statistics stats;
    moved = 0;
    for(int round = 0; round < 4; ++round)
      moved += P::optimize_angles(context, m, no_feature, [](V) { return false; }, P::Angle_optimization_settings(), 30, max_deviation, stats);
    smallest = min_angle(m);
    const std::vector<double> after = midpoint_distances(m);
    double excess = 0;
    for(std::size_t i = 0; i < after.size(); ++i) excess = std::max(excess, after[i] - std::max(before[i], reach));
    return excess;
  };
  std::size_t moved_with = 0, moved_without = 0;
  double smallest_with = 0, smallest_without = 0;
  CHECK(stretched(tolerance, moved_with, smallest_with) <= 1e-12);
  CHECK(moved_with > 100);
  CHECK(smallest_with >= worst);
  CHECK(stretched(0, moved_without, smallest_without) > 0.1 * reach);   // (the check off)
}

TEST_CASE("angle smoothing: a free vertex climbs the gradient of its ring's smallest angles", "[operators][angles]")
{
  // the directions of the smoothing's gradient steps against central differences of the
  // law-of-cosines angles (the judge's angle_deg), on random stars in the plane z = 0, some ring
  // vertices with a tip scale; only stars whose smallest corners are not nearly tied (where the
  // sum is smooth). A step along either direction raises what it climbs; where the sum's terms
  // cancel (its gradient is nil), no direction is given.
  typedef K::Vector_3 Vector;
  typedef P::internal::vertex_angle_search_detail::Ring_triangle<Point, Vector> Ring_triangle;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  const Vector nn(0, 0, 1);
  auto unit_vector = [](const Vector& v) { return v / std::sqrt(v.squared_length()); };
  // each triangle's smallest scaled angle (radians), and the gap to its second smallest
  auto smallest = [](const Ring_triangle& t, const Point& q, double* gap = nullptr) {
    std::array<double, 3> x = {t.sa * angle_deg(t.a, q, t.b), angle_deg(q, t.a, t.b), t.sb * angle_deg(t.b, q, t.a)};
    std::sort(x.begin(), x.end());
    if(gap != nullptr) *gap = x[1] - x[0];
    return x[0] * CGAL_PI / 180;
  };
  int judged = 0, cancelled = 0, opposite = 0;
  for(int trial = 0; trial < 400; ++trial) {
    const int k = 4 + int(unit(rng) * 5);
    std::vector<Point> ring_points;
    std::vector<double> scale;   // (a tip scale per ring vertex, as the search gives them)
    for(int i = 0; i < k; ++i) {
      const double phi = (i + 0.8 * (unit(rng) - 0.5)) * 2 * CGAL_PI / k;
      const double r = 0.5 + unit(rng);
      ring_points.push_back(Point(r * std::cos(phi), r * std::sin(phi), 0));
      scale.push_back(unit(rng) < 0.2 ? 1.5 : 1.0);
    }
    std::vector<Ring_triangle> ring;
    for(std::size_t i = 0; i < std::size_t(k); ++i) {
      const std::size_t j = (i + 1) % std::size_t(k);
      ring.push_back(Ring_triangle{ring_points[i], ring_points[j], nn, 1, scale[i], scale[j]});
    }
    const double qx = 0.3 * (unit(rng) - 0.5);
    const double qy = 0.3 * (unit(rng) - 0.5);
    const Point q(qx, qy, 0);
    bool smooth = true;
    double least = 10;
    std::size_t least_at = 0;
    for(std::size_t i = 0; i < ring.size(); ++i) {
      double gap;
      const double x = smallest(ring[i], q, &gap);
      if(gap < 0.5) smooth = false;
      if(x < least - 1e-3) { least = x; least_at = i; }
      else if(x < least + 1e-3) smooth = false;   // (two least triangles: no single gradient)
    }
    if(!smooth) continue;
    const double h = 1e-6;
    auto sum_at = [&](const Point& x) {
      double s = 0;
      for(const Ring_triangle& t : ring) s += smallest(t, x);
      return s;
    };
    auto gradient = [&](auto f) {
      return Vector((f(q + Vector(h, 0, 0)) - f(q - Vector(h, 0, 0))) / (2 * h), (f(q + Vector(0, h, 0)) - f(q - Vector(0, h, 0))) / (2 * h), 0);
    };
    const Vector g_sum = gradient(sum_at), g_least = gradient([&](const Point& x) { return smallest(ring[least_at], x); });
    double terms = 0;   // (the lengths of the sum's terms' gradients)
    for(const Ring_triangle& t : ring) terms += std::sqrt(gradient([&](const Point& x) { return smallest(t, x); }).squared_length());
    Vector d_sum, d_both;
    P::internal::vertex_angle_search_detail::ascent_directions(ring, q, nn, d_sum, d_both);
    INFO("trial " << trial);
    if(std::sqrt(g_sum.squared_length()) < 1e-6 * terms) {
      // the terms cancel (the smallest angles beside an edge from q at its other end): no
      // direction for the sum, the least angle's alone
      ++cancelled;
      CHECK(d_sum == CGAL::NULL_VECTOR);
      CHECK(d_both == CGAL::NULL_VECTOR);
      continue;
    } else {
      ++judged;
      CHECK(d_sum * unit_vector(g_sum) > 0.9999);
      CHECK(std::abs(d_sum.squared_length() - 1) < 1e-12);
      CHECK(sum_at(q + 1e-4 * d_sum) > sum_at(q));   // (a short step along it raises the sum)
      const Vector both = unit_vector(g_sum) + unit_vector(g_least);
      if(both.squared_length() < 1e-12) {   // (opposite: no direction raises both)
        ++opposite;
        CHECK(d_both == CGAL::NULL_VECTOR);
        continue;
      }
      CHECK(d_both * unit_vector(both) > 0.9999);
    }
    CHECK(smallest(ring[least_at], q + 1e-4 * d_both) > least);
  }
  INFO(judged << " stars with a gradient of the sum (" << opposite << " opposite to the least angle's), " << cancelled << " without");
  CHECK(judged > 50);
  CHECK(cancelled > 5);
  // a flat regular star of valence 7 or 8, off its centre: every triangle's smallest angle is at
  // the centre vertex, and they sum to 2 pi wherever it moves
  for(int k : {7, 8}) {
    std::vector<Ring_triangle> ring;
    for(int i = 0; i < k; ++i) {
      const double a0 = 2 * CGAL_PI * i / k, a1 = 2 * CGAL_PI * (i + 1) / k;
      ring.push_back(Ring_triangle{Point(std::cos(a0), std::sin(a0), 0), Point(std::cos(a1), std::sin(a1), 0), nn, 1, 1, 1});
    }
    Vector d_sum, d_both;
    P::internal::vertex_angle_search_detail::ascent_directions(ring, Point(0.01, -0.02, 0), nn, d_sum, d_both);
    CHECK(d_sum == CGAL::NULL_VECTOR);
    CHECK(d_both == CGAL::NULL_VECTOR);
  }
}

TEST_CASE("regularity flips: a grid with one diagonal turned gets its valence-6 vertices back", "[operators][regularity]")
{
  const Square_input plane(24);
  for(bool on : {false, true}) {
    INFO("regularity flips " << (on ? "on" : "off"));
    Mesh m = square(6);
    const std::size_t regular = irregular(m);
    // the diagonal of the interior quad at (2..3, 2..3) turned: four vertices 5 or 7
    const auto h = halfedge(vertex_at(m, 2.0 / 6, 2.0 / 6), vertex_at(m, 3.0 / 6, 3.0 / 6), m);
    REQUIRE(h.second);
    CGAL::Euler::flip_edge(h.first, m);
    REQUIRE(irregular(m) == regular + 4);
    PR::Relaxation_settings s = nothing_but_the_last_lloyd_pass();
    if(on) s.regularity.rounds = 4;
    const auto stats = plane.relaxer.relax(m, no_feature, [](V) { return true; }, s);
    CHECK(no_fold_in_plane(m));
    if(on) {
      CHECK(stats.valence_flips >= 1);
      CHECK(irregular(m) == regular);
      CHECK(min_angle(m) >= 45 - 1e-9);
    } else {
      CHECK(irregular(m) == regular + 4);
    }
  }
}

namespace {
// square(6) with an interior vertex pushed towards its diagonal neighbour: sharp triangles
Mesh grid_with_a_pushed_vertex()
{
  Mesh m = square(6);
  const V v = vertex_at(m, 3.0 / 6, 3.0 / 6);
  m.point(v) = Point(3.0 / 6 + 0.8 / 6, 3.0 / 6 + 0.7 / 6, 0);
  REQUIRE(count_below(m, 30) >= 2);
  REQUIRE(no_fold_in_plane(m));
  return m;
}
// after a change: still a flat square, one border, no fold, as many holes as before (`chi`)
void check_still_the_flat_square(Mesh& m, long chi)
{
  m.collect_garbage();
  CHECK(euler_characteristic(m) == chi);
  CHECK(border_cycles(m) == 1);
  CHECK(no_fold_in_plane(m));
  for(V x : vertices(m)) CHECK(std::abs(m.point(x).z()) < 1e-12);
}
} // namespace

TEST_CASE("refinement: a sharp triangle at pinned vertices gets a flip, a removal or a new vertex", "[operators][refinement]")
{
  const Square_input plane(24);
  for(bool on : {false, true}) {
    INFO("refinement " << (on ? "on" : "off"));
    // every vertex pinned: only a change of connectivity can mend the triangles
    Mesh m = grid_with_a_pushed_vertex();
    const std::size_t sharp = count_below(m, 30);
    const double worst = min_angle(m);
    const long chi = euler_characteristic(m);
    PR::Relaxation_settings s = nothing_but_the_last_lloyd_pass();
    if(on) s.refinement.rounds = 3;
    std::vector<std::pair<V, bool>> added;
    const auto stats = plane.relaxer.relax(m, no_feature, [](V) { return true; }, s, Counting_new_vertex{&added});
    check_still_the_flat_square(m, chi);
    INFO("smallest angle " << worst << " -> " << min_angle(m) << ", triangles under 30: " << sharp << " -> " << count_below(m, 30));
    if(on) {
      CHECK(stats.refinement_flips + stats.refinement_removals + stats.refinement_insertions > 0);
      CHECK(count_below(m, 30) <= sharp);
      CHECK(min_angle(m) > worst + 5);
    } else {
      CHECK(count_below(m, 30) == sharp);
      CHECK(min_angle(m) == worst);
    }
  }
}

TEST_CASE("local repair: a sharp triangle at vertices that may not move gets the change that, with the moves after it, raises its region", "[operators][repair]")
{
  const Square_input plane(24);
  for(bool on : {false, true}) {
    INFO("local repair " << (on ? "on" : "off"));
    // every vertex of the grid is fixed (only the vertices a change adds may move): a flip or a
    // split, and the new vertex's moves, must mend the triangles
    Mesh m = grid_with_a_pushed_vertex();
    std::vector<V> grid(vertices(m).begin(), vertices(m).end());
    auto fixed = [&](V x) { return std::find(grid.begin(), grid.end(), x) != grid.end(); };
    const std::size_t sharp = count_below(m, 30);
    const double worst = min_angle(m);
    const long chi = euler_characteristic(m);
    const std::size_t count = num_vertices(m);
    PR::Relaxation_settings s = nothing_but_the_last_lloyd_pass();
    if(on) s.local_repair.rounds = 4;
    std::vector<std::pair<V, bool>> added;
    const auto stats = plane.relaxer.relax(m, no_feature, fixed, s, Counting_new_vertex{&added});
    check_still_the_flat_square(m, chi);
    INFO("smallest angle " << worst << " -> " << min_angle(m) << ", triangles under 30: " << sharp << " -> " << count_below(m, 30));
    if(on) {
      CHECK(stats.repair_changes > 0);
      CHECK(count_below(m, 30) < sharp);
      CHECK(min_angle(m) > worst + 5);
      CHECK(num_vertices(m) <= count + stats.repair_changes);   // (a split per change at most; the trials' vertices removed)
    } else {
      CHECK(stats.repair_changes == 0);
      CHECK(added.empty());
      CHECK(count_below(m, 30) == sharp);
      CHECK(min_angle(m) == worst);
    }
  }
}

// The local self-intersection checks that every operator's take-backs rest on: the pairs near a few
// changed faces (found through a grid of their boxes) are those of a whole-mesh check (CGAL's
// self_intersections, called here directly) that involve a changed face; and after vertex moves,
// the new crossings found with only the crossing pairs put back for a moment are those that a
// whole-mesh check of the earlier state gives.
TEST_CASE("local self-intersection checks agree with whole-mesh checks", "[operators][intersections]")
{
  // two 12 x 12 grids that cross: the unit square at z = 0 and a square standing at x = 0.53
  analytic::Soup s;
  const std::size_t n = 12;
  auto add_grid = [&](auto place) {
    const std::size_t first = s.points.size();
    for(std::size_t j = 0; j <= n; ++j)
      for(std::size_t i = 0; i <= n; ++i) s.points.push_back(place(double(i) / double(n), double(j) / double(n)));
    auto id = [&](std::size_t i, std::size_t j) { return first + j * (n + 1) + i; };
    for(std::size_t j = 0; j < n; ++j)
      for(std::size_t i = 0; i < n; ++i) {
        s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
  };
  add_grid([](double u, double v) { return std::array<double, 3>{{u, v, 0}}; });
  add_grid([](double u, double v) { return std::array<double, 3>{{0.53, u, v - 0.47}}; });
  Mesh m = s.to_mesh<Mesh>();
  typedef std::pair<Mesh::Face_index, Mesh::Face_index> Pair;
  auto whole = [](const Mesh& mesh) {
    std::vector<Pair> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(pairs));
    for(Pair& p : pairs) if(p.second < p.first) std::swap(p.first, p.second);
    std::sort(pairs.begin(), pairs.end());
    return pairs;
  };
  const std::vector<Pair> all = whole(m);
  REQUIRE(all.size() > 20);
  std::vector<Mesh::Face_index> fs(faces(m).begin(), faces(m).end());
  // changed sets of 3, 20 and 250 faces, drawn with a fixed step
  for(std::size_t count : {3u, 20u, 250u}) {
    REQUIRE(2 * count <= fs.size());
    std::vector<Mesh::Face_index> changed;
    for(std::size_t k = 0; k < count; ++k) changed.push_back(fs[(k * 7919 + count) % fs.size()]);
    // (and always a face on the crossing)
    changed.push_back(all.front().first);
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    const auto near = PR::internal::intersecting_pairs_near(m, changed);
    std::size_t expected = 0;
    for(const Pair& p : all)
      if(std::binary_search(changed.begin(), changed.end(), p.first) || std::binary_search(changed.begin(), changed.end(), p.second)) {
        ++expected;
        CHECK(std::binary_search(near.begin(), near.end(), p));
      }
    CHECK(expected > 0);
    for(const Pair& p : near) CHECK(std::binary_search(all.begin(), all.end(), p));
  }

  // moves: vertices of the flat grid near the standing one lifted through it or beside it
  const Mesh flat = square(4);
  const Context context(flat, PR::detect_features(flat));
  std::vector<std::pair<V, Point>> from;
  for(V v : vertices(m)) {
    const Point p = m.point(v);
    if(p.z() != 0 || std::abs(p.x() - 0.5) > 0.1 || p.y() < 0.2 || p.y() > 0.8) continue;
    from.push_back({v, p});
    m.point(v) = Point(p.x() + (p.x() < 0.53 ? 0.06 : 0.01), p.y(), 0.02 * std::sin(7 * p.y()));
  }
  REQUIRE(from.size() >= 4);
  std::sort(from.begin(), from.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<V> movers;
  for(const auto& x : from) movers.push_back(x.first);
  const auto changed = PR::internal::faces_around(m, movers);
  std::vector<V> local, reference;
  const Mesh moved = m;
  context.for_vertices_of_new_intersections_after_moves(m, from, changed, [&](V x) { local.push_back(x); });
  // (the moves were put back and forth: the mesh is as it was)
  for(V v : vertices(m)) CHECK(m.point(v) == moved.point(v));
  context.for_vertices_of_new_intersections(m, all, changed, [&](V x) { reference.push_back(x); });
  for(auto* list : {&local, &reference}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  CHECK(!reference.empty());
  CHECK(local == reference);
}

// The fidelity insertions skip the distance queries of points within the tolerance of a point of
// the mesh (or of the input): found in a grid of cells as large as the tolerance
// (internal/near_points.h), judged against a scan of every point.
TEST_CASE("the crossing search finds CGAL's pairs, with its grid and star tests where faces are near-equal", "[operators][intersections]")
{
  // The judge is CGAL's self_intersections() itself, on meshes built to cross in every way its
  // rule distinguishes: faces folded onto a neighbour across an edge (coplanar overlap), faces
  // sharing a vertex whose star is folded, faces of two sheets that pass through each other, a
  // zero-area face; and on data meshes (irregular: CGAL's search is taken there).
  typedef std::pair<Mesh::Face_index, Mesh::Face_index> Pair;
  auto judge = [](const Mesh& mesh, const std::vector<Mesh::Face_index>& range) {
    std::vector<Pair> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(range, mesh, std::back_inserter(pairs));
    for(Pair& p : pairs) if(p.second < p.first) std::swap(p.first, p.second);
    std::sort(pairs.begin(), pairs.end());
    return pairs;
  };
  std::size_t grid_runs = 0, crossing_grid_runs = 0;
  auto compare = [&](const Mesh& mesh, std::size_t least) {
    const std::vector<Mesh::Face_index> all(faces(mesh).begin(), faces(mesh).end());
    std::vector<Mesh::Face_index> some;   // (two faces of three)
    for(std::size_t i = 0; i < all.size(); ++i) if(i % 3 != 1) some.push_back(all[i]);
    const std::vector<Mesh::Face_index>* ranges[2] = {&all, &some};
    for(const std::vector<Mesh::Face_index>* range : ranges) {
      bool grid = false;
      const auto expected = judge(mesh, *range);
      const auto found = PR::internal::intersecting_face_pairs(mesh, *range, get(CGAL::vertex_point, mesh), std::size_t(-1), &grid);
      CHECK(found == expected);
      if(range == &all) CHECK(found.size() >= least);
#ifdef CGAL_LINKED_WITH_TBB
      CHECK(PR::internal::intersecting_face_pairs<CGAL::Parallel_tag>(mesh, *range, get(CGAL::vertex_point, mesh)) == found);
#endif
      if(grid) { ++grid_runs; if(!found.empty()) ++crossing_grid_runs; }
      // bounded: that many pairs, each of them one of the judge's
      if(found.size() > 3) {
        const auto first = PR::internal::intersecting_face_pairs(mesh, *range, get(CGAL::vertex_point, mesh), 3);
        CHECK(first.size() == 3);
        for(const Pair& p : first) CHECK(std::binary_search(expected.begin(), expected.end(), p));
#ifdef CGAL_LINKED_WITH_TBB
        // (the parallel search takes its candidates in the same order: the same first pairs)
        CHECK(PR::internal::intersecting_face_pairs<CGAL::Parallel_tag>(mesh, *range, get(CGAL::vertex_point, mesh), 3) == first);
#endif
      }
    }
  };
  // a sphere as it is (no crossing), and with every 29th vertex slid past a neighbour (folded
  // stars), and with a second sphere through it (crossings of faces far apart on the mesh)
  const analytic::Soup ball = analytic::sphere(24, 12);
  Mesh sphere = ball.to_mesh<Mesh>();
  compare(sphere, 0);
  Mesh pushed = sphere;
  std::size_t k = 0;
  for(V v : vertices(pushed))   // (past a neighbour, its star folded over the neighbour's)
    if(++k % 29 == 0) pushed.point(v) = pushed.point(v) + 1.6 * (pushed.point(source(halfedge(v, pushed), pushed)) - pushed.point(v));
  compare(pushed, 10);
  // a finer sphere so folded: more occupied grid cells (5,714) than the parallel search takes in
  // one group (4,096)
  Mesh fine = analytic::sphere(240, 120).to_mesh<Mesh>();
  k = 0;
  for(V v : vertices(fine))
    if(++k % 97 == 0) fine.point(v) = fine.point(v) + 1.6 * (fine.point(source(halfedge(v, fine), fine)) - fine.point(v));
  compare(fine, 50);
  analytic::Soup two = ball;
  for(const auto& p : ball.points) two.points.push_back({p[0] + 0.6, p[1] + 0.3, p[2]});
  for(const auto& t : ball.triangles) two.triangles.push_back({t[0] + ball.points.size(), t[1] + ball.points.size(), t[2] + ball.points.size()});
  compare(two.to_mesh<Mesh>(), 50);
  // a flat grid with a vertex slid in the plane past its neighbour (triangles folded onto others
  // across an edge), and one moved onto the middle of an edge of its star (a zero-area face)
  Mesh folded = square(8);
  for(V v : vertices(folded)) {
    const Point p = folded.point(v);
    if(std::abs(p.x() - 0.5) < 1e-9 && std::abs(p.y() - 0.5) < 1e-9) folded.point(v) = Point(0.5 + 0.19, 0.5 + 0.02, 0);
  }
  compare(folded, 2);
  Mesh flat = square(8);
  for(V v : vertices(flat)) {
    const Point p = flat.point(v);
    if(std::abs(p.x() - 0.25) < 1e-9 && std::abs(p.y() - 0.25) < 1e-9) {
      const auto h = halfedge(v, flat);   // (onto the middle of the edge opposite v in one of its faces)
      const auto g = is_border(h, flat) ? opposite(next(opposite(h, flat), flat), flat) : next(h, flat);
      flat.point(v) = CGAL::midpoint(flat.point(target(g, flat)), flat.point(target(next(g, flat), flat)));
    }
  }
  compare(flat, 1);
  // data meshes that cut themselves
  for(const char* name : {"meshes/bones.off", "meshes/elephant-with-holes.off"}) {
    Mesh d;
    REQUIRE(CGAL::IO::read_polygon_mesh(test_support::data_mesh(name), d));
    compare(d, 100);
  }
  // the grid and star tests were what ran on the meshes of near-equal faces, crossings found too
  CHECK(grid_runs >= 8);
  CHECK(crossing_grid_runs >= 6);
}

// The grids sort their (cell key, index) pairs, made in index order, by a stable radix sort
// (internal/radix_sort.h): judged against std::sort of the pairs.
TEST_CASE("the grids' radix sort orders (key, index) pairs as std::sort does", "[operators][intersections]")
{
  std::mt19937_64 draw(11);
  // keys of every bit, keys with many ties, keys that differ in their top bytes alone, one key
  const std::function<std::uint64_t()> kinds[] = {
      [&] { return std::uint64_t(draw()); }, [&] { return std::uint64_t(draw() % 7); },
      [&] { return std::uint64_t(draw() % 5) << 50 | 0x1234; }, [&] { return std::uint64_t(42); }};
  for(const auto& key : kinds)
    for(std::size_t n : {0, 1, 2, 37, 5000}) {
      std::vector<std::pair<std::uint64_t, std::uint32_t>> v;
      for(std::uint32_t i = 0; i < n; ++i) v.emplace_back(key(), i);
      auto expected = v;
      std::sort(expected.begin(), expected.end());
      PR::internal::stable_sort_by_key(v);
      CHECK(v == expected);
    }
}

TEST_CASE("the point grid finds a point within a distance exactly when there is one", "[operators][fidelity]")
{
  std::mt19937 draw(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::vector<Point> points;
  for(int i = 0; i < 400; ++i) points.push_back(Point(coordinate(draw), coordinate(draw), 0.1 * coordinate(draw)));
  const double cell = 0.08;
  const PR::internal::Near_points<Point> grid(points, cell);
  std::size_t near = 0, far = 0;
  for(int i = 0; i < 4000; ++i) {
    const Point q(1.1 * coordinate(draw), 1.1 * coordinate(draw), 0.2 * coordinate(draw));
    for(double d : {cell, 0.5 * cell, 0.1 * cell}) {
      bool any = false;
      for(const Point& p : points) any = any || CGAL::squared_distance(p, q) <= d * d;
      CHECK(grid.within(q, d) == any);
      (any ? near : far) += 1;
    }
  }
  // (both answers were met; a point of the grid is within any distance of itself)
  CHECK(near > 1000);
  CHECK(far > 1000);
  CHECK(grid.within(points[0], 0));
  // the nearest point's squared distance, exact when it is within a cell (never under the nearest)
  std::size_t exact = 0;
  for(int i = 0; i < 2000; ++i) {
    const Point q(1.1 * coordinate(draw), 1.1 * coordinate(draw), 0.2 * coordinate(draw));
    double nearest = std::numeric_limits<double>::infinity();
    for(const Point& p : points) nearest = std::min(nearest, CGAL::to_double(CGAL::squared_distance(p, q)));
    const double found = grid.squared_distance(q);
    CHECK(found >= nearest);
    if(nearest <= cell * cell) { CHECK(found == nearest); ++exact; }
  }
  CHECK(exact > 500);
  // the nearest point: its place among the points and its squared distance as a scan finds them
  // (the first place of the nearest), whenever it lies within a cell; never nearer than the nearest
  // otherwise. With `enough`, a point within it when there is one, else the nearest again
  std::size_t nearest_found = 0, enough_met = 0;
  for(int i = 0; i < 2000; ++i) {
    const Point q(1.1 * coordinate(draw), 1.1 * coordinate(draw), 0.2 * coordinate(draw));
    std::size_t best = std::size_t(-1);
    double best_d2 = std::numeric_limits<double>::infinity();
    for(std::size_t k = 0; k < points.size(); ++k) {
      const double d2 = CGAL::to_double(CGAL::squared_distance(points[k], q));
      if(d2 < best_d2) { best_d2 = d2; best = k; }
    }
    const auto found = grid.nearest(q);
    if(best_d2 <= cell * cell) {
      CHECK(found.first == best);
      CHECK(found.second == best_d2);
      ++nearest_found;
    } else {
      CHECK(found.second >= best_d2);
    }
    const double enough = 0.5 * cell * cell;
    const auto early = grid.nearest(q, enough);
    if(best_d2 <= enough) {
      REQUIRE(early.first < points.size());
      CHECK(early.second <= enough);
      CHECK(early.second == CGAL::to_double(CGAL::squared_distance(points[early.first], q)));
      ++enough_met;
    } else if(best_d2 <= cell * cell) {
      CHECK(early.first == best);
    }
  }
  CHECK(nearest_found > 500);
  CHECK(enough_met > 100);
  // a triangle within a distance of a point: small triangles (the cells around them) and ones
  // larger than the points' spread (every point)
  std::size_t hits = 0, misses = 0;
  for(int i = 0; i < 1000; ++i) {
    const double scale = i % 10 == 0 ? 3.0 : 0.1;
    const Point a(1.1 * coordinate(draw), 1.1 * coordinate(draw), 0.2 * coordinate(draw));
    const K::Triangle_3 t(a, a + scale * K::Vector_3(coordinate(draw), coordinate(draw), 0.1 * coordinate(draw)),
                          a + scale * K::Vector_3(coordinate(draw), coordinate(draw), 0.1 * coordinate(draw)));
    for(double d : {cell, 0.3 * cell}) {
      bool any = false;
      for(const Point& p : points) any = any || CGAL::to_double(CGAL::squared_distance(p, t)) < d * d;
      CHECK(grid.near_triangle(t, d) == any);
      (any ? hits : misses) += 1;
    }
  }
  CHECK(hits > 100);
  CHECK(misses > 100);
  // cells spanning more than 2^21 along an axis (sorted on the cells themselves, not one key)
  std::vector<Point> spread = points;
  spread.push_back(Point(1e6, -1e6, 0));
  const PR::internal::Near_points<Point> wide(spread, cell);
  for(int i = 0; i < 1000; ++i) {
    const Point q(1.1 * coordinate(draw), 1.1 * coordinate(draw), 0.2 * coordinate(draw));
    CHECK(wide.within(q, cell) == grid.within(q, cell));
  }
  CHECK(wide.within(Point(1e6, -1e6, 0.5 * cell), cell));
  // no point: nothing near
  const PR::internal::Near_points<Point> empty(std::vector<Point>(), cell);
  CHECK_FALSE(empty.within(points[0], cell));
  CHECK(empty.squared_distance(points[0]) == std::numeric_limits<double>::infinity());
  CHECK(empty.nearest(points[0]).first == std::size_t(-1));
}

// Postprocessing/internal/near_surface.h, the fidelity insertions' test of "within the tolerance":
// the squared distance to the triangles around the nearest vertex is never under the distance to
// the whole mesh (CGAL's AABB tree is the judge), equals it for nearly every point near the
// surface, and a search told that a distance is enough stops at one that is
TEST_CASE("the triangles around the nearest vertex bound the distance to the mesh", "[operators][fidelity]")
{
  Mesh m;
  REQUIRE(CGAL::IO::read_polygon_mesh(test_support::data_mesh("meshes/fandisk.off"), m));
  CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> tree(faces(m).first, faces(m).second, m);
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  for(V v : vertices(m)) points.push_back(m.point(v));
  double length = 0;
  for(auto e : edges(m)) length += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  length /= double(num_edges(m));
  for(auto f : faces(m)) {
    std::array<std::size_t, 3> t;
    std::size_t k = 0;
    for(V v : vertices_around_face(halfedge(f, m), m)) t[k++] = std::size_t(v);
    triangles.push_back(t);
  }
  const PR::Postprocessing::internal::Near_surface<Point> surface(points, triangles, 2 * length, CGAL::Sequential_tag());
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::size_t equal = 0, enough_met = 0;
  const int n = 3000;
  for(int i = 0; i < n; ++i) {
    const Point v = points[std::size_t(random()) % points.size()];
    const double step = 0.5 * length;
    const Point q(v.x() + step * unit(random), v.y() + step * unit(random), v.z() + step * unit(random));
    const double exact = CGAL::to_double(tree.squared_distance(q));
    const double bound = surface.squared_distance_bound(q);
    // (both rounded: a slack of 1e-9 of the distance and 1e-12 of an edge)
    const double slack = 1e-9 * exact + 1e-12 * length * length;
    CHECK(bound >= exact - slack);
    if(bound <= exact + slack) ++equal;
    const double enough = 0.01 * length * length;
    const double early = surface.squared_distance_bound(q, enough);
    CHECK(early >= exact - slack);
    if(early <= enough) ++enough_met;
    else CHECK(early == bound);
  }
  CHECK(equal > 0.9 * n);
  CHECK(enough_met > 0.1 * n);
  // a point farther than a cell from every vertex: no bound
  CGAL::Bbox_3 box;
  for(const Point& p : points) box += p.bbox();
  CHECK(surface.squared_distance_bound(Point(box.xmax() + 10 * length, box.ymax(), box.zmax())) == std::numeric_limits<double>::infinity());
  // a vertex on no triangle is no point of the surface: a point on it is not near by it
  const Point lone(box.xmax() + 0.5 * length, 0.5 * (box.ymin() + box.ymax()), 0.5 * (box.zmin() + box.zmax()));
  std::vector<Point> with_lone = points;
  with_lone.push_back(lone);
  const PR::Postprocessing::internal::Near_surface<Point> lonely(with_lone, triangles, 2 * length, CGAL::Sequential_tag());
  CHECK(lonely.squared_distance_bound(lone) >= CGAL::to_double(tree.squared_distance(lone)) * (1 - 1e-12));
  CHECK(lonely.squared_distance_bound(lone, 1e-6 * length * length) > 1e-6 * length * length);
  // built on TBB's threads, the same grid: the same bounds
  const PR::Postprocessing::internal::Near_surface<Point> parallel(points, triangles, 2 * length, CGAL::Parallel_tag());
  std::mt19937 again(7);
  for(int i = 0; i < 2000; ++i) {
    const Point v = points[std::size_t(again()) % points.size()];
    const Point q(v.x() + length * unit(again), v.y() + length * unit(again), v.z() + length * unit(again));
    CHECK(parallel.squared_distance_bound(q) == surface.squared_distance_bound(q));
    CHECK(parallel.squared_distance_bound(q, 0.01 * length * length) == surface.squared_distance_bound(q, 0.01 * length * length));
  }
}

// internal/closest_point.h's box query (the fidelity insertions' faces near a split triangle): the
// faces whose boxes meet a box, judged against a scan of every face
TEST_CASE("the tree's box query finds every face whose box meets the box", "[operators][fidelity]")
{
  Mesh m;
  REQUIRE(CGAL::IO::read_polygon_mesh(test_support::data_mesh("meshes/fandisk.off"), m));
  CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> tree(faces(m).first, faces(m).second, m);
  CGAL::Bbox_3 all;
  for(V v : vertices(m)) all += m.point(v).bbox();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t found = 0;
  for(int i = 0; i < 300; ++i) {
    double lo[3], hi[3];
    for(int k = 0; k < 3; ++k) {
      const double a = all.min(k) + (all.max(k) - all.min(k)) * unit(random), size = (all.max(k) - all.min(k)) * 0.1 * unit(random);
      lo[k] = a;
      hi[k] = a + size;
    }
    const CGAL::Bbox_3 b(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    std::vector<Mesh::Face_index> ours, judge;
    PR::internal::primitives_meeting_box(tree, b, std::back_inserter(ours));
    for(auto f : faces(m)) {
      CGAL::Bbox_3 fb;
      for(V v : vertices_around_face(halfedge(f, m), m)) fb += m.point(v).bbox();
      if(CGAL::do_overlap(fb, b)) judge.push_back(f);
    }
    std::sort(ours.begin(), ours.end());
    CHECK(ours == judge);
    found += judge.size();
  }
  CHECK(found > 300);
}

TEST_CASE("the untangling's face box grid finds every face whose box meets a box, after moves too", "[operators][intersections]")
{
  // a 10 x 10 grid with one huge triangle (its box covers the whole grid: kept aside), judged
  // against a scan of every face's box; then vertices move and their faces' boxes are updated
  Mesh m = square(10);
  const V far_a = m.add_vertex(Point(-5, -5, 1)), far_b = m.add_vertex(Point(6, -5, 1)), far_c = m.add_vertex(Point(0, 6, 1));
  REQUIRE(m.add_face(far_a, far_b, far_c) != Mesh::null_face());
  auto box_of = [&](Mesh::Face_index f) {
    CGAL::Bbox_3 b;
    for(V v : vertices_around_face(halfedge(f, m), m)) b += m.point(v).bbox();
    return b;
  };
  P::internal::Face_box_grid<Mesh> grid(faces(m), box_of);
  auto check = [&](const CGAL::Bbox_3& q) {
    std::vector<Mesh::Face_index> found, expected;
    grid.overlapping(q, found);
    for(auto f : faces(m)) if(CGAL::do_overlap(box_of(f), q)) expected.push_back(f);
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    std::sort(expected.begin(), expected.end());
    CHECK(found == expected);
    return expected.size();
  };
  std::size_t met = 0;
  for(int k = 0; k < 40; ++k) {   // query boxes from a point to a tenth of the square, and one larger than it
    const double x = 0.037 * (k % 27), y = 0.029 * (k % 34), s = k == 39 ? 3.0 : 0.0025 * k;
    met += check(CGAL::Bbox_3(x, y, -0.01, x + s, y + s, 0.01));
  }
  CHECK(met > 40);
  // the vertices of a row moved up and sideways (their faces' boxes grow), then the queries again
  for(V v : vertices(m)) {
    const Point p = m.point(v);
    if(p.z() != 0 || std::abs(p.y() - 0.5) > 1e-9) continue;
    m.point(v) = Point(p.x() + 0.13, p.y() + 0.2, 0.3);
    for(auto h : halfedges_around_target(halfedge(v, m), m))
      if(!is_border(h, m)) grid.update(face(h, m), box_of(face(h, m)));
  }
  for(int k = 0; k < 40; ++k) {
    const double x = 0.031 * (k % 31), y = 0.023 * (k % 43), s = 0.004 * k;
    check(CGAL::Bbox_3(x, y, 0.1, x + s, y + s, 0.35));
  }
}

// The local repair's crossing checks look for the faces near its region in a grid of the other
// faces' boxes (face_box_grid.h, Region_near_faces) while the region's vertices move and its edges
// flip, split and join again, kept or taken back. Judged by a scan of every face's box, and by
// CGAL's self_intersections on the faces that scan finds near the changed ones.
TEST_CASE("the local repair's grid finds the faces near its region through trials and after them", "[operators][intersections]")
{
  // two 10 x 10 sheets 0.02 apart (the other sheet's faces are near every region); the regions'
  // vertices are lifted through the upper sheet
  Mesh m = square(10);
  {
    Mesh upper = square(10);
    for(V v : vertices(upper)) upper.point(v) = Point(upper.point(v).x() + 0.003, upper.point(v).y(), 0.02);
    CGAL::copy_face_graph(upper, m);
  }
  typedef Mesh::Face_index F;
  typedef std::pair<F, F> Pair;
  auto box_of = [&](F f) {
    CGAL::Bbox_3 b;
    for(V v : vertices_around_face(halfedge(f, m), m)) b += m.point(v).bbox();
    return b;
  };
  P::internal::Region_near_faces<Mesh, decltype(box_of)> near(m, box_of);
  std::size_t found = 0;
  // every face whose box meets q is among the answers
  auto check_query = [&](const CGAL::Bbox_3& q) {
    std::vector<F> answer, expected;
    near(q, answer);
    for(F f : faces(m)) if(CGAL::do_overlap(box_of(f), q)) expected.push_back(f);
    std::sort(answer.begin(), answer.end());
    for(F f : expected) CHECK(std::binary_search(answer.begin(), answer.end(), f));
    found += expected.size();
  };
  // the pairs near `changed`: CGAL's among the faces whose boxes meet a changed face's box
  std::size_t crossing = 0;
  auto check_pairs = [&](const std::vector<V>& region) {
    const auto changed = PR::internal::faces_around(m, region);
    std::vector<F> nearby;
    for(F f : faces(m))
      for(F c : changed)
        if(CGAL::do_overlap(box_of(f), box_of(c))) { nearby.push_back(f); break; }
    std::vector<Pair> expected;
    CGAL::Polygon_mesh_processing::self_intersections(nearby, m, std::back_inserter(expected));
    for(Pair& p : expected) if(p.second < p.first) std::swap(p.first, p.second);
    std::sort(expected.begin(), expected.end());
    CHECK(PR::internal::intersecting_pairs_near(m, changed, near) == expected);
    crossing += expected.size();
    CGAL::Bbox_3 all;
    for(F c : changed) all += box_of(c);
    check_query(all);
  };
  std::vector<V> lower;
  for(V v : vertices(m)) if(m.point(v).z() == 0 && !is_border(v, m)) lower.push_back(v);
  for(std::size_t k = 0; k < 6; ++k) {
    // the region: an inner vertex of the lower sheet and its rings, two deep
    std::vector<V> region{lower[(k * 37 + 11) % lower.size()]};
    for(int ring = 0; ring < 2; ++ring) {
      const std::vector<V> inner = region;
      for(V x : inner)
        for(auto h : halfedges_around_target(halfedge(x, m), m))
          if(std::find(region.begin(), region.end(), source(h, m)) == region.end()) region.push_back(source(h, m));
    }
    near.begin(region);
    std::vector<std::pair<V, Point>> was;
    for(V x : region) was.push_back({x, m.point(x)});
    // moves: up through the upper sheet
    for(std::size_t i = 0; i < region.size(); ++i) {
      const Point p = m.point(region[i]);
      m.point(region[i]) = Point(p.x() + 0.004 * double(i % 3), p.y(), 0.015 + 0.01 * double(i % 4));
    }
    check_pairs(region);
    // a flip of an edge of the first vertex, a split of another
    const auto h = halfedge(region[0], m);
    CGAL::Euler::flip_edge(h, m);
    check_pairs(region);
    const auto g = next(h, m);
    const V a = source(g, m), b = target(g, m);
    const V added = Context::insert_vertex_on_edge(g, CGAL::midpoint(m.point(a), m.point(b)) + K::Vector_3(0, 0, 0.01), m);
    std::vector<V> with_added = region;
    with_added.push_back(added);
    check_pairs(with_added);
    if(k % 2 == 1) {   // taken back: the split vertex removed, the flip flipped back, the points put back
      Context::remove_vertex_on_edge(added, a, b, m);
      CGAL::Euler::flip_edge(h, m);
      for(const auto& [x, p] : was) m.point(x) = p;
      check_pairs(region);
    }
    near.end();
    // after it, boxes from a point to a fifth of the square all over both sheets
    for(int q = 0; q < 30; ++q) {
      const double x = 0.033 * (q % 31), y = 0.041 * ((q * 7) % 25), side = 0.007 * q;
      check_query(CGAL::Bbox_3(x, y, -0.01, x + side, y + side, 0.05));
    }
  }
  CHECK(found > 1000);
  CHECK(crossing > 0);
}

// internal/closest_point.h, the projections of every step: CGAL's AABB_tree::closest_point is the
// judge, on an input with features (fandisk), from points near the surface (a vertex moved a little,
// the relaxation's case, with the vertex as the hint) and far from it (no hint)
TEST_CASE("the nearer-first projection finds CGAL's closest point", "[projection]")
{
  Mesh m;
  REQUIRE(CGAL::IO::read_polygon_mesh(test_support::data_mesh("meshes/fandisk.off"), m));
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> Tree;
  Tree tree(faces(m).first, faces(m).second, m);
  tree.accelerate_distance_queries();
  CGAL::Bbox_3 box;
  for(V v : vertices(m)) box += m.point(v).bbox();
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) + CGAL::square(box.zmax() - box.zmin()));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<V> vs(vertices(m).begin(), vertices(m).end());
  double worst_near = 0, worst_far = 0;
  std::size_t other_face = 0;
  for(int i = 0; i < 2000; ++i) {
    const Point v = m.point(vs[std::size_t(random()) % vs.size()]);
    const double step = 0.02 * diagonal;
    const Point q(v.x() + step * unit(random), v.y() + step * unit(random), v.z() + step * unit(random));
    const double judge = std::sqrt(CGAL::to_double(tree.squared_distance(q)));
    const double ours = std::sqrt(CGAL::squared_distance(q, PR::internal::closest_point(tree, q, v)));
    worst_near = std::max(worst_near, std::abs(ours - judge));
    const Point far(box.xmin() + (box.xmax() - box.xmin()) * (1.5 * unit(random) + 0.5), box.ymin() + (box.ymax() - box.ymin()) * (1.5 * unit(random) + 0.5),
                    box.zmin() + (box.zmax() - box.zmin()) * (1.5 * unit(random) + 0.5));
    const auto hit = PR::internal::closest_point_and_primitive(tree, far);
    worst_far = std::max(worst_far, std::abs(std::sqrt(CGAL::squared_distance(far, hit.first)) - std::sqrt(CGAL::to_double(tree.squared_distance(far)))));
    // (the primitive given is the one the point lies on)
    const auto h = halfedge(hit.second, m);
    const K::Triangle_3 t(m.point(source(h, m)), m.point(target(h, m)), m.point(target(next(h, m), m)));
    if(std::sqrt(CGAL::squared_distance(t, hit.first)) > 1e-12 * diagonal) ++other_face;
  }
  CHECK(worst_near <= 1e-12 * diagonal);
  CHECK(worst_far <= 1e-12 * diagonal);
  CHECK(other_face == 0);
  // a query on the surface is its own closest point, also when it is the hint
  for(int i = 0; i < 200; ++i) {
    const Point v = m.point(vs[std::size_t(random()) % vs.size()]);
    CHECK(PR::internal::closest_point(tree, v, v) == v);
    CHECK(CGAL::squared_distance(PR::internal::closest_point(tree, v), v) <= CGAL::square(1e-12 * diagonal));
  }
  // trees of one, two and three triangles (CGAL's traversal takes them apart)
  for(std::size_t n = 1; n <= 3; ++n) {
    std::vector<Mesh::Face_index> some(faces(m).begin(), faces(m).begin() + std::ptrdiff_t(n));
    Tree small(some.begin(), some.end(), m);
    for(int i = 0; i < 100; ++i) {
      const Point q(box.xmin() + (box.xmax() - box.xmin()) * unit(random), box.ymin() + (box.ymax() - box.ymin()) * unit(random),
                    box.zmin() + (box.zmax() - box.zmin()) * unit(random));
      const auto hit = PR::internal::closest_point_and_primitive(small, q);
      CHECK(std::abs(std::sqrt(CGAL::squared_distance(q, hit.first)) - std::sqrt(CGAL::to_double(small.squared_distance(q)))) <= 1e-12 * diagonal);
      CHECK(std::find(some.begin(), some.end(), hit.second) != some.end());
    }
  }
}

// internal/closest_point.h's distance filter (a leaf's triangle or segment passed over when its
// distance in double is surely beyond the best so far): CGAL's AABB_tree::closest_point is the
// judge, on what makes that distance least exact -- a fan of long, thin triangles far from the
// origin, triangles with collinear or equal corners, needles -- and on a tree of segments (the
// feature curves') with a segment of zero length
TEST_CASE("the projection's distance filter keeps CGAL's closest point", "[projection]")
{
  const K::Vector_3 far_away(1.0e4, -3.0e3, 7.0e3);
  Mesh m;
  const V centre = m.add_vertex(Point(0, 0, 0) + far_away);
  std::vector<V> rim;
  const int n = 300;
  for(int i = 0; i < n; ++i) {
    const double a = 2 * CGAL_PI * i / n;
    rim.push_back(m.add_vertex(Point(std::cos(a), std::sin(a), 0.05 * std::sin(7 * a)) + far_away));
  }
  for(int i = 0; i < n; ++i) m.add_face(centre, rim[std::size_t(i)], rim[std::size_t((i + 1) % n)]);
  // beside the fan: a face with collinear corners and one with two equal corners
  const V a = m.add_vertex(Point(2, 0, 0) + far_away), b = m.add_vertex(Point(2.5, 0.1, 0) + far_away),
          c = m.add_vertex(Point(3, 0.2, 0) + far_away), d = m.add_vertex(Point(2, 1, 0.3) + far_away),
          e = m.add_vertex(Point(2, 1, 0.3) + far_away), f = m.add_vertex(Point(2.4, 1.2, 0.1) + far_away);
  m.add_face(a, b, c);
  m.add_face(d, e, f);
  REQUIRE(num_faces(m) == std::size_t(n + 2));
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> Tree;
  Tree tree(faces(m).first, faces(m).second, m);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<V> vs(vertices(m).begin(), vertices(m).end());
  double worst = 0;
  for(int i = 0; i < 3000; ++i) {
    const Point v = m.point(vs[std::size_t(random()) % vs.size()]);
    const double step = i % 3 == 0 ? 1e-9 : i % 3 == 1 ? 0.01 : 0.5;
    const Point q(v.x() + step * unit(random), v.y() + step * unit(random), v.z() + step * unit(random));
    const double judge = std::sqrt(CGAL::to_double(tree.squared_distance(q)));
    worst = std::max(worst, std::abs(std::sqrt(CGAL::squared_distance(q, PR::internal::closest_point(tree, q, v))) - judge));
    worst = std::max(worst, std::abs(std::sqrt(CGAL::squared_distance(q, PR::internal::closest_point(tree, q))) - judge));
  }
  CHECK(worst <= 1e-9);   // (a few ulps of coordinates near 1e4)

  // needles (a corner a height h off the opposite side, h down to 1e-8 of the length), a query on
  // the needle, and as hint a point of a triangle 1e-4 away: a needle's face distance in double is
  // not to be trusted there, and the needle is the closest
  typedef std::vector<K::Triangle_3>::const_iterator Triangle_iterator;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Triangle_iterator>>> Triangle_tree;
  std::uniform_real_distribution<double> fraction(0, 1);
  std::size_t farther = 0;
  for(const double offset : {0.0, 1.0e4})
    for(const double h : {1e-5, 1e-7, 1e-8})
      for(int i = 0; i < 300; ++i) {
        const K::Vector_3 o(offset, offset, offset);
        const double t = 0.2 + 0.6 * fraction(random);
        const Point a0 = Point(0, 0, 0) + o, b0 = Point(1, 0.3, 0.2) + o, c0 = Point(t, 0.3 * t + h, 0.2 * t) + o;
        const std::vector<K::Triangle_3> triangles{K::Triangle_3(a0, b0, c0),
                                                   K::Triangle_3(Point(-1, -1, 1e-4) + o, Point(2, -1, 1e-4) + o, Point(0, 2, 1e-4) + o)};
        Triangle_tree needle(triangles.cbegin(), triangles.cend());
        double wa = fraction(random), wb = fraction(random), wc = fraction(random);
        const double sum = wa + wb + wc;
        wa /= sum; wb /= sum; wc /= sum;
        const Point q(wa * a0.x() + wb * b0.x() + wc * c0.x(), wa * a0.y() + wb * b0.y() + wc * c0.y(), wa * a0.z() + wb * b0.z() + wc * c0.z());
        const Point hint = triangles[1].supporting_plane().projection(q);
        const double judge = CGAL::to_double(needle.squared_distance(q));
        if(CGAL::to_double(CGAL::squared_distance(q, PR::internal::closest_point(needle, q, hint))) > judge * (1 + 1e-9) + 1e-24) ++farther;
      }
  CHECK(farther == 0);

  typedef std::vector<K::Segment_3>::const_iterator Iterator;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_segment_primitive<K, Iterator>>> Segment_tree;
  std::vector<K::Segment_3> segments;
  Point last(0.3, 0.2, 0.1);
  for(int i = 0; i < 500; ++i) {
    const Point next = i == 250 ? last : Point(last.x() + 0.01 * unit(random) + 0.004, last.y() + 0.01 * unit(random), last.z() + 0.002 * unit(random));
    segments.emplace_back(last, next);
    last = next;
  }
  Segment_tree curves(segments.cbegin(), segments.cend());
  double worst_segment = 0;
  for(int i = 0; i < 3000; ++i) {
    const K::Segment_3& s = segments[std::size_t(random()) % segments.size()];
    const Point v = CGAL::midpoint(s.source(), s.target());
    const double step = i % 2 == 0 ? 0.002 : 0.05;
    const Point q(v.x() + step * unit(random), v.y() + step * unit(random), v.z() + step * unit(random));
    const double judge = std::sqrt(CGAL::to_double(curves.squared_distance(q)));
    worst_segment = std::max(worst_segment, std::abs(std::sqrt(CGAL::squared_distance(q, PR::internal::closest_point(curves, q, v))) - judge));
  }
  CHECK(worst_segment <= 1e-14);
}

// A projection onto the feature curves from a start point (the driver's feature-edge test asks
// only whether the curves come within a distance: its search starts from a point at that
// distance): CGAL's AABB_tree::closest_point on the curves' segments is the judge; the answer is
// its closest point when that is nearer than the start, else the start itself.
TEST_CASE("a projection onto the features from a start point finds CGAL's closest point within the start's distance", "[projection]")
{
  // a square of 6 x 6 cells folded 90 degrees along x = 0.5: the fold and the border are features
  Mesh m = square(6);
  for(V v : vertices(m)) {
    const Point p = m.point(v);
    if(p.x() > 0.5) m.point(v) = Point(0.5, p.y(), p.x() - 0.5);
  }
  const PR::Feature_set<Mesh> features = PR::detect_features(m);
  std::vector<K::Segment_3> segments;
  for(auto e : edges(m))
    if(features.is_feature(e)) segments.emplace_back(m.point(source(halfedge(e, m), m)), m.point(target(halfedge(e, m), m)));
  REQUIRE(segments.size() > 24);
  CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_segment_primitive<K, std::vector<K::Segment_3>::const_iterator>>> judge(segments.begin(), segments.end());
  const PR::Lloyd_relaxer<Mesh, K> relaxer(m, features);
  std::size_t nearer = 0, beyond = 0;
  for(int k = 0; k < 400; ++k) {
    const Point q(0.013 * (k % 83), 0.017 * (k % 61), 0.011 * (k % 47) - 0.1);
    const Point c = judge.closest_point(q);
    const double d2 = CGAL::squared_distance(q, c);
    // a start at 0.5 to 1.5 times the curves' distance, in one of three directions
    const double f = 0.5 + double(k % 11) / 10;
    const K::Vector_3 dir = k % 3 == 0 ? K::Vector_3(1, 0, 0) : k % 3 == 1 ? K::Vector_3(0, -0.6, 0.8) : K::Vector_3(0, 0, -1);
    const Point start = q + f * std::sqrt(d2) * dir;
    const Point got = relaxer.project_on_features(q, start);
    if(CGAL::squared_distance(q, start) > d2 * (1 + 1e-9)) {
      ++nearer;
      CHECK(CGAL::squared_distance(q, got) == Approx(d2).margin(1e-15));   // (the same point, or one as near)
    } else if(CGAL::squared_distance(q, start) < d2 * (1 - 1e-9)) {
      ++beyond;
      CHECK(got == start);
    }
  }
  CHECK(nearer > 100);
  CHECK(beyond > 100);
}

// internal/vector_angle.h, the relaxation's and the tessellation's triangle angles: std::atan2 is the judge
TEST_CASE("the vector angle is atan2's to the last bits", "[projection]")
{
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  double worst = 0;
  for(int i = 0; i < 1000000; ++i) {
    const double y = std::abs(unit(random)) * std::pow(10.0, 6 * unit(random)), x = unit(random) * std::pow(10.0, 6 * unit(random));
    worst = std::max(worst, std::abs(PR::internal::vector_angle(y, x) - std::atan2(y, x)));
  }
  CHECK(worst <= 1e-15);
  for(double x : {0.0, -0.0, 1.0, -1.0, 1e-300, -1e300}) CHECK(PR::internal::vector_angle(0.0, x) == std::atan2(0.0, x));
  for(double y : {1e-300, 1.0, 1e300}) {
    CHECK(PR::internal::vector_angle(y, 0.0) == Approx(std::atan2(y, 0.0)).epsilon(1e-15));
    CHECK(PR::internal::vector_angle(y, -0.0) == Approx(std::atan2(y, -0.0)).epsilon(1e-15));
  }
  // subnormal and extreme arguments
  const double tiny = std::numeric_limits<double>::denorm_min();
  for(double y : {tiny, 1e-310, 1.0, 1e308})
    for(double x : {tiny, -tiny, 1e-310, -1e-310, 1.0, -1.0, 1e308, -1e308})
      CHECK(std::abs(PR::internal::vector_angle(y, x) - std::atan2(y, x)) <= 1e-15);
  CHECK(std::isnan(PR::internal::vector_angle(std::nan(""), 1.0)));
  CHECK(PR::internal::vector_angle(std::numeric_limits<double>::infinity(), 1.0) == std::atan2(std::numeric_limits<double>::infinity(), 1.0));
}
