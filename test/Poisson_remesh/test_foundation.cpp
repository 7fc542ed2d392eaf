// Tests of the package's foundation: input reading and validation, the quality report (against an
// independent computation), named parameters, atomic output, sizing relations.
#include "analytic_meshes.h"
#include "test_support.h"

#include <Poisson_remesh/IO/write_mesh_svg.h>
#include <Poisson_remesh/IO/write_quality_report.h>
#include <Poisson_remesh/parameters.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>
#include <Poisson_remesh/sizing.h>
#include <Poisson_remesh/write_surface_mesh.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <CGAL/Polygon_mesh_processing/manifoldness.h>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef CGAL::Polyhedron_3<K> Polyhedron;
namespace PR = Poisson_remesh;
namespace PMP = CGAL::Polygon_mesh_processing;
using test_support::data_mesh;

// ------------------------------------------------------------------ an independent judge
// Reads an OFF file with its own parser and computes the figures with long double and the law
// of cosines -- no code shared with quality_report().
namespace independent {

struct Figures
{
  std::size_t V = 0, F = 0, E = 0, border_edges = 0;
  long double min_angle = 180, mean_min_angle = 0, max_angle = 0, share_below_30 = 0, irregular = 0;
};

inline Figures off_figures(const std::string& file)
{
  std::ifstream in(file);
  std::stringstream clean;
  std::string line;
  while(std::getline(in, line)) clean << line.substr(0, line.find('#')) << "\n";
  std::string header;
  clean >> header;
  REQUIRE((header == "OFF" || header == "COFF"));
  std::size_t nv, nf, ne;
  clean >> nv >> nf >> ne;
  std::getline(clean, line);
  std::vector<std::array<long double, 3>> p(nv);
  for(auto& q : p) {
    do { std::getline(clean, line); } while(line.find_first_not_of(" \t\r") == std::string::npos);
    std::istringstream ls(line); // x y z, then colours in COFF
    ls >> q[0] >> q[1] >> q[2];
  }
  Figures fig;
  fig.V = nv;
  fig.F = nf;
  std::map<std::pair<std::size_t, std::size_t>, int> edge_faces;
  std::size_t below = 0;
  for(std::size_t f = 0; f < nf; ++f) {
    std::size_t n, a, b, c;
    clean >> n >> a >> b >> c;
    REQUIRE(n == 3);
    std::getline(clean, line); // colours, if any
    auto len = [&](std::size_t i, std::size_t j) {
      long double s = 0;
      for(int k = 0; k < 3; ++k) s += (p[i][k] - p[j][k]) * (p[i][k] - p[j][k]);
      return std::sqrt(s);
    };
    const long double la = len(b, c), lb = len(c, a), lc = len(a, b);
    auto angle = [](long double opposite, long double s1, long double s2) {
      long double c = (s1 * s1 + s2 * s2 - opposite * opposite) / (2 * s1 * s2);
      c = std::max<long double>(-1, std::min<long double>(1, c));
      return std::acos(c) * 180.0L / 3.14159265358979323846264338327950288L;
    };
    const long double A[3] = {angle(la, lb, lc), angle(lb, lc, la), angle(lc, la, lb)};
    const long double amin = std::min({A[0], A[1], A[2]}), amax = std::max({A[0], A[1], A[2]});
    fig.min_angle = std::min(fig.min_angle, amin);
    fig.max_angle = std::max(fig.max_angle, amax);
    fig.mean_min_angle += amin;
    if(amin < 30) ++below;
    for(auto e : {std::make_pair(a, b), std::make_pair(b, c), std::make_pair(c, a)})
      ++edge_faces[std::minmax(e.first, e.second)];
  }
  fig.mean_min_angle /= nf;
  fig.share_below_30 = (long double)below / nf;
  fig.E = edge_faces.size();
  std::vector<std::size_t> degree(nv, 0);
  std::vector<bool> border(nv, false);
  for(const auto& e : edge_faces) {
    ++degree[e.first.first];
    ++degree[e.first.second];
    if(e.second == 1) { ++fig.border_edges; border[e.first.first] = border[e.first.second] = true; }
  }
  std::size_t irregular = 0;
  for(std::size_t v = 0; v < nv; ++v) if(degree[v] != (border[v] ? 4u : 6u)) ++irregular;
  fig.irregular = (long double)irregular / nv;
  return fig;
}

} // namespace independent

TEST_CASE("quality report agrees with an independent computation on CGAL data meshes", "[quality]")
{
  for(const std::string name : {"meshes/fandisk.off", "meshes/triceratops.off", "meshes/dino.off", "meshes/elephant.off"}) {
    INFO(name);
    Mesh m;
    PR::read_surface_mesh(data_mesh(name), m);
    const PR::Quality_report r = PR::quality_report(m, PR::parameters::check_self_intersections(false));
    const independent::Figures fig = independent::off_figures(data_mesh(name));
    CHECK(r.number_of_vertices == fig.V);
    CHECK(r.number_of_faces == fig.F);
    CHECK(r.number_of_edges == fig.E);
    CHECK(r.number_of_border_edges == fig.border_edges);
    CHECK(std::abs(r.min_angle - double(fig.min_angle)) < 1e-3);
    CHECK(std::abs(r.mean_min_angle - double(fig.mean_min_angle)) < 1e-3);
    CHECK(std::abs(r.max_angle - double(fig.max_angle)) < 1e-3);
    CHECK(std::abs(r.share_min_angle_below_30 - double(fig.share_below_30)) < 1e-12);
    CHECK(std::abs(r.irregular_share - double(fig.irregular)) < 1e-12);
    CHECK(r.euler_characteristic == long(fig.V) - long(fig.E) + long(fig.F));
  }
}

TEST_CASE("quality report of the paper's triceratops shows its skinny triangles", "[quality]")
{
  Mesh m;
  PR::read_surface_mesh(data_mesh("meshes/triceratops.off"), m);
  const PR::Quality_report r = PR::quality_report(m);
  CHECK(r.number_of_vertices == 2832);
  CHECK(r.min_angle == Approx(0.0002).margin(0.00005));
  CHECK(r.mean_min_angle == Approx(29.83).margin(0.005));
  CHECK(r.number_of_components == 1);
  CHECK(r.genus == 0);
  CHECK(r.number_of_border_edges == 0);
  CHECK(r.self_intersections_checked);
}

TEST_CASE("quality report gives the topology of analytic meshes", "[quality]")
{
  SECTION("sphere: closed, genus 0") {
    const PR::Quality_report r = PR::quality_report(analytic::sphere(24, 12).to_mesh<Mesh>());
    CHECK(r.euler_characteristic == 2);
    CHECK(r.genus == 0);
    CHECK(r.number_of_components == 1);
    CHECK(r.number_of_border_edges == 0);
    CHECK(r.number_of_self_intersecting_face_pairs == 0);
  }
  SECTION("torus: closed, genus 1") {
    const PR::Quality_report r = PR::quality_report(analytic::torus(30, 12).to_mesh<Mesh>());
    CHECK(r.euler_characteristic == 0);
    CHECK(r.genus == 1);
    CHECK(r.number_of_border_cycles == 0);
  }
  SECTION("cylinder: two borders, genus 0") {
    const PR::Quality_report r = PR::quality_report(analytic::cylinder(16, 5).to_mesh<Mesh>());
    CHECK(r.number_of_border_cycles == 2);
    CHECK(r.number_of_border_edges == 32);
    CHECK(r.genus == 0);
  }
  SECTION("plane grid: irregular vertices are exactly the four corners") {
    const std::size_t n = 10;
    const PR::Quality_report r = PR::quality_report(analytic::plane(n, n).to_mesh<Mesh>());
    CHECK(r.number_of_border_cycles == 1);
    CHECK(r.genus == 0);
    CHECK(r.irregular_share == Approx(4.0 / double((n + 1) * (n + 1))));
    CHECK(r.min_angle == Approx(45));
    CHECK(r.max_angle == Approx(90));
    // right isosceles triangles: Q = sqrt(3) / (1 + sqrt(2))
    CHECK(r.mean_shape_quality == Approx(std::sqrt(3.0) / (1 + std::sqrt(2.0))));
  }
  SECTION("sphere and torus in one mesh: two components, total genus 1") {
    analytic::Soup s = analytic::sphere(12, 6), t = analytic::torus(16, 8, 5, 1);
    const std::size_t offset = s.points.size();
    for(auto p : t.points) s.points.push_back({p[0] + 10, p[1], p[2]});
    for(auto f : t.triangles) s.triangles.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
    const PR::Quality_report r = PR::quality_report(s.to_mesh<Mesh>());
    CHECK(r.number_of_components == 2);
    CHECK(r.genus == 1);
    CHECK(r.euler_characteristic == 2);
  }
}

TEST_CASE("quality report ignores the removed elements of a Surface_mesh", "[quality]")
{
  Mesh m = analytic::sphere(12, 6).to_mesh<Mesh>();
  const std::size_t V = num_vertices(m);
  m.remove_vertex(m.add_vertex(Point(5, 5, 5)));
  REQUIRE(m.has_garbage());
  const PR::Quality_report r = PR::quality_report(m);
  CHECK(r.number_of_vertices == V);
  CHECK(r.euler_characteristic == 2);
  CHECK(r.irregular_share == PR::quality_report(analytic::sphere(12, 6).to_mesh<Mesh>()).irregular_share);
}

TEST_CASE("quality report: equilateral triangle has quality 1 and 60 degree angles", "[quality]")
{
  analytic::Soup s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}};
  s.triangles = {{0, 1, 2}};
  const PR::Quality_report r = PR::quality_report(s.to_mesh<Mesh>());
  CHECK(r.min_angle == Approx(60));
  CHECK(r.max_angle == Approx(60));
  CHECK(r.min_shape_quality == Approx(1));
  CHECK(r.irregular_share == 1.0); // three border vertices of valence 2
}

TEST_CASE("quality report finds self-intersections and measures the Hausdorff distance", "[quality]")
{
  SECTION("two interpenetrating spheres intersect") {
    analytic::Soup s = analytic::sphere(16, 8), t = analytic::sphere(16, 8);
    const std::size_t offset = s.points.size();
    for(auto p : t.points) s.points.push_back({p[0] + 0.5, p[1], p[2]});
    for(auto f : t.triangles) s.triangles.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
    const Mesh both = s.to_mesh<Mesh>();
    const PR::Quality_report r = PR::quality_report(both);
    CHECK(r.number_of_self_intersecting_face_pairs > 0);
    CHECK(!r.number_of_self_intersecting_face_pairs_away_from_reference_ones);   // (no reference)
    // against itself, every crossing is one of the reference's own ...
    const PR::Quality_report own = PR::quality_report(both, both);
    REQUIRE(own.number_of_reference_self_intersecting_face_pairs);
    CHECK(*own.number_of_reference_self_intersecting_face_pairs == r.number_of_self_intersecting_face_pairs);
    CHECK(*own.number_of_self_intersecting_face_pairs_away_from_reference_ones == 0);
    // ... and two more crossing each other far from them make crossings away from them
    analytic::Soup u = s;
    for(double x : {-5.0, -4.5}) {
      const analytic::Soup w = analytic::sphere(16, 8);
      const std::size_t o2 = u.points.size();
      for(auto p : w.points) u.points.push_back({p[0] + x, p[1], p[2]});
      for(auto f : w.triangles) u.triangles.push_back({f[0] + o2, f[1] + o2, f[2] + o2});
    }
    const PR::Quality_report three = PR::quality_report(u.to_mesh<Mesh>(), both);
    CHECK(three.number_of_self_intersecting_face_pairs > r.number_of_self_intersecting_face_pairs);
    CHECK(*three.number_of_self_intersecting_face_pairs_away_from_reference_ones > 0);
    CHECK(*three.number_of_self_intersecting_face_pairs_away_from_reference_ones < three.number_of_self_intersecting_face_pairs);
    // a mesh that does not cut itself has none, whatever its reference does
    const PR::Quality_report one = PR::quality_report(analytic::sphere(16, 8).to_mesh<Mesh>(), both);
    CHECK(*one.number_of_self_intersecting_face_pairs_away_from_reference_ones == 0);
    // the reference's count given beforehand (reference_self_intersections): the same figures,
    // with or without crossings in the mesh
    const std::size_t known = r.number_of_self_intersecting_face_pairs;
    const PR::Quality_report one_known = PR::quality_report(analytic::sphere(16, 8).to_mesh<Mesh>(), both,
                                                            PR::parameters::reference_self_intersections(known));
    REQUIRE(one_known.number_of_reference_self_intersecting_face_pairs);
    CHECK(*one_known.number_of_reference_self_intersecting_face_pairs == known);
    CHECK(*one_known.number_of_self_intersecting_face_pairs_away_from_reference_ones == 0);
    const PR::Quality_report three_known = PR::quality_report(u.to_mesh<Mesh>(), both, PR::parameters::reference_self_intersections(known));
    CHECK(*three_known.number_of_reference_self_intersecting_face_pairs == known);
    CHECK(*three_known.number_of_self_intersecting_face_pairs_away_from_reference_ones ==
          *three.number_of_self_intersecting_face_pairs_away_from_reference_ones);
  }
  SECTION("a translated copy is at the translation distance") {
    const Mesh a = analytic::plane(8, 8).to_mesh<Mesh>();
    Mesh b = a;
    for(auto v : vertices(b)) b.point(v) = b.point(v) + K::Vector_3(0, 0, 0.01);
    const PR::Quality_report r = PR::quality_report(b, a);
    REQUIRE(r.hausdorff);
    CHECK(*r.hausdorff_absolute == Approx(0.01).epsilon(1e-3));
    CHECK(*r.hausdorff == Approx(0.01 / std::sqrt(2.0)).epsilon(1e-3));
  }
}

TEST_CASE("quality report leaves out only the angles at the reference's sharp corners", "[quality]")
{
  SECTION("a sharp tetrahedron: its angles under 30 degrees are all at corners whose own angle is smaller") {
    analytic::Soup s;
    const double a = 20 * CGAL_PI / 180;
    s.points = {{0, 0, 0}, {1, 0, 0}, {std::cos(a), std::sin(a), 0}, {0.6, 0.2, 0.9}};
    s.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    const Mesh m = s.to_mesh<Mesh>();
    const PR::Quality_report r = PR::quality_report(m, m);
    CHECK(r.min_angle < 20.5);
    REQUIRE(r.min_angle_away_from_sharp_corners);
    CHECK(r.number_of_angles_at_sharp_corners >= 2);
    CHECK(*r.min_angle_away_from_sharp_corners >= 30);
  }
  SECTION("a tip whose input angle sum is 96 degrees but whose cone angle at the mesh's scale is 60") {
    // reference: a cone tip of half-angle 16 degrees over 0.1 (angle sum 96 at the apex), bending
    // to a half-angle of 9.6 degrees (cone angle 60) down to a flat base; six vertices per ring
    analytic::Soup s;
    const double a1 = std::asin(96.0 / 360.0), a2 = std::asin(60.0 / 360.0);   // cone angle = 360 sin(half-angle)
    const double r1 = 0.1 * std::sin(a1), z1 = 1 - 0.1 * std::cos(a1);
    const double r2 = r1 + 0.5 * std::sin(a2), z2 = z1 - 0.5 * std::cos(a2);
    const double r3 = r1 + 1.0 * std::sin(a2), z3 = z1 - 1.0 * std::cos(a2);
    s.points.push_back({0, 0, 1});
    for(const auto& rz : {std::make_pair(r1, z1), std::make_pair(r2, z2), std::make_pair(r3, z3)})
      for(int i = 0; i < 6; ++i) s.points.push_back({rz.first * std::cos(i * CGAL_PI / 3), rz.first * std::sin(i * CGAL_PI / 3), rz.second});
    s.points.push_back({0, 0, z3});
    auto ring = [](int k, int i) { return std::size_t(1 + 6 * k + (i % 6)); };
    for(int i = 0; i < 6; ++i) {
      s.triangles.push_back({0, ring(0, i), ring(0, i + 1)});
      for(int k = 0; k < 2; ++k) {
        s.triangles.push_back({ring(k, i), ring(k + 1, i), ring(k + 1, i + 1)});
        s.triangles.push_back({ring(k, i), ring(k + 1, i + 1), ring(k, i + 1)});
      }
      s.triangles.push_back({19, ring(2, i + 1), ring(2, i)});
    }
    const Mesh ref = s.to_mesh<Mesh>();
    // the mesh: the apex and three points on the base rim (midpoints of rim edges: just inside the
    // reach of the rim's vertices), a tetrahedron whose apex angles are about 19 degrees
    analytic::Soup t;
    t.points.push_back({0, 0, 1});
    for(int i : {0, 2, 4}) {
      const K::Point_3 p = CGAL::midpoint(K::Point_3(s.points[ring(2, i)][0], s.points[ring(2, i)][1], s.points[ring(2, i)][2]),
                                          K::Point_3(s.points[ring(2, i + 1)][0], s.points[ring(2, i + 1)][1], s.points[ring(2, i + 1)][2]));
      t.points.push_back({p.x(), p.y(), p.z()});
    }
    t.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
    const Mesh m = t.to_mesh<Mesh>();
    const PR::Quality_report own = PR::quality_report(ref, ref), r = PR::quality_report(m, ref);
    // at the input's own scale (its ring at 0.1, where the cone angle is 96 degrees) three
    // triangles at the apex could have 96 / 3 = 32 degrees only if flat: on the cone (half-angle
    // asin(96 / 360) = 15.5 degrees), the best is 2 asin(sin 15.5 sin 60) = 26.7 degrees, so the
    // reference's own six apex angles (16 degrees each) are left out
    CHECK(own.number_of_angles_at_sharp_corners == 6);
    CHECK(r.min_angle < 25);
    CHECK(r.number_of_angles_at_sharp_corners == 3);     // the three apex angles
    REQUIRE(r.min_angle_away_from_sharp_corners);
    CHECK(*r.min_angle_away_from_sharp_corners >= 59);   // the base and the side triangles' other angles
  }
  SECTION("a skinny triangle inside a plane is no corner's fault") {
    Mesh m = analytic::plane(8, 8).to_mesh<Mesh>();
    for(auto v : vertices(m)) {
      if(is_border(v, m)) continue;
      m.point(v) = m.point(v) + 0.7 * (m.point(source(halfedge(v, m), m)) - m.point(v));
      break;
    }
    const PR::Quality_report r = PR::quality_report(m, m);
    CHECK(r.min_angle < 15);
    CHECK(r.number_of_angles_at_sharp_corners == 0);
    CHECK(*r.min_angle_away_from_sharp_corners == Approx(r.min_angle));
  }
}

TEST_CASE("quality report is the same on Polyhedron_3 and Surface_mesh", "[quality][polyhedron]")
{
  Mesh sm;
  Polyhedron poly;
  PR::read_surface_mesh(data_mesh("meshes/fandisk.off"), sm);
  PR::read_surface_mesh(data_mesh("meshes/fandisk.off"), poly);
  const PR::Quality_report a = PR::quality_report(sm), b = PR::quality_report(poly);
  CHECK(a.number_of_vertices == b.number_of_vertices);
  CHECK(a.number_of_faces == b.number_of_faces);
  CHECK(a.genus == b.genus);
  CHECK(a.min_angle == b.min_angle);
  CHECK(a.mean_min_angle == Approx(b.mean_min_angle).epsilon(1e-12));
  CHECK(a.irregular_share == b.irregular_share);
  CHECK(a.number_of_self_intersecting_face_pairs == b.number_of_self_intersecting_face_pairs);
}

TEST_CASE("quality report JSON and SVG carry the figures", "[quality][io]")
{
  const PR::Quality_report r = PR::quality_report(analytic::plane(4, 4).to_mesh<Mesh>());
  std::ostringstream json, svg;
  PR::write_quality_json(json, {{"plane", r}});
  PR::write_angle_histogram_svg(svg, {{"plane", r}, {"again", r}});
  CHECK(json.str().find("\"plane\": {") != std::string::npos);
  CHECK(json.str().find("\"min_angle_deg\": 45") != std::string::npos);
  CHECK(json.str().find("\"vertices\": 25") != std::string::npos);
  CHECK(svg.str().rfind("<svg", 0) == 0);
  CHECK(svg.str().find("</svg>") != std::string::npos);
  CHECK(svg.str().find("stroke=\"red\"") != std::string::npos);
}

TEST_CASE("mesh pictures: one path per face, back to front, the triangles under 30 degrees in red", "[io]")
{
  // a UV sphere: slivers at the poles, near-square quads elsewhere; and a plane of 45-degree triangles
  const Mesh sphere = analytic::sphere(24, 12).to_mesh<Mesh>();
  const Mesh plane = analytic::plane(4, 4).to_mesh<Mesh>();
  std::size_t expected_marked = 0;   // judged with CGAL's angle, not the picture's code
  for(auto f : faces(sphere)) {
    const auto h = halfedge(f, sphere);
    const K::Point_3 p = sphere.point(source(h, sphere)), q = sphere.point(target(h, sphere)),
                     r = sphere.point(target(next(h, sphere), sphere));
    const double smallest = std::min({CGAL::approximate_angle(q, p, r), CGAL::approximate_angle(p, q, r),
                                      CGAL::approximate_angle(p, r, q)});
    expected_marked += smallest < 30;
  }
  REQUIRE(expected_marked > 0);
  std::ostringstream os;
  PR::Mesh_svg_view view;
  view.width = 400;
  view.title = "a <sphere> & a plane";
  PR::write_mesh_comparison_svg<Mesh>(os, {{&sphere, "sphere"}, {&plane, "plane"}}, view);
  const std::string svg = os.str();
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for(std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(svg.find("</svg>") != std::string::npos);
  CHECK(svg.find("a &lt;sphere&gt; &amp; a plane") != std::string::npos);   // the title, escaped
  CHECK(count("<path ") == num_faces(sphere) + num_faces(plane));
  CHECK(count("class=\"marked\"") == expected_marked);   // the plane's 45-degree triangles are not red
  // every vertex inside the picture: two panels of 400 pixels
  const std::size_t h_at = svg.find("height=\""), w_at = svg.find("width=\"");
  const double width = std::stod(svg.substr(w_at + 7)), height = std::stod(svg.substr(h_at + 8));
  CHECK(width == 800);
  std::istringstream paths(svg);
  std::string line;
  std::vector<std::string> fills;
  while(std::getline(paths, line)) {
    const std::size_t d = line.find(" d=\"M");
    if(d == std::string::npos) continue;
    std::string coords = line.substr(d + 5, line.find('Z', d) - d - 5);
    std::replace(coords.begin(), coords.end(), 'L', ' ');
    std::istringstream xy(coords);
    double x, y;
    while(xy >> x >> y) {
      CHECK((x >= 0 && x <= width));
      CHECK((y >= 0 && y <= height));
    }
    fills.push_back(line);
  }
  REQUIRE(fills.size() == num_faces(sphere) + num_faces(plane));
  // back to front: without red marks, the first face drawn of the closed sphere is a back face
  // (blue-grey: more blue than red) and the last a front face (grey)
  view.marked_angle_degrees = 0;
  std::ostringstream alone;
  PR::write_mesh_svg(alone, sphere, view);
  const std::string s2 = alone.str();
  CHECK(s2.find("class=\"marked\"") == std::string::npos);
  const std::size_t first = s2.find("fill=\"#"), last = s2.rfind("fill=\"#");
  auto blue_over_red = [&](std::size_t at) {
    return std::stoi(s2.substr(at + 11, 2), nullptr, 16) > std::stoi(s2.substr(at + 7, 2), nullptr, 16);
  };
  REQUIRE(first != last);
  CHECK(blue_over_red(first));
  CHECK_FALSE(blue_over_red(last));
  // the side seen first is the front, whatever the orientation: the sphere turned inside out
  // looks the same
  Mesh inside_out = sphere;
  CGAL::Polygon_mesh_processing::reverse_face_orientations(inside_out);
  std::ostringstream flipped;
  PR::write_mesh_svg(flipped, inside_out, view);
  const std::string s3 = flipped.str();
  auto blue_over_red_3 = [&](std::size_t at) {
    return std::stoi(s3.substr(at + 11, 2), nullptr, 16) > std::stoi(s3.substr(at + 7, 2), nullptr, 16);
  };
  CHECK(blue_over_red_3(s3.find("fill=\"#")));
  CHECK_FALSE(blue_over_red_3(s3.rfind("fill=\"#")));
}

// ------------------------------------------------------------------ named parameters
TEST_CASE("named parameters: the package's and CGAL's chain in one expression and take effect", "[parameters]")
{
  Mesh m = analytic::plane(4, 4).to_mesh<Mesh>();
  auto doubled = m.add_property_map<Mesh::Vertex_index, Point>("v:doubled").first;
  for(auto v : vertices(m)) put(doubled, v, Point(2 * m.point(v).x(), 2 * m.point(v).y(), 2 * m.point(v).z()));

  // ours, then CGAL's, then ours again
  const PR::Quality_report r = PR::quality_report(
    m, PR::parameters::angle_histogram_bin_width(10.0).vertex_point_map(doubled).check_self_intersections(false));
  CHECK(r.angle_histogram.size() == 18);
  CHECK(r.bbox_diagonal == Approx(2 * std::sqrt(2.0)));
  CHECK_FALSE(r.self_intersections_checked);

  // a CGAL function reads CGAL's parameters from our chain
  const CGAL::Bbox_3 box = PMP::bbox(m, PR::parameters::angle_histogram_bin_width(5.0).vertex_point_map(doubled));
  CHECK(box.xmax() == Approx(2));
  CHECK(box.ymax() == Approx(2));
  // and a plain CGAL chain is accepted by ours
  const PR::Quality_report r2 = PR::quality_report(m, CGAL::parameters::vertex_point_map(doubled));
  CHECK(r2.bbox_diagonal == Approx(2 * std::sqrt(2.0)));
  CHECK(r2.angle_histogram.size() == 180);
}

// ------------------------------------------------------------------ reading and validation
namespace {

PR::Input_error_code read_error(const std::string& file, std::string* message = nullptr, bool strict = false)
{
  Mesh m;
  try {
    PR::read_surface_mesh(file, m, PR::parameters::strict_input(strict));
  } catch(const PR::Input_error& e) {
    if(message) *message = e.what();
    CHECK(is_empty(m));
    return e.code();
  }
  FAIL("no error reading " << file);
  return PR::Input_error_code::cannot_open;
}

} // namespace

TEST_CASE("reading refuses bad input with a specific error", "[read]")
{
  const auto dir = test_support::scratch_dir("read");
  using C = PR::Input_error_code;
  using test_support::write_text;
  std::string msg;

  CHECK(read_error((dir / "missing.off").string(), &msg) == C::cannot_open);
  CHECK_THAT(msg, Catch::Contains("no such file"));
  CHECK(read_error(dir.string(), &msg) == C::cannot_open);
  CHECK_THAT(msg, Catch::Contains("directory"));
  CHECK(read_error(write_text(dir / "empty.off", ""), &msg) == C::empty_file);
  CHECK(read_error(write_text(dir / "mesh.xyz", "0 0 0\n"), &msg) == C::unsupported_format);
  CHECK_THAT(msg, Catch::Contains("xyz"));
  CHECK(read_error(write_text(dir / "garbage.off", "this is not a mesh\n\x01\x02\x03"), &msg) == C::parse_error);
  CHECK(read_error(write_text(dir / "truncated.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n"), &msg) == C::parse_error);
  CHECK(read_error(write_text(dir / "binary.ply", std::string("ply\nformat binary_little_endian 1.0\nelement vertex 3\n") + std::string(7, '\xff')), &msg) == C::parse_error);
  CHECK(read_error(write_text(dir / "nothing.off", "OFF\n0 0 0\n"), &msg) == C::empty_mesh);
  CHECK(read_error(write_text(dir / "no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), &msg) == C::empty_mesh);

  CHECK(read_error(write_text(dir / "nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), &msg) == C::invalid_coordinates);
  CHECK_THAT(msg, Catch::Contains("line 4"));
  CHECK(read_error(write_text(dir / "inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n"), &msg) == C::invalid_coordinates);

  CHECK(read_error(write_text(dir / "repeated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n"), &msg) == C::invalid_face);
  CHECK_THAT(msg, Catch::Contains("repeats vertex 1"));

  // three triangles on the edge (0, 1)
  CHECK(read_error(write_text(dir / "fin.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n"), &msg) == C::non_manifold_edges);
  CHECK_THAT(msg, Catch::Contains("1 non-manifold edges"));
  // two tetrahedra sharing only vertex 0
  CHECK(read_error(write_text(dir / "bowtie.off",
                              "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
                              "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n"
                              "3 0 5 4\n3 0 4 6\n3 4 5 6\n3 0 6 5\n"), &msg, true) == C::non_manifold_vertices);
  CHECK_THAT(msg, Catch::Contains("vertex 0"));
  // a Moebius strip of 5 quads
  {
    std::ostringstream s;
    const int n = 5;
    s << "OFF\n" << 2 * n << " " << n << " 0\n";
    for(int i = 0; i < n; ++i) {
      const double t = 2 * M_PI * i / n, h = 0.3;
      for(int side : {-1, 1}) {
        const double w = side * h * std::cos(t / 2), z = side * h * std::sin(t / 2);
        s << (2 + w) * std::cos(t) << " " << (2 + w) * std::sin(t) << " " << z << "\n";
      }
    }
    for(int i = 0; i < n - 1; ++i) s << "4 " << 2 * i << " " << 2 * i + 2 << " " << 2 * i + 3 << " " << 2 * i + 1 << "\n";
    s << "4 " << 2 * (n - 1) << " 1 0 " << 2 * (n - 1) + 1 << "\n"; // the half twist
    CHECK(read_error(write_text(dir / "moebius.off", s.str()), &msg) == C::non_orientable);
  }
  // collinear triangle on an otherwise valid open mesh
  // (the last two only with strict_input: by default they are repaired)
  CHECK(read_error(write_text(dir / "flat.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n2 0 0\n1 1 0\n3 0 1 3\n3 0 2 1\n"), &msg, true) == C::degenerate_faces);
  CHECK_THAT(msg, Catch::Contains("1 degenerate"));
}

TEST_CASE("reading accepts imperfect but valid input and says what it did", "[read]")
{
  const auto dir = test_support::scratch_dir("read_ok");
  using test_support::write_text;
  SECTION("polygons are triangulated") {
    const std::string cube = "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                             "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
    Mesh m;
    const PR::Read_report rr = PR::read_surface_mesh(write_text(dir / "cube.off", cube), m);
    CHECK(rr.triangulated_polygons == 6);
    CHECK(num_faces(m) == 12);
    CHECK(CGAL::is_closed(m));
    CHECK(CGAL::to_double(PMP::area(m)) == Approx(6));
  }
  SECTION("points no face uses are dropped (found by fuzzing: they made an invalid mesh)") {
    Mesh m;
    const PR::Read_report rr = PR::read_surface_mesh(
        write_text(dir / "unused.off", "OFF\n5 1 0\n0 0 0\n9 9 9\n1 0 0\n0 1 0\n7 7 7\n3 0 2 3\n"), m);
    CHECK(rr.removed_isolated_points == 2);
    CHECK(num_vertices(m) == 3);
    CHECK(CGAL::is_valid_polygon_mesh(m));
    CHECK(!rr.warnings.empty());
  }
  SECTION("inconsistent orientation is made consistent") {
    const std::string flipped = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
    Mesh m;
    const PR::Read_report rr = PR::read_surface_mesh(write_text(dir / "flipped.off", flipped), m);
    CHECK(rr.reoriented);
    CHECK(CGAL::is_closed(m));
    CHECK(num_faces(m) == 4);
    // the same tetrahedron consistently oriented (face 1 turned back) is read as it is
    const std::string consistent = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
    Mesh n;
    const PR::Read_report rn = PR::read_surface_mesh(write_text(dir / "consistent.off", consistent), n);
    CHECK(!rn.reoriented);
    CHECK(CGAL::is_closed(n));
    CHECK(CGAL::Polygon_mesh_processing::is_outward_oriented(n));
  }
  SECTION("OBJ, ASCII PLY and ASCII STL are read") {
    Mesh a, b, c;
    PR::read_surface_mesh(write_text(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"), a);
    PR::read_surface_mesh(write_text(dir / "t.ply",
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n"), b);
    std::ostringstream stl;
    stl << "solid t\n";
    const double P[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int T[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    for(auto& t : T) {
      stl << "facet normal 0 0 0\nouter loop\n";
      for(int k : t) stl << "vertex " << P[k][0] << " " << P[k][1] << " " << P[k][2] << "\n";
      stl << "endloop\nendfacet\n";
    }
    stl << "endsolid t\n";
    PR::read_surface_mesh(write_text(dir / "t.stl", stl.str()), c);
    for(const Mesh* m : {&a, &b, &c}) {
      CHECK(num_vertices(*m) == 4);
      CHECK(num_faces(*m) == 4);
      CHECK(CGAL::is_closed(*m));
    }
  }
  SECTION("open meshes and several components are valid") {
    Mesh m;
    const std::string two = "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n5 0 0\n6 0 0\n5 1 0\n3 0 1 2\n3 3 4 5\n";
    PR::read_surface_mesh(write_text(dir / "two.off", two), m);
    CHECK(PR::quality_report(m).number_of_components == 2);
  }
  SECTION("degenerate faces are removed by default") {
    Mesh m;
    const std::string strip = "OFF\n5 3 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n2 1 0\n3 0 1 3\n3 1 2 4\n3 1 4 3\n";
    std::ofstream(dir / "ok.off") << strip;
    PR::read_surface_mesh((dir / "ok.off").string(), m);
    CHECK(num_faces(m) == 3);
    const std::string with_flat = "OFF\n4 2 0\n0 0 0\n1 0 0\n2 0 0\n1 1 0\n3 0 1 3\n3 0 2 1\n";
    Mesh r;
    const PR::Read_report rr = PR::read_surface_mesh(write_text(dir / "flat.off", with_flat), r);
    CHECK(rr.removed_degenerate_faces == 1);
    CHECK(PR::quality_report(r).number_of_degenerate_faces == 0);
    // an explicit false wins over the default, and strict input refuses them
    Mesh s;
    CHECK_THROWS_AS(PR::read_surface_mesh(dir.string() + "/flat.off", s, PR::parameters::repair_degenerate_faces(false)), PR::Input_error);
    CHECK(is_empty(s));
  }
  SECTION("non-manifold vertices are split, one vertex per fan") {
    // two tetrahedra sharing only vertex 0, and a fan of two triangles touching a third at vertex 0
    const std::string bowtie = "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
                               "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n"
                               "3 0 5 4\n3 0 4 6\n3 4 5 6\n3 0 6 5\n";
    Mesh r;
    const PR::Read_report rr = PR::read_surface_mesh(write_text(dir / "bowtie.off", bowtie), r);
    CHECK(rr.split_non_manifold_vertices == 1);
    CHECK(num_vertices(r) == 8);
    CHECK(num_faces(r) == 8);
    CHECK(CGAL::is_valid_polygon_mesh(r));
    for(auto v : vertices(r)) CHECK(!PMP::is_non_manifold_vertex(v, r));
    // two components, each a closed tetrahedron: Euler characteristic 2 each
    CHECK(long(num_vertices(r)) - long(num_edges(r)) + long(num_faces(r)) == 4);
    // CGAL's own polygon_mesh.off has two such vertices
    Mesh p;
    const PR::Read_report rp = PR::read_surface_mesh(data_mesh("meshes/polygon_mesh.off"), p);
    CHECK(rp.split_non_manifold_vertices == 2);
    for(auto v : vertices(p)) CHECK(!PMP::is_non_manifold_vertex(v, p));
  }
  SECTION("a removed degenerate face leaves no pinched vertex (found by fuzzing)") {
    // triangles A and B joined only through the zero-area face (0, 2, 3)
    const std::string pinch = "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n-1 -0.5 0\n3 0 1 2\n3 0 2 3\n3 0 3 4\n";
    Mesh r;
    PR::read_surface_mesh(write_text(dir / "pinch.off", pinch), r, PR::parameters::repair_degenerate_faces(true));
    CHECK(CGAL::is_valid_polygon_mesh(r));
    CHECK(PR::quality_report(r).number_of_degenerate_faces == 0);
    for(auto v : vertices(r)) CHECK(!PMP::is_non_manifold_vertex(v, r));
  }
}

// ------------------------------------------------------------------ output
TEST_CASE("outputs are written atomically: a failure leaves the destination untouched", "[write]")
{
  const auto dir = test_support::scratch_dir("write");
  const Mesh m = analytic::sphere(8, 4).to_mesh<Mesh>();
  const std::string out = (dir / "out.off").string();
  test_support::write_text(out, "precious");

  SECTION("a writer that fails midway does not clobber the file") {
    CHECK_THROWS_AS(PR::write_file_atomically(out, [](std::ostream& os) { os << "partial"; throw std::runtime_error("boom"); }),
                    std::runtime_error);
    CHECK(test_support::read_text(out) == "precious");
  }
  SECTION("an unwritable destination throws Output_error and creates nothing") {
    CHECK_THROWS_AS(PR::write_surface_mesh((dir / "no" / "such" / "dir.off").string(), m), PR::Output_error);
    CHECK_THROWS_AS(PR::write_surface_mesh((dir / "mesh.unknown").string(), m), PR::Output_error);
    CHECK_FALSE(std::filesystem::exists(dir / "no"));
  }
  SECTION("a successful write replaces the file and round-trips exactly") {
    PR::write_surface_mesh(out, m);
    Mesh back;
    PR::read_surface_mesh(out, back);
    CHECK(num_vertices(back) == num_vertices(m));
    auto v = vertices(back).begin();
    for(auto u : vertices(m)) CHECK(back.point(*v++) == m.point(u));
  }
  std::size_t leftovers = 0;
  for(const auto& e : std::filesystem::directory_iterator(dir))
    if(e.path().filename().string().find(".partial-") != std::string::npos) ++leftovers;
  CHECK(leftovers == 0);
}

TEST_CASE("the plain OFF reader and writer agree with CGAL's", "[read][write]")
{
  const auto dir = test_support::scratch_dir("plain_off");
  using test_support::write_text;
  typedef std::vector<std::vector<std::size_t>> Polygons;
  // the judge: CGAL's own reader
  auto cgal_read = [](const std::string& file, std::vector<Point>& points, Polygons& polygons) {
    return CGAL::IO::read_polygon_soup(file, points, polygons, CGAL::parameters::verbose(false));
  };
  auto same_as_cgal = [&](const std::string& file) {
    std::vector<Point> p, q;
    Polygons f, g;
    const bool plain = PR::internal::read_plain_off(file, p, f);
    REQUIRE(cgal_read(file, q, g));
    return plain && p == q && f == g;
  };
  SECTION("the files it takes, it reads as CGAL does") {
    // comments, blank lines, counts beside the keyword, tabs, CRLF, quads, exponents, COFF colours
    CHECK(same_as_cgal(write_text(dir / "a.off", "# a comment\nOFF\n\n4 2 0\n0 0 0\n1 0 0 # the x axis\n\n0 1 0\n1e-3 .5 -2.\n3 0 1 2\n3 2 1 3\n")));
    CHECK(same_as_cgal(write_text(dir / "b.off", "OFF 4 1 4\n0\t0\t0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")));
    CHECK(same_as_cgal(write_text(dir / "c.off", "OFF\r\n3 1 0\r\n0.1 0.2 0.3\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n")));
    CHECK(same_as_cgal(write_text(dir / "d.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0.5 0.5 0.5\n3 0 1 2\n")));
  }
  SECTION("anything else it leaves to CGAL's reader") {
    std::vector<Point> p;
    Polygons f;
    auto declines = [&](const std::string& name, const std::string& text) {
      const bool plain = PR::internal::read_plain_off(write_text(dir / name, text), p, f);
      return !plain && p.empty() && f.empty();
    };
    const std::string tail = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    CHECK(declines("noff.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"));
    CHECK(declines("face_colour.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n"));
    CHECK(declines("vertex_extra.off", "OFF\n3 1 0\n0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n"));
    CHECK(declines("plus.off", "OFF\n3 1 0\n+1 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    CHECK(declines("nan.off", "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    CHECK(declines("huge.off", "OFF\n3 1 0\n1e999 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    CHECK(declines("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"));
    CHECK(declines("two_sided.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"));
    CHECK(declines("more_faces.off", "OFF\n3 1 0\n" + tail + "3 0 2 1\n"));
    CHECK(declines("fewer_vertices.off", "OFF\n4 1 0\n" + tail));
    CHECK(declines("two_counts.off", "OFF\n3 1\n" + tail));
    CHECK(declines("no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"));
    CHECK(declines("binary.off", "OFF BINARY\n" + std::string(12, '\0')));
  }
  SECTION("CGAL's data meshes it takes are read as CGAL reads them") {
    std::size_t taken = 0, files = 0;
    for(const auto& entry : std::filesystem::directory_iterator(data_mesh("meshes"))) {
      if(entry.path().extension() != ".off") continue;
      ++files;
      std::vector<Point> p, q;
      Polygons f, g;
      if(!PR::internal::read_plain_off(entry.path().string(), p, f)) continue;
      ++taken;
      INFO(entry.path().string());
      REQUIRE(cgal_read(entry.path().string(), q, g));
      CHECK(p == q);
      CHECK(f == g);
    }
    CHECK(taken >= files * 9 / 10);
  }
  SECTION("what it writes, CGAL reads back to the same doubles and faces") {
    std::mt19937_64 rng(3);
    std::vector<std::array<double, 3>> coordinates = {{0.1, -0.0, 1e300}, {std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::max(), 1.0 / 3}, {5e-324 * 7, 123456789.125, -2.5e-8}};
    for(int i = 0; i < 1000; ++i) {
      std::array<double, 3> c;
      for(double& x : c) {
        std::uint64_t bits = rng();
        std::memcpy(&x, &bits, sizeof x);
        if(!std::isfinite(x)) x = double(bits % 1000) / 7;
      }
      coordinates.push_back(c);
    }
    Polygons polygons;
    for(std::size_t i = 0; i + 3 < coordinates.size(); i += 2) polygons.push_back({i, i + 1, i + 2});
    polygons.push_back({0, 1, 2, 3});
    const auto file = dir / "written.off";
    {
      std::ofstream os(file, std::ios::binary);
      PR::internal::write_plain_off(os, coordinates, polygons);
    }
    std::vector<Point> back;
    Polygons back_polygons;
    REQUIRE(cgal_read(file.string(), back, back_polygons));
    REQUIRE(back.size() == coordinates.size());
    std::size_t exact = 0;
    for(std::size_t i = 0; i < back.size(); ++i)
      exact += std::size_t(back[i].x() == coordinates[i][0] && back[i].y() == coordinates[i][1] && back[i].z() == coordinates[i][2] &&
                           std::signbit(back[i].y()) == std::signbit(coordinates[i][1]));
    CHECK(exact == back.size());
    CHECK(back_polygons == polygons);
    // and write_surface_mesh, which uses it for .off without options, the same
    const Mesh m = analytic::sphere(8, 4).to_mesh<Mesh>();
    PR::write_surface_mesh((dir / "sphere.off").string(), m);
    std::vector<Point> sphere;
    Polygons sphere_faces;
    REQUIRE(cgal_read((dir / "sphere.off").string(), sphere, sphere_faces));
    REQUIRE(sphere.size() == num_vertices(m));
    REQUIRE(sphere_faces.size() == num_faces(m));
    std::size_t i = 0;
    for(auto v : vertices(m)) CHECK(sphere[i++] == m.point(v));
  }
}

// ------------------------------------------------------------------ sizing
TEST_CASE("sizing: edge length and disk radius follow from the vertex count", "[sizing]")
{
  // an ideal equilateral mesh of area A with V vertices: A = V * sqrt(3)/2 * L^2
  const double L = PR::edge_length_from_vertex_count(10.0, 1000.0);
  CHECK(1000.0 * std::sqrt(3.0) / 2 * L * L == Approx(10.0));
  CHECK(PR::vertex_count_from_edge_length(10.0, L) == Approx(1000.0));
  // Eq. 1 with rho = 1 is the hexagonal packing radius: N = 1 / (2 sqrt(3) r^2)
  const double r = PR::disk_radius_from_vertex_count(1.0, 500.0, 1.0);
  CHECK(1.0 / (2 * std::sqrt(3.0) * r * r) == Approx(500.0));
  CHECK(PR::disk_radius_from_vertex_count(1.0, 500.0) == Approx(0.844 * r));
  CHECK_THROWS_AS(PR::edge_length_from_vertex_count(-1, 10), std::invalid_argument);
}

TEST_CASE("the parallel quality report gives the sequential one's figures", "[report][parallel]")
{
  // a mesh that cuts itself, against a jittered copy of it that cuts itself more (both searches,
  // both Hausdorff directions, and the crossings away from the reference's own)
  analytic::Soup s = analytic::sphere(24, 12), t = analytic::sphere(24, 12);
  const std::size_t offset = s.points.size();
  for(auto p : t.points) s.points.push_back({p[0] + 0.5, p[1], p[2]});
  for(auto f : t.triangles) s.triangles.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  const Mesh reference = s.to_mesh<Mesh>();
  Mesh m = reference;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  for(auto v : vertices(m)) m.point(v) = m.point(v) + K::Vector_3(u(rng), u(rng), u(rng));
  for(bool sampled : {true, false}) {
    const auto np = PR::parameters::sampled_hausdorff(sampled).hausdorff_relative_error_bound(1e-3);
    const PR::Quality_report a = PR::quality_report(m, reference, np);
    const PR::Quality_report b = PR::quality_report<CGAL::Parallel_if_available_tag>(m, reference, np);
    REQUIRE(a.number_of_self_intersecting_face_pairs > 0);
    CHECK(b.number_of_self_intersecting_face_pairs == a.number_of_self_intersecting_face_pairs);
    REQUIRE(a.number_of_reference_self_intersecting_face_pairs);
    CHECK(*b.number_of_reference_self_intersecting_face_pairs == *a.number_of_reference_self_intersecting_face_pairs);
    CHECK(*b.number_of_self_intersecting_face_pairs_away_from_reference_ones == *a.number_of_self_intersecting_face_pairs_away_from_reference_ones);
    REQUIRE(a.hausdorff);
    REQUIRE(b.hausdorff);
    CHECK(b.hausdorff_sampled == sampled);
    CHECK(*b.hausdorff == *a.hausdorff);   // (the largest of the same distances)
    CHECK(*b.hausdorff_error_bound == *a.hausdorff_error_bound);
    CHECK(b.min_angle == a.min_angle);
    CHECK(b.mean_min_angle == a.mean_min_angle);
    CHECK(b.irregular_share == a.irregular_share);
    const PR::Quality_report c = PR::quality_report(m), d = PR::quality_report<CGAL::Parallel_if_available_tag>(m);
    CHECK(d.number_of_self_intersecting_face_pairs == c.number_of_self_intersecting_face_pairs);
  }
}

TEST_CASE("the sampled Hausdorff distance is the largest of every sample point's distance", "[report]")
{
  // the report searches only the points that could raise the largest distance; here every
  // vertex, edge midpoint and centroid of both meshes is searched, by brute force in a plain tree
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> Tree;
  auto largest = [](const Mesh& a, const Mesh& b) {
    Tree tree(faces(b).first, faces(b).second, b);
    double d2 = 0;
    for(auto v : vertices(a)) d2 = std::max(d2, CGAL::to_double(tree.squared_distance(a.point(v))));
    for(auto e : edges(a))
      d2 = std::max(d2, CGAL::to_double(tree.squared_distance(CGAL::midpoint(a.point(source(e, a)), a.point(target(e, a))))));
    for(auto f : faces(a)) {
      const auto h = halfedge(f, a);
      d2 = std::max(d2, CGAL::to_double(tree.squared_distance(
                            CGAL::centroid(a.point(source(h, a)), a.point(target(h, a)), a.point(target(next(h, a), a))))));
    }
    return std::sqrt(d2);
  };
  // a noisy sphere against the sphere, a coarse sphere against a fine one, an open patch bent
  const Mesh sphere = analytic::sphere(24, 12).to_mesh<Mesh>(), coarse = analytic::sphere(10, 5).to_mesh<Mesh>();
  Mesh noisy = sphere;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for(auto v : vertices(noisy)) noisy.point(v) = noisy.point(v) + K::Vector_3(u(rng), u(rng), u(rng));
  const Mesh plane = analytic::plane(9, 7).to_mesh<Mesh>();
  Mesh bent = plane;
  for(auto v : vertices(bent)) { const Point p = bent.point(v); bent.point(v) = Point(p.x(), p.y(), 0.3 * p.x() * p.x() + 0.05 * u(rng)); }
  const std::vector<std::pair<const Mesh*, const Mesh*>> pairs = {{&noisy, &sphere}, {&coarse, &sphere}, {&bent, &plane}};
  for(const auto& pair : pairs) {
    const Mesh& a = *pair.first;
    const Mesh& b = *pair.second;
    const auto np = PR::parameters::check_self_intersections(false).sampled_hausdorff(true);
    for(const PR::Quality_report& r : {PR::quality_report(a, b, np), PR::quality_report<CGAL::Parallel_if_available_tag>(a, b, np)}) {
      REQUIRE(r.hausdorff_absolute);
      CHECK(*r.hausdorff_absolute == Approx(std::max(largest(a, b), largest(b, a))).epsilon(1e-9));
    }
  }
}

TEST_CASE("the sampled Hausdorff distance brackets CGAL's bounded-error one", "[report]")
{
  // a coarse and a fine sphere, and a cube against its finer triangulation (flat: distance 0)
  const Mesh coarse = analytic::sphere(12, 6).to_mesh<Mesh>(), fine = analytic::sphere(48, 24).to_mesh<Mesh>();
  const Mesh cube = analytic::cube(1).to_mesh<Mesh>(), fine_cube = analytic::cube(6).to_mesh<Mesh>();
  for(const auto& pair : {std::make_pair(&coarse, &fine), std::make_pair(&cube, &fine_cube)}) {
    const PR::Quality_report exact = PR::quality_report(*pair.first, *pair.second, PR::parameters::check_self_intersections(false));
    const PR::Quality_report sampled =
      PR::quality_report(*pair.first, *pair.second, PR::parameters::check_self_intersections(false).sampled_hausdorff(true));
    REQUIRE(sampled.hausdorff);
    REQUIRE(sampled.hausdorff_error_bound);
    CHECK(sampled.hausdorff_sampled);
    CHECK_FALSE(exact.hausdorff_sampled);
    // a lower bound of the true distance, which is at most the stated gap more
    CHECK(*sampled.hausdorff <= *exact.hausdorff + *exact.hausdorff_error_bound + 1e-12);
    CHECK(*exact.hausdorff - *exact.hausdorff_error_bound <= *sampled.hausdorff + *sampled.hausdorff_error_bound + 1e-12);
  }
}
