// Tests of the mutual tessellation (paper §6.1): samples inserted, original vertices removed,
// topology, corners and feature curves kept.
#include "analytic_meshes.h"
#include "test_support.h"

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Tessellation/internal/polygon_cdt.h>
#include <Poisson_remesh/Tessellation/mutual_tessellation.h>
#include <Poisson_remesh/poisson_disk_sample.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
namespace PR = Poisson_remesh;

template <class M>
using Samples = std::vector<PR::Poisson_sample<M, Point>>;

/// Consecutive samples along every feature curve of `fs` (on `in`), as pairs of sample indices.
template <class M>
std::vector<std::pair<std::size_t, std::size_t>>
consecutive_feature_samples(const M& in, const PR::Feature_set<M>& fs, const Samples<M>& s)
{
  typedef typename boost::graph_traits<M>::vertex_descriptor vertex_descriptor;
  // position of a curve point: (curve, halfedge rank + t)
  std::map<std::pair<vertex_descriptor, vertex_descriptor>, std::pair<std::size_t, std::size_t>> rank; // (src, tgt) -> (curve, k)
  for(std::size_t c = 0; c < fs.curves.size(); ++c)
    for(std::size_t k = 0; k < fs.curves[c].halfedges.size(); ++k) {
      const auto h = fs.curves[c].halfedges[k];
      rank[{source(h, in), target(h, in)}] = {c, k};
    }
  std::vector<std::vector<std::pair<double, std::size_t>>> along(fs.curves.size());
  for(std::size_t i = 0; i < s.size(); ++i) {
    if(s[i].kind == PR::Sample_kind::surface) continue;
    const auto h0 = halfedge(s[i].location.first, in);
    const vertex_descriptor fv[3] = {source(h0, in), target(h0, in), target(next(h0, in), in)};
    const auto& b = s[i].location.second;
    for(int k = 0; k < 3; ++k)
      for(int l = 0; l < 3; ++l) {
        if(k == l) continue;
        const int z = 3 - k - l;
        if(b[z] > 1e-12) continue;
        auto it = rank.find({fv[k], fv[l]});
        if(it == rank.end()) continue;
        // point = b[k] fv[k] + b[l] fv[l]: parameter along (fv[k] -> fv[l]) is b[l]
        along[it->second.first].push_back({double(it->second.second) + b[l], i});
      }
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for(std::size_t c = 0; c < along.size(); ++c) {
    auto& a = along[c];
    std::sort(a.begin(), a.end());
    // a corner at a curve end is seen twice (end of one halfedge, start of the next): dedupe
    a.erase(std::unique(a.begin(), a.end(), [](const auto& x, const auto& y) { return x.second == y.second; }), a.end());
    for(std::size_t j = 1; j < a.size(); ++j) pairs.push_back({a[j - 1].second, a[j].second});
    if(fs.curves[c].closed && a.size() > 2) pairs.push_back({a.back().second, a.front().second});
  }
  return pairs;
}

/// The edges of `out` that a flip of §6.1 would still take: an edge inside the surface and on no
/// feature curve (`feature`: vertex pairs, both ways) whose flip raises the smallest angle of its
/// two triangles (by more than a margin), makes an edge that is not there yet, leaves both its
/// ends more than three edges, turns no new triangle's normal more than `beta` degrees from an old
/// one's and changes the angle between the two normals by at most `gamma` degrees. The
/// tessellation flips until there is none.
template <class M>
std::size_t flippable_edges(const M& out,
                            const std::set<std::pair<typename boost::graph_traits<M>::vertex_descriptor, typename boost::graph_traits<M>::vertex_descriptor>>& feature,
                            double beta, double gamma)
{
  typedef K::Vector_3 V;
  auto p = [&](auto v) { return get(CGAL::vertex_point, out, v); };
  auto angle = [](const V& a, const V& b) {
    const double c = CGAL::to_double(a * b) / std::sqrt(CGAL::to_double(a.squared_length() * b.squared_length()));
    return std::acos(std::max(-1.0, std::min(1.0, c))) * 180 / CGAL_PI;
  };
  auto smallest = [&](const Point& a, const Point& b, const Point& c) {
    return std::min({angle(b - a, c - a), angle(a - b, c - b), angle(a - c, b - c)});
  };
  const double margin = 1e-4;   // (degrees: only a flip that gains this much counts)
  std::size_t n = 0;
  for(auto e : edges(out)) {
    const auto h = halfedge(e, out);
    if(CGAL::is_border_edge(h, out)) continue;
    const auto a = source(h, out), b = target(h, out);
    if(feature.count({a, b})) continue;
    const auto c = target(next(h, out), out), d = target(next(opposite(h, out), out), out);
    if(c == d || halfedge(c, d, out).second || degree(a, out) <= 3 || degree(b, out) <= 3) continue;
    const double before = std::min(smallest(p(a), p(b), p(c)), smallest(p(b), p(a), p(d)));
    const double after = std::min(smallest(p(c), p(a), p(d)), smallest(p(d), p(b), p(c)));
    if(!(after > before + margin)) continue;
    const V n1 = CGAL::cross_product(p(b) - p(a), p(c) - p(a)), n2 = CGAL::cross_product(p(a) - p(b), p(d) - p(b));
    const V m1 = CGAL::cross_product(p(a) - p(c), p(d) - p(c)), m2 = CGAL::cross_product(p(b) - p(d), p(c) - p(d));
    bool guarded = false;
    for(const V& m : {m1, m2})
      for(const V& o : {n1, n2}) guarded = guarded || angle(m, o) > beta - margin;
    guarded = guarded || std::abs(angle(m1, m2) - angle(n1, n2)) > gamma - margin;
    if(!guarded) ++n;
  }
  return n;
}

struct Figures
{
  std::size_t flippable = 0;   ///< edges a flip of §6.1 would still take (flippable_edges)
  std::size_t leftovers = 0, self_intersections = 0, unjoined_feature_pairs = 0, feature_pairs = 0;
  std::size_t corners_kept = 0;   ///< corners (at the sampling scale) found among the output's vertex points
  std::size_t corners = 0;        ///< corners at the sampling scale
};

/// Samples `in` at `factor` times its vertex count, tessellates and checks §6.1's promises.
template <class M>
Figures tessellate_and_check(const std::string& name, const M& in, double factor)
{
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = std::size_t(factor * double(num_vertices(in)));
  Samples<M> samples;
  // the tessellation must see the features the sampler sampled: those at the sampling scale
  const auto np = PR::parameters::target_vertex_count(n).random_seed(3u);
  const double radius = PR::internal::sampling_radius_from_parameters(in, get(CGAL::vertex_point, in), np);
  PR::poisson_disk_sample(in, std::back_inserter(samples), np);
  const auto fs = PR::detect_features(in, PR::parameters::minimum_feature_length(PR::feature_length_in_radii * radius));
  const auto t1 = std::chrono::steady_clock::now();
  M out;
  const auto r = PR::mutual_tessellation(in, samples, fs, out);
  const auto t2 = std::chrono::steady_clock::now();

  const PR::Quality_report qin = PR::quality_report(in, PR::parameters::check_self_intersections(false));
  const PR::Quality_report q = PR::quality_report(out);
  Figures fig;
  fig.leftovers = r.leftover_vertices.size();
  fig.self_intersections = q.number_of_self_intersecting_face_pairs;

  INFO(name << " x" << factor);
  CHECK(CGAL::is_valid_polygon_mesh(out));
  CHECK(CGAL::is_triangle_mesh(out));
  CHECK(CGAL::is_closed(out) == CGAL::is_closed(in));
  CHECK(q.number_of_components == qin.number_of_components);
  CHECK(q.number_of_border_cycles == qin.number_of_border_cycles);
  CHECK(q.euler_characteristic == qin.euler_characteristic);
  CHECK(num_vertices(out) == samples.size() + r.leftover_vertices.size());
  REQUIRE(r.vertices.size() == num_vertices(out));
  for(const auto& v : r.vertices)
    if(v.sample != r.no_sample) {
      CHECK(get(CGAL::vertex_point, out, v.vertex) == samples[v.sample].point);
      CHECK(r.sample_vertices[v.sample] == v.vertex);
    }
  std::size_t corners = 0;
  for(const auto& s : samples) if(s.kind == PR::Sample_kind::corner) ++corners;
  CHECK(r.number_of_vertex_samples >= corners);   // corners are input vertices, marked not inserted

  {
    std::set<Point> out_points;
    for(auto v : vertices(out)) out_points.insert(get(CGAL::vertex_point, out, v));
    for(auto c : fs.corners) fig.corners_kept += out_points.count(get(CGAL::vertex_point, in, c));
    fig.corners = fs.corners.size();
  }

  // consecutive feature samples are joined by an output edge
  std::set<std::pair<typename boost::graph_traits<M>::vertex_descriptor, typename boost::graph_traits<M>::vertex_descriptor>> feature;
  for(const auto& pr : consecutive_feature_samples(in, fs, samples)) {
    ++fig.feature_pairs;
    const auto a = r.sample_vertices[pr.first], b = r.sample_vertices[pr.second];
    if(!halfedge(a, b, out).second) ++fig.unjoined_feature_pairs;
    feature.insert({a, b});
    feature.insert({b, a});
  }
  const PR::Mutual_tessellation_settings settings;
  fig.flippable = flippable_edges(out, feature, settings.beta, settings.gamma);
  // (the flips after each removal pass look only where the pass changed the mesh: none is missed;
  // an edge the repair flipped to undo a crossing may be one the angles would flip back)
  CHECK(fig.flippable <= r.number_of_repair_flips);

  std::cout << "[tessellation] " << name << " x" << factor << ": V in " << num_vertices(in) << ", samples "
            << samples.size() << ", V out " << num_vertices(out) << ", leftovers " << fig.leftovers
            << ", chi " << qin.euler_characteristic << " -> " << q.euler_characteristic
            << ", self-intersecting pairs " << fig.self_intersections << ", flips " << r.number_of_flips << " (+" << r.number_of_repair_flips << " repair)"
            << ", flippable left " << fig.flippable << ", passes " << r.number_of_removal_passes << " (refused: star " << r.refused_star << ", feature edge "
            << r.refused_feature_edge << ", pocket " << r.refused_pocket << ", triangulation " << r.refused_triangulation << ")" << ", feature pairs joined "
            << (fig.feature_pairs - fig.unjoined_feature_pairs) << "/" << fig.feature_pairs
            << "; min angle " << q.min_angle << ", mean min angle " << q.mean_min_angle
            << ", irregular " << q.irregular_share << "; sampling "
            << std::chrono::duration<double>(t1 - t0).count() << " s, tessellation "
            << std::chrono::duration<double>(t2 - t1).count() << " s" << std::endl;
  return fig;
}

Mesh data(const std::string& name)
{
  Mesh m;
  PR::read_surface_mesh(test_support::data_mesh(name), m);
  return m;
}

} // namespace

TEST_CASE("tessellated sphere, torus and cube keep topology, corners and samples", "[tessellation]")
{
  const std::vector<std::pair<std::string, Mesh>> meshes = {
    {"sphere", analytic::sphere(24, 12).to_mesh<Mesh>()},
    {"torus", analytic::torus(32, 16).to_mesh<Mesh>()},
    {"cube", analytic::cube(8).to_mesh<Mesh>()}};
  for(const auto& nm : meshes)
    for(double factor : {1.0, 0.5}) {
      const Figures f = tessellate_and_check(nm.first, nm.second, factor);
      CHECK(f.leftovers == 0);
      CHECK(f.self_intersections == 0);
      CHECK(f.unjoined_feature_pairs == 0);
    }
}

TEST_CASE("tessellated plane and cylinder keep their borders", "[tessellation]")
{
  const std::vector<std::pair<std::string, Mesh>> meshes = {
    {"plane", analytic::plane(12, 12).to_mesh<Mesh>()},
    {"cylinder", analytic::cylinder(24, 12).to_mesh<Mesh>()}};
  for(const auto& nm : meshes)
    for(double factor : {1.0, 0.5}) {
      const Figures f = tessellate_and_check(nm.first, nm.second, factor);
      CHECK(f.leftovers == 0);
      CHECK(f.self_intersections == 0);
      CHECK(f.feature_pairs > 0);
      CHECK(f.unjoined_feature_pairs == 0);
    }
}

TEST_CASE("tessellated fandisk joins consecutive feature samples", "[tessellation]")
{
  const Mesh m = data("meshes/fandisk.off");
  for(double factor : {1.0, 0.5}) {
    const Figures f = tessellate_and_check("fandisk", m, factor);
    CHECK(f.corners >= 20);
    CHECK(f.corners_kept == f.corners);
    CHECK(f.feature_pairs > 0);
    CHECK(f.unjoined_feature_pairs == 0);
    CHECK(f.leftovers == 0);
    CHECK(f.self_intersections == 0);
  }
}

TEST_CASE("tessellated elephant keeps topology with at most one original vertex left", "[tessellation]")
{
  const Mesh m = data("meshes/elephant.off");
  for(double factor : {1.0, 0.5}) {
    const Figures f = tessellate_and_check("elephant", m, factor);
    // (seed 3: none at x1; at x0.5 one vertex on a crease that turns sharply at the scale of a
    // ring but not at the sampling scale is refused, and reported)
    CHECK(f.leftovers <= 1);
    CHECK(f.self_intersections == 0);
  }
}

TEST_CASE("tessellated triceratops keeps topology despite skinny input triangles", "[tessellation]")
{
  const Mesh m = data("meshes/triceratops.off");
  for(double factor : {1.0, 0.5}) {
    const Figures f = tessellate_and_check("triceratops", m, factor);
    // The thin horns and frill are sampled with few samples across. Measured with seed 3: x1 1
    // leftover and no intersecting pair, x0.5 no leftover and 2 pairs (on a horn), since the
    // features are judged at the sampling scale, crease curves may merge into an existing feature
    // edge and the last original vertices are collapsed onto a sample (before: 2-4 leftovers, up
    // to 6 pairs). The remesher's relaxation removes the pairs (see test_remesh.cpp).
    CHECK(f.leftovers <= 1);
    CHECK(f.self_intersections <= (factor < 1 ? 2u : 0u));
  }
}

TEST_CASE("mutual tessellation runs on Polyhedron_3", "[tessellation]")
{
  typedef CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3> Polyhedron;
  Polyhedron p = analytic::cube(4).to_mesh<Polyhedron>();
  CGAL::set_halfedgeds_items_id(p);   // CGAL's rule: a const mesh's internal ids must be initialized
  const Figures f = tessellate_and_check("cube (Polyhedron_3)", p, 1.0);
  CHECK(f.leftovers == 0);
  CHECK(f.unjoined_feature_pairs == 0);
}

namespace {
// the angle at corner o of triangle (o, a, b) by the law of cosines (the judge of the tessellator's
// angles below)
double law_of_cosines_angle(const std::array<double, 3>& o, const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  double ab = 0, oa = 0, ob = 0;
  for(int i = 0; i < 3; ++i) {
    ab += (a[i] - b[i]) * (a[i] - b[i]);
    oa += (a[i] - o[i]) * (a[i] - o[i]);
    ob += (b[i] - o[i]) * (b[i] - o[i]);
  }
  return std::acos(std::max(-1.0, std::min(1.0, (oa + ob - ab) / (2 * std::sqrt(oa * ob)))));
}
} // namespace

TEST_CASE("the tessellation's smallest angle of a triangle is the least of its three angles", "[tessellation]")
{
  // the tessellator takes the angle opposite the shortest side; judged here by the law of
  // cosines at all three corners
  typedef std::array<double, 3> V;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t checked = 0;
  for(int k = 0; k < 20000; ++k) {
    V p[3];
    for(auto& x : p) x = {u(rng), u(rng), u(rng)};
    if(k % 4 == 1) p[2] = {0.5 * (p[0][0] + p[1][0]) + 1e-3 * u(rng), 0.5 * (p[0][1] + p[1][1]), 0.5 * (p[0][2] + p[1][2])};   // flat
    if(k % 4 == 2) p[2] = {p[0][0] + 1e-3 * u(rng), p[0][1] + 1e-3 * u(rng), p[0][2]};                                          // needle
    const double want = std::min({law_of_cosines_angle(p[0], p[1], p[2]), law_of_cosines_angle(p[1], p[2], p[0]), law_of_cosines_angle(p[2], p[0], p[1])});
    for(int r = 0; r < 3; ++r) {   // every order of the corners
      const double got = PR::internal::smallest_angle(p[r], p[(r + 1) % 3], p[(r + 2) % 3]);
      REQUIRE(got == Approx(want).margin(1e-6));
      ++checked;
    }
  }
  CHECK(checked == 60000);
}

TEST_CASE("the flips' tangent of the smallest angle turns down only what the angles turn down", "[tessellation]")
{
  // the flips turn an edge down without its angles when the new triangles' least tangent is no
  // larger than the old ones': judged by the law of cosines, that must never turn down a pair
  // whose angles differ by more than the flips' 1e-9; a triangle without a positive cosine at
  // that corner (here: three equal points) has a NaN tangent, and its angle is left to atan2
  typedef std::array<double, 3> V;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  auto triangle = [&](int k, V* p) {
    for(int i = 0; i < 3; ++i) p[i] = {u(rng), u(rng), u(rng)};
    if(k % 5 == 1) p[2] = {0.5 * (p[0][0] + p[1][0]) + 1e-4 * u(rng), 0.5 * (p[0][1] + p[1][1]), 0.5 * (p[0][2] + p[1][2])};   // flat
    if(k % 5 == 2) p[2] = {p[0][0] + 1e-4 * u(rng), p[0][1] + 1e-4 * u(rng), p[0][2]};                                           // needle
    if(k % 5 == 3) p[1] = p[2] = p[0];                                                                                            // a point
  };
  std::size_t turned_down = 0, nan = 0;
  for(int k = 0; k < 20000; ++k) {
    V p[3], q[3];
    triangle(k, p);
    triangle(k / 5, q);
    const double tp = PR::internal::smallest_angle_tangent(p[0], p[1], p[2]), tq = PR::internal::smallest_angle_tangent(q[0], q[1], q[2]);
    auto least = [&](const V* x) { return std::min({law_of_cosines_angle(x[0], x[1], x[2]), law_of_cosines_angle(x[1], x[2], x[0]), law_of_cosines_angle(x[2], x[0], x[1])}); };
    if(std::isnan(tp)) { ++nan; REQUIRE(k % 5 == 3); continue; }
    REQUIRE(tp >= 0);
    REQUIRE(std::atan(tp) == Approx(least(p)).margin(1e-6));
    if(std::isnan(tq)) continue;
    if(tp <= tq) {
      ++turned_down;
      REQUIRE(least(p) <= least(q) + 1e-9);
    }
  }
  CHECK(nan == 4000);
  CHECK(turned_down > 5000);
}

TEST_CASE("a star-shaped layout is triangulated directly into CGAL's constrained Delaunay triangles", "[tessellation]")
{
  // Layouts as the removal makes them (paper §6.1: a star's ring around the origin, full or half),
  // with random angles and radii, and some on one circle (cocircular: not unique). The judge is
  // CGAL's constrained Delaunay triangulation of the polygon, its inside faces told by their
  // centroids (CGAL::bounded_side_2).
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K2;
  typedef CGAL::Constrained_Delaunay_triangulation_2<K2, CGAL::Default, CGAL::Exact_predicates_tag> CDT;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t found = 0, cocircular = 0, tried = 0, regular_tried = 0;
  std::vector<std::array<std::size_t, 3>> tris;
  for(int it = 0; it < 20000; ++it) {
    std::size_t n = 3 + std::size_t(unit(rng) * 10);
    const bool full = unit(rng) < 0.7, regular = it % 10 == 0;
    std::vector<std::array<double, 2>> pts;
    if(regular) {
      // points with integer coordinates on the circle of radius 5, in angle order (exactly
      // cocircular): the first, every other one with probability 1/2, at most a quarter turn apart
      const double circle[12][2] = {{5, 0}, {4, 3}, {3, 4}, {0, 5}, {-3, 4}, {-4, 3}, {-5, 0}, {-4, -3}, {-3, -4}, {0, -5}, {3, -4}, {4, -3}};
      const std::size_t last = full ? 11 : 6;
      std::size_t since = 0;
      for(std::size_t i = 0; i <= last; ++i, ++since)
        if(i == 0 || i == last || since >= 3 || unit(rng) < 0.5) { pts.push_back({circle[i][0], circle[i][1]}); since = 0; }
      n = pts.size();
    } else {
      // (a half layout's sectors leave room for a half turn: each under it, so star-shaped)
      std::vector<double> sector(full ? n : n - 1);
      double total = 0;
      for(double& a : sector) { a = 0.3 + unit(rng); total += a; }
      double cum = 0;
      for(std::size_t i = 0; i < n; ++i) {
        const double r = 0.3 + 1.4 * unit(rng), theta = (full ? 2 : 1) * CGAL_PI * cum / total;
        pts.push_back({r * std::cos(theta), r * std::sin(theta)});
        if(i < sector.size()) cum += sector[i];
      }
    }
    std::vector<K2::Point_2> poly;
    for(const auto& x : pts) poly.emplace_back(x[0], x[1]);
    const auto outcome = PR::internal::polygon_cdt(pts, full, tris);
    (regular ? regular_tried : tried) += 1;
    if(outcome == PR::internal::Polygon_cdt_outcome::cocircular) { ++cocircular; continue; }
    if(outcome != PR::internal::Polygon_cdt_outcome::found) continue;
    if(!regular) ++found;
    CDT cdt;
    for(std::size_t i = 0; i < n; ++i) cdt.insert_constraint(poly[i], poly[(i + 1) % n]);
    std::set<std::array<K2::Point_2, 3>> judge, mine;
    auto canonical = [](std::array<K2::Point_2, 3> t) {
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      return t;
    };
    for(auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      const std::array<K2::Point_2, 3> t = {f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()};
      if(CGAL::bounded_side_2(poly.begin(), poly.end(), CGAL::centroid(t[0], t[1], t[2]), K2()) == CGAL::ON_BOUNDED_SIDE) judge.insert(canonical(t));
    }
    CHECK(tris.size() + 2 == n);
    for(const auto& t : tris) {
      REQUIRE(CGAL::orientation(poly[t[0]], poly[t[1]], poly[t[2]]) == CGAL::LEFT_TURN);
      mine.insert(canonical({poly[t[0]], poly[t[1]], poly[t[2]]}));
    }
    INFO("layout " << it << ", " << n << " vertices, " << (full ? "full" : "half"));
    CHECK(mine == judge);
  }
  std::cout << "[tessellation] star layouts: " << found << " of " << tried << " triangulated directly, " << cocircular
            << " cocircular (of " << regular_tried << " on one circle)" << std::endl;
  // (the direct path serves nearly every layout with random angles; those on one circle are cocircular)
  CHECK(found >= tried * 95 / 100);
  CHECK(cocircular >= regular_tried * 8 / 10);

  // layouts the direct path must leave to CGAL: not starting on the positive x axis, two vertices
  // out of angle order, a sector of a half turn or more, and a half layout whose closing side
  // passes just above the origin with a vertex below it (not simple)
  std::vector<std::array<double, 2>> ring = {{1, 0}, {0.3, 0.9}, {-0.8, 0.5}, {-0.7, -0.6}, {0.4, -0.9}};
  auto refused = [&](const std::vector<std::array<double, 2>>& layout, bool full) {
    return PR::internal::polygon_cdt(layout, full, tris) == PR::internal::Polygon_cdt_outcome::not_found;
  };
  CHECK(!refused(ring, true));
  std::vector<std::array<double, 2>> turned = ring;
  for(auto& x : turned) x = {0.8 * x[0] - 0.6 * x[1], 0.6 * x[0] + 0.8 * x[1]};
  CHECK(refused(turned, true));
  std::vector<std::array<double, 2>> swapped = ring;
  std::swap(swapped[1], swapped[2]);
  CHECK(refused(swapped, true));
  CHECK(refused({{1, 0}, {0.3, 0.9}, {-0.8, 0.5}, {-0.7, 0.1}}, true));   // (the last sector: over a half turn)
  CHECK(!refused({{1, 0}, {0.5, 1e-13}, {0, 1}, {-1, 1e-13}}, false));
  CHECK(refused({{1, 0}, {0.5, 1e-14}, {0, 1}, {-1, 1e-13}}, false));   // (0.5, 1e-14) lies below the closing side
}
