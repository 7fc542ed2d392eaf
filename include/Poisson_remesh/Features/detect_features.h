// Poisson_remesh/Features/detect_features.h
//
// Entry point: detect_features(mesh, np) -- paper §3 and §4.2.4: the sharp edges and corners
// that the remesh must keep, found before any sampling.
//   1. strong edges: dihedral angle sharper than `sharp_angle` (CGAL detect_sharp_edges), or the
//      user's `edge_is_constrained_map`, or none -- the feature-preservation policy;
//   2. false features removed, in the spirit of Jiao and Heath (2002): feature chains that dangle
//      (one end not attached to any other feature) and are made of fewer than
//      `dangling_chain_min_edges` edges, or shorter than `minimum_feature_length`, are noise, not
//      creases, and are dropped, repeatedly; so are closed feature loops shorter than it. The
//      sampler and the remesher set that length from the sampling radius (a crease shorter than
//      two sample spacings cannot be represented by the output's edges anyway), which removes
//      the hundreds of false "features" a 60 degree threshold finds on coarsely meshed curved surfaces;
//   3. mesh borders are always feature curves (whatever the policy: the remesh keeps them);
//   4. corners: vertices where the feature graph branches or ends (feature degree != 2), and
//      vertices of degree 2 where the curve turns by more than `corner_angle`;
//   5. feature curves: the chains of feature edges between corners, or closed loops.
// feature_sample_locations() then places points at even intervals no shorter than a spacing
// along each curve (§4.2.4), as surface locations.

#ifndef POISSON_REMESH_FEATURES_DETECT_FEATURES_H
#define POISSON_REMESH_FEATURES_DETECT_FEATURES_H

#include <Poisson_remesh/parameters.h>

#include <CGAL/Kernel_traits.h>
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
/// `minimum_feature_length` over the scale s at which corners are measured and short curves
/// between corners dropped (s = r when the sampler sets the length to 4r).
constexpr double feature_length_in_radii_ratio = 4.0;
/// A vertex is a tip (step 6) when the angle defect summed within the scale exceeds this (radians).
constexpr double tip_angle_defect = 0.5 * CGAL_PI;

namespace internal {

// An edge index for any FaceGraph, from the halfedge index map (in [0, num_halfedges)).
// CGAL 5.5's initialized edge index map of a Polyhedron_3 reads ids that plain Polyhedron_3
// items do not have, while its halfedge index map is initialized for every FaceGraph.
template <class TriangleMesh>
struct Edge_index_through_halfedge
{
  typedef typename boost::graph_traits<TriangleMesh>::edge_descriptor key_type;
  typedef std::size_t value_type;
  typedef std::size_t reference;
  typedef boost::readable_property_map_tag category;

  Edge_index_through_halfedge() = default;
  explicit Edge_index_through_halfedge(const TriangleMesh& tm) : tm_(&tm), him_(CGAL::get_initialized_halfedge_index_map(tm)) {}

  // (the smaller of its two halfedges' indices: an edge descriptor may hold either halfedge, as
  // Surface_mesh's edge(h) does)
  friend std::size_t get(const Edge_index_through_halfedge& m, key_type e)
  {
    const auto h = halfedge(e, *m.tm_);
    return std::size_t((std::min)(get(m.him_, h), get(m.him_, opposite(h, *m.tm_))));
  }

private:
  const TriangleMesh* tm_ = nullptr;
  typename CGAL::GetInitializedHalfedgeIndexMap<TriangleMesh>::const_type him_;
};

} // namespace internal

/// The features of a mesh, as detect_features() finds them: the feature edges, the corners and
/// the feature curves between them (borders included).
template <class TriangleMesh>
struct Feature_set
{
  /// `boost::graph_traits<TriangleMesh>`
  typedef boost::graph_traits<TriangleMesh> GT;
  /// the mesh's vertex descriptor
  typedef typename GT::vertex_descriptor vertex_descriptor;
  /// the mesh's halfedge descriptor
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  /// the mesh's edge descriptor
  typedef typename GT::edge_descriptor edge_descriptor;

  /// A feature curve: consecutive halfedges (target of one = source of the next), from a corner
  /// to a corner, or a closed loop without corner (then `closed` and it starts anywhere).
  struct Curve
  {
    std::vector<halfedge_descriptor> halfedges;   ///< in order along the curve
    bool closed = false;   ///< a closed loop without corner
    bool border = false;   ///< made of mesh border edges
    double length = 0;     ///< the curve's length
  };

  /// the corners (the pointed tips are the last `number_of_tips` of them)
  std::vector<vertex_descriptor> corners;
  std::vector<Curve> curves;   ///< the feature curves
  std::size_t number_of_feature_edges = 0;   ///< edges on a feature curve (borders included)
  std::size_t number_of_removed_false_features = 0;  ///< edges dropped by the filtering
  std::size_t number_of_tips = 0;                    ///< corners that are pointed tips (step 6)

  /// whether `e` is a feature edge
  bool is_feature(edge_descriptor e) const { return feature_edge[get(eim, e)]; }
  /// whether `v` is a corner
  bool is_corner(vertex_descriptor v) const { return corner[get(vim, v)]; }

  // indexing
  /// the mesh's edge index map (`feature_edge` is indexed by it: the index of the edge's
  /// halfedge, below `num_halfedges(tm)`, which works on every FaceGraph)
  internal::Edge_index_through_halfedge<TriangleMesh> eim;
  /// the mesh's vertex index map (`corner` is indexed by it)
  typename CGAL::GetInitializedVertexIndexMap<TriangleMesh>::const_type vim;
  std::vector<bool> feature_edge;   ///< per edge index: a feature edge
  std::vector<bool> corner;         ///< per vertex index: a corner
};

namespace internal {

template <class TriangleMesh, class VPM>
double edge_length(typename boost::graph_traits<TriangleMesh>::halfedge_descriptor h, const TriangleMesh& tm, VPM vpm)
{
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(get(vpm, source(h, tm)), get(vpm, target(h, tm)))));
}

// 2 pi minus the angle sum at v (radians); 0 at an isolated vertex, on a border, and beside a
// zero-length edge (no angle there: atan2(0, -0) would be pi)
template <class TriangleMesh, class VPM>
double angle_defect(typename boost::graph_traits<TriangleMesh>::vertex_descriptor v, const TriangleMesh& tm, VPM vpm)
{
  if(halfedge(v, tm) == boost::graph_traits<TriangleMesh>::null_halfedge()) return 0.0;
  const auto p = get(vpm, v);
  double sum = 0;
  for(auto h : CGAL::halfedges_around_target(halfedge(v, tm), tm)) {
    if(is_border(h, tm)) return 0.0;
    const auto a = get(vpm, source(h, tm)) - p, b = get(vpm, target(next(h, tm), tm)) - p;
    if(!(CGAL::to_double(a.squared_length()) > 0) || !(CGAL::to_double(b.squared_length()) > 0)) return 0.0;
    sum += std::atan2(std::sqrt(CGAL::to_double(CGAL::cross_product(a, b).squared_length())), CGAL::to_double(a * b));
  }
  return 2 * CGAL_PI - sum;
}

// The vertices within straight-line distance `reach` of a vertex, reached through edges without
// leaving that ball, each once (the tips of detect_features() and of the feature grading).
template <class TriangleMesh, class VPM>
class Vertex_ball
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
public:
  /// `index_bound`: one past the largest vertex index
  Vertex_ball(const TriangleMesh& tm, VPM vpm, std::size_t index_bound)
    : tm_(tm), vpm_(vpm), vim_(CGAL::get_initialized_vertex_index_map(tm)), stamp_(index_bound, 0) {}

  /// calls f(w, squared distance from v to w) for v and each vertex of its ball
  template <class F>
  void visit(vertex_descriptor v, double reach, F f)
  {
    ++visit_;
    stack_.assign(1, v);
    stamp_[get(vim_, v)] = visit_;
    const auto p = get(vpm_, v);
    while(!stack_.empty()) {
      const vertex_descriptor w = stack_.back();
      stack_.pop_back();
      f(w, CGAL::to_double(CGAL::squared_distance(get(vpm_, w), p)));
      for(auto h : CGAL::halfedges_around_target(halfedge(w, tm_), tm_)) {
        const vertex_descriptor x = source(h, tm_);
        if(stamp_[get(vim_, x)] == visit_) continue;
        stamp_[get(vim_, x)] = visit_;
        if(CGAL::to_double(CGAL::squared_distance(get(vpm_, x), p)) <= reach * reach) stack_.push_back(x);
      }
    }
  }

private:
  const TriangleMesh& tm_;
  VPM vpm_;
  typename CGAL::GetInitializedVertexIndexMap<TriangleMesh>::const_type vim_;
  std::vector<std::size_t> stamp_;
  std::size_t visit_ = 0;
  std::vector<vertex_descriptor> stack_;
};

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
  - `minimum_feature_length` (length, default 0: off): dangling feature chains and closed
    feature loops shorter than this are false features (borders are always kept).
    poisson_disk_sample() and poisson_remesh() default it to `feature_length_in_radii` times r.
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
  const double min_length = choose_parameter(get_parameter(np, internal_np::minimum_feature_length), 0.0);

  Features fs;
  fs.eim = internal::Edge_index_through_halfedge<TriangleMesh>(tm);
  fs.vim = CGAL::get_initialized_vertex_index_map(tm);
  fs.feature_edge.assign(num_halfedges(tm), false);
  fs.corner.assign(num_vertices(tm), false);
  auto eidx = [&](edge_descriptor e) { return std::size_t(get(fs.eim, e)); };
  auto vidx = [&](vertex_descriptor v) { return std::size_t(get(fs.vim, v)); };

  // 1. strong edges
  std::vector<bool> border_edge(num_halfedges(tm), false);
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

  const double scale = min_length / feature_length_in_radii_ratio;
  // 1b. with a scale s, a detected edge is a crease only if it is sharp at that scale: the faces
  // within s of its midpoint, reached from either side without crossing a feature edge, stay
  // apart, and their mean normals still make more than half of sharp_angle. A dihedral spike of a
  // coarse or noisy organic mesh is not (Jiao and Heath: features are judged on a neighbourhood).
  if(scale > 0 && policy == Feature_policy::detect) {
    typedef typename GT::face_descriptor face_descriptor;
    // (a dynamic map: the face ids of a const Polyhedron_3 may not be initialized)
    auto stamp = get(CGAL::dynamic_face_property_t<std::size_t>(), tm);
    for(face_descriptor f : faces(tm)) put(stamp, f, std::size_t(0));
    std::size_t visit = 0;
    std::vector<bool> keep(num_halfedges(tm), true);
    const double cos_half = std::cos(0.5 * sharp_angle * CGAL_PI / 180.0);
    for(edge_descriptor e : edges(tm)) {
      if(!fs.feature_edge[eidx(e)] || border_edge[eidx(e)]) continue;
      const halfedge_descriptor h = halfedge(e, tm);
      const auto mid = CGAL::midpoint(get(vpm, source(h, tm)), get(vpm, target(h, tm)));
      typename CGAL::Kernel_traits<typename boost::property_traits<decltype(vpm)>::value_type>::Kernel::Vector_3 n[2];
      bool met = false;
      ++visit;
      for(int side = 0; side < 2 && !met; ++side) {
        const face_descriptor f0 = face(side == 0 ? h : opposite(h, tm), tm);
        const std::size_t mark = 2 * visit + std::size_t(side);
        if(side == 1 && get(stamp, f0) == 2 * visit) { met = true; break; }   // side 0 reached it
        std::vector<face_descriptor> stack{f0};
        put(stamp, f0, mark);
        n[side] = CGAL::NULL_VECTOR;
        while(!stack.empty() && !met) {
          const face_descriptor f = stack.back();
          stack.pop_back();
          const halfedge_descriptor hf = halfedge(f, tm);
          const auto a = get(vpm, source(hf, tm)), b = get(vpm, target(hf, tm)), c = get(vpm, target(next(hf, tm), tm));
          n[side] = n[side] + 0.5 * CGAL::cross_product(b - a, c - a);
          for(halfedge_descriptor g : CGAL::halfedges_around_face(hf, tm)) {
            if(fs.feature_edge[eidx(edge(g, tm))] || border_edge[eidx(edge(g, tm))]) continue;
            const face_descriptor fo = face(opposite(g, tm), tm);
            const std::size_t st = get(stamp, fo);
            if(st == mark) continue;
            if(st == 2 * visit) { met = true; break; }   // reached the other side's start region
            if(CGAL::to_double(CGAL::squared_distance(get(vpm, target(g, tm)), mid)) > scale * scale &&
               CGAL::to_double(CGAL::squared_distance(get(vpm, source(g, tm)), mid)) > scale * scale) continue;
            put(stamp, fo, mark);
            stack.push_back(fo);
          }
        }
      }
      if(met) { keep[eidx(e)] = false; continue; }
      const double l0 = std::sqrt(CGAL::to_double(n[0].squared_length())), l1 = std::sqrt(CGAL::to_double(n[1].squared_length()));
      if(!(l0 > 0 && l1 > 0) || CGAL::to_double(n[0] * n[1]) / (l0 * l1) > cos_half) keep[eidx(e)] = false;
    }
    for(edge_descriptor e : edges(tm))
      if(fs.feature_edge[eidx(e)] && !keep[eidx(e)]) { fs.feature_edge[eidx(e)] = false; ++fs.number_of_removed_false_features; }
    // a face whose three edges are creases is a crease cycle no output edge can follow (the
    // tessellation would merge two of its curves): its least sharp edge is dropped -- unless every
    // edge at each of its vertices is a crease, three at least: the face is then a facet of a
    // coarse polyhedron, each of its vertices the meeting point of three curves or more and each
    // side a curve of its own between two of them, and it may be a face of the output (dropping
    // one edge of every such face would break all of the polyhedron's curves)
    std::vector<std::size_t> creases(num_vertices(tm), 0);
    for(edge_descriptor e : edges(tm))
      if(fs.feature_edge[eidx(e)] && !border_edge[eidx(e)]) {
        ++creases[vidx(source(halfedge(e, tm), tm))];
        ++creases[vidx(target(halfedge(e, tm), tm))];
      }
    for(face_descriptor f : faces(tm)) {
      bool between_corners = true;
      for(halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(f, tm), tm))
        between_corners = between_corners && creases[vidx(target(g, tm))] >= 3 && creases[vidx(target(g, tm))] == degree(target(g, tm), tm);
      if(between_corners) continue;
      halfedge_descriptor least = GT::null_halfedge();
      double least_cos = -2;
      std::size_t sharp = 0;
      for(halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(f, tm), tm)) {
        if(!fs.feature_edge[eidx(edge(g, tm))] || border_edge[eidx(edge(g, tm))]) continue;
        ++sharp;
        const auto p = get(vpm, source(g, tm)), q = get(vpm, target(g, tm));
        const auto n1 = CGAL::cross_product(q - p, get(vpm, target(next(g, tm), tm)) - p);
        const auto n2 = CGAL::cross_product(p - q, get(vpm, target(next(opposite(g, tm), tm), tm)) - q);   // face (q, p, s)
        const double l1 = std::sqrt(CGAL::to_double(n1.squared_length())), l2 = std::sqrt(CGAL::to_double(n2.squared_length()));
        const double c = l1 > 0 && l2 > 0 ? CGAL::to_double(n1 * n2) / (l1 * l2) : 1;
        if(c > least_cos) { least_cos = c; least = g; }
      }
      if(sharp == 3) {
        fs.feature_edge[eidx(edge(least, tm))] = false;
        ++fs.number_of_removed_false_features;
        --creases[vidx(source(least, tm))];
        --creases[vidx(target(least, tm))];
      }
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
  auto remove_chain = [&](const std::vector<halfedge_descriptor>& chain) {
    for(halfedge_descriptor g : chain) {
      fs.feature_edge[eidx(edge(g, tm))] = false;
      --degree[vidx(source(g, tm))];
      --degree[vidx(target(g, tm))];
      ++fs.number_of_removed_false_features;
    }
  };
  // 2a. dangling chains: fewer than dangling_chain_min_edges edges, or shorter than min_length
  auto remove_dangling_chains = [&] {
    bool removed = true;
    while(removed) {
      removed = false;
      for(vertex_descriptor v : vertices(tm)) {
        if(degree[vidx(v)] != 1) continue;
        // walk from the free end through degree-2 vertices to the next node
        std::vector<halfedge_descriptor> chain;
        halfedge_descriptor h = GT::null_halfedge();
        for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm))
          if(feature_or_border(edge(g, tm))) { h = g; break; }
        bool has_border = false;
        double length = 0;
        while(h != GT::null_halfedge()) {
          chain.push_back(h);
          length += internal::edge_length(h, tm, vpm);
          has_border = has_border || border_edge[eidx(edge(h, tm))];
          if(degree[vidx(target(h, tm))] != 2 || target(h, tm) == v) break;
          h = next_feature_halfedge(h);
        }
        if(has_border || (chain.size() >= dangling_chain_min_edges && length >= min_length)) continue;
        remove_chain(chain);
        removed = true;
      }
    }
  };
  // 2b. closed loops of degree-2 vertices shorter than min_length
  auto remove_short_loops = [&] {
    if(!(min_length > 0)) return;
    std::vector<bool> seen(num_halfedges(tm), false);
    for(edge_descriptor e : edges(tm)) {
      if(!fs.feature_edge[eidx(e)] || border_edge[eidx(e)] || seen[eidx(e)]) continue;
      std::vector<halfedge_descriptor> chain;
      double length = 0;
      bool loop = true;
      halfedge_descriptor h = halfedge(e, tm);
      do {
        chain.push_back(h);
        seen[eidx(edge(h, tm))] = true;
        length += internal::edge_length(h, tm, vpm);
        if(degree[vidx(target(h, tm))] != 2 || border_edge[eidx(edge(h, tm))]) { loop = false; break; }
        h = next_feature_halfedge(h);
      } while(h != GT::null_halfedge() && edge(h, tm) != e);
      if(loop && h != GT::null_halfedge() && length < min_length) remove_chain(chain);
    }
  };

  // 4. corners: feature degree != 2, or a turn sharper than corner_angle. With a scale s (from
  // min_length) the turn is measured between the points s away along the curve on both sides, a
  // corner must turn more than its neighbours within s, and it is not within s of a node: the
  // zig-zags of a noisy crease are not corners at the scale of the output.
  const double cos_corner = std::cos(corner_angle * CGAL_PI / 180.0);
  // from v along its feature halfedge g: the point at arc length >= scale (or the next node), the
  // largest turn met on the way (`turn` indexed by vertex), whether a node was met
  auto walk = [&](halfedge_descriptor g, const std::vector<double>* turn, double& best, std::size_t& best_index, bool& node) {
    double length = 0;
    node = false;
    const halfedge_descriptor g0 = g;
    while(true) {
      length += internal::edge_length(g, tm, vpm);
      const vertex_descriptor w = target(g, tm);
      if(degree[vidx(w)] != 2) { node = true; return w; }
      if(turn && ((*turn)[vidx(w)] > best || ((*turn)[vidx(w)] == best && vidx(w) < best_index))) { best = (*turn)[vidx(w)]; best_index = vidx(w); }
      if(length >= scale) return w;
      g = next_feature_halfedge(g);
      if(g == GT::null_halfedge() || g == g0) return w;   // (a loop shorter than the scale)
    }
  };
  auto find_corners = [&] {
    fs.corners.clear();
    std::fill(fs.corner.begin(), fs.corner.end(), false);
    std::vector<double> turn(num_vertices(tm), -1);   // cosine of the angle between the two sides, negated
    for(vertex_descriptor v : vertices(tm)) {
      if(degree[vidx(v)] != 2) continue;
      std::vector<halfedge_descriptor> fe;
      for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm))
        if(feature_or_border(edge(g, tm))) fe.push_back(g);
      double unused = 0;
      std::size_t unused_index = 0;
      bool node = false;
      const auto p = get(vpm, v);
      const auto a = get(vpm, walk(fe[0], nullptr, unused, unused_index, node)) - p;
      const auto b = get(vpm, walk(fe[1], nullptr, unused, unused_index, node)) - p;
      const double la = std::sqrt(CGAL::to_double(a * a)), lb = std::sqrt(CGAL::to_double(b * b));
      // turning angle = 180 - angle(a, b): larger turn, larger value
      turn[vidx(v)] = la > 0 && lb > 0 ? CGAL::to_double(a * b) / (la * lb) : 1;
    }
    for(vertex_descriptor v : vertices(tm)) {
      const std::size_t d = degree[vidx(v)];
      if(d == 0) continue;
      bool is_corner = d != 2;
      if(!is_corner && turn[vidx(v)] > -cos_corner) {   // turns by more than corner_angle
        is_corner = true;
        if(scale > 0)
          for(halfedge_descriptor g : CGAL::halfedges_around_source(v, tm)) {
            if(!feature_or_border(edge(g, tm))) continue;
            double best = turn[vidx(v)];
            std::size_t best_index = vidx(v);
            bool node = false;
            walk(g, &turn, best, best_index, node);
            if(node || best_index != vidx(v)) is_corner = false;
          }
      }
      if(is_corner) { fs.corner[vidx(v)] = true; fs.corners.push_back(v); }
    }
  };

  // 5. curves: from every corner along each feature edge, then the remaining closed loops
  auto trace_curves = [&] {
    fs.curves.clear();
    std::vector<bool> used(num_halfedges(tm), false);
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
  };

  // 3. borders are features
  for(edge_descriptor e : edges(tm)) if(border_edge[eidx(e)]) fs.feature_edge[eidx(e)] = true;
  // 2-5 until stable: a curve between two corners shorter than the scale cannot be an edge of the
  // output (it would pin a sliver) and is dropped, which may leave new dangling chains
  while(true) {
    remove_dangling_chains();
    remove_short_loops();
    find_corners();
    trace_curves();
    bool dropped = false;
    if(scale > 0)
      for(const auto& c : fs.curves)
        if(!c.border && !c.closed && c.length < scale) { remove_chain(c.halfedges); dropped = true; }
    if(!dropped) break;
  }
  for(edge_descriptor e : edges(tm)) if(fs.feature_edge[eidx(e)]) ++fs.number_of_feature_edges;

  // 6. tips: with a scale s and sharp features detected, the points where the surface is pointed
  // at that scale (a horn, a claw: the angle defect summed within s is over tip_angle_defect) are
  // corners too, so that the output keeps them (Jiao and Heath's cone points)
  if(scale > 0 && policy == Feature_policy::detect) {
    std::vector<double> defect(num_vertices(tm), 0);
    for(vertex_descriptor v : vertices(tm)) defect[vidx(v)] = internal::angle_defect(v, tm, vpm);
    std::vector<std::pair<double, vertex_descriptor>> candidates;
    internal::Vertex_ball<TriangleMesh, decltype(vpm)> ball(tm, vpm, num_vertices(tm));   // within s of v
    for(vertex_descriptor v : vertices(tm)) {
      if(defect[vidx(v)] <= 0 || degree[vidx(v)] > 0) continue;   // corners and curves are traced already
      double sum = 0;
      bool pointiest = true;
      ball.visit(v, scale, [&](vertex_descriptor w, double) {
        sum += defect[vidx(w)];
        if(defect[vidx(w)] > defect[vidx(v)] || (defect[vidx(w)] == defect[vidx(v)] && vidx(w) < vidx(v))) pointiest = false;
      });
      if(pointiest && sum > tip_angle_defect) candidates.push_back({sum, v});
    }
    // the pointiest first; no two tips (nor a tip and a corner) closer than 2s
    std::sort(candidates.begin(), candidates.end(), [&](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && vidx(a.second) < vidx(b.second)); });
    for(const auto& c : candidates) {
      const auto p = get(vpm, c.second);
      bool free = true;
      for(vertex_descriptor w : fs.corners)
        if(CGAL::to_double(CGAL::squared_distance(get(vpm, w), p)) < 4 * scale * scale) { free = false; break; }
      if(!free) continue;
      fs.corner[vidx(c.second)] = true;
      fs.corners.push_back(c.second);
      ++fs.number_of_tips;
    }
  }
  return fs;
}

/// A point on a feature curve, as a location on the surface and a 3D point.
template <class TriangleMesh, class Point_3>
struct Feature_sample
{
  CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> location;   ///< on the surface
  Point_3 point;      ///< its 3D point
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

/*!
  the same with a spacing that varies along the curves (adaptive density, §5): `spacing(v)` at the
  vertices, linear along each edge. A curve gets n = floor(T) equal steps of T = the integral of
  ds / spacing(s) along it (the curve's length in local spacings), so consecutive samples are about
  one local spacing apart.
*/
template <class TriangleMesh, class VPM, class VertexSpacing>
std::vector<Feature_sample<TriangleMesh, typename boost::property_traits<VPM>::value_type>>
feature_sample_locations_with_spacing(const TriangleMesh& tm, VPM vpm, const Feature_set<TriangleMesh>& fs,
                                      VertexSpacing spacing)
{
  typedef typename boost::property_traits<VPM>::value_type Point_3;
  std::vector<Feature_sample<TriangleMesh, Point_3>> out;
  // the number of local spacings along halfedge h (spacing linear from a to b), and the arc
  // length at which that count reaches tau
  auto spacings = [&](double l, double a, double b) {
    return std::abs(b - a) < 1e-9 * a ? l / a : l / (b - a) * std::log(b / a);
  };
  auto length_at = [&](double l, double a, double b, double tau) {
    return std::abs(b - a) < 1e-9 * a ? tau * a : a * l / (b - a) * std::expm1(tau * (b - a) / l);
  };
  for(std::size_t ci = 0; ci < fs.curves.size(); ++ci) {
    const auto& c = fs.curves[ci];
    std::vector<double> tau_of_edge;
    double T = 0;
    for(auto h : c.halfedges) {
      const double a = spacing(source(h, tm)), b = spacing(target(h, tm));
      if(!(a > 0) || !(b > 0)) throw std::invalid_argument("feature_sample_locations_with_spacing: spacing must be positive");
      tau_of_edge.push_back(spacings(internal::edge_length(h, tm, vpm), a, b));
      T += tau_of_edge.back();
    }
    const std::size_t n = std::size_t(std::floor(T));
    std::size_t count;
    double step;
    if(c.closed) { count = std::max<std::size_t>(1, n); step = T / double(count); }
    else { if(n < 2) continue; count = n - 1; step = T / double(n); }
    double next_tau = c.closed ? 0.0 : step, tau0 = 0;
    std::size_t placed = 0, k = 0;
    for(auto h : c.halfedges) {
      const double l = internal::edge_length(h, tm, vpm), a = spacing(source(h, tm)), b = spacing(target(h, tm));
      const double te = tau_of_edge[k++];
      while(placed < count && next_tau <= tau0 + te + 1e-12 * T) {
        const double t = l > 0 ? std::min(1.0, std::max(0.0, length_at(l, a, b, next_tau - tau0) / l)) : 0.0;
        auto loc = location_on_halfedge(h, t, tm);
        out.push_back({loc, CGAL::Polygon_mesh_processing::construct_point(loc, tm, CGAL::parameters::vertex_point_map(vpm)), ci});
        ++placed;
        next_tau += step;
      }
      tau0 += te;
    }
  }
  return out;
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_FEATURES_DETECT_FEATURES_H
