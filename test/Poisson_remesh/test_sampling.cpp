// Tests of the sampling stage (paper §3, §4): feature detection and feature sampling.
#include "analytic_meshes.h"
#include "test_support.h"

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Surface_mesh.h>

#include <catch2/catch.hpp>

#include <cmath>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
namespace PR = Poisson_remesh;
namespace PMP = CGAL::Polygon_mesh_processing;

TEST_CASE("features of a cube: 8 corners, 12 straight curves", "[features]")
{
  const Mesh m = analytic::cube(4).to_mesh<Mesh>();
  const auto fs = PR::detect_features(m);
  CHECK(fs.corners.size() == 8);
  REQUIRE(fs.curves.size() == 12);
  CHECK(fs.number_of_feature_edges == 48);
  CHECK(fs.number_of_removed_false_features == 0);
  for(const auto& c : fs.curves) {
    CHECK_FALSE(c.closed);
    CHECK(c.halfedges.size() == 4);
    CHECK(c.length == Approx(1));
    CHECK(fs.is_corner(source(c.halfedges.front(), m)));
    CHECK(fs.is_corner(target(c.halfedges.back(), m)));
    for(std::size_t i = 1; i < c.halfedges.size(); ++i) CHECK(target(c.halfedges[i - 1], m) == source(c.halfedges[i], m));
  }
  SECTION("even samples along the edges, at least the spacing apart") {
    const auto samples = PR::feature_sample_locations(m, get(CGAL::vertex_point, m), fs, 0.3);
    CHECK(samples.size() == 24); // floor(1 / 0.3) = 3 intervals, 2 interior samples per edge
    for(const auto& s : samples) {
      const Point p = PMP::construct_point(s.location, m);
      CHECK(CGAL::squared_distance(p, s.point) < 1e-24);
      // on a cube edge: two coordinates are 0 or 1, the third is 1/3 or 2/3
      int on_face = 0, third = 0;
      for(int k = 0; k < 3; ++k) {
        if(std::abs(p[k]) < 1e-12 || std::abs(p[k] - 1) < 1e-12) ++on_face;
        if(std::abs(p[k] - 1.0 / 3) < 1e-12 || std::abs(p[k] - 2.0 / 3) < 1e-12) ++third;
      }
      CHECK(on_face == 2);
      CHECK(third == 1);
    }
  }
}

TEST_CASE("feature policies: none keeps only borders, user_map reads the user's edges", "[features]")
{
  SECTION("a smooth closed surface has no features") {
    const Mesh m = analytic::sphere(24, 12).to_mesh<Mesh>();
    CHECK(PR::detect_features(m).number_of_feature_edges == 0);
  }
  SECTION("cube with policy none: nothing") {
    const Mesh m = analytic::cube(3).to_mesh<Mesh>();
    const auto fs = PR::detect_features(m, PR::parameters::feature_policy(PR::Feature_policy::none));
    CHECK(fs.number_of_feature_edges == 0);
    CHECK(fs.corners.empty());
  }
  SECTION("plane with policy none: the border is a feature with its 4 corners") {
    const Mesh m = analytic::plane(5, 5).to_mesh<Mesh>();
    const auto fs = PR::detect_features(m, PR::parameters::feature_policy(PR::Feature_policy::none));
    CHECK(fs.number_of_feature_edges == 20);
    CHECK(fs.corners.size() == 4);
    CHECK(fs.curves.size() == 4);
    for(const auto& c : fs.curves) CHECK(c.border);
  }
  SECTION("open cylinder: its two borders are closed curves without corners") {
    const Mesh m = analytic::cylinder(16, 4).to_mesh<Mesh>();
    const auto fs = PR::detect_features(m);
    CHECK(fs.corners.empty());
    REQUIRE(fs.curves.size() == 2);
    for(const auto& c : fs.curves) {
      CHECK(c.closed);
      CHECK(c.halfedges.size() == 16);
      const auto samples = PR::feature_sample_locations(m, get(CGAL::vertex_point, m), fs, 1.0);
      CHECK(samples.size() == 2 * std::size_t(std::floor(c.length / 1.0)));
    }
  }
  SECTION("user map: one marked chain is the only feature") {
    Mesh m = analytic::plane(6, 1).to_mesh<Mesh>();
    // close nothing: mark the interior edges of the middle row... here the diagonals of quads 2-3
    auto ecm = get(CGAL::dynamic_edge_property_t<bool>(), m);
    std::size_t marked = 0;
    for(auto e : edges(m)) {
      const Point a = m.point(source(halfedge(e, m), m)), b = m.point(target(halfedge(e, m), m));
      const bool vertical_inside = a.x() == b.x() && a.x() > 0 && a.x() < 1;
      put(ecm, e, vertical_inside && std::abs(a.x() - 0.5) < 1e-9);
      if(get(ecm, e)) ++marked;
    }
    REQUIRE(marked == 1);
    const auto fs = PR::detect_features(m, PR::parameters::edge_is_constrained_map(ecm));
    CHECK(fs.number_of_feature_edges == 14 + 1); // the border (2*6 + 2) and the marked edge
    CHECK(fs.curves.size() >= 5);
  }
}

TEST_CASE("features of fandisk: sharp creases kept, short dangling chains removed", "[features]")
{
  Mesh m;
  PR::read_surface_mesh(test_support::data_mesh("meshes/fandisk.off"), m);
  const auto fs = PR::detect_features(m, PR::parameters::sharp_angle(60.0));
  auto sharp = get(CGAL::dynamic_edge_property_t<bool>(), m);
  for(auto e : edges(m)) put(sharp, e, false);
  PMP::detect_sharp_edges(m, 60.0, sharp);
  std::size_t sharp_count = 0, kept = 0;
  for(auto e : edges(m)) if(get(sharp, e)) { ++sharp_count; if(fs.is_feature(e)) ++kept; }
  CHECK(sharp_count > 0);
  CHECK(kept + fs.number_of_removed_false_features == sharp_count);
  CHECK(fs.number_of_feature_edges == kept);
  CHECK(fs.corners.size() >= 8);
  // every curve is a connected chain; no dangling chain shorter than the filter's limit is left
  std::size_t edges_in_curves = 0;
  for(const auto& c : fs.curves) {
    edges_in_curves += c.halfedges.size();
    for(std::size_t i = 1; i < c.halfedges.size(); ++i) CHECK(target(c.halfedges[i - 1], m) == source(c.halfedges[i], m));
  }
  CHECK(edges_in_curves == fs.number_of_feature_edges);
}
