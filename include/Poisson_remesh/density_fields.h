// Poisson_remesh/density_fields.h
//
// Density fields for adaptive sampling and remeshing (paper §5), models of the concept
// `DensityField` (doc/Poisson_remesh/Concepts/DensityField.h): a relative density of samples per
// unit area given at the input's vertices, turned into a disk radius per vertex by Eq. 1 and
// interpolated linearly inside faces (Eq. 3).
//   - Uniform_density: the default (the uniform sampler and remesher);
//   - Curvature_density: from principal curvatures estimated at each vertex by CGAL's
//     Monge_via_jet_fitting (a degree-2 jet on the 2-ring; chosen over Rusinkiewicz's per-face
//     tensors because CGAL ships it and a jet is less sensitive to skinny triangles), raised to the
//     normal curvature across the sharpest incident edge where a thin rim escapes the jet, through
//     a gamma curve, clamped between a minimum and a maximum edge length, Laplacian-smoothed;
//     given the creases the remesh keeps (its feature edges), it is measured beside them;
//   - Vertex_density<Map>: the user's value per vertex (a readable vertex property map);
//   - Point_density<F>: the user's functor on 3D points, evaluated at the vertices.
// Entry points: vertex_densities(field, tm, vpm) (for Curvature_density also with the creases,
// vertex_densities(field, tm, vpm, creases)) and vertex_disk_radii(tm, vpm, densities,
// target_vertex_count), which scales the field so that Eq. 1 predicts the target count and limits
// the radius gradient to 1/2 (the available boundary of §5.1 needs |grad r| < 1).

#ifndef POISSON_REMESH_DENSITY_FIELDS_H
#define POISSON_REMESH_DENSITY_FIELDS_H

#include <Poisson_remesh/sizing.h>

#include <CGAL/Eigen_svd.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Kernel_traits.h>

#include <boost/property_map/function_property_map.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {

/// Uniform density: every point of the surface alike (the default).
struct Uniform_density {};

/// Curvature-adaptive density (§5.1): denser where the surface bends.
struct Curvature_density
{
  /// density ~ (RMS curvature)^gamma before clamping: 0 is uniform, 1 (the default) gives edges
  /// ~ 1 / sqrt(curvature), which evens out the distance to the input (the chord error).
  double gamma = 1.0;
  /// the shortest and the longest target edge (0: set by `edge_ratio` and the vertex count)
  /// @{
  double min_edge = 0, max_edge = 0;
  /// @}
  /// the longest over the shortest edge when min_edge and max_edge are not both given
  double edge_ratio = 5.0;
  /// passes of Laplacian smoothing of the density (Fig. 6)
  unsigned int smoothing = 8;
  /// (beyond the paper) where the input bends at a crease the remesh keeps -- a feature edge,
  /// sampled along its curve and kept as an edge -- the output follows the crease and loses no
  /// distance to the input across it: its dihedral angle is no curvature to pay for, and the
  /// curvature is measured on each side of it, a curved crease's own bend counting (with the
  /// crease edges given to vertex_densities(); the sampler and the remesher give the feature
  /// edges they detect at the uniform density's radius). False: the creases count like any bend.
  bool beside_creases = true;
};

/// The user's density at each vertex (relative; scaled to the target vertex count).
template <class VertexDensityMap>
struct Vertex_density
{
  VertexDensityMap map;   ///< a readable vertex property map of positive numbers
};
/// The density field of the user's values per vertex, `map` (a readable vertex property map).
template <class VertexDensityMap>
Vertex_density<VertexDensityMap> vertex_density(VertexDensityMap map) { return {map}; }

/// The user's density as a function of the 3D point (relative; evaluated at the vertices).
template <class Function>
struct Point_density
{
  Function function;   ///< `function(p)`: a positive number for the 3D point `p`
};
/// The density field of the user's function `f` of the 3D point (evaluated at the vertices).
template <class Function>
Point_density<Function> point_density(Function f) { return {f}; }

template <class T> struct is_uniform_density : std::is_same<typename std::decay<T>::type, Uniform_density> {};

namespace internal {

// One past the largest vertex index: per-vertex vectors are indexed by the vertex index map,
// whose values are not contiguous when the mesh holds removed elements (a Surface_mesh after
// remove_degenerate_faces(), before collect_garbage()).
// (of the elements of `range` under the index map `index`)
template <class Range, class IndexMap>
std::size_t index_bound(const Range& range, const IndexMap& index)
{
  std::size_t n = 0;
  for(auto x : range) n = (std::max)(n, std::size_t(get(index, x)) + 1);
  return n;
}
template <class TriangleMesh>
std::size_t vertex_index_bound(const TriangleMesh& tm)
{
  return index_bound(vertices(tm), CGAL::get_initialized_vertex_index_map(tm));
}

// per vertex index: its neighbours' indices and the lengths of the edges to them
typedef std::vector<std::vector<std::pair<std::size_t, double>>> Edge_adjacency;
template <class TriangleMesh, class VPM>
Edge_adjacency edge_adjacency(const TriangleMesh& tm, VPM vpm)
{
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  Edge_adjacency adj(vertex_index_bound(tm));
  for(auto e : edges(tm)) {
    const auto a = source(halfedge(e, tm), tm), b = target(halfedge(e, tm), tm);
    const double length = std::sqrt(CGAL::to_double(CGAL::squared_distance(get(vpm, a), get(vpm, b))));
    adj[get(vim, a)].push_back({std::size_t(get(vim, b)), length});
    adj[get(vim, b)].push_back({std::size_t(get(vim, a)), length});
  }
  return adj;
}

// (radius, vertex index), smallest first
typedef std::pair<double, std::size_t> Radius_item;
typedef std::priority_queue<Radius_item, std::vector<Radius_item>, std::greater<Radius_item>> Radius_queue;

// lowers the radii `r` so that they grow by at most `rate` per unit of length along the edges,
// from the vertices in `queue` (a Dijkstra sweep; it empties the queue)
inline void limit_radius_growth(std::vector<double>& r, const Edge_adjacency& adj, double rate, Radius_queue& queue)
{
  while(!queue.empty()) {
    const Radius_item it = queue.top();
    queue.pop();
    if(it.first > r[it.second]) continue;
    for(const auto& nb : adj[it.second])
      if(r[nb.first] > it.first + rate * nb.second) { r[nb.first] = it.first + rate * nb.second; queue.push({r[nb.first], nb.first}); }
  }
}

// per vertex: the larger of the RMS of the principal curvatures of a degree-2 jet fitted to the
// 2-ring (CGAL::Monge_via_jet_fitting) and the largest normal curvature across an incident edge.
// `is_crease(e)`: the edges where the surface may bend without it counting (see
// Curvature_density::beside_creases): no normal curvature is taken across them, and a jet whose
// 2-ring would reach over one is fitted on each side of it instead (the faces reached from the
// vertex's faces across the other edges), the vertex taking the largest of its sides' curvatures.
template <class TriangleMesh, class VPM, class IsCrease>
std::vector<double> vertex_curvatures(const TriangleMesh& tm, VPM vpm, IsCrease is_crease)
{
  typedef typename boost::property_traits<VPM>::value_type Point_3;
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel K;
  typedef CGAL::Monge_via_jet_fitting<K, CGAL::Simple_cartesian<double>, CGAL::Eigen_svd> Fitting;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  auto fim = CGAL::get_initialized_face_index_map(tm);
  std::vector<double> kappa(vertex_index_bound(tm), 0.0);
  std::vector<int> stamp(kappa.size(), -1);
  // the vertices on a crease
  std::vector<char> on_crease(kappa.size(), 0);
  for(auto e : edges(tm))
    if(!is_border(e, tm) && is_crease(e)) on_crease[get(vim, source(halfedge(e, tm), tm))] = on_crease[get(vim, target(halfedge(e, tm), tm))] = 1;
  std::vector<int> face_stamp;
  int k = 0;
  std::vector<Point_3> pts;
  // the RMS curvature of the jet through `pts`, if there are enough of them
  auto fitted = [&](double& out) {
    if(pts.size() < 6) return false;
    Fitting fit;
    const auto form = fit(pts.begin(), pts.end(), 2, 2);
    const double k1 = CGAL::to_double(form.principal_curvatures(0)), k2 = CGAL::to_double(form.principal_curvatures(1));
    if(!(std::isfinite(k1) && std::isfinite(k2))) return false;
    out = std::sqrt(0.5 * (k1 * k1 + k2 * k2));
    return true;
  };
  auto add_point = [&](vertex_descriptor w) {
    if(stamp[get(vim, w)] != k) { stamp[get(vim, w)] = k; pts.push_back(get(vpm, w)); }
  };
  std::vector<vertex_descriptor> ring, outer;
  std::vector<face_descriptor> incident, side, frontier, next_faces;   // (one side's faces, and the steps from them)
  std::vector<char> taken;   // (which faces of `incident` a side holds)
  std::vector<vertex_descriptor> along;   // (v's neighbours along a crease)
  for(vertex_descriptor v : vertices(tm)) {
    if(halfedge(v, tm) == GT::null_halfedge()) continue;
    // the 2-ring (3-ring when the 2-ring has too few points for a degree-2 jet); `over` when it spreads
    // from a vertex on a crease, reaching past it
    ++k;
    pts.clear();
    ring.assign(1, v);
    stamp[get(vim, v)] = k;
    pts.push_back(get(vpm, v));
    bool over = false;
    for(int depth = 0; depth < 3 && (depth < 2 || pts.size() < 10); ++depth) {
      outer.clear();
      for(vertex_descriptor u : ring) {
        if(on_crease[get(vim, u)]) over = true;
        for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(u, tm), tm))
          if(stamp[get(vim, w)] != k) { stamp[get(vim, w)] = k; outer.push_back(w); pts.push_back(get(vpm, w)); }
      }
      ring.swap(outer);
    }
    double value = 0;
    if(!over) {
      if(fitted(value)) kappa[get(vim, v)] = value;
      continue;
    }
    // each side: the faces around v joined across edges that are no crease, and the faces reached
    // from them across such edges (two steps, up to four while there are fewer than ten points)
    if(face_stamp.empty()) face_stamp.assign(index_bound(faces(tm), fim), -1);   // (by face index)
    incident.clear();
    for(auto h : CGAL::halfedges_around_target(halfedge(v, tm), tm))
      if(!is_border(h, tm)) incident.push_back(face(h, tm));
    taken.assign(incident.size(), 0);
    double best = 0;
    for(std::size_t s = 0; s < incident.size(); ++s) {
      if(taken[s]) continue;
      ++k;   // (a new stamp for this side's points and faces)
      pts.clear();
      add_point(v);
      side.assign(1, incident[s]);
      taken[s] = 1;
      face_stamp[get(fim, incident[s])] = k;
      // the side's faces around v
      for(std::size_t i = 0; i < side.size(); ++i)
        for(auto h : CGAL::halfedges_around_face(halfedge(side[i], tm), tm)) {
          if(is_border(edge(h, tm), tm) || is_crease(edge(h, tm))) continue;
          if(source(h, tm) != v && target(h, tm) != v) continue;
          const face_descriptor g = face(opposite(h, tm), tm);
          const auto it = std::find(incident.begin(), incident.end(), g);
          if(it == incident.end() || taken[std::size_t(it - incident.begin())]) continue;
          taken[std::size_t(it - incident.begin())] = 1;
          face_stamp[get(fim, g)] = k;
          side.push_back(g);
        }
      for(face_descriptor f : side)
        for(vertex_descriptor w : CGAL::vertices_around_face(halfedge(f, tm), tm)) add_point(w);
      frontier = side;
      for(int depth = 0; depth < 4 && (depth < 2 || pts.size() < 10) && !frontier.empty(); ++depth) {
        next_faces.clear();
        for(face_descriptor f : frontier)
          for(auto h : CGAL::halfedges_around_face(halfedge(f, tm), tm)) {
            if(is_border(edge(h, tm), tm) || is_crease(edge(h, tm))) continue;
            const face_descriptor g = face(opposite(h, tm), tm);
            if(face_stamp[get(fim, g)] == k) continue;
            face_stamp[get(fim, g)] = k;
            next_faces.push_back(g);
            for(vertex_descriptor w : CGAL::vertices_around_face(halfedge(g, tm), tm)) add_point(w);
          }
        frontier.swap(next_faces);
      }
      if(fitted(value)) best = (std::max)(best, value);
    }
    // and the crease's own bend, where v is on one crease curve: its feature samples are as far
    // apart as the radius there asks (the turn at v over the mean length of its two crease edges)
    along.clear();
    for(auto h : CGAL::halfedges_around_target(halfedge(v, tm), tm))
      if(!is_border(edge(h, tm), tm) && is_crease(edge(h, tm))) along.push_back(source(h, tm));
    if(along.size() == 2) {
      const auto a = get(vpm, along[0]) - get(vpm, v), b = get(vpm, along[1]) - get(vpm, v);
      const double la = std::sqrt(CGAL::to_double(a.squared_length())), lb = std::sqrt(CGAL::to_double(b.squared_length()));
      if(la > 0 && lb > 0) {
        const double turn = std::acos(std::max(-1.0, std::min(1.0, -CGAL::to_double(a * b) / (la * lb))));
        best = (std::max)(best, turn / (0.5 * (la + lb)));
      }
    }
    kappa[get(vim, v)] = best;
  }
  // a jet smooths over rims and creases narrower than the 2-ring (thin protrusions of a coarse
  // input), where a remesh loses most: the normal curvature across each edge (the angle between
  // the normals of its faces over the distance between their centroids) is taken as well, and the
  // larger of the two used
  {
    namespace PMP = CGAL::Polygon_mesh_processing;
    for(auto e : edges(tm)) {
      auto h = halfedge(e, tm);
      if(is_border_edge(h, tm) || is_crease(e)) continue;
      auto f1 = face(h, tm), f2 = face(opposite(h, tm), tm);
      auto n1 = PMP::compute_face_normal(f1, tm, CGAL::parameters::vertex_point_map(vpm));
      auto n2 = PMP::compute_face_normal(f2, tm, CGAL::parameters::vertex_point_map(vpm));
      double ang = std::acos(std::max(-1.0, std::min(1.0, CGAL::to_double(n1 * n2))));
      auto c1 = CGAL::centroid(get(vpm, source(h, tm)), get(vpm, target(h, tm)), get(vpm, target(next(h, tm), tm)));
      auto h2 = opposite(h, tm);
      auto c2 = CGAL::centroid(get(vpm, source(h2, tm)), get(vpm, target(h2, tm)), get(vpm, target(next(h2, tm), tm)));
      const double k = ang / std::sqrt(CGAL::to_double(CGAL::squared_distance(c1, c2)));
      if(!std::isfinite(k)) continue;   // degenerate faces: no normal, or coincident centroids
      for(auto v : {source(h, tm), target(h, tm)}) kappa[get(vim, v)] = std::max(kappa[get(vim, v)], k);
    }
  }
  return kappa;
}

template <class TriangleMesh>
void laplacian_smooth(const TriangleMesh& tm, std::vector<double>& value, unsigned int passes)
{
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  std::vector<double> next(value.size());
  for(unsigned int p = 0; p < passes; ++p) {
    for(auto v : vertices(tm)) {
      const std::size_t i = get(vim, v);
      double sum = 0;
      std::size_t n = 0;
      if(halfedge(v, tm) != boost::graph_traits<TriangleMesh>::null_halfedge())
        for(auto w : CGAL::vertices_around_target(halfedge(v, tm), tm)) { sum += value[get(vim, w)]; ++n; }
      next[i] = n ? 0.5 * value[i] + 0.5 * sum / double(n) : value[i];
    }
    value.swap(next);
  }
}

inline double quantile(std::vector<double> v, double q)
{
  if(v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

} // namespace internal

/// The relative density at each vertex (indexed by the vertex index map) of `field` on `tm`.
template <class TriangleMesh, class VPM>
std::vector<double> vertex_densities(const Uniform_density&, const TriangleMesh& tm, VPM)
{
  return std::vector<double>(internal::vertex_index_bound(tm), 1.0);
}

/// The user's density at each vertex (indexed by the vertex index map).
template <class TriangleMesh, class VPM, class Map>
std::vector<double> vertex_densities(const Vertex_density<Map>& field, const TriangleMesh& tm, VPM)
{
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  std::vector<double> d(internal::vertex_index_bound(tm), 1.0);
  for(auto v : vertices(tm)) d[get(vim, v)] = double(get(field.map, v));
  return d;
}

/// The user's function evaluated at each vertex (indexed by the vertex index map).
template <class TriangleMesh, class VPM, class Function>
std::vector<double> vertex_densities(const Point_density<Function>& field, const TriangleMesh& tm, VPM vpm)
{
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  std::vector<double> d(internal::vertex_index_bound(tm), 1.0);
  for(auto v : vertices(tm)) d[get(vim, v)] = double(field.function(get(vpm, v)));
  return d;
}

/// Curvature density: (RMS curvature)^gamma, clamped so that the edge lengths it asks for span at
/// most `edge_ratio` (the flattest 2% and the most curved 2% are clamped), Laplacian-smoothed.
/// min_edge / max_edge, when given, are applied by vertex_disk_radii() (they are absolute).
/// With `creases`, a readable edge property map of `bool` (true on the edges the remesh keeps as
/// feature edges), the curvature is measured beside them (Curvature_density::beside_creases).
template <class TriangleMesh, class VPM, class EdgeIsCreaseMap>
std::vector<double> vertex_densities(const Curvature_density& field, const TriangleMesh& tm, VPM vpm, EdgeIsCreaseMap creases)
{
  if(!(field.gamma >= 0)) throw std::invalid_argument("Curvature_density: gamma must be >= 0");
  if(!(field.edge_ratio >= 1)) throw std::invalid_argument("Curvature_density: edge_ratio must be >= 1");
  std::vector<double> kappa = internal::vertex_curvatures(tm, vpm, [&](typename boost::graph_traits<TriangleMesh>::edge_descriptor e) {
    return field.beside_creases && bool(get(creases, e));
  });
  for(double& k : kappa) if(!std::isfinite(k)) k = 0;
  double hi = internal::quantile(kappa, 0.98);
  if(!(hi > 0) || !std::isfinite(std::pow(hi, field.gamma))) return std::vector<double>(kappa.size(), 1.0);   // flat: uniform
  std::vector<double> d(kappa.size());
  const double ratio = (field.min_edge > 0 && field.max_edge > 0) ? field.max_edge / field.min_edge : field.edge_ratio;
  const double dmax = std::pow(hi, field.gamma), dmin = dmax / (ratio * ratio);   // density ~ 1 / edge^2
  for(std::size_t i = 0; i < kappa.size(); ++i) d[i] = std::min(dmax, std::max(dmin, std::pow(kappa[i], field.gamma)));
  internal::laplacian_smooth(tm, d, field.smoothing);
  return d;
}

/// The same without creases: every bend counts.
template <class TriangleMesh, class VPM>
std::vector<double> vertex_densities(const Curvature_density& field, const TriangleMesh& tm, VPM vpm)
{
  return vertex_densities(field, tm, vpm, boost::make_function_property_map<typename boost::graph_traits<TriangleMesh>::edge_descriptor>(
                                            [](typename boost::graph_traits<TriangleMesh>::edge_descriptor) { return false; }));
}

/*!
  The disk radius at each vertex (by vertex index) for the relative densities `density`: Eq. 1
  with rho = 0.844 gives r ~ 1 / sqrt(density); the field is scaled so that the integral of the
  density Eq. 1 associates with r (linear inside faces) over the surface is `target_vertex_count`,
  radii are clamped to [min_edge / 2, max_edge / 2] when those are given (> 0), and the gradient is
  limited to 1/2 (a radius is lowered to its neighbour's plus half the edge between them).
*/
template <class TriangleMesh, class VPM>
std::vector<double> vertex_disk_radii(const TriangleMesh& tm, VPM vpm, const std::vector<double>& density,
                                      double target_vertex_count, double min_edge = 0, double max_edge = 0)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  if(!(target_vertex_count > 0)) throw std::invalid_argument("vertex_disk_radii: the target vertex count must be positive");
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  const std::size_t n = internal::vertex_index_bound(tm);
  if(density.size() < n) throw std::invalid_argument("vertex_disk_radii: one density per vertex is needed");
  for(auto v : vertices(tm)) {
    const double d = density[get(vim, v)];
    if(!(d > 0) || !std::isfinite(d)) throw std::invalid_argument("vertex_disk_radii: densities must be positive and finite");
  }
  // Eq. 1: r = rho sqrt(1 / (2 sqrt(3) N)) for N points per unit area, i.e. N = rho^2 / (2 sqrt(3) r^2)
  const double c = paper_rho * paper_rho / (2 * std::sqrt(3.0));
  std::vector<double> base(n);
  for(std::size_t i = 0; i < n; ++i) base[i] = density[i] > 0 ? std::sqrt(c / density[i]) : 1.0;   // radius for density 1x
  std::vector<double> area(num_faces(tm));
  std::vector<std::array<std::size_t, 3>> fv;
  // |grad r| of a face from its three radii, in the face's own 2D layout
  struct Gradient
  {
    double l0 = 0, x2 = 0, y2 = 0;
    double operator()(double r0, double r1, double r2) const
    {
      if(!(l0 > 0) || !(y2 > 0)) return 0;
      const double ax = (r1 - r0) / l0, ay = (r2 - r0 - ax * x2) / y2;
      return std::hypot(ax, ay);
    }
  };
  std::vector<Gradient> face_gradient;
  for(auto f : faces(tm)) {
    area[fv.size()] = CGAL::to_double(PMP::face_area(f, tm, CGAL::parameters::vertex_point_map(vpm)));
    const auto h = halfedge(f, tm);
    fv.push_back({get(vim, source(h, tm)), get(vim, target(h, tm)), get(vim, target(next(h, tm), tm))});
    const auto p0 = get(vpm, source(h, tm)), p1 = get(vpm, target(h, tm)), p2 = get(vpm, target(next(h, tm), tm));
    Gradient g;
    g.l0 = std::sqrt(CGAL::to_double(CGAL::squared_distance(p0, p1)));
    if(g.l0 > 0) {
      g.x2 = CGAL::to_double((p2 - p0) * (p1 - p0)) / g.l0;
      g.y2 = 2 * area[fv.size() - 1] / g.l0;
    }
    face_gradient.push_back(g);
  }
  const internal::Edge_adjacency adj = internal::edge_adjacency(tm, vpm);
  std::vector<double> r(n);
  // radii for scale s: s * base, clamped, gradient-limited (a Dijkstra-like sweep from the smallest)
  auto radii = [&](double s) {
    std::vector<internal::Radius_item> items(n);
    for(std::size_t i = 0; i < n; ++i) {
      r[i] = s * base[i];
      if(min_edge > 0) r[i] = std::max(r[i], 0.5 * min_edge);
      if(max_edge > 0) r[i] = std::min(r[i], 0.5 * max_edge);
      items[i] = {r[i], i};
    }
    internal::Radius_queue q(std::greater<internal::Radius_item>(), std::move(items));
    auto sweep = [&]() { internal::limit_radius_growth(r, adj, 0.5, q); };
    sweep();
    // the gradient inside a needle face can be far steeper than along its edges: such faces
    // have their radii pulled towards their smallest one (radii only decrease, so this ends)
    for(int pass = 0; pass < 20; ++pass) {
      bool changed = false;
      for(std::size_t f = 0; f < fv.size(); ++f) {
        const double g = face_gradient[f](r[fv[f][0]], r[fv[f][1]], r[fv[f][2]]);
        if(!(g > 0.5 + 1e-12)) continue;
        const double lo_r = std::min({r[fv[f][0]], r[fv[f][1]], r[fv[f][2]]});
        for(std::size_t k : fv[f]) {
          r[k] = lo_r + (r[k] - lo_r) * (0.5 / g);
          q.push({r[k], k});
        }
        changed = true;
      }
      if(!changed) break;
      sweep();
    }
  };
  // the count Eq. 1 predicts: the density c / r^2, linear inside faces
  auto count = [&]() {
    double total = 0;
    for(std::size_t f = 0; f < fv.size(); ++f)
      total += area[f] * (c / (r[fv[f][0]] * r[fv[f][0]]) + c / (r[fv[f][1]] * r[fv[f][1]]) + c / (r[fv[f][2]] * r[fv[f][2]])) / 3;
    return total;
  };
  // count ~ 1 / s^2 where neither the clamps nor the gradient limit act: fixed-point iteration on
  // s, then bisection if the clamps make it stall
  // indices no vertex uses (removed elements) get a radius of a vertex, so that statistics over
  // the vector stay meaningful
  auto fill_unused = [&](std::vector<double>& radius) {
    std::vector<char> used(n, 0);
    for(auto v : vertices(tm)) used[get(vim, v)] = 1;
    double any = 0;
    for(std::size_t i = 0; i < n; ++i) if(used[i]) { any = radius[i]; break; }
    for(std::size_t i = 0; i < n; ++i) if(!used[i]) radius[i] = any;
  };
  double s = 1;
  radii(s);
  for(int it = 0; it < 12; ++it) {
    const double ratio = count() / target_vertex_count;
    if(std::abs(ratio - 1) < 1e-4) { fill_unused(r); return r; }
    s *= std::sqrt(ratio);
    radii(s);
  }
  double lo = s / 16, hi = s * 16;
  for(int it = 0; it < 40; ++it) {
    const double mid = std::sqrt(lo * hi);
    radii(mid);
    if(count() > target_vertex_count) lo = mid; else hi = mid;
  }
  radii(std::sqrt(lo * hi));
  fill_unused(r);
  return r;
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_DENSITY_FIELDS_H
