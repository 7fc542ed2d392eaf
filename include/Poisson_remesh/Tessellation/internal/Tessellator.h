// Poisson_remesh/Tessellation/internal/Tessellator.h
//
// The working state of the mutual tessellation (paper §6.1; entry point and documentation in
// Poisson_remesh/Tessellation/mutual_tessellation.h): the mesh being tessellated, what each of
// its vertices is (input vertex or sample), which edges are features, and the local operations
// of the paper -- the guarded edge flip, the removal of an original vertex through the §6.1
// layout and a constrained Delaunay triangulation -- plus the fallbacks of this implementation.
// Not part of the interface: users must not rely on it.

#ifndef POISSON_REMESH_TESSELLATION_INTERNAL_TESSELLATOR_H
#define POISSON_REMESH_TESSELLATION_INTERNAL_TESSELLATOR_H

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>
#include <Poisson_remesh/Tessellation/internal/polygon_cdt.h>
#include <Poisson_remesh/internal/memory_free_order.h>
#include <Poisson_remesh/internal/self_intersections.h>
#include <Poisson_remesh/internal/vector_angle.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

typedef std::array<double, 3> Vec3;
inline Vec3 sub3(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 cross3(const Vec3& a, const Vec3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm3(const Vec3& a) { return std::sqrt(dot3(a, a)); }
inline double angle3(const Vec3& a, const Vec3& b) // radians, in [0, pi]
{
  return vector_angle(norm3(cross3(a, b)), dot3(a, b));
}
// the smallest angle of triangle abc lies opposite its shortest side: its two sides at that
// corner, so that one angle is measured instead of three (the flips of the tessellation ask for
// it four times per edge they look at)
typedef std::pair<Vec3, Vec3> Corner_sides;
inline Corner_sides smallest_angle_sides(const Vec3& a, const Vec3& b, const Vec3& c)
{
  auto squared_length = [](const Vec3& v) { return dot3(v, v); };
  const double ab = squared_length(sub3(b, a)), bc = squared_length(sub3(c, b)), ca = squared_length(sub3(a, c));
  if(bc <= ab && bc <= ca) return {sub3(b, a), sub3(c, a)};   // at a
  if(ca <= ab) return {sub3(a, b), sub3(c, b)};                // at b
  return {sub3(a, c), sub3(b, c)};                             // at c
}
inline double corner_angle(const Corner_sides& s) { return angle3(s.first, s.second); }
inline double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c) { return corner_angle(smallest_angle_sides(a, b, c)); }
// the tangent of that angle, without atan2: the smallest angle is at most 60 degrees, where the
// tangent grows with the angle, so that the flips below compare tangents first and only take the
// angles of the few edges the tangents do not turn down; NaN when the cosine term is not
// positive (a degenerate triangle: the angles decide)
inline double corner_tangent(const Corner_sides& s)
{
  const double d = dot3(s.first, s.second);
  return d > 0 ? norm3(cross3(s.first, s.second)) / d : std::numeric_limits<double>::quiet_NaN();
}
inline double smallest_angle_tangent(const Vec3& a, const Vec3& b, const Vec3& c) { return corner_tangent(smallest_angle_sides(a, b, c)); }
inline Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return cross3(sub3(b, a), sub3(c, a)); }

/// The working state: the mesh being tessellated and what each of its elements is.
template <class TriangleMesh, class VPM, class Settings>
class Tessellator
{
public:
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::edge_descriptor edge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename boost::property_traits<VPM>::value_type Point_3;

  // origin of a vertex: >= 0 the sample index, < 0 the input vertex -(origin + 1)
  typedef typename boost::property_map<TriangleMesh, CGAL::dynamic_vertex_property_t<long>>::type Origin_map;
  typedef typename boost::property_map<TriangleMesh, CGAL::dynamic_edge_property_t<bool>>::type Feature_map;
  typedef typename boost::property_map<TriangleMesh, CGAL::dynamic_face_property_t<std::size_t>>::type Owner_map;
  typedef typename boost::property_map<TriangleMesh, CGAL::dynamic_vertex_property_t<std::size_t>>::type Changed_map;

  Tessellator(TriangleMesh& tm, VPM vpm, const Settings& s)
    : tm(tm), vpm(vpm), settings(s),
      origin(get(CGAL::dynamic_vertex_property_t<long>(), tm)),
      feature(get(CGAL::dynamic_edge_property_t<bool>(), tm)),
      owner(get(CGAL::dynamic_face_property_t<std::size_t>(), tm)),
      changed(get(CGAL::dynamic_vertex_property_t<std::size_t>(), tm))
  {}

  TriangleMesh& tm;
  VPM vpm;
  Settings settings;
  Origin_map origin;
  Feature_map feature;
  Owner_map owner;
  std::size_t flips = 0;
  bool last_resort = false;   // removal guard raised (see the settings)
  std::array<std::size_t, 4> refusals = {{0, 0, 0, 0}};   // star, feature edge, pocket, triangulation
  // The vertices whose edges may have become flippable since the flips last ran: those whose ring,
  // degree or edges' feature marks a removal, collapse or repair flip changed (a list, and each
  // one's place in it plus one, 0 when not in it; a vertex about to be removed is struck off). An
  // edge elsewhere has kept its two triangles, its ends' degrees, the edge its flip would make and
  // its mark since the flips left it, so that try_flip would turn it down again:
  // flip_changed_edges() looks at these vertices' edges only. (Not covered: an edge turned down
  // because the edge its flip would make existed, and a flip removed that edge since; it needs
  // two triangles on each side of a thin sheet, and is flipped when a removal touches its ends.)
  Changed_map changed;
  std::vector<vertex_descriptor> changed_list;
  void touch(vertex_descriptor x)
  {
    if(get(changed, x) != 0) return;
    changed_list.push_back(x);
    put(changed, x, changed_list.size());
  }
  void forget(vertex_descriptor x)   // (before x is removed)
  {
    const std::size_t i = get(changed, x);
    if(i == 0) return;
    changed_list[i - 1] = GT::null_vertex();
    put(changed, x, 0);
  }

  bool is_sample(vertex_descriptor v) const { return get(origin, v) >= 0; }
  Vec3 xyz(vertex_descriptor v) const
  {
    const Point_3& p = get(vpm, v);
    return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
  }
  bool is_feature(halfedge_descriptor h) const { return get(feature, edge(h, tm)); }
  bool edge_exists(vertex_descriptor a, vertex_descriptor b) const { return halfedge(a, b, tm).second; }

  // ---- 2. flips ------------------------------------------------------------------------------

  /// flips h when the smallest angle of its two triangles grows and the §6.1 guards hold.
  bool try_flip(halfedge_descriptor h)
  {
    if(is_border_edge(h, tm) || is_feature(h)) return false;
    const vertex_descriptor a = source(h, tm), b = target(h, tm);
    const vertex_descriptor c = target(next(h, tm), tm), d = target(next(opposite(h, tm), tm), tm);
    if(c == d) return false;
    const Vec3 pa = xyz(a), pb = xyz(b), pc = xyz(c), pd = xyz(d);
    // old triangles (a, b, c), (b, a, d); new ones (c, a, d), (d, b, c); the angle test first:
    // most edges fail it, and it is cheaper than walking the rings below (and most fail it by the
    // tangents already: a new smallest angle no larger than the old one is turned down, as the
    // angles would; a NaN tangent leaves it to the angles)
    const Corner_sides s[4] = {smallest_angle_sides(pa, pb, pc), smallest_angle_sides(pb, pa, pd),
                               smallest_angle_sides(pc, pa, pd), smallest_angle_sides(pd, pb, pc)};
    const double t[4] = {corner_tangent(s[0]), corner_tangent(s[1]), corner_tangent(s[2]), corner_tangent(s[3])};
    if(!std::isnan(t[0] + t[1] + t[2] + t[3]) && std::min(t[2], t[3]) <= std::min(t[0], t[1])) return false;
    const double old_min = std::min(corner_angle(s[0]), corner_angle(s[1]));
    const double new_min = std::min(corner_angle(s[2]), corner_angle(s[3]));
    if(!(new_min > old_min + 1e-9)) return false;
    if(edge_exists(c, d)) return false;   // the new edge must not exist already
    if(degree(a, tm) <= 3 || degree(b, tm) <= 3) return false;
    const Vec3 n1 = triangle_normal(pa, pb, pc), n2 = triangle_normal(pb, pa, pd);
    const Vec3 m1 = triangle_normal(pc, pa, pd), m2 = triangle_normal(pd, pb, pc);
    if(norm3(m1) == 0 || norm3(m2) == 0) return false;
    const double beta = settings.beta * CGAL_PI / 180, gamma = settings.gamma * CGAL_PI / 180;
    for(const Vec3& m : {m1, m2})
      for(const Vec3& n : {n1, n2})
        if(angle3(m, n) > beta) return false;
    if(std::abs(angle3(m1, m2) - angle3(n1, n2)) > gamma) return false;
    CGAL::Euler::flip_edge(h, tm);
    ++flips;
    return true;
  }

  /// flips until no flip improves the smallest angle (each flip raises the sorted angle vector
  /// of the two triangles lexicographically, so this ends; a cap guards against round-off).
  std::size_t flip_edges()
  {
    std::deque<halfedge_descriptor> queue;
    for(edge_descriptor e : edges(tm)) queue.push_back(halfedge(e, tm));
    for(vertex_descriptor x : changed_list) if(x != GT::null_vertex()) put(changed, x, 0);   // (all looked at)
    changed_list.clear();
    return flip_from(std::move(queue), num_edges(tm));
  }

  /// the same, starting from the edges around the changed vertices only (see `changed`), each
  /// once, in the order the vertices changed
  std::size_t flip_changed_edges()
  {
    std::deque<halfedge_descriptor> queue;
    std::vector<vertex_descriptor> live;
    for(vertex_descriptor x : changed_list) if(x != GT::null_vertex()) live.push_back(x);
    changed_list.clear();
    for(vertex_descriptor x : live) {
      put(changed, x, 0);
      // (an edge to a changed vertex not yet visited is taken from that one)
      for(halfedge_descriptor h : CGAL::halfedges_around_target(x, tm))
        if(get(changed, source(h, tm)) == 0) queue.push_back(h);
    }
    return flip_from(std::move(queue), num_edges(tm));
  }

  std::size_t flip_from(std::deque<halfedge_descriptor> queue, std::size_t edge_count)
  {
    const std::size_t before = flips;
    const std::size_t cap = 50 * edge_count + 1000;
    std::size_t done = 0;
    while(!queue.empty() && done < cap) {
      const halfedge_descriptor h = queue.front();
      queue.pop_front();
      if(!try_flip(h)) continue;
      ++done;
      for(halfedge_descriptor g : {next(h, tm), prev(h, tm), next(opposite(h, tm), tm), prev(opposite(h, tm), tm)})
        queue.push_back(g);
    }
    return flips - before;
  }

  // ---- 3. removal of an original vertex -------------------------------------------------------

  /// A triangle of a polygon: indices of its vertices in the polygon, counterclockwise.
  typedef std::array<std::size_t, 3> Tri;

  /// triangles (indices into `pts`, counterclockwise) of the polygon pts[0..n-1] by a constrained
  /// Delaunay triangulation with the polygon's sides as constraints, keeping the inside faces;
  /// false when the polygon is not simple (its CDT does not have exactly n - 2 inside faces).
  /// `full`: the layout of a whole ring, else of a half one. With `direct`, a layout the origin
  /// sees all of, whose triangulation is unique, is triangulated directly (polygon_cdt.h: the
  /// same triangles, in another order; most of the removals' time saved); the others by CGAL.
  static bool cdt_triangulate(const std::vector<std::array<double, 2>>& pts, bool full, std::vector<Tri>& out, bool direct = true)
  {
    if(direct && polygon_cdt(pts, full, out) == Polygon_cdt_outcome::found) return true;
    return cgal_cdt_triangulate(pts, out);
  }

  /// the same by CGAL's Constrained_Delaunay_triangulation_2
  static bool cgal_cdt_triangulate(const std::vector<std::array<double, 2>>& pts, std::vector<Tri>& out)
  {
    typedef CGAL::Exact_predicates_inexact_constructions_kernel K2;
    typedef CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K2> Vb;
    typedef CGAL::Triangulation_face_base_with_info_2<int, K2> Fbi;
    typedef CGAL::Constrained_triangulation_face_base_2<K2, Fbi> Fb;
    typedef CGAL::Triangulation_data_structure_2<Vb, Fb> Tds;
    typedef CGAL::Constrained_Delaunay_triangulation_2<K2, Tds, CGAL::Exact_predicates_tag> CDT;
    out.clear();
    const std::size_t n = pts.size();
    if(n < 3) return n == 2;
    CDT cdt;
    std::vector<typename CDT::Vertex_handle> vh(n);
    for(std::size_t i = 0; i < n; ++i) {
      vh[i] = cdt.insert(typename K2::Point_2(pts[i][0], pts[i][1]));
      vh[i]->info() = i;
    }
    if(cdt.number_of_vertices() != n) return false;
    for(std::size_t i = 0; i < n; ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % n]);
    if(cdt.number_of_vertices() != n) return false;   // constraints crossed
    // inside = odd number of constraints crossed from the infinite face
    for(auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
    std::deque<std::pair<typename CDT::Face_handle, int>> q;
    q.push_back({cdt.infinite_face(), 0});
    while(!q.empty()) {
      auto [f, level] = q.front();
      q.pop_front();
      if(f->info() != -1) continue;
      f->info() = level;
      for(int i = 0; i < 3; ++i) {
        auto g = f->neighbor(i);
        if(g->info() == -1) q.push_back({g, cdt.is_constrained({f, i}) ? level + 1 : level});
      }
    }
    for(auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
      if(f->info() % 2 == 1) out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    return is_polygon_triangulation(n, out);
  }

  /// true when `t` is a triangulation of the polygon 0..n-1 (counterclockwise): every side used
  /// once in its direction, every other edge once in each direction.
  static bool is_polygon_triangulation(std::size_t n, const std::vector<Tri>& t)
  {
    if(t.size() + 2 != n) return false;
    std::vector<std::pair<std::size_t, std::size_t>> directed;
    for(const Tri& tri : t)
      for(int i = 0; i < 3; ++i) directed.push_back({tri[i], tri[(i + 1) % 3]});
    std::sort(directed.begin(), directed.end());
    if(std::adjacent_find(directed.begin(), directed.end()) != directed.end()) return false;
    for(std::size_t i = 0; i < n; ++i)
      if(!std::binary_search(directed.begin(), directed.end(), std::make_pair(i, (i + 1) % n))) return false;
    for(const auto& d : directed) {
      if(d.second == (d.first + 1) % n) continue;
      if(!std::binary_search(directed.begin(), directed.end(), std::make_pair(d.second, d.first))) return false;
    }
    return true;
  }

  /// A side of the star of v to re-triangulate: ring vertices (consecutive, counterclockwise),
  /// closed by the edge last -> first (the whole ring when `full`).
  struct Side
  {
    std::vector<vertex_descriptor> polygon;
    std::vector<double> sector_angles;   // angle at v between polygon[i] and polygon[i+1]
    bool full = false;
    Vec3 normal = {0, 0, 0};             // sum of the star faces' normals on this side
  };

  /// §6.1 layout: radial lengths kept, angles at v scaled to sum to 2 pi (pi for a half side).
  std::vector<std::array<double, 2>> layout(vertex_descriptor v, const Side& s) const
  {
    const Vec3 pv = xyz(v);
    double total = 0;
    for(double a : s.sector_angles) total += a;
    const double span = s.full ? 2 * CGAL_PI : CGAL_PI;
    std::vector<std::array<double, 2>> pts;
    double cum = 0;
    for(std::size_t i = 0; i < s.polygon.size(); ++i) {
      const double r = norm3(sub3(xyz(s.polygon[i]), pv));
      const double theta = total > 0 ? span * cum / total : 0;
      pts.push_back({r * std::cos(theta), r * std::sin(theta)});
      if(i < s.sector_angles.size()) cum += s.sector_angles[i];
    }
    return pts;
  }

  /// a valid triangulation of a side (the CDT of the layout first, else the best of all
  /// triangulations): new edges absent from the mesh, triangles not folded against the side's
  /// normal. Empty `tris` for a two-vertex side. (`direct`: see cdt_triangulate)
  bool triangulate_side(vertex_descriptor v, const Side& s, std::vector<Tri>& tris, bool direct = true) const
  {
    const std::size_t n = s.polygon.size();
    tris.clear();
    if(n == 2) return !s.full;
    const auto pts = layout(v, s);
    const double max_dev = (last_resort ? settings.max_removal_normal_deviation_last_resort
                                        : settings.max_removal_normal_deviation) * CGAL_PI / 180;
    auto valid = [&](const std::vector<Tri>& t) -> double {   // smallest 3D angle, or -1
      double q = CGAL_PI;
      for(const Tri& tri : t) {
        const Vec3 a = xyz(s.polygon[tri[0]]), b = xyz(s.polygon[tri[1]]), c = xyz(s.polygon[tri[2]]);
        const Vec3 nt = triangle_normal(a, b, c);
        if(!(norm3(nt) > 0) || angle3(nt, s.normal) > max_dev) return -1;
        for(int i = 0; i < 3; ++i) {
          const std::size_t x = std::min(tri[i], tri[(i + 1) % 3]), y = std::max(tri[i], tri[(i + 1) % 3]);
          if(y == x + 1 || (x == 0 && y == n - 1)) continue;   // a polygon side, or the feature edge (caller)
          if(edge_exists(s.polygon[x], s.polygon[y])) return -1;
        }
        q = std::min(q, smallest_angle(a, b, c));
      }
      return q;
    };
    std::vector<Tri> t;
    if(cdt_triangulate(pts, s.full, t, direct) && valid(t) >= 0) { tris = t; return true; }
    return best_triangulation(s, max_dev, tris);
  }

  /// fallback when the CDT of the layout is refused: among all triangulations of the polygon
  /// (dynamic programming over sub-polygons, O(n^3)), the one with the largest smallest angle
  /// whose new edges are absent from the mesh and whose triangles are not folded.
  bool best_triangulation(const Side& s, double max_dev, std::vector<Tri>& tris) const
  {
    const std::size_t n = s.polygon.size();
    const double none = -1;
    std::vector<Vec3> p(n);
    for(std::size_t i = 0; i < n; ++i) p[i] = xyz(s.polygon[i]);
    auto edge_ok = [&](std::size_t x, std::size_t y) {   // x < y
      if(y == x + 1 || (x == 0 && y == n - 1)) return true;
      return !edge_exists(s.polygon[x], s.polygon[y]);
    };
    std::vector<double> best(n * n, none);
    std::vector<std::size_t> arg(n * n, 0);
    for(std::size_t i = 0; i + 1 < n; ++i) best[i * n + i + 1] = CGAL_PI;
    for(std::size_t len = 2; len < n; ++len)
      for(std::size_t i = 0; i + len < n; ++i) {
        const std::size_t j = i + len;
        for(std::size_t k = i + 1; k < j; ++k) {
          const double l = best[i * n + k], r = best[k * n + j];
          if(l < 0 || r < 0 || !edge_ok(i, k) || !edge_ok(k, j)) continue;
          const Vec3 nt = triangle_normal(p[i], p[k], p[j]);
          if(!(norm3(nt) > 0) || angle3(nt, s.normal) > max_dev) continue;
          const double q = std::min({l, r, smallest_angle(p[i], p[k], p[j])});
          if(q > best[i * n + j]) { best[i * n + j] = q; arg[i * n + j] = k; }
        }
      }
    if(best[n - 1] < 0) return false;
    tris.clear();
    std::vector<std::pair<std::size_t, std::size_t>> stack{{0, n - 1}};
    while(!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      if(j <= i + 1) continue;
      const std::size_t k = arg[i * n + j];
      tris.push_back({i, k, j});
      stack.push_back({i, k});
      stack.push_back({k, j});
    }
    return true;
  }

  /// removes the border vertex v by collapsing it onto its border neighbour a or b (the fan of
  /// the half disk from that neighbour), used when a ring edge is also a border edge (a strip one
  /// face wide, where removing the star's faces would also remove that edge).
  bool collapse_onto_border_neighbour(vertex_descriptor v, const Side& side)
  {
    const double max_dev = (last_resort ? settings.max_removal_normal_deviation_last_resort
                                        : settings.max_removal_normal_deviation) * CGAL_PI / 180;
    const std::size_t n = side.polygon.size();
    for(std::size_t end : {std::size_t(0), n - 1}) {
      const vertex_descriptor keep = side.polygon[end];
      bool ok = true;
      for(std::size_t i = 0; i + 1 < n && ok; ++i) {
        if(i == end || i + 1 == end) continue;
        const Vec3 nt = end == 0 ? triangle_normal(xyz(keep), xyz(side.polygon[i]), xyz(side.polygon[i + 1]))
                                 : triangle_normal(xyz(side.polygon[i]), xyz(side.polygon[i + 1]), xyz(keep));
        ok = norm3(nt) > 0 && angle3(nt, side.normal) <= max_dev;
      }
      const auto hv = halfedge(v, keep, tm);
      if(!ok || !hv.second || !CGAL::Euler::does_satisfy_link_condition(edge(hv.first, tm), tm)) continue;
      // the feature edges around, as vertex pairs (v renamed keep), to mark again afterwards
      std::vector<std::pair<vertex_descriptor, vertex_descriptor>> marked;
      for(vertex_descriptor x : side.polygon)
        for(halfedge_descriptor h : CGAL::halfedges_around_source(x, tm))
          if(is_feature(h)) marked.push_back({source(h, tm) == v ? keep : source(h, tm), target(h, tm) == v ? keep : target(h, tm)});
      const Point_3 kp = get(vpm, keep);
      const long korigin = get(origin, keep);
      const vertex_descriptor gone = source(halfedge(edge(hv.first, tm), tm), tm);   // (collapse_edge keeps the target)
      forget(gone);
      const vertex_descriptor kept = CGAL::Euler::collapse_edge(edge(hv.first, tm), tm);
      put(vpm, kept, kp);
      put(origin, kept, korigin);
      for(vertex_descriptor x : side.polygon) if(x != gone) touch(x);
      touch(kept);
      for(halfedge_descriptor h : CGAL::halfedges_around_source(kept, tm)) put(feature, edge(h, tm), false);
      for(const auto& pr : marked) {
        const vertex_descriptor x = pr.first == keep ? kept : pr.first, y = pr.second == keep ? kept : pr.second;
        const auto h = halfedge(x, y, tm);
        if(h.second) put(feature, edge(h.first, tm), true);
      }
      return true;
    }
    ++refusals[3];
    return false;
  }

  /// removes an original vertex v on a border (a feature curve): its star is one half disk from
  /// a to b, laid out on a half disk like a side of a feature curve; the faces are removed and
  /// the triangulation added back with Euler::add_face, and a-b becomes the border edge.
  bool try_remove_border_vertex(vertex_descriptor v)
  {
    halfedge_descriptor g0 = GT::null_halfedge();
    std::size_t border_fans = 0, features = 0;
    for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm)) {
      if(is_border(opposite(g, tm), tm) && !is_border(g, tm)) { g0 = g; ++border_fans; }
      if(is_feature(g)) ++features;
    }
    if(border_fans != 1 || features != 2) { ++refusals[0]; return false; }
    Side side;
    const Vec3 pv = xyz(v);
    std::vector<face_descriptor> star;
    halfedge_descriptor g = g0;
    side.polygon.push_back(target(g, tm));
    bool strip = false;   // a ring edge also on the border: it would vanish with the star
    while(!is_border(g, tm)) {
      if(is_border(opposite(next(g, tm), tm), tm)) strip = true;
      star.push_back(face(g, tm));
      const vertex_descriptor w = target(next(g, tm), tm);
      const Vec3 a = xyz(side.polygon.back()), b = xyz(w);
      side.sector_angles.push_back(angle3(sub3(a, pv), sub3(b, pv)));
      const Vec3 n = triangle_normal(pv, a, b);
      side.normal = {side.normal[0] + n[0], side.normal[1] + n[1], side.normal[2] + n[2]};
      side.polygon.push_back(w);
      g = opposite(prev(g, tm), tm);
    }
    const vertex_descriptor fa = side.polygon.front(), fb = side.polygon.back();
    {
      std::vector<vertex_descriptor> sorted = side.polygon;
      std::sort(sorted.begin(), sorted.end());
      if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) { ++refusals[0]; return false; }
    }
    if(side.polygon.size() > 2 && edge_exists(fa, fb)) { ++refusals[1]; return false; }
    if(strip) return collapse_onto_border_neighbour(v, side);
    std::vector<Tri> tris;
    // (CGAL's triangulation alone: the order of its triangles decides the order of the faces added below)
    if(!triangulate_side(v, side, tris, false)) { ++refusals[3]; return false; }
    forget(v);
    for(face_descriptor f : star) CGAL::Euler::remove_face(halfedge(f, tm), tm);   // v goes with its last face
    // add the triangles next to the mesh first, so that each addition is at the border
    std::vector<bool> added(tris.size(), false);
    for(std::size_t done = 0; done < tris.size();) {
      bool progress = false;
      for(std::size_t k = 0; k < tris.size(); ++k) {
        if(added[k]) continue;
        std::array<vertex_descriptor, 3> tv = {side.polygon[tris[k][0]], side.polygon[tris[k][1]], side.polygon[tris[k][2]]};
        bool touches = false;
        for(int i = 0; i < 3; ++i) touches = touches || edge_exists(tv[i], tv[(i + 1) % 3]);
        if(!touches) continue;
        if(CGAL::Euler::add_face(tv, tm) == GT::null_face())
          throw std::logic_error("mutual_tessellation: a triangle could not be added at a border");
        for(int i = 0; i < 3; ++i) {
          const auto he = halfedge(tv[i], tv[(i + 1) % 3], tm);
          const edge_descriptor e = edge(he.first, tm);
          const bool polygon_side = std::abs(long(tris[k][i]) - long(tris[k][(i + 1) % 3])) == 1;
          if(!polygon_side) put(feature, e, false);
        }
        added[k] = true;
        ++done;
        progress = true;
      }
      if(!progress) throw std::logic_error("mutual_tessellation: a border hole could not be filled");
    }
    put(feature, edge(halfedge(fa, fb, tm).first, tm), true);
    for(vertex_descriptor x : side.polygon) touch(x);
    return true;
  }

  /// removes the original vertex v (§6.1); false (mesh unchanged) when refused.
  bool try_remove(vertex_descriptor v)
  {
    if(is_sample(v)) return false;
    if(is_border(v, tm)) return try_remove_border_vertex(v);
    // ring, counterclockwise: face (v, ring[i], ring[i+1]) for every i
    std::vector<vertex_descriptor> ring;
    std::vector<halfedge_descriptor> out_h;
    const halfedge_descriptor h0 = opposite(halfedge(v, tm), tm);
    halfedge_descriptor g = h0;
    do {
      out_h.push_back(g);
      ring.push_back(target(g, tm));
      g = opposite(prev(g, tm), tm);
    } while(g != h0);
    const std::size_t m = ring.size();
    if(m < 3) { ++refusals[0]; return false; }
    {
      std::vector<vertex_descriptor> sorted = ring;
      std::sort(sorted.begin(), sorted.end());
      if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) { ++refusals[0]; return false; }
    }
    const Vec3 pv = xyz(v);
    std::vector<double> sector(m);
    std::vector<Vec3> fnormal(m);
    for(std::size_t i = 0; i < m; ++i) {
      const Vec3 a = xyz(ring[i]), b = xyz(ring[(i + 1) % m]);
      sector[i] = angle3(sub3(a, pv), sub3(b, pv));
      fnormal[i] = triangle_normal(pv, a, b);
    }
    std::vector<std::size_t> feature_at;
    for(std::size_t i = 0; i < m; ++i) if(is_feature(out_h[i])) feature_at.push_back(i);
    if(feature_at.size() != 0 && feature_at.size() != 2) { ++refusals[0]; return false; }   // a corner: never an original

    std::vector<Side> sides;
    auto make_side = [&](std::size_t from, std::size_t to, bool full) {
      Side s;
      s.full = full;
      std::size_t i = from;
      do {
        s.polygon.push_back(ring[i]);
        s.sector_angles.push_back(sector[i]);
        s.normal = {s.normal[0] + fnormal[i][0], s.normal[1] + fnormal[i][1], s.normal[2] + fnormal[i][2]};
        i = (i + 1) % m;
      } while(i != to);
      if(!full) s.polygon.push_back(ring[to]);
      sides.push_back(s);
    };
    vertex_descriptor fa = GT::null_vertex(), fb = GT::null_vertex();
    if(feature_at.empty()) {
      make_side(0, 0, true);
      if(m == 3) {
        // the ring triangle must not already be a face (a pocket of four faces closed on itself)
        const halfedge_descriptor r01 = halfedge(ring[1], ring[0], tm).first;
        if(!is_border(r01, tm) && target(next(r01, tm), tm) == ring[2]) { ++refusals[2]; return false; }
      }
    } else {
      fa = ring[feature_at[0]];
      fb = ring[feature_at[1]];
      make_side(feature_at[0], feature_at[1], false);
      make_side(feature_at[1], feature_at[0], false);
      const bool adjacent = sides[0].polygon.size() == 2 || sides[1].polygon.size() == 2;
      if(!adjacent && edge_exists(fa, fb)) {   // the feature edge would be doubled
        // last resort (beyond the paper): the curve takes the existing edge fa-fb as its own,
        // v leaves the curve and is removed as a smooth vertex; undone if that fails
        const halfedge_descriptor ab = halfedge(fa, fb, tm).first;
        if(last_resort && !is_feature(ab) && !is_border_edge(ab, tm)) {
          put(feature, edge(ab, tm), true);
          put(feature, edge(out_h[feature_at[0]], tm), false);
          put(feature, edge(out_h[feature_at[1]], tm), false);
          if(try_remove(v)) return true;
          put(feature, edge(ab, tm), false);
          put(feature, edge(out_h[feature_at[0]], tm), true);
          put(feature, edge(out_h[feature_at[1]], tm), true);
        }
        ++refusals[1];
        return false;
      }
      if(sides[0].polygon.size() == 2 && sides[1].polygon.size() == 2) { ++refusals[0]; return false; }
    }
    std::vector<std::vector<Tri>> tris(sides.size());
    for(std::size_t k = 0; k < sides.size(); ++k)
      if(!triangulate_side(v, sides[k], tris[k])) { ++refusals[3]; return false; }

    // the new edges: the feature edge, then the diagonals of each side
    std::vector<std::pair<vertex_descriptor, vertex_descriptor>> diagonals;
    if(fa != GT::null_vertex() && !edge_exists(fa, fb)) diagonals.push_back({fa, fb});
    for(std::size_t k = 0; k < sides.size(); ++k) {
      const std::size_t n = sides[k].polygon.size();
      for(const Tri& t : tris[k])
        for(int i = 0; i < 3; ++i) {
          const std::size_t x = t[i], y = t[(i + 1) % 3];
          if(x > y) continue;                            // each inner edge once (y > x side)
          if(y == x + 1 || (x == 0 && y == n - 1)) continue;   // polygon side or closing edge
          diagonals.push_back({sides[k].polygon[x], sides[k].polygon[y]});
        }
    }
    // (split in an order that does not depend on memory: it decides the order of the new faces)
    std::sort(diagonals.begin(), diagonals.end(), Poisson_remesh::internal::Memory_free_order<TriangleMesh, VPM>(tm, vpm));
    diagonals.erase(std::unique(diagonals.begin(), diagonals.end()), diagonals.end());

    // apply: merge the star into one face, then split it along the new edges
    forget(v);
    const halfedge_descriptor hm = CGAL::Euler::remove_center_vertex(halfedge(v, tm), tm);
    for(vertex_descriptor x : ring) touch(x);
    std::vector<face_descriptor> hole_faces{face(hm, tm)};
    for(const auto& dg : diagonals) {
      bool done = false;
      for(std::size_t fi = 0; fi < hole_faces.size() && !done; ++fi) {
        halfedge_descriptor hx = GT::null_halfedge(), hy = GT::null_halfedge();
        for(halfedge_descriptor hf : CGAL::halfedges_around_face(halfedge(hole_faces[fi], tm), tm)) {
          if(target(hf, tm) == dg.first) hx = hf;
          if(target(hf, tm) == dg.second) hy = hf;
        }
        if(hx == GT::null_halfedge() || hy == GT::null_halfedge()) continue;
        const halfedge_descriptor hn = CGAL::Euler::split_face(hx, hy, tm);
        put(feature, edge(hn, tm), (dg.first == fa && dg.second == fb) || (dg.first == fb && dg.second == fa));
        hole_faces.push_back(face(opposite(hn, tm), tm));
        done = true;
      }
      if(!done) throw std::logic_error("mutual_tessellation: a diagonal left its hole");
    }
    if(fa != GT::null_vertex()) {
      put(feature, edge(halfedge(fa, fb, tm).first, tm), true);
      // when fa-fb was a feature edge already, v's curve merged into it and fa, fb lost a feature
      // edge: an original vertex left at the free end of a curve cannot be removed, so that end
      // (dangling, between originals only) is no feature any more
      prune_dangling(fa);
      prune_dangling(fb);
    }
    return true;
  }

  /// while x is an original vertex with one feature edge, that edge stops being a feature and x
  /// moves to its other end
  void prune_dangling(vertex_descriptor x)
  {
    while(!is_sample(x)) {
      halfedge_descriptor only = GT::null_halfedge();
      std::size_t n = 0;
      for(halfedge_descriptor h : CGAL::halfedges_around_source(x, tm))
        if(is_feature(h) && !is_border_edge(h, tm)) { only = h; ++n; }
      if(n != 1) return;
      put(feature, edge(only, tm), false);
      touch(x);
      x = target(only, tm);
      touch(x);
    }
  }

  /// (beyond the paper) removes the original vertex v by collapsing one of its edges onto a
  /// sample neighbour: along a feature edge when v is on a feature curve (feature degree 2), onto
  /// any sample otherwise; the neighbour giving the largest smallest angle wins. Refused when the
  /// link condition fails (the topology would change), a ring vertex would be left with degree 2,
  /// or a triangle would turn by more than the last-resort deviation.
  bool try_collapse(vertex_descriptor v)
  {
    if(is_sample(v)) return false;
    std::size_t features = 0;
    for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm)) if(is_feature(g)) ++features;
    if(features != 0 && features != 2) return false;
    const double max_dev = settings.max_removal_normal_deviation_last_resort * CGAL_PI / 180;
    halfedge_descriptor best = GT::null_halfedge();
    double best_q = -1;
    for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm)) {   // g: v -> w
      const vertex_descriptor w = target(g, tm);
      if(!is_sample(w) || (features == 2 && !is_feature(g))) continue;
      if(features == 2) {   // the other feature neighbour must not be joined to w by a feature edge already
        bool merges = false;
        for(halfedge_descriptor h : CGAL::halfedges_around_source(v, tm))
          if(is_feature(h) && target(h, tm) != w && edge_exists(w, target(h, tm)) && is_feature(halfedge(w, target(h, tm), tm).first)) merges = true;
        if(merges) continue;
      }
      if(!CGAL::Euler::does_satisfy_link_condition(edge(g, tm), tm)) continue;
      bool ok = true;
      for(halfedge_descriptor x : {g, opposite(g, tm)})
        if(!is_border(x, tm) && degree(target(next(x, tm), tm), tm) <= 3) ok = false;
      if(!ok) continue;
      const Vec3 pw = xyz(w), pv = xyz(v);
      double q = CGAL_PI;
      for(halfedge_descriptor h : CGAL::halfedges_around_target(v, tm)) {   // face (source(h), v, next)
        if(is_border(h, tm)) continue;
        const vertex_descriptor a = source(h, tm), b = target(next(h, tm), tm);
        if(a == w || b == w) continue;   // goes with the collapse
        const Vec3 pa = xyz(a), pb = xyz(b);
        const Vec3 before = triangle_normal(pa, pv, pb), after = triangle_normal(pa, pw, pb);
        if(!(norm3(after) > 0) || angle3(before, after) > max_dev) { ok = false; break; }
        q = std::min(q, smallest_angle(pa, pw, pb));
      }
      if(ok && q > best_q) { best_q = q; best = g; }
    }
    if(best == GT::null_halfedge()) return false;
    if(target(halfedge(edge(best, tm), tm), tm) != target(best, tm)) return false;   // collapse_edge keeps target(halfedge(e))
    // the feature edges around, as vertex pairs (v renamed w), to mark again afterwards
    const vertex_descriptor w = target(best, tm);
    std::vector<std::pair<vertex_descriptor, vertex_descriptor>> marked;
    for(halfedge_descriptor h : CGAL::halfedges_around_source(v, tm))
      if(is_feature(h) && target(h, tm) != w) marked.push_back({w, target(h, tm)});
    for(halfedge_descriptor h : CGAL::halfedges_around_source(w, tm))
      if(is_feature(h) && target(h, tm) != v) marked.push_back({w, target(h, tm)});
    const Point_3 pw = get(vpm, w);
    const long ow = get(origin, w);
    std::vector<vertex_descriptor> ring;
    for(halfedge_descriptor h : CGAL::halfedges_around_target(v, tm)) ring.push_back(source(h, tm));
    forget(v);
    const vertex_descriptor kept = CGAL::Euler::collapse_edge(edge(best, tm), tm);   // keeps target(best) = w
    for(vertex_descriptor x : ring) touch(x);
    put(vpm, kept, pw);
    put(origin, kept, ow);
    for(halfedge_descriptor h : CGAL::halfedges_around_source(kept, tm)) put(feature, edge(h, tm), false);
    for(const auto& pr : marked) {
      const auto h = halfedge(pr.first == w ? kept : pr.first, pr.second, tm);
      if(h.second) put(feature, edge(h.first, tm), true);
    }
    return true;
  }

  // ---- 4. (beyond the paper) self-intersections left in thin parts, repaired by flips ----------

  /// number of faces of `others` that triangle (a, b, c) meets other than along what they share
  /// (faces sharing one vertex: an edge of one opposite to it crosses the other, as PMP does).
  std::size_t count_crossings(vertex_descriptor a, vertex_descriptor b, vertex_descriptor c,
                              const std::vector<face_descriptor>& others) const
  {
    typedef typename CGAL::Kernel_traits<Point_3>::Kernel K;
    typedef typename K::Triangle_3 Triangle;
    typedef typename K::Segment_3 Segment;
    const Triangle t(get(vpm, a), get(vpm, b), get(vpm, c));
    if(t.is_degenerate()) return others.size() + 1;
    const vertex_descriptor tv[3] = {a, b, c};
    std::size_t n = 0;
    for(face_descriptor f : others) {
      const halfedge_descriptor h = halfedge(f, tm);
      const vertex_descriptor fv[3] = {source(h, tm), target(h, tm), target(next(h, tm), tm)};
      int shared = 0, si = -1, sj = -1;
      for(int i = 0; i < 3; ++i)
        for(int j = 0; j < 3; ++j)
          if(tv[i] == fv[j]) { ++shared; si = i; sj = j; }
      const Triangle u(get(vpm, fv[0]), get(vpm, fv[1]), get(vpm, fv[2]));
      if(u.is_degenerate()) continue;   // (no plane to cross; do_intersect needs one)
      if(shared == 0) n += CGAL::do_intersect(t, u) ? 1 : 0;
      else if(shared == 1) {
        const Segment st(get(vpm, tv[(si + 1) % 3]), get(vpm, tv[(si + 2) % 3]));
        const Segment su(get(vpm, fv[(sj + 1) % 3]), get(vpm, fv[(sj + 2) % 3]));
        if(CGAL::do_intersect(st, u) || CGAL::do_intersect(su, t)) ++n;
      }
    }
    return n;
  }

  /// flips non-feature edges of self-intersecting faces when the flip lowers the number of
  /// crossings with the faces involved and the stars around (a fold needs a flip that changes
  /// normals a lot, so beta and gamma do not apply; the crossing count is the guard).
  /// (`ConcurrencyTag`: the mode of the whole-mesh crossing search, which finds the same pairs in both)
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  std::size_t repair_self_intersections(std::size_t rounds = 4)
  {
    std::size_t repaired = 0;
    for(std::size_t round = 0; round < rounds; ++round) {
      const auto pairs = Poisson_remesh::internal::intersecting_face_pairs<ConcurrencyTag>(tm, faces(tm), vpm, 2 * num_faces(tm) + 1);
      if(pairs.empty()) break;
      // a surface that cuts itself everywhere (input faces folded onto each other) has more
      // crossings than flips can mend, at a cost quadratic in them: left alone
      if(pairs.size() > 2 * num_faces(tm)) break;
      std::vector<face_descriptor> involved;
      // each face with the faces it crosses (the crossings a flip is judged by: counting against
      // every involved face made a round quadratic in their number)
      std::vector<std::pair<face_descriptor, face_descriptor>> partner;
      for(const auto& pr : pairs) {
        involved.push_back(pr.first);
        involved.push_back(pr.second);
        partner.push_back(pr);
        partner.push_back({pr.second, pr.first});
      }
      // (visited in an order that does not depend on memory: each flip depends on those before it)
      std::sort(involved.begin(), involved.end(), Poisson_remesh::internal::Memory_free_order<TriangleMesh, VPM>(tm, vpm));
      involved.erase(std::unique(involved.begin(), involved.end()), involved.end());
      std::sort(partner.begin(), partner.end());
      auto partners_of = [&](face_descriptor f, std::vector<face_descriptor>& out) {
        for(auto it = std::lower_bound(partner.begin(), partner.end(), std::make_pair(f, face_descriptor()));
            it != partner.end() && it->first == f; ++it)
          out.push_back(it->second);
      };
      std::size_t before = repaired;
      for(std::size_t i = 0; i < involved.size(); ++i) {
        for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(involved[i], tm), tm)) {
          if(is_border_edge(h, tm) || is_feature(h)) continue;
          const vertex_descriptor a = source(h, tm), b = target(h, tm);
          const vertex_descriptor c = target(next(h, tm), tm), d = target(next(opposite(h, tm), tm), tm);
          if(c == d || edge_exists(c, d) || degree(a, tm) <= 3 || degree(b, tm) <= 3) continue;
          const Vec3 pa = xyz(a), pb = xyz(b), pc = xyz(c), pd = xyz(d);
          if(!(norm3(triangle_normal(pc, pa, pd)) > 0) || !(norm3(triangle_normal(pd, pb, pc)) > 0)) continue;
          // the faces to count against: those the two faces cross, and the stars of the two faces' four vertices
          std::vector<face_descriptor> others;
          partners_of(face(h, tm), others);
          if(!is_border(opposite(h, tm), tm)) partners_of(face(opposite(h, tm), tm), others);
          for(vertex_descriptor x : {a, b, c, d})
            for(face_descriptor f : CGAL::faces_around_target(halfedge(x, tm), tm))
              if(f != GT::null_face()) others.push_back(f);
          std::sort(others.begin(), others.end());
          others.erase(std::unique(others.begin(), others.end()), others.end());
          const face_descriptor fh = face(h, tm), fo = face(opposite(h, tm), tm);
          others.erase(std::remove_if(others.begin(), others.end(), [&](face_descriptor f) { return f == fh || f == fo; }), others.end());
          const std::size_t old_x = count_crossings(a, b, c, others) + count_crossings(b, a, d, others);
          const std::size_t new_x = count_crossings(c, a, d, others) + count_crossings(d, b, c, others);
          if(new_x >= old_x) continue;
          CGAL::Euler::flip_edge(h, tm);
          for(vertex_descriptor x : {a, b, c, d}) touch(x);
          ++repaired;
          break;   // the face changed: next face
        }
      }
      if(repaired == before) break;
    }
    return repaired;
  }
};

} // namespace internal

} // namespace Poisson_remesh

#endif // POISSON_REMESH_TESSELLATION_INTERNAL_TESSELLATOR_H
