// Poisson_remesh/quality_report.h
//
// Entry point: quality_report(mesh, np) and quality_report(mesh, reference, np).
// The figures by which the paper judges a remesh (Table 1: smallest angle, mean of the triangles'
// smallest angles, irregular vertices) and those a user of the output needs (topology, shape
// quality, self-intersections, two-sided Hausdorff distance to the input), always computed the
// same way:
//   theta_min       smallest angle of the mesh, in degrees
//   mean_min_angle  mean over triangles of each triangle's smallest angle
//   irregular_share share of vertices whose valence is not 6 (not 4 on a border)
//   hausdorff       two-sided Hausdorff distance to the reference over the reference's bbox diagonal
//   shape quality   Frey-Borouchaki Q = 2*sqrt(3) * area / (half_perimeter * longest_edge), 1 when equilateral
// Works on any FaceGraph whose faces are triangles (Surface_mesh, Polyhedron_3, ...).

#ifndef POISSON_REMESH_QUALITY_REPORT_H
#define POISSON_REMESH_QUALITY_REPORT_H

#include <Poisson_remesh/parameters.h>

// CGAL's distance.h calls CGAL::midpoint with a qualified name: the kernel's global functions
// must be declared before it is parsed, whatever the user included first.
#include <CGAL/Kernel/global_functions.h>
#include <Poisson_remesh/Features/detect_features.h>   // (internal::Vertex_ball)
#include <Poisson_remesh/internal/parallel.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <boost/function_output_iterator.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <type_traits>
#include <utility>
#include <vector>

namespace Poisson_remesh {

/// The quality figures of a triangle mesh (angles in degrees).
struct Quality_report
{
  // size and topology
  std::size_t number_of_vertices = 0;   ///< V
  std::size_t number_of_edges = 0;      ///< E
  std::size_t number_of_faces = 0;      ///< F
  std::size_t number_of_components = 0; ///< connected components
  long euler_characteristic = 0;        ///< V - E + F
  long genus = 0;                       ///< sum over components of (2 - chi_c - b_c) / 2
  std::size_t number_of_border_edges = 0;  ///< edges on a border
  std::size_t number_of_border_cycles = 0; ///< borders (b)

  // angles
  double min_angle = 0;                 ///< theta_min
  double mean_min_angle = 0;            ///< mean of each triangle's smallest angle
  double max_angle = 0;                 ///< the largest angle of the mesh
  double share_min_angle_below_30 = 0;  ///< share of triangles whose smallest angle is under 30 degrees
  std::size_t number_of_degenerate_faces = 0; ///< faces with a zero-length edge or zero area
  double angle_histogram_bin_width = 1; ///< degrees
  std::vector<std::size_t> angle_histogram; ///< all 3F angles, bins of angle_histogram_bin_width over [0, 180]

  // shape quality (Frey-Borouchaki)
  double min_shape_quality = 0;         ///< the smallest Q = 2 sqrt(3) area / (half-perimeter * longest edge)
  double mean_shape_quality = 0;        ///< the mean Q over the triangles (1: all equilateral)

  // connectivity
  double irregular_share = 0;           ///< valence != 6 inside, != 4 on a border
  std::map<std::size_t, std::size_t> valence_histogram;   ///< valence -> number of vertices

  // geometry
  double bbox_diagonal = 0;             ///< of the mesh's bounding box
  bool self_intersections_checked = false;   ///< false with `check_self_intersections(false)`
  std::size_t number_of_self_intersecting_face_pairs = 0;   ///< (when checked)

  // against a reference (the input of a remesh)
  std::optional<double> hausdorff;      ///< two-sided, over the reference's bbox diagonal
  std::optional<double> hausdorff_absolute;   ///< two-sided, in the unit of the coordinates
  /// the error bound of `hausdorff` (relative to the reference's bbox diagonal, as it): the
  /// true distance is within this of the figure (named parameter hausdorff_relative_error_bound)
  std::optional<double> hausdorff_error_bound;
  /// `hausdorff` was sampled (named parameter sampled_hausdorff): a lower bound of the true
  /// distance, which is at most `hausdorff_error_bound` more; else the true distance is within
  /// `hausdorff_error_bound` of it
  bool hausdorff_sampled = false;
  /// theta_min leaving out the angles at the reference's sharp corners: vertices of the
  /// reference whose own angle is under 30 degrees, so that no mesh keeping them can do better
  /// there (see quality_report(tm, reference, np))
  std::optional<double> min_angle_away_from_sharp_corners;
  std::size_t number_of_angles_at_sharp_corners = 0;   ///< the angles left out of it
  /// (when self-intersections are checked) the reference's own self-intersecting face pairs, and
  /// those of tm not within two mean edge lengths (of tm) of them: where two sheets of the
  /// reference cross, a mesh following it closely crosses too
  /// @{
  std::optional<std::size_t> number_of_reference_self_intersecting_face_pairs;
  std::optional<std::size_t> number_of_self_intersecting_face_pairs_away_from_reference_ones;
  /// @}
};

namespace internal {

// true for CGAL::Named_function_parameters and the types derived from it (ours).
template <class T, class Tag, class Base>
std::true_type is_named_parameters_test(const CGAL::Named_function_parameters<T, Tag, Base>*);
std::false_type is_named_parameters_test(...);
template <class X>
struct is_named_parameters : decltype(is_named_parameters_test(static_cast<const X*>(nullptr))) {};

// The three angles of a triangle (degrees), computed with atan2(|a x b|, a.b), which stays
// accurate for angles close to 0 and 180 degrees where acos does not.
template <class Vector>
std::array<double, 3> triangle_angles(const Vector& e01, const Vector& e12, const Vector& e20)
{
  auto angle = [](const Vector& u, const Vector& v) {
    const double cx = CGAL::to_double(u.y() * v.z() - u.z() * v.y());
    const double cy = CGAL::to_double(u.z() * v.x() - u.x() * v.z());
    const double cz = CGAL::to_double(u.x() * v.y() - u.y() * v.x());
    const double d = CGAL::to_double(u.x() * v.x() + u.y() * v.y() + u.z() * v.z());
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), d) * 180.0 / CGAL_PI;
  };
  // angle at vertex 0 is between e01 and -e20, etc.
  return { angle(e01, -e20), angle(e12, -e01), angle(e20, -e12) };
}

template <class TriangleMesh, class Report>
void fill_topology(const TriangleMesh& tm, Report& r)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::vertex_descriptor vertex_descriptor;

  // count the ranges: num_vertices() of a Surface_mesh with garbage includes removed elements
  r.number_of_vertices = std::size_t(std::distance(vertices(tm).begin(), vertices(tm).end()));
  r.number_of_edges = std::size_t(std::distance(edges(tm).begin(), edges(tm).end()));
  r.number_of_faces = std::size_t(std::distance(faces(tm).begin(), faces(tm).end()));
  r.euler_characteristic = long(r.number_of_vertices) - long(r.number_of_edges) + long(r.number_of_faces);

  auto fim = CGAL::get_initialized_face_index_map(tm);
  std::vector<std::size_t> component(num_faces(tm), 0);
  auto fcc = boost::make_iterator_property_map(component.begin(), fim);
  r.number_of_components = faces(tm).empty() ? 0
    : CGAL::Polygon_mesh_processing::connected_components(tm, fcc, CGAL::parameters::face_index_map(fim));

  // per component: V, E, F and border cycles, for the genus
  std::vector<long> V(r.number_of_components, 0), E(V), F(V), B(V);
  for(face_descriptor f : faces(tm)) ++F[get(fcc, f)];
  auto component_of = [&](halfedge_descriptor h) -> long {
    if(!is_border(h, tm)) return long(get(fcc, face(h, tm)));
    halfedge_descriptor o = opposite(h, tm);
    if(!is_border(o, tm)) return long(get(fcc, face(o, tm)));
    return -1;
  };
  for(auto e : edges(tm)) {
    long c = component_of(halfedge(e, tm));
    if(c >= 0) ++E[c];
    if(is_border(e, tm)) ++r.number_of_border_edges;
  }
  for(vertex_descriptor v : vertices(tm)) {
    halfedge_descriptor h = halfedge(v, tm);
    if(h == GT::null_halfedge()) continue;
    long c = component_of(h);
    if(c >= 0) ++V[c];
  }
  std::vector<bool> seen(num_halfedges(tm), false);
  auto him = CGAL::get_initialized_halfedge_index_map(tm);
  for(halfedge_descriptor h : halfedges(tm)) {
    if(!is_border(h, tm) || seen[get(him, h)]) continue;
    ++r.number_of_border_cycles;
    long c = component_of(h);
    if(c >= 0) ++B[c];
    for(halfedge_descriptor g : CGAL::halfedges_around_face(h, tm)) seen[get(him, g)] = true;
  }
  r.genus = 0;
  for(std::size_t c = 0; c < r.number_of_components; ++c)
    r.genus += (2 - (V[c] - E[c] + F[c]) - B[c]) / 2;
}

template <class TriangleMesh, class VPM, class Report>
void fill_angles_and_shapes(const TriangleMesh& tm, VPM vpm, double bin_width, Report& r)
{
  r.angle_histogram_bin_width = bin_width;
  r.angle_histogram.assign(std::size_t(std::ceil(180.0 / bin_width)), 0);
  double min_angle = 180, max_angle = 0, sum_min = 0, min_q = 1, sum_q = 0;
  std::size_t below_30 = 0, counted = 0;
  for(auto f : faces(tm)) {
    auto h = halfedge(f, tm);
    const auto& p0 = get(vpm, source(h, tm));
    const auto& p1 = get(vpm, target(h, tm));
    const auto& p2 = get(vpm, target(next(h, tm), tm));
    const auto e01 = p1 - p0, e12 = p2 - p1, e20 = p0 - p2;
    const double l01 = std::sqrt(CGAL::to_double(e01.squared_length()));
    const double l12 = std::sqrt(CGAL::to_double(e12.squared_length()));
    const double l20 = std::sqrt(CGAL::to_double(e20.squared_length()));
    std::array<double, 3> a = triangle_angles(e01, e12, e20);
    const bool degenerate = l01 == 0 || l12 == 0 || l20 == 0 || !(std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]));
    if(degenerate) { ++r.number_of_degenerate_faces; a = {0, 0, 180}; }
    const double amin = std::min({a[0], a[1], a[2]});
    const double amax = std::max({a[0], a[1], a[2]});
    min_angle = std::min(min_angle, amin);
    max_angle = std::max(max_angle, amax);
    sum_min += amin;
    if(amin < 30) ++below_30;
    for(double x : a) {
      std::size_t bin = std::min(r.angle_histogram.size() - 1, std::size_t(std::max(0.0, x) / bin_width));
      ++r.angle_histogram[bin];
    }
    // Frey-Borouchaki: 2 sqrt(3) * area / (half perimeter * longest edge)
    double q = 0;
    if(!degenerate) {
      const double cx = CGAL::to_double(e01.y() * e12.z() - e01.z() * e12.y());
      const double cy = CGAL::to_double(e01.z() * e12.x() - e01.x() * e12.z());
      const double cz = CGAL::to_double(e01.x() * e12.y() - e01.y() * e12.x());
      const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
      const double s = 0.5 * (l01 + l12 + l20);
      q = 2 * std::sqrt(3.0) * area / (s * std::max({l01, l12, l20}));
    }
    min_q = std::min(min_q, q);
    sum_q += q;
    ++counted;
  }
  if(counted) {
    r.min_angle = min_angle;
    r.max_angle = max_angle;
    r.mean_min_angle = sum_min / double(counted);
    r.share_min_angle_below_30 = double(below_30) / double(counted);
    r.min_shape_quality = min_q;
    r.mean_shape_quality = sum_q / double(counted);
  }
}

template <class TriangleMesh, class Report>
void fill_valences(const TriangleMesh& tm, Report& r)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  std::size_t irregular = 0, counted = 0;
  for(auto v : vertices(tm)) {
    if(halfedge(v, tm) == GT::null_halfedge()) continue; // isolated
    const std::size_t d = degree(v, tm);
    const bool on_border = bool(is_border(v, tm));
    ++r.valence_histogram[d];
    if(d != (on_border ? 4u : 6u)) ++irregular;
    ++counted;
  }
  r.irregular_share = counted ? double(irregular) / double(counted) : 0;
}


// theta_min of tm without the angles at sharp corners of `reference`. A vertex of tm at the same
// point as a vertex v of the reference, in a triangle whose direction from v (to the midpoint of
// the opposite edge) lies in a sector of v whose own angle is under 30 degrees, is left out. The
// sectors of v are delimited by its sharp edges (dihedral angle sharper than sharp_angle, CGAL
// detect_sharp_edges) and border edges; a sector's own angle is the sum of the reference's angles
// at v in it over the least number of triangles that can fill it: 1 between two sharp edges, 3
// around a vertex with fewer (a cone tip: a closed surface has at least 3 triangles there). At a
// tip of tm -- on a vertex v of the reference with fewer than two sharp edges that is the
// pointiest (largest angle defect) within 0.9 s of it, s the mean length of the tip's edges in tm --
// the own angle is the best smallest angle at v of a fan of three triangles whose other vertices
// lie on the reference at distance s from v (see fan_bound below: on a cone, 2 asin(sin(a) sin 60)
// for a half-angle a, under a third of the cone angle 360 sin(a), which only a flat fan reaches).
template <class TriangleMesh, class VPM, class ReferenceMesh>
void fill_min_angle_away_from_sharp_corners(const TriangleMesh& tm, VPM vpm, const ReferenceMesh& ref, double sharp_angle, Quality_report& r)
{
  typedef boost::graph_traits<ReferenceMesh> RGT;
  typedef typename RGT::vertex_descriptor ref_vertex;
  typedef typename RGT::face_descriptor ref_face;
  typedef std::array<double, 3> V3;
  auto rvpm = get_const_property_map(CGAL::vertex_point, ref);
  auto to_v3 = [](const auto& p) { return V3{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}; };
  auto sub = [](const V3& a, const V3& b) { return V3{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto cross = [](const V3& a, const V3& b) { return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; };
  auto dot = [](const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto angle = [&](const V3& u, const V3& w) { return std::atan2(std::sqrt(dot(cross(u, w), cross(u, w))), dot(u, w)) * 180 / CGAL_PI; };

  auto sharp = get(CGAL::dynamic_edge_property_t<bool>(), ref);
  CGAL::Polygon_mesh_processing::detect_sharp_edges(ref, sharp_angle, sharp);
  auto is_cut = [&](typename RGT::halfedge_descriptor h) { return is_border_edge(h, ref) || get(sharp, edge(h, ref)); };

  // angle defects (degrees; 0 on borders and isolated vertices: filled with the sectors below)
  auto defect = get(CGAL::dynamic_vertex_property_t<double>(), ref);
  for(ref_vertex v : vertices(ref)) put(defect, v, 0.0);
  std::size_t index_bound = 0;
  const auto vim = CGAL::get_initialized_vertex_index_map(ref);
  for(ref_vertex v : vertices(ref)) index_bound = std::max(index_bound, std::size_t(get(vim, v)) + 1);
  Vertex_ball<ReferenceMesh, decltype(rvpm)> ball(ref, rvpm, index_bound);
  // v is the pointiest vertex within 0.9 `scale` of it (well inside), where the defects add up
  // to more than 0
  auto pointiest_tip = [&](ref_vertex v, double scale) {
    if(!(scale > 0) || !(get(defect, v) > 0)) return false;
    double sum = 0;
    bool pointiest = true;
    ball.visit(v, 0.9 * scale, [&](ref_vertex w, double) {
      sum += get(defect, w);
      if(get(defect, w) > get(defect, v)) pointiest = false;
    });
    return pointiest && sum > 0;
  };

  // the reference's vertices with a sector under 30 degrees, and the own angle of each face's sector there
  std::map<V3, std::vector<std::pair<ref_face, double>>> corners;
  std::map<V3, ref_vertex> tips;   // the other vertices with fewer than two sharp edges and a positive defect
  std::vector<typename RGT::halfedge_descriptor> ring;   // halfedges into v, in turning order
  std::vector<std::pair<ref_face, double>> sectors;
  std::vector<ref_face> members;
  for(ref_vertex v : vertices(ref)) {
    if(halfedge(v, ref) == RGT::null_halfedge()) continue;
    ring.clear();
    for(auto h : CGAL::halfedges_around_target(halfedge(v, ref), ref)) ring.push_back(h);
    const std::size_t n = ring.size();
    // face i is face(ring[i]); it meets face i+1 across edge(next(ring[i]))
    std::size_t cuts = 0, first_cut = n;
    for(std::size_t i = 0; i < n; ++i)
      if(is_cut(next(ring[i], ref))) { ++cuts; if(first_cut == n) first_cut = i; }
    const double least = cuts >= 2 ? 1 : 3;
    sectors.clear();
    members.clear();
    const std::size_t start = cuts == 0 ? 0 : first_cut + 1;
    double sum = 0, total = 0;
    bool small = false;
    for(std::size_t k = 0; k < n; ++k) {
      const auto h = ring[(start + k) % n];
      if(!is_border(h, ref)) {
        const V3 o = to_v3(get(rvpm, v));
        const double a = angle(sub(to_v3(get(rvpm, source(h, ref))), o), sub(to_v3(get(rvpm, target(next(h, ref), ref))), o));
        sum += a;
        total += a;
        members.push_back(face(h, ref));
      }
      if(k + 1 == n || (cuts >= 2 && is_cut(next(h, ref)))) {
        if(sum / least < 30) small = true;
        for(ref_face f : members) sectors.push_back({f, sum / least});
        sum = 0;
        members.clear();
      }
    }
    if(!is_border(v, ref)) put(defect, v, 360 - total);
    if(small) corners[to_v3(get(rvpm, v))] = sectors;
    else if(cuts < 2 && get(defect, v) > 0) tips[to_v3(get(rvpm, v))] = v;
  }
  // the largest smallest angle at v of a fan of triangles whose other vertices lie on the
  // reference at distance `scale` from v: seen from v, the reference's points at that distance
  // form a loop of unit directions of length L; the angle at v of a triangle
  // is the great-circle distance between the directions of its other two vertices, so a fan of k
  // triangles has one of at most L / k, and for k = 3 (every two of the three vertices in one
  // triangle) the best is found by trying the triples of directions along the loop
  auto fan_bound = [&](ref_vertex v, double scale) {
    const V3 o = to_v3(get(rvpm, v));
    std::set<ref_face> near_faces;   // the faces with a vertex inside the ball, reached through such vertices
    ball.visit(v, scale, [&](ref_vertex w, double) {
      for(auto h : CGAL::halfedges_around_target(halfedge(w, ref), ref))
        if(!is_border(h, ref)) near_faces.insert(face(h, ref));
    });
    auto unit = [&](const V3& d) { const double l = std::sqrt(dot(d, d)); return V3{d[0] / l, d[1] / l, d[2] / l}; };
    std::vector<V3> dirs;
    double loop = 0;
    for(ref_face f : near_faces) {
      V3 p[3];
      auto h = halfedge(f, ref);
      for(int i = 0; i < 3; ++i, h = next(h, ref)) p[i] = to_v3(get(rvpm, target(h, ref)));
      std::vector<V3> cross_points;
      for(int i = 0; i < 3; ++i) {
        V3 a = p[i], b = p[(i + 1) % 3];
        V3 e = sub(a, o);
        if((dot(e, e) < scale * scale) == (dot(sub(b, o), sub(b, o)) < scale * scale)) continue;
        if(!(dot(e, e) < scale * scale)) { std::swap(a, b); e = sub(a, o); }   // a inside
        const V3 d = sub(b, a);
        const double dd = dot(d, d), ed = dot(e, d), c = dot(e, e) - scale * scale;
        const double t = (-ed + std::sqrt(std::max(0.0, ed * ed - dd * c))) / dd;
        cross_points.push_back(V3{a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]});
      }
      if(cross_points.size() != 2) continue;
      const int m = 6;
      V3 last{};
      for(int k = 0; k < m; ++k) {
        const double t = double(k) / (m - 1);
        const V3 x = unit(sub(V3{cross_points[0][0] + t * (cross_points[1][0] - cross_points[0][0]),
                                 cross_points[0][1] + t * (cross_points[1][1] - cross_points[0][1]),
                                 cross_points[0][2] + t * (cross_points[1][2] - cross_points[0][2])}, o));
        if(k > 0) loop += angle(last, x);
        dirs.push_back(x);
        last = x;
      }
    }
    if(dirs.size() < 3) return 180.0;
    // (in an order that does not depend on the faces' handles, duplicates of shared crossing
    // points removed, then at most 90 directions: 120,000 triples)
    std::sort(dirs.begin(), dirs.end());
    dirs.erase(std::unique(dirs.begin(), dirs.end()), dirs.end());
    const std::size_t stride = dirs.size() / 90 + 1;
    std::vector<V3> few;
    for(std::size_t i = 0; i < dirs.size(); i += stride) few.push_back(dirs[i]);
    double best = 0;
    for(std::size_t i = 0; i < few.size(); ++i)
      for(std::size_t j = i + 1; j < few.size(); ++j) {
        const double ij = angle(few[i], few[j]);
        if(ij <= best) continue;
        for(std::size_t k = j + 1; k < few.size(); ++k)
          best = std::max(best, std::min({ij, angle(few[j], few[k]), angle(few[i], few[k])}));
      }
    // (L / 4 bounds a fan of four triangles from above; it may not be reached, but a tip where it
    // is 30 degrees or more is not one whose own angle is under 30)
    return std::max(best, loop / 4);
  };
  // the own angle at a vertex of tm on a tip: that bound at the mean length of its edges (when v
  // is the pointiest vertex within it)
  auto tip_angle = [&](typename boost::graph_traits<TriangleMesh>::vertex_descriptor x, ref_vertex v) {
    double length = 0;
    std::size_t n = 0;
    const V3 o = to_v3(get(vpm, x));
    for(auto h : CGAL::halfedges_around_target(halfedge(x, tm), tm)) {
      const V3 d = sub(to_v3(get(vpm, source(h, tm))), o);
      length += std::sqrt(dot(d, d));
      ++n;
    }
    if(n == 0 || !pointiest_tip(v, length / double(n))) return 180.0;
    return fan_bound(v, length / double(n));
  };

  std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, double> tip_angles;
  double worst = 180;
  for(auto f : faces(tm)) {
    auto h = halfedge(f, tm);
    for(int k = 0; k < 3; ++k, h = next(h, tm)) {
      const V3 c = to_v3(get(vpm, target(h, tm))), a = to_v3(get(vpm, source(h, tm))), b = to_v3(get(vpm, target(next(h, tm), tm)));
      const double x = angle(sub(a, c), sub(b, c));
      auto it = corners.find(c);
      if(it != corners.end()) {
        // the reference face around the corner whose wedge holds the triangle's direction best
        const V3 d = sub(V3{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}, c);
        double best = -std::numeric_limits<double>::infinity(), own = 180;
        for(const auto& [rf, bound] : it->second) {
          const auto rh = halfedge(rf, ref);
          V3 q[3] = {to_v3(get(rvpm, source(rh, ref))), to_v3(get(rvpm, target(rh, ref))), to_v3(get(rvpm, target(next(rh, ref), ref)))};
          int i = 0;
          while(i < 3 && q[i] != c) ++i;
          if(i == 3) continue;
          const V3 u = sub(q[(i + 1) % 3], c), w = sub(q[(i + 2) % 3], c), nrm = cross(u, w);
          const double ln = std::sqrt(dot(nrm, nrm)) * std::sqrt(dot(d, d));
          if(!(ln > 0)) continue;
          const double score = std::min(dot(cross(u, d), nrm) / (ln * std::sqrt(dot(u, u))),
                                        dot(cross(d, w), nrm) / (ln * std::sqrt(dot(w, w))));
          if(score > best) { best = score; own = bound; }
        }
        if(own < 30) { ++r.number_of_angles_at_sharp_corners; continue; }
      } else if(auto tip = tips.find(c); tip != tips.end()) {
        auto cached = tip_angles.find(target(h, tm));
        if(cached == tip_angles.end()) cached = tip_angles.insert({target(h, tm), tip_angle(target(h, tm), tip->second)}).first;
        if(cached->second < 30) { ++r.number_of_angles_at_sharp_corners; continue; }
      }
      if(std::isfinite(x)) worst = std::min(worst, x);
    }
  }
  r.min_angle_away_from_sharp_corners = worst;
}

// the mean length of tm's edges (0 without edges)
template <class TriangleMesh, class VPM>
double mean_edge_length(const TriangleMesh& tm, VPM vpm)
{
  double length = 0;
  std::size_t n = 0;
  for(auto e : edges(tm)) {
    length += std::sqrt(CGAL::to_double(CGAL::squared_distance(get(vpm, source(e, tm)), get(vpm, target(e, tm)))));
    ++n;
  }
  return n ? length / double(n) : 0;
}

// the faces of a reference mesh that cut another of its faces (PMP::self_intersections; a
// degenerate face, reported as the pair (f, f), is no crossing of two sheets), and whether a face
// of another mesh lies near them: its centroid within `reach` of one of them. The quality report
// counts the crossings of tm away from the reference's own with it, and the remesher's remakes
// (internal/regrading.h) look for theirs the same way.
template <class ReferenceMesh>
class Reference_crossings
{
  typedef typename boost::graph_traits<ReferenceMesh>::face_descriptor ref_face;
  typedef typename boost::property_traits<decltype(get_const_property_map(CGAL::vertex_point, std::declval<const ReferenceMesh&>()))>::value_type Ref_point;
  typedef typename CGAL::Kernel_traits<Ref_point>::Kernel RK;
  typedef CGAL::AABB_face_graph_triangle_primitive<ReferenceMesh> Primitive;

public:
  /// (`ConcurrencyTag`: the mode of the search, the same pairs)
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  explicit Reference_crossings(const ReferenceMesh& ref, ConcurrencyTag = ConcurrencyTag())
  {
    std::vector<std::pair<ref_face, ref_face>> ref_pairs;
    CGAL::Polygon_mesh_processing::self_intersections<ConcurrencyTag>(ref, std::back_inserter(ref_pairs));
    ref_pairs.erase(std::remove_if(ref_pairs.begin(), ref_pairs.end(), [](const auto& p) { return p.first == p.second; }), ref_pairs.end());
    number_of_pairs = ref_pairs.size();
    for(const auto& p : ref_pairs) { faces_.push_back(p.first); faces_.push_back(p.second); }
    std::sort(faces_.begin(), faces_.end());
    faces_.erase(std::unique(faces_.begin(), faces_.end()), faces_.end());
    if(!faces_.empty()) tree_.rebuild(faces_.begin(), faces_.end(), ref);
  }
  std::size_t number_of_pairs = 0;   ///< the reference's own crossing face pairs
  template <class TriangleMesh, class VPM>
  bool near(const TriangleMesh& tm, VPM vpm, typename boost::graph_traits<TriangleMesh>::face_descriptor f, double reach) const
  {
    if(faces_.empty()) return false;
    double c[3] = {0, 0, 0};
    for(auto v : CGAL::vertices_around_face(halfedge(f, tm), tm)) {
      const auto& p = get(vpm, v);
      c[0] += CGAL::to_double(p.x()) / 3; c[1] += CGAL::to_double(p.y()) / 3; c[2] += CGAL::to_double(p.z()) / 3;
    }
    return CGAL::to_double(tree_.squared_distance(typename RK::Point_3(c[0], c[1], c[2]))) <= reach * reach;
  }

private:
  std::vector<ref_face> faces_;
  CGAL::AABB_tree<CGAL::AABB_traits<RK, Primitive>> tree_;
};

// the reference's self-intersecting face pairs, and those of tm's (`pairs`) that are not near them: a pair of tm is
// near when both its triangles' centroids are within two mean edge lengths of tm of a triangle
// of the reference that cuts another
template <class TriangleMesh, class VPM, class ReferenceMesh>
void fill_self_intersections_away_from_reference_ones(
  const TriangleMesh& tm, VPM vpm, const ReferenceMesh& ref,
  const std::vector<std::pair<typename boost::graph_traits<TriangleMesh>::face_descriptor, typename boost::graph_traits<TriangleMesh>::face_descriptor>>& pairs,
  Quality_report& r)
{
  const Reference_crossings<ReferenceMesh> crossings(ref);   // (sequential, as in quality_report_of)
  r.number_of_reference_self_intersecting_face_pairs = crossings.number_of_pairs;
  if(crossings.number_of_pairs == 0) {
    r.number_of_self_intersecting_face_pairs_away_from_reference_ones = r.number_of_self_intersecting_face_pairs;
    return;
  }
  const double reach = 2 * mean_edge_length(tm, vpm);
  std::size_t away = 0;
  for(const auto& p : pairs)
    if(!crossings.near(tm, vpm, p.first, reach) || !crossings.near(tm, vpm, p.second, reach)) ++away;
  r.number_of_self_intersecting_face_pairs_away_from_reference_ones = away;
}

// quality_report(tm, np), and the self-intersecting face pairs in `pairs` (when checked and
// `pairs` is given)
template <class ConcurrencyTag, class TriangleMesh, class NamedParameters>
Quality_report quality_report_of(const TriangleMesh& tm, const NamedParameters& np,
                                 std::vector<std::pair<typename boost::graph_traits<TriangleMesh>::face_descriptor,
                                                       typename boost::graph_traits<TriangleMesh>::face_descriptor>>* pairs)
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  using parameters::choose_parameter;
  using parameters::get_parameter;
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  const bool check_si = choose_parameter(get_parameter(np, internal_np::check_self_intersections), true);
  const double bin_width = choose_parameter(get_parameter(np, internal_np::angle_histogram_bin_width), 1.0);

  Quality_report r;
  internal::fill_topology(tm, r);
  internal::fill_angles_and_shapes(tm, vpm, bin_width > 0 ? bin_width : 1.0, r);
  internal::fill_valences(tm, r);
  if(!faces(tm).empty()) {
    CGAL::Bbox_3 b = CGAL::Polygon_mesh_processing::bbox(tm, CGAL::parameters::vertex_point_map(vpm));
    r.bbox_diagonal = std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                                CGAL::square(b.zmax() - b.zmin()));
  }
  if(check_si && !faces(tm).empty()) {
    std::size_t count = 0;
    // (on one thread whatever ConcurrencyTag says: CGAL 5.5's parallel search took longer than its
    // sequential one on two cores; RESULTS, "The program around the remesh")
    CGAL::Polygon_mesh_processing::self_intersections<CGAL::Sequential_tag>(
      tm, boost::make_function_output_iterator([&](const std::pair<face_descriptor, face_descriptor>& fp) {
        ++count;
        if(pairs) pairs->push_back(fp);
      }),
      CGAL::parameters::vertex_point_map(vpm));
    r.self_intersections_checked = true;
    r.number_of_self_intersecting_face_pairs = count;
  }
  return r;
}

// A sampled one-sided Hausdorff distance from `a` to the surface of `b` (`tree`: b's faces; the
// sampled Hausdorff of the quality report): the largest distance from a's vertices, edge midpoints
// and face centroids to b (a lower bound of the true one-sided distance), and how much more the
// true one can be: the distance to a surface is 1-Lipschitz, and every point of a triangle whose
// longest edge is l lies within l / (2 sqrt 3) of one of its vertices or edge midpoints (the four
// half-size triangles they make each lie within their circumradius, at most their longest edge
// over sqrt 3, of one of their corners).
// Only the largest distance is wanted, so a midpoint or centroid is searched in the tree only
// when it could raise it: its distance to any faces of b bounds its distance to b from above, and
// the points are searched by decreasing bound until the bound is no more than the largest distance
// found (the same figure as searching every point, to within `negligible`, for a fraction of the
// searches).
// (`ConcurrencyTag`: the vertices' searches, the bounds and the blocks of searches by TBB's
// threads, the same figures)
template <class ConcurrencyTag, class Mesh, class VPM, class MeshB, class VPMB, class Tree>
std::pair<double, double> sampled_one_sided_hausdorff(const Mesh& a, VPM vpm, const MeshB& b, VPMB vpm_b, const Tree& tree,
                                                      double negligible)
{
  typedef typename Tree::Point Point;
  typedef typename CGAL::Kernel_traits<Point>::Kernel K;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<Mesh>::edge_descriptor edge_descriptor;
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  typedef typename boost::graph_traits<MeshB>::face_descriptor face_b;
  const std::vector<vertex_descriptor> vs(vertices(a).begin(), vertices(a).end());
  const std::vector<edge_descriptor> es(edges(a).begin(), edges(a).end());
  const std::vector<face_descriptor> fs(faces(a).begin(), faces(a).end());
  auto index = get(CGAL::dynamic_vertex_property_t<std::size_t>(), a);
  for(std::size_t i = 0; i < vs.size(); ++i) put(index, vs[i], i);
  // (each element's squared distance in its own slot, the largest taken after: any order of the
  // threads gives the same figure)
  std::vector<face_b> nearest_face(vs.size());
  std::vector<double> dv(vs.size()), longest(fs.size());
  for_each_index<ConcurrencyTag>(vs.size(), [&](std::size_t i) {
    const Point p = get(vpm, vs[i]);
    const auto hit = tree.closest_point_and_primitive(p);
    nearest_face[i] = hit.second;
    dv[i] = CGAL::to_double(CGAL::squared_distance(p, hit.first));
  });
  // (the largest vertex distance: a midpoint or centroid nearer than it cannot raise the figure)
  double lower = 0, cover = 0;
  for(double x : dv) lower = std::max(lower, x);
  // (a bound within rounding of the largest distance found, or under `negligible`, cannot raise it
  // by more than that: on a flat part every distance is rounding noise, and all would be searched)
  const double rounding = 1 + 1e-12;
  auto could_raise = [&](double bound) { return bound > lower * rounding && bound > negligible * negligible; };
  // the midpoints and centroids, each with an upper bound of its squared distance to b: its
  // distance to the nearest of the faces of b nearest its own vertices (one to three triangles; a
  // whole ring of faces around them cost more than the searches it saved), and that face
  struct Candidate { Point x; face_b face; double bound; };
  std::vector<Candidate> cs(es.size() + fs.size());
  auto triangle = [&](face_b g) {
    const auto h = halfedge(g, b);
    return typename K::Triangle_3(get(vpm_b, source(h, b)), get(vpm_b, target(h, b)), get(vpm_b, target(next(h, b), b)));
  };
  // (a degenerate triangle is measured as its segments)
  auto distance = [&](const Point& x, face_b g) { return CGAL::to_double(CGAL::squared_distance(x, triangle(g))); };
  auto candidate = [&](const Point& x, const std::size_t* element, std::size_t n) {
    Candidate c{x, nearest_face[element[0]], std::numeric_limits<double>::infinity()};
    for(std::size_t k = 0; k < n; ++k) {
      const face_b g = nearest_face[element[k]];
      if(std::find_if(element, element + k, [&](std::size_t w) { return nearest_face[w] == g; }) != element + k) continue;
      const double d = distance(x, g);
      if(d < c.bound) { c.bound = d; c.face = g; }
    }
    return c;
  };
  // A point that could raise the figure is first brought nearer: from its face to the neighbour
  // across an edge that is nearer, while there is one (a few steps; on a flat part the point's
  // own face, at distance 0). Then, if it still could, it is searched in the tree from the point
  // of that face nearest to it (a search from there visits few boxes).
  auto searched = [&](const Candidate& c) {
    face_b g = c.face;
    double d = c.bound;
    for(int step = 0; step < 8 && d > 0; ++step) {
      face_b best = g;
      for(auto h : CGAL::halfedges_around_face(halfedge(g, b), b)) {
        const face_b n = face(opposite(h, b), b);
        if(n == boost::graph_traits<MeshB>::null_face()) continue;
        const double dn = distance(c.x, n);
        if(dn < d) { d = dn; best = n; }
      }
      if(best == g) break;
      g = best;
    }
    if(!could_raise(d)) return 0.0;
    Point start = K().construct_projected_point_3_object()(triangle(g), c.x);
    // (the search's start must lie on b: a corner of the face if the projection failed)
    if(!(std::isfinite(CGAL::to_double(start.x())) && std::isfinite(CGAL::to_double(start.y())) &&
         std::isfinite(CGAL::to_double(start.z()))))
      start = get(vpm_b, target(halfedge(g, b), b));
    return CGAL::to_double(tree.squared_distance(c.x, start));
  };
  for_each_index<ConcurrencyTag>(es.size(), [&](std::size_t i) {
    const auto h = halfedge(es[i], a);
    const std::size_t element[2] = {get(index, source(h, a)), get(index, target(h, a))};
    cs[i] = candidate(CGAL::midpoint(get(vpm, source(h, a)), get(vpm, target(h, a))), element, 2);
  });
  for_each_index<ConcurrencyTag>(fs.size(), [&](std::size_t i) {
    const auto h = halfedge(fs[i], a);
    const auto p = get(vpm, source(h, a)), q = get(vpm, target(h, a)), r = get(vpm, target(next(h, a), a));
    const std::size_t element[3] = {get(index, source(h, a)), get(index, target(h, a)), get(index, target(next(h, a), a))};
    cs[es.size() + i] = candidate(CGAL::centroid(p, q, r), element, 3);
    longest[i] = std::max({CGAL::to_double(CGAL::squared_distance(p, q)), CGAL::to_double(CGAL::squared_distance(q, r)),
                           CGAL::to_double(CGAL::squared_distance(r, p))});
  });
  for(double x : longest) cover = std::max(cover, x);
  std::vector<std::size_t> order;
  for(std::size_t i = 0; i < cs.size(); ++i)
    if(could_raise(cs[i].bound)) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return cs[i].bound > cs[j].bound || (cs[i].bound == cs[j].bound && i < j); });
  // (in blocks of 256, each searched by TBB's threads: a block may search a few points the one-by-one
  // loop would have skipped, whose distances are under the largest found, so the figure is the same)
  std::vector<double> found;
  for(std::size_t start = 0; start < order.size() && could_raise(cs[order[start]].bound); start += 256) {
    const std::size_t n = std::min<std::size_t>(256, order.size() - start);
    found.assign(n, 0);
    for_each_index<ConcurrencyTag>(n, [&](std::size_t k) { found[k] = searched(cs[order[start + k]]); });
    for(double d : found) lower = std::max(lower, d);
  }
  return {std::sqrt(lower), std::sqrt(cover) / (2 * std::sqrt(3.0))};
}

} // namespace internal

/*!
  computes the quality figures of `tm`, a triangle mesh modelling `FaceListGraph`.

  Named parameters:
  - `vertex_point_map` (default `boost::get(CGAL::vertex_point, tm)`)
  - `check_self_intersections` (bool, default true): count self-intersecting face pairs with
    `CGAL::Polygon_mesh_processing::self_intersections()`
  - `angle_histogram_bin_width` (degrees, default 1)

  `ConcurrencyTag`: CGAL::Sequential_tag (the default) or CGAL::Parallel_tag (needs TBB) /
  CGAL::Parallel_if_available_tag, with the same figures. Here it changes nothing: the
  self-intersection search runs on one thread (CGAL 5.5's parallel search was the slower one on two
  cores); the form with a reference below runs its Hausdorff queries on TBB's threads.
*/
template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleMesh, class T = bool, class Tag = CGAL::internal_np::all_default_t,
          class Base = CGAL::internal_np::No_property>
Quality_report quality_report(const TriangleMesh& tm,
                              const CGAL::Named_function_parameters<T, Tag, Base>& np = parameters::default_values())
{
  return internal::quality_report_of<ConcurrencyTag>(tm, np, nullptr);
}

/*!
  as above, and the two-sided Hausdorff distance between `tm` and `reference` (computed with
  `CGAL::Polygon_mesh_processing::bounded_error_symmetric_Hausdorff_distance()`), absolute and
  over the reference's bounding-box diagonal.

  Extra named parameters: `hausdorff_relative_error_bound` (default 1e-4): the error bound of the
  Hausdorff estimate, relative to the reference's bounding-box diagonal; `sampled_hausdorff`
  (bool, default false): instead, the largest distance from the vertices, edge midpoints and face
  centroids of each mesh to the other (much cheaper on large flat parts), a lower bound whose gap
  to the true distance is bounded by the longest edge of either mesh over 2 sqrt 3
  (`hausdorff_error_bound`); `sharp_angle` (degrees,
  default 60): the dihedral angle of the reference's sharp edges, for
  `min_angle_away_from_sharp_corners` (theta_min without the angles at corners of the reference
  whose own angle is under 30 degrees: cone tips with an angle sum under 90 degrees, or -- at a
  tip that is the pointiest within the scale of its edges in tm -- whose best fan of three
  triangles with their other vertices on the reference at that distance has an angle under 30
  at the tip (a cone of half-angle a: 2 asin(sin(a) sin 60 degrees)); wedges between sharp edges
  under 30 degrees; there no mesh keeping the corner reaches 30). When self-intersections are
  checked, also the reference's own self-intersecting pairs and tm's pairs away from them
  (`number_of_self_intersecting_face_pairs_away_from_reference_ones`);
  `reference_self_intersections` (std::size_t; std::size_t(-1), the default: unknown): the reference's own count of
  self-intersecting pairs of two distinct faces, when the caller has it (from the reference's
  report, when it has no degenerate face): the reference is then searched only if tm has
  self-intersecting pairs. `ConcurrencyTag`: as above
  (the sampled Hausdorff distance's queries too; CGAL's bounded-error one runs on one thread:
  its parallel mode needs METIS).
*/
template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleMesh, class ReferenceMesh, class T = bool, class Tag = CGAL::internal_np::all_default_t,
          class Base = CGAL::internal_np::No_property,
          class = std::enable_if_t<!internal::is_named_parameters<ReferenceMesh>::value>>
Quality_report quality_report(const TriangleMesh& tm, const ReferenceMesh& reference,
                              const CGAL::Named_function_parameters<T, Tag, Base>& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  std::vector<std::pair<face_descriptor, face_descriptor>> pairs;   // (tm's self-intersections)
  Quality_report r = internal::quality_report_of<ConcurrencyTag>(tm, np, &pairs);
  if(faces(tm).empty() || faces(reference).empty()) return r;
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  const double rel_bound = choose_parameter(get_parameter(np, internal_np::hausdorff_relative_error_bound), 1e-4);
  CGAL::Bbox_3 b = CGAL::Polygon_mesh_processing::bbox(reference);
  const double diag = std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                                CGAL::square(b.zmax() - b.zmin()));
  if(choose_parameter(get_parameter(np, internal_np::sampled_hausdorff), false)) {
    // (cheap: a few closest-point queries per element, with the gap to the true value stated)
    typedef typename boost::property_traits<decltype(vpm)>::value_type Point;
    typedef typename CGAL::Kernel_traits<Point>::Kernel RK;
    typedef CGAL::AABB_tree<CGAL::AABB_traits<RK, CGAL::AABB_face_graph_triangle_primitive<TriangleMesh, decltype(vpm)>>> Tm_tree;
    typedef CGAL::AABB_tree<CGAL::AABB_traits<RK, CGAL::AABB_face_graph_triangle_primitive<ReferenceMesh>>> Reference_tree;
    Tm_tree tm_tree(faces(tm).first, faces(tm).second, tm, vpm);
    Reference_tree reference_tree(faces(reference).first, faces(reference).second, reference);
    // (built here, not by the first query: the queries may run on several threads)
    tm_tree.build();
    reference_tree.build();
    tm_tree.accelerate_distance_queries();
    reference_tree.accelerate_distance_queries();
    const auto rvpm = get_const_property_map(CGAL::vertex_point, reference);
    // (distances under 1e-12 of the diagonal are not told apart: far below the figure's precision)
    const auto there = internal::sampled_one_sided_hausdorff<ConcurrencyTag>(tm, vpm, reference, rvpm, reference_tree, 1e-12 * diag);
    const auto back = internal::sampled_one_sided_hausdorff<ConcurrencyTag>(reference, rvpm, tm, vpm, tm_tree, 1e-12 * diag);
    const double h = std::max(there.first, back.first);
    r.hausdorff_absolute = h;
    r.hausdorff = diag > 0 ? h / diag : 0.0;
    r.hausdorff_sampled = true;
    r.hausdorff_error_bound = diag > 0 ? std::max(there.first + there.second, back.first + back.second) / diag - *r.hausdorff : 0.0;
  } else {
    const double h = CGAL::Polygon_mesh_processing::bounded_error_symmetric_Hausdorff_distance<CGAL::Sequential_tag>(
      tm, reference, rel_bound * diag, CGAL::parameters::vertex_point_map(vpm));
    r.hausdorff_absolute = h;
    r.hausdorff = diag > 0 ? h / diag : 0.0;
    r.hausdorff_error_bound = rel_bound;
  }
  internal::fill_min_angle_away_from_sharp_corners(tm, vpm, reference, choose_parameter(get_parameter(np, internal_np::sharp_angle), 60.0), r);
  // (the reference's own crossings are searched only when tm has crossings to tell from them, if
  // the caller knows the reference's count: a second search of the same mesh otherwise)
  const std::size_t known = choose_parameter(get_parameter(np, internal_np::reference_self_intersections), std::size_t(-1));
  if(r.self_intersections_checked && pairs.empty() && known != std::size_t(-1)) {
    r.number_of_reference_self_intersecting_face_pairs = known;
    r.number_of_self_intersecting_face_pairs_away_from_reference_ones = 0;
  } else if(r.self_intersections_checked)
    internal::fill_self_intersections_away_from_reference_ones(tm, vpm, reference, pairs, r);
  return r;
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_QUALITY_REPORT_H
