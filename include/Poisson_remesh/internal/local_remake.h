// Poisson_remesh/internal/local_remake.h
//
// (beyond the paper) The remakes of the regions at fault alone: what poisson_remesh() does with
// `local_remakes` (off by default) instead of remeshing the whole input again, when its result
// keeps triangles under 30 degrees without cutting itself (internal/regrading.h finds the places
// at fault and lowers the disk radii there; a result that cuts itself is still made again whole).
// Objective: the smallest angle near the places. The rest of the mesh is left exactly as it is
// (same vertices, same triangles), and the work is in proportion to the region.
//
//   1. the region: the output's free vertices (surface samples, leftover input vertices, corners
//      on no feature edge that are no pointed tip) within `region_reach` disk radii of a place;
//      the patch: every triangle of a region vertex. Feature and corner vertices stay.
//   2. sampling: a boundary sampler on the input at the lowered radii, the kept vertices within
//      `kept_reach` radii of the region inserted first (so that the new samples keep their
//      distance from what stays), drawing only on the input's faces within 2r of a region vertex:
//      the new samples fill the region's gaps maximally.
//   3. tessellation: the patch, cut out as a mesh of its own, is the "input" of the mutual
//      tessellation (§6.1) with its kept vertices as samples at its own vertices and the new
//      samples (on the input) located on it; its region vertices are removed. The patch's
//      border is a border of that mesh, so the result has the same border vertices and edges;
//      the output's feature edges inside the patch are its feature edges.
//   4. relaxation: the default relaxer on the result, the kept vertices fixed, projecting onto
//      the input (without fidelity insertions, which would take every input point outside the
//      patch as far from it, and without merging close corners: the kept vertices are none).
//   5. the stitch: the patch's triangles replaced by the result's, after a check that the whole
//      face set is still a consistently oriented manifold (else nothing changes).
// A remake whose patch or result is no valid mesh, or whose result lost a border vertex of the
// patch, changes nothing and reports false. A remake is taken back (undo_remake) by the same
// replacement the other way.

#ifndef POISSON_REMESH_INTERNAL_LOCAL_REMAKE_H
#define POISSON_REMESH_INTERNAL_LOCAL_REMAKE_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Relaxation/Lloyd_relaxer.h>
#include <Poisson_remesh/Sampling/Boundary_sampler.h>
#include <Poisson_remesh/Tessellation/mutual_tessellation.h>
#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/internal/regrading.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace Poisson_remesh {
namespace internal {

struct Local_remake_settings
{
  /// disk radii r around a place within which the free vertices are drawn anew: the reach of the
  /// lowered radii (Regrading_settings::reach, 2) and their grading back to r (from the smallest
  /// radius, r / 16, at a growth of 1/4 per unit of length: 3.75 r), so that the new samples next
  /// to the vertices that stay are at their spacing
  double region_reach = 6;
  /// disk radii beyond the region within which the kept vertices are given to the sampler: two
  /// disks (2 r) and a margin
  double kept_reach = 3;
};

/// What a local remake did.
struct Local_remake_statistics
{
  std::size_t region_vertices = 0;   ///< output vertices drawn anew
  std::size_t patch_faces = 0;       ///< triangles replaced
  std::size_t kept_samples = 0;      ///< kept vertices given to the sampler
  std::size_t new_samples = 0;       ///< samples drawn in the region (and tessellated)
  std::size_t dropped_samples = 0;   ///< samples off the patch or on its border
};

// Replaces the faces of `tm` flagged in `is_old` (by `tm`'s face index) by the faces of `patch`.
// A patch vertex w is `tm`'s vertex to_tm[w] when that one keeps a face outside the old ones;
// else (a null vertex, or a vertex all of whose faces go) it is added, at its point, with kind
// `kind_of(w)`. Nothing changes, and false is returned, when the new face set would not be a
// consistently oriented manifold.
// `added` receives the new faces, `in_tm` each patch vertex's vertex in `tm`.
template <class Mesh, class KindMap, class PatchKind>
bool replace_patch(Mesh& tm, KindMap kind_map, const std::vector<char>& is_old, const Mesh& patch,
                   const std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, typename boost::graph_traits<Mesh>::vertex_descriptor>& to_tm,
                   PatchKind kind_of, std::vector<typename boost::graph_traits<Mesh>::face_descriptor>& added,
                   std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, typename boost::graph_traits<Mesh>::vertex_descriptor>& in_tm)
{
  typedef boost::graph_traits<Mesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  auto fim = CGAL::get_initialized_face_index_map(tm);
  const std::size_t n = vertex_index_bound(tm);
  std::vector<char> survives(n, 0);
  std::vector<face_descriptor> old;
  std::vector<std::vector<std::size_t>> polygons;
  for(face_descriptor f : faces(tm)) {
    if(is_old[get(fim, f)]) { old.push_back(f); continue; }
    std::vector<std::size_t> poly;
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, tm), tm)) { survives[get(vim, v)] = 1; poly.push_back(get(vim, v)); }
    polygons.push_back(std::move(poly));
  }
  std::map<vertex_descriptor, std::size_t> index;   // of the patch's vertices in the soup
  std::size_t next = n;
  for(vertex_descriptor w : vertices(patch)) {
    const auto it = to_tm.find(w);
    index[w] = (it != to_tm.end() && it->second != GT::null_vertex() && survives[get(vim, it->second)]) ? std::size_t(get(vim, it->second)) : next++;
  }
  for(face_descriptor f : faces(patch)) {
    std::vector<std::size_t> poly;
    for(vertex_descriptor w : CGAL::vertices_around_face(halfedge(f, patch), patch)) poly.push_back(index[w]);
    polygons.push_back(std::move(poly));
  }
  if(!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons)) return false;

  for(face_descriptor f : old) CGAL::Euler::remove_face(halfedge(f, tm), tm);
  in_tm.clear();
  added.clear();
  auto vpm = get(CGAL::vertex_point, tm);
  auto ppm = get(CGAL::vertex_point, patch);
  for(vertex_descriptor w : vertices(patch)) {
    if(index[w] < n) { in_tm[w] = to_tm.at(w); continue; }
    const vertex_descriptor v = add_vertex(tm);
    put(vpm, v, get(ppm, w));
    put(kind_map, v, kind_of(w));
    in_tm[w] = v;
  }
  for(face_descriptor f : faces(patch)) {
    std::vector<vertex_descriptor> vs;
    for(vertex_descriptor w : CGAL::vertices_around_face(halfedge(f, patch), patch)) vs.push_back(in_tm[w]);
    const face_descriptor g = CGAL::Euler::add_face(vs, tm);
    if(g == GT::null_face()) throw std::logic_error("local remake: a face of a valid soup could not be added");
    added.push_back(g);
  }
  return true;
}

/// What takes a local remake back: the triangles it replaced (as a mesh of their own, with the
/// kinds of their vertices and, for those that stayed, their vertex in the output) and the
/// triangles it added.
template <class TriangleMesh>
struct Local_remake_undo
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  TriangleMesh patch;
  std::map<vertex_descriptor, int> kind;
  std::map<vertex_descriptor, vertex_descriptor> to_output;
  std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor> added;
};

/// Takes back the remake that filled `undo` (the output unchanged since, garbage not collected).
template <class TriangleMesh, class KindMap>
void undo_remake(TriangleMesh& output, KindMap kind_map, const Local_remake_undo<TriangleMesh>& undo)
{
  auto fim = CGAL::get_initialized_face_index_map(output);
  std::size_t bound = 0;
  for(auto f : faces(output)) bound = std::max<std::size_t>(bound, get(fim, f) + 1);
  std::vector<char> is_old(bound, 0);
  for(auto f : undo.added) is_old[get(fim, f)] = 1;
  std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor> added;
  std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, typename boost::graph_traits<TriangleMesh>::vertex_descriptor> in_tm;
  if(!replace_patch(output, kind_map, is_old, undo.patch, undo.to_output, [&](auto w) { return undo.kind.at(w); }, added, in_tm))
    throw std::logic_error("local remake: the faces replaced could not be put back");
}

/// Remakes the regions of `output` around `places`: see the file's comment. `kind_map` gives each
/// output vertex's Sample_kind as an int (-1: a leftover input vertex, fixed), and is kept up to
/// date; `is_feature(e)` tells the output's feature edges, `is_tip(v)` its pointed tips. `radii`:
/// the lowered disk radii by input vertex index (empty: `radius` everywhere). The relaxation uses
/// `relaxer` (built on `input`) with `settings`. Returns whether the output changed.
template <class TriangleMesh, class InputVPM, class Oracle, class Relaxer, class KindMap, class IsFeature, class IsTip, class Point_3>
bool remake_regions(const TriangleMesh& input, InputVPM in_vpm, const Oracle& oracle, const Relaxer& relaxer,
                    Relaxation_settings settings, TriangleMesh& output, KindMap kind_map, IsFeature is_feature, IsTip is_tip,
                    const std::vector<Point_3>& places, double radius, const std::vector<double>& radii, unsigned int seed,
                    const Local_remake_settings& ls, Local_remake_statistics& stats, Local_remake_undo<TriangleMesh>& undo)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename GT::edge_descriptor edge_descriptor;
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel K;
  typedef PMP::Face_location<TriangleMesh, double> Face_location;
  stats = Local_remake_statistics();
  if(places.empty()) return false;
  const int corner = int(Sample_kind::corner), surface = int(Sample_kind::surface);
  const int kept_kind = -2;   // (in the patch: a vertex that stays)

  // 1. the region and the patch
  auto vpm = get(CGAL::vertex_point, output);
  auto ovim = CGAL::get_initialized_vertex_index_map(output);
  auto ofim = CGAL::get_initialized_face_index_map(output);
  const double region_d = ls.region_reach * radius, kept_d = region_d + ls.kept_reach * radius;
  const Near_points<Point_3> near_place(places, kept_d);
  auto free_vertex = [&](vertex_descriptor v) {
    const int k = get(kind_map, v);
    return k < 0 || k == surface || (k == corner && is_loose_corner(v, output, is_tip, is_feature));
  };
  std::vector<char> in_region(vertex_index_bound(output), 0), kept_near(vertex_index_bound(output), 0);
  std::vector<vertex_descriptor> region;
  for(vertex_descriptor v : vertices(output)) {
    if(halfedge(v, output) == GT::null_halfedge()) continue;
    const double d2 = near_place.squared_distance(get(vpm, v));
    if(d2 < region_d * region_d && free_vertex(v)) { in_region[get(ovim, v)] = 1; region.push_back(v); }
    else if(d2 < kept_d * kept_d) kept_near[get(ovim, v)] = 1;
  }
  if(region.empty()) return false;
  std::size_t face_bound = 0;
  for(face_descriptor f : faces(output)) face_bound = std::max<std::size_t>(face_bound, get(ofim, f) + 1);
  std::vector<char> in_patch(face_bound, 0);
  std::vector<face_descriptor> patch_faces;
  for(vertex_descriptor v : region)
    for(face_descriptor f : CGAL::faces_around_target(halfedge(v, output), output))
      if(f != GT::null_face() && !in_patch[get(ofim, f)]) { in_patch[get(ofim, f)] = 1; patch_faces.push_back(f); }
  std::sort(patch_faces.begin(), patch_faces.end(), [&](face_descriptor a, face_descriptor b) { return get(ofim, a) < get(ofim, b); });

  TriangleMesh& patch = undo.patch;
  clear(patch);
  undo.kind.clear();
  undo.to_output.clear();
  undo.added.clear();
  auto ppm = get(CGAL::vertex_point, patch);
  std::map<vertex_descriptor, vertex_descriptor> o2p, p2o;   // (output <-> patch; region vertices too)
  for(face_descriptor f : patch_faces) {
    std::vector<vertex_descriptor> tri;
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, output), output)) {
      auto it = o2p.find(v);
      if(it == o2p.end()) {
        const vertex_descriptor w = add_vertex(patch);
        put(ppm, w, get(vpm, v));
        it = o2p.emplace(v, w).first;
        p2o[w] = v;
      }
      tri.push_back(it->second);
    }
    if(CGAL::Euler::add_face(tri, patch) == GT::null_face()) return false;   // (the patch pinches: not a mesh of its own)
  }
  stats.region_vertices = region.size();
  stats.patch_faces = patch_faces.size();
  // the kept vertices to give the sampler: those near the region, and every patch vertex that stays
  for(const auto& pw : p2o)
    if(!in_region[get(ovim, pw.second)]) kept_near[get(ovim, pw.second)] = 1;

  // 2. the new samples
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<TriangleMesh, InputVPM>>> Input_tree;
  Input_tree input_tree;
  PMP::build_AABB_tree(input, input_tree, CGAL::parameters::vertex_point_map(in_vpm));
  auto on_input = [&](const Point_3& p) {
    const auto loc = PMP::locate_with_AABB_tree(p, input_tree, input, CGAL::parameters::vertex_point_map(in_vpm));
    return Face_location(loc.first, {{CGAL::to_double(loc.second[0]), CGAL::to_double(loc.second[1]), CGAL::to_double(loc.second[2])}});
  };
  Boundary_sampler<TriangleMesh, InputVPM, Oracle> sampler(input, in_vpm, seed, oracle);
  auto ivim = CGAL::get_initialized_vertex_index_map(input);
  if(radii.empty()) sampler.set_radius(radius);
  else sampler.set_radius_field([&](vertex_descriptor v) { return radii[get(ivim, v)]; });
  std::map<vertex_descriptor, double> kept_radius;   // (output vertex -> its disk radius, for the Lloyd weights)
  for(vertex_descriptor v : vertices(output)) {
    if(!kept_near[get(ovim, v)]) continue;
    const Face_location loc = on_input(get(vpm, v));
    sampler.insert(loc, Sample_kind::surface, false);
    kept_radius[v] = sampler.radius_at(loc);
    ++stats.kept_samples;
  }
  const std::size_t first_new = sampler.samples().size();
  {
    auto ifim = CGAL::get_initialized_face_index_map(input);
    // (the input's faces within a spacing of a region vertex: the patch's, about)
    std::vector<Point_3> region_points;
    for(vertex_descriptor v : region) region_points.push_back(get(vpm, v));
    const Near_points<Point_3> near_region(region_points, 2 * radius);
    std::vector<char> pickable(num_faces(input), 0);
    for(face_descriptor f : faces(input)) {
      const halfedge_descriptor h = halfedge(f, input);
      const typename K::Triangle_3 t(get(in_vpm, source(h, input)), get(in_vpm, target(h, input)), get(in_vpm, target(next(h, input), input)));
      if(near_region.near_triangle(t, 2 * radius)) pickable[get(ifim, f)] = 1;
    }
    sampler.restrict_draws_to(std::move(pickable));
  }
  sampler.fill();

  // 3. the tessellation of the patch
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<TriangleMesh>>> Patch_tree;
  Patch_tree patch_tree;
  PMP::build_AABB_tree(patch, patch_tree);
  typedef Poisson_sample<TriangleMesh, Point_3> Sample;
  std::vector<Sample> samples;
  std::vector<vertex_descriptor> sample_origin;   // (the output vertex of a kept sample, else null)
  for(vertex_descriptor w : vertices(patch)) {
    const vertex_descriptor v = p2o.at(w);
    if(in_region[get(ovim, v)]) continue;
    halfedge_descriptor h = halfedge(w, patch);
    if(is_border(h, patch)) h = opposite(next(h, patch), patch);   // (a face of w: h's target is w)
    const halfedge_descriptor h0 = halfedge(face(h, patch), patch);
    Sample s;
    s.location.first = face(h, patch);
    s.location.second = {{0, 0, 0}};
    s.location.second[target(h0, patch) == w ? 1 : target(next(h0, patch), patch) == w ? 2 : 0] = 1;
    s.point = get(ppm, w);
    s.kind = Sample_kind::corner;
    s.radius = kept_radius.count(v) ? kept_radius[v] : radius;
    samples.push_back(s);
    sample_origin.push_back(v);
  }
  const std::size_t number_of_kept = samples.size();
  for(std::size_t i = first_new; i < sampler.samples().size(); ++i) {
    const auto& s = sampler.samples()[i];
    auto loc = PMP::locate_with_AABB_tree(s.point, patch_tree, patch);
    const Point_3 q = PMP::construct_point(loc, patch);
    bool drop = CGAL::to_double(CGAL::squared_distance(q, s.point)) > 0.25 * s.radius * s.radius;
    // on the patch's border (or at one of its vertices): it would split a border edge
    const halfedge_descriptor h0 = halfedge(loc.first, patch);
    const halfedge_descriptor opposite_to[3] = {next(h0, patch), next(next(h0, patch), patch), h0};
    for(int k = 0; k < 3 && !drop; ++k) {
      if(CGAL::to_double(loc.second[k]) < 1e-9 && is_border(opposite(opposite_to[k], patch), patch)) drop = true;
      if(CGAL::to_double(loc.second[k]) > 1 - 1e-9) drop = true;   // (on a patch vertex: taken by it)
    }
    if(drop) { ++stats.dropped_samples; continue; }
    Sample t;
    t.location = Face_location(loc.first, {{CGAL::to_double(loc.second[0]), CGAL::to_double(loc.second[1]), CGAL::to_double(loc.second[2])}});
    t.point = s.point;
    t.kind = Sample_kind::surface;
    t.radius = s.radius;
    samples.push_back(t);
    sample_origin.push_back(GT::null_vertex());
  }
  stats.new_samples = samples.size() - number_of_kept;
  Feature_set<TriangleMesh> patch_features;
  patch_features.eim = Edge_index_through_halfedge<TriangleMesh>(patch);
  patch_features.vim = CGAL::get_initialized_vertex_index_map(patch);
  patch_features.feature_edge.assign(num_halfedges(patch), false);
  patch_features.corner.assign(vertex_index_bound(patch), false);
  for(edge_descriptor e : edges(patch)) {
    const auto oe = edge(p2o.at(source(e, patch)), p2o.at(target(e, patch)), output);
    if(oe.second && is_feature(oe.first)) patch_features.feature_edge[get(patch_features.eim, e)] = true;
  }
  TriangleMesh remade;
  Mutual_tessellation_result<TriangleMesh> tess;
  try {
    tess = mutual_tessellation(patch, samples, patch_features, remade);
  } catch(const std::exception&) {   // (a patch the tessellation cannot take: nothing changes)
    return false;
  }

  // 4. the relaxation, the kept vertices fixed
  auto kind = get(CGAL::dynamic_vertex_property_t<int>(), remade);
  auto density = get(CGAL::dynamic_vertex_property_t<double>(), remade);
  std::map<vertex_descriptor, vertex_descriptor> to_output;   // (remade -> output, kept vertices)
  for(vertex_descriptor w : vertices(remade)) { put(kind, w, -1); put(density, w, 0.0); }
  for(const auto& rv : tess.vertices) {
    if(rv.sample == tess.no_sample) continue;
    const std::size_t i = rv.sample;
    put(kind, rv.vertex, i < number_of_kept ? kept_kind : surface);
    put(density, rv.vertex, radii.empty() ? 1.0 : 1.0 / (samples[i].radius * samples[i].radius));
    if(i < number_of_kept) to_output[rv.vertex] = sample_origin[i];
  }
  auto rpm = get(CGAL::vertex_point, remade);
  auto is_fixed = [&](vertex_descriptor w) { return get(kind, w) < 0; };
  // a feature edge: a border edge of the patch, or one of the output's feature edges between two kept vertices
  auto remade_feature = [&](edge_descriptor e) {
    if(is_border(e, remade)) return true;
    const auto a = to_output.find(source(e, remade)), b = to_output.find(target(e, remade));
    if(a != to_output.end() && b != to_output.end()) {
      const auto oe = edge(a->second, b->second, output);
      return oe.second && is_feature(oe.first);
    }
    // (an edge split by the relaxation: between feature or corner vertices, along a feature curve)
    auto on_curve = [&](vertex_descriptor w, typename std::map<vertex_descriptor, vertex_descriptor>::const_iterator it) {
      const int k = it != to_output.end() ? int(get(kind_map, it->second)) : get(kind, w);
      return k == corner || k == int(Sample_kind::feature);
    };
    if(!on_curve(source(e, remade), a) || !on_curve(target(e, remade), b)) return false;
    const Point_3 p = get(rpm, source(e, remade)), q = get(rpm, target(e, remade)), mid = CGAL::midpoint(p, q);
    return CGAL::to_double(CGAL::squared_distance(mid, relaxer.project_on_features(mid))) < 0.0025 * CGAL::to_double(CGAL::squared_distance(p, q));
  };
  auto new_vertex = [&](vertex_descriptor w, bool on_feature) { put(kind, w, int(on_feature ? Sample_kind::feature : Sample_kind::surface)); put(density, w, 0.0); };
  auto vertex_density = [&](vertex_descriptor w) {
    const double d = get(density, w);
    if(d > 0) return d;
    double sum = 0;
    int n = 0;
    for(vertex_descriptor u : CGAL::vertices_around_target(halfedge(w, remade), remade))
      if(get(density, u) > 0) { sum += get(density, u); ++n; }
    put(density, w, n ? sum / n : 1.0);
    return get(density, w);
  };
  settings.fidelity.max_deviation = 0;
  settings.sliver_collapse.merge_close_corners = false;   // (the kept vertices are no corners to merge)
  std::size_t border_before = 0;
  for(halfedge_descriptor h : halfedges(patch)) if(is_border(h, patch)) ++border_before;
  if(radii.empty()) relaxer.relax(remade, remade_feature, is_fixed, settings, new_vertex);
  else relaxer.relax(remade, remade_feature, is_fixed, settings, new_vertex, vertex_density);
  // the border must be the patch's: the same vertices (fixed), the same number of edges
  std::size_t border_after = 0;
  for(halfedge_descriptor h : halfedges(remade)) {
    if(!is_border(h, remade)) continue;
    ++border_after;
    const auto it = to_output.find(target(h, remade));
    if(it == to_output.end() || get(rpm, target(h, remade)) != get(vpm, it->second)) return false;
  }
  if(border_after != border_before) return false;

  // 5. the stitch
  std::vector<char> is_old(face_bound, 0);
  for(face_descriptor f : patch_faces) is_old[get(ofim, f)] = 1;
  std::map<vertex_descriptor, vertex_descriptor> kept_to;   // (remade -> output, kept and unmoved)
  for(const auto& kv : to_output)
    if(get(rpm, kv.first) == get(vpm, kv.second)) kept_to.insert(kv);
  std::map<vertex_descriptor, int> remade_kind;   // (read before the output's vertices go)
  for(vertex_descriptor w : vertices(remade)) {
    const int k = get(kind, w);
    remade_kind[w] = k == kept_kind ? int(get(kind_map, to_output.at(w))) : k;
  }
  for(const auto& pw : p2o) undo.kind[pw.first] = int(get(kind_map, pw.second));
  std::map<vertex_descriptor, vertex_descriptor> in_output;
  if(!replace_patch(output, kind_map, is_old, remade, kept_to, [&](vertex_descriptor w) { return remade_kind.at(w); }, undo.added, in_output))
    return false;
  // (the patch's vertices that stayed, where they are now: a kept vertex all of whose triangles
  // were replaced was added again)
  std::map<vertex_descriptor, vertex_descriptor> now;
  for(const auto& kv : to_output) now[kv.second] = in_output.at(kv.first);
  for(const auto& pw : p2o)
    if(!in_region[get(ovim, pw.second)]) undo.to_output[pw.first] = now.count(pw.second) ? now[pw.second] : pw.second;
  return true;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_LOCAL_REMAKE_H
