// Poisson_remesh/Features/detect_features.h
//
// Entry point: detect_features(mesh, np) -- paper §3 and §4.2.4: the sharp edges and corners
// that the remesh must keep, found before any sampling.
//   1. strong edges: dihedral angle sharper than `sharp_angle` (CGAL detect_sharp_edges), or the
//      user's `edge_is_constrained_map`, or none -- the feature-preservation policy;
//   2. false features removed, in the spirit of Jiao and Heath (2002): feature chains that dangle
//      (one end not attached to any other feature) and are made of fewer than
//      `dangling_chain_min_edges` edges are noise, not creases, and are dropped, repeatedly;
//   3. mesh borders are always feature curves (whatever the policy: the remesh keeps them);
//   4. corners: vertices where the feature graph branches or ends (feature degree != 2), and
//      vertices of degree 2 where the curve turns by more than `corner_angle`;
//   5. feature curves: the chains of feature edges between corners, or closed loops.
// feature_sample_locations() then places points at even intervals no shorter than a spacing
// along each curve (§4.2.4), as surface locations.

#ifndef POISSON_REMESH_FEATURES_DETECT_FEATURES_H
#define POISSON_REMESH_FEATURES_DETECT_FEATURES_H

#include <Poisson_remesh/parameters.h>

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace Poisson_remesh {

/// How features are chosen (named parameter `feature_policy`).
enum class Feature_policy {
  detect,      ///< edges whose dihedral angle is sharper than `sharp_angle` (default)
  user_map,    ///< the edges marked by the user's `edge_is_constrained_map`
  none         ///< no sharp features (borders are still kept)
};

/// Feature chains dangling with fewer edges than this are noise (step 2 above).
constexpr std::size_t dangling_chain_min_edges = 3;

template <class TriangleMesh>
struct Feature_set
{
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::edge_descriptor edge_descriptor;

  /// A feature curve: consecutive halfedges (target of one = source of the next), from a corner
  /// to a corner, or a closed loop without corner (then `closed` and it starts anywhere).
  struct Curve
  {
    std::vector<halfedge_descriptor> halfedges;
    bool closed = false;
    bool border = false;   ///< made of mesh border edges
    double length = 0;
  };

  std::vector<vertex_descriptor> corners;
  std::vector<Curve> curves;
  std::size_t number_of_feature_edges = 0;
  std::size_t number_of_removed_false_features = 0;  ///< edges dropped by the filtering

  bool is_feature(edge_descriptor e) const { return feature_edge[get(eim, e)]; }
  bool is_corner(vertex_descriptor v) const { return corner[get(vim, v)]; }

  // indexing
  typename CGAL::GetInitializedEdgeIndexMap<TriangleMesh>::const_type eim;
  typename CGAL::GetInitializedVertexIndexMap<TriangleMesh>::const_type vim;
  std::vector<bool> feature_edge;
  std::vector<bool> corner;
};

namespace internal {

template <class TriangleMesh, class VPM>
double edge_length(typename boost::graph_traits<TriangleMesh>::halfedge_descriptor h, const TriangleMesh& tm, VPM vpm)
{
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(get(vpm, source(h, tm)), get(vpm, target(h, tm)))));
}

} // namespace internal

/*!
  detects the features of `tm` (see the file comment).

  Named parameters:
  - `feature_policy` (Feature_policy, default `detect`)
  - `sharp_angle` (degrees, default 60): dihedral-angle threshold of `detect`
  - `edge_is_constrained_map` (CGAL): the user's feature edges, read with `user_map`
    (and, if given, implies `user_map` when no policy is named)
  - `corner_angle` (degrees, default 60): a feature vertex of degree 2 is a corner when its two
    feature edges turn by more than this
  - `vertex_point_map` (CGAL)
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Feature_set<TriangleMesh> detect_features(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using parameters::is_default_parameter;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::edge_descriptor edge_descriptor;
  typedef Feature_set<TriangleMesh> Features;

  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  const bool has_user_map = !is_default_parameter<NamedParameters, CGAL::internal_np::edge_is_constrained_t>::value;
  const Feature_policy policy = choose_parameter(get_parameter(np, internal_np::feature_policy),
                                                 has_user_map ? Feature_policy::user_map : Feature_policy::detect);
  const double sharp_angle = choose_parameter(get_parameter(np, internal_np::sharp_angle), 60.0);
  const double corner_angle = choose_parameter(get_parameter(np, internal_np::corner_angle), 60.0);

  Features fs;
  fs.eim = CGAL::get_initialized_edge_index_map(tm);
  fs.vim = CGAL::get_initialized_vertex_index_map(tm);
  fs.feature_edge.assign(num_edges(tm), false);
  fs.corner.assign(num_vertices(tm), false);
  auto eidx = [&](edge_descriptor e) { return std::size_t(get(fs.eim, e)); };
  auto vidx = [&](vertex_descriptor v) { return std::size_t(get(fs.vim, v)); };

  // 1. strong edges
  std::vector<bool> border_edge(num_edges(tm), false);
  for(edge_descriptor e : edges(tm)) border_edge[eidx(e)] = is_border(e, tm);
  if(policy == Feature_policy::detect) {
    auto sharp = get(CGAL::dynamic_edge_property_t<bool>(), tm);
    for(edge_descriptor e : edges(tm)) put(sharp, e, false);
    CGAL::Polygon_mesh_processing::detect_sharp_edges(tm, sharp_angle, sharp, CGAL::parameters::vertex_point_map(vpm));
    for(edge_descriptor e : edges(tm)) fs.feature_edge[eidx(e)] = get(sharp, e);
  } else if(policy == Feature_policy::user_map) {
    if constexpr(!is_default_parameter<NamedParameters, CGAL::internal_np::edge_is_constrained_t>::value) {
      auto ecm = get_parameter(np, CGAL::internal_np::edge_is_constrained);
      for(edge_descriptor e : edges(tm)) fs.feature_edge[eidx(e)] = get(ecm, e);
    } else {
      throw std::invalid_argument("detect_features: Feature_policy::user_map needs an edge_is_constrained_map");
    }
  }

  // 2. remove dangling short chains of sharp (non-border) edges, until none is left
  std::vector<std::size_t> degree(num_vertices(tm), 0);
  auto feature_or_border = [&](edge_descriptor e) { return fs.feature_edge[eidx(e)] || border_edge[eidx(e)]; };
  for(edge_descriptor e : edges(tm))
    if(feature_or_border(e)) { ++degree[vidx(source(halfedge(e, tm), tm))]; ++degree[vidx(target(halfedge(e, tm), tm))]; }
  auto next_feature_halfedge = [&](halfedge_descriptor h) -> halfedge_descriptor {
    // the other feature edge at target(h), when target(h) has feature degree 2
    for(halfedge_descriptor g : CGAL::halfedges_around_source(target(h, tm), tm))
      if(edge(g, tm) != edge(h, tm) && feature_or_border(edge(g, tm))) return g;
    return GT::null_halfedge();
  };
  bool removed = true;
  while(removed) {
    removed = false;
    for(vertex_descriptor v : vertices(tm)) {
      if(degree[vidx(v)] != 1) continue;
      // walk from the free end through degree-2 vertices
      std::vector<halfedge_descriptor> chain;
      halfedge_descriptor h = GT::null_halfedge();
      for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm))
        if(feature_or_border(edge(g, tm))) { h = g; break; }
      bool has_border = false;
      while(h != GT::null_halfedge() && chain.size() < dangling_chain_min_edges) {
        chain.push_back(h);
        has_border = has_border || border_edge[eidx(edge(h, tm))];
        if(degree[vidx(target(h, tm))] != 2) break;
        h = next_feature_halfedge(h);
      }
      if(has_border || chain.size() >= dangling_chain_min_edges) continue;
      for(halfedge_descriptor g : chain) {
        fs.feature_edge[eidx(edge(g, tm))] = false;
        --degree[vidx(source(g, tm))];
        --degree[vidx(target(g, tm))];
        ++fs.number_of_removed_false_features;
      }
      removed = true;
    }
  }

  // 3. borders are features
  for(edge_descriptor e : edges(tm)) if(border_edge[eidx(e)]) fs.feature_edge[eidx(e)] = true;
  for(edge_descriptor e : edges(tm)) if(fs.feature_edge[eidx(e)]) ++fs.number_of_feature_edges;

  // 4. corners
  const double cos_corner = std::cos(corner_angle * CGAL_PI / 180.0);
  for(vertex_descriptor v : vertices(tm)) {
    const std::size_t d = degree[vidx(v)];
    if(d == 0) continue;
    bool is_corner = d != 2;
    if(!is_corner) {
      std::vector<halfedge_descriptor> fe;
      for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm))
        if(fs.feature_edge[eidx(edge(g, tm))]) fe.push_back(g);
      const auto p = get(vpm, v);
      const auto a = get(vpm, target(fe[0], tm)) - p, b = get(vpm, target(fe[1], tm)) - p;
      const double la = std::sqrt(CGAL::to_double(a * a)), lb = std::sqrt(CGAL::to_double(b * b));
      // turning angle = 180 - angle(a, b); corner when turning > corner_angle
      const double cos_between = la > 0 && lb > 0 ? CGAL::to_double(a * b) / (la * lb) : -1;
      is_corner = -cos_between < cos_corner;
    }
    if(is_corner) { fs.corner[vidx(v)] = true; fs.corners.push_back(v); }
  }

  // 5. curves: from every corner along each feature edge, then the remaining closed loops
  std::vector<bool> used(num_edges(tm), false);
  auto trace = [&](halfedge_descriptor start) {
    typename Features::Curve c;
    halfedge_descriptor h = start;
    do {
      c.halfedges.push_back(h);
      used[eidx(edge(h, tm))] = true;
      c.border = c.border || border_edge[eidx(edge(h, tm))];
      c.length += internal::edge_length(h, tm, vpm);
      if(fs.corner[vidx(target(h, tm))]) break;
      h = next_feature_halfedge(h);
    } while(h != GT::null_halfedge() && h != start && !used[eidx(edge(h, tm))]);
    c.closed = !fs.corner[vidx(target(c.halfedges.back(), tm))] && target(c.halfedges.back(), tm) == source(start, tm);
    fs.curves.push_back(std::move(c));
  };
  for(vertex_descriptor v : fs.corners)
    for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm))
      if(fs.feature_edge[eidx(edge(g, tm))] && !used[eidx(edge(g, tm))]) trace(g);
  for(edge_descriptor e : edges(tm))
    if(fs.feature_edge[eidx(e)] && !used[eidx(e)]) trace(halfedge(e, tm));
  return fs;
}

/// A point on a feature curve, as a location on the surface and a 3D point.
template <class TriangleMesh, class Point_3>
struct Feature_sample
{
  CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> location;
  Point_3 point;
  std::size_t curve;  ///< index in Feature_set::curves
};

/// The surface location of the point at parameter t in [0, 1] along halfedge h (source to target),
/// expressed in a face incident to h (CGAL's barycentric convention).
template <class TriangleMesh>
CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>
location_on_halfedge(typename boost::graph_traits<TriangleMesh>::halfedge_descriptor h, double t, const TriangleMesh& tm)
{
  if(is_border(h, tm)) { h = opposite(h, tm); t = 1 - t; }
  const auto f = face(h, tm);
  const auto h0 = halfedge(f, tm);
  std::array<double, 3> b = {{0, 0, 0}};
  // vertex i of f: 0 = source(h0), 1 = target(h0), 2 = target(next(h0))
  const auto vs = source(h, tm), vt = target(h, tm);
  const decltype(vs) fv[3] = {source(h0, tm), target(h0, tm), target(next(h0, tm), tm)};
  for(int i = 0; i < 3; ++i) {
    if(fv[i] == vs) b[i] = 1 - t;
    if(fv[i] == vt) b[i] = t;
  }
  return {f, b};
}

/*!
  places samples at even intervals along every curve of `fs` (paper §4.2.4): a curve of length L
  between two corners gets n = floor(L / spacing) equal intervals (so consecutive samples are
  L / n >= spacing apart along the curve) and n - 1 interior samples; a closed loop gets
  max(1, floor(L / spacing)) samples. Corners are not included (sample them first).
*/
template <class TriangleMesh, class VPM>
std::vector<Feature_sample<TriangleMesh, typename boost::property_traits<VPM>::value_type>>
feature_sample_locations(const TriangleMesh& tm, VPM vpm, const Feature_set<TriangleMesh>& fs, double spacing)
{
  typedef typename boost::property_traits<VPM>::value_type Point_3;
  std::vector<Feature_sample<TriangleMesh, Point_3>> out;
  if(!(spacing > 0)) throw std::invalid_argument("feature_sample_locations: spacing must be positive");
  for(std::size_t ci = 0; ci < fs.curves.size(); ++ci) {
    const auto& c = fs.curves[ci];
    const std::size_t n = std::size_t(std::floor(c.length / spacing));
    std::size_t count;
    double step;
    if(c.closed) { count = std::max<std::size_t>(1, n); step = c.length / double(count); }
    else { if(n < 2) continue; count = n - 1; step = c.length / double(n); }
    double next_s = c.closed ? 0.0 : step;   // arc length of the next sample
    double s0 = 0;                           // arc length at the current halfedge's source
    std::size_t placed = 0;
    for(auto h : c.halfedges) {
      const double l = internal::edge_length(h, tm, vpm);
      while(placed < count && next_s <= s0 + l + 1e-12 * c.length) {
        const double t = l > 0 ? std::min(1.0, std::max(0.0, (next_s - s0) / l)) : 0.0;
        auto loc = location_on_halfedge(h, t, tm);
        out.push_back({loc, CGAL::Polygon_mesh_processing::construct_point(loc, tm, CGAL::parameters::vertex_point_map(vpm)), ci});
        ++placed;
        next_s += step;
      }
      s0 += l;
    }
  }
  return out;
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_FEATURES_DETECT_FEATURES_H
