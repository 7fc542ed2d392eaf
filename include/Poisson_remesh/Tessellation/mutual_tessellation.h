// Poisson_remesh/Tessellation/mutual_tessellation.h
//
// Entry point: mutual_tessellation(input, samples, features, output, np, settings) -- paper §6.1,
// "Mesh Reconstruction From Sampling Point Set", the mutual tessellation of Turk (1992): the
// connectivity of the sample set is recovered from the input's, so the topology is kept.
//   1. insert_samples: the input is copied and every sample is inserted by splitting the triangle
//      it lies in (or the edge it lies on); a corner sample *is* an input vertex and only marks it;
//   2. flip_edges: edges are flipped when the smallest angle of their two triangles grows, under
//      the paper's guards (new edge not present, normal change < beta, dihedral change < gamma,
//      feature edges never flipped);
//   3. remove_original_vertices: every original vertex is removed; its one-ring is laid out by the
//      exponential map of §6.1 (Floater 1997: radial lengths kept, angles scaled to sum to 2 pi)
//      and the hole is re-triangulated by a 2D constrained Delaunay triangulation of the ring
//      polygon; a removal that would create an edge already in the mesh (the paper's check against
//      joining two sheets, Fig. 8, is the 3-ring; any existing edge is refused here) is refused.
//      An original vertex on a feature curve is removed so that its two neighbours along the curve
//      are joined by a feature edge (each side of the curve is laid out on a half disk and
//      triangulated alone; a border vertex likewise, with its one half disk). Passes of removal
//      and flips alternate until nothing more goes; the vertices left are reported, never
//      silently kept.
// Beyond the paper (each a documented setting or a fallback; internal/Tessellator.h):
//   - when the CDT of the layout would create an existing edge or fold a triangle over, the best
//     of all triangulations of the ring polygon that does neither is used (dynamic programming);
//   - when a pass removes nothing, the fold-over guard is raised once (a last resort, mostly at
//     the tips of thin parts);
//   - a border vertex whose star is a strip one face wide is collapsed onto a border neighbour;
//   - finally, edges of self-intersecting faces are flipped when that removes crossings.
// The output's vertices are the samples (plus the reported leftovers), each with its sample
// index and its location on the input.
//
// Models: works on any triangle mesh modelling MutableFaceGraph (Surface_mesh, Polyhedron_3 with
// ids); the output is a compact copy of the working mesh (copy_face_graph).

#ifndef POISSON_REMESH_TESSELLATION_MUTUAL_TESSELLATION_H
#define POISSON_REMESH_TESSELLATION_MUTUAL_TESSELLATION_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Sampling/Boundary_sampler.h>
#include <Poisson_remesh/parameters.h>

#include <Poisson_remesh/Tessellation/internal/Tessellator.h>

#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <boost/iterator/function_output_iterator.hpp>

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

/// The guards of the tessellation (angles in degrees).
struct Mutual_tessellation_settings
{
  /// beta of §6.1: a flip is refused when a new triangle's normal is more than beta away from
  /// either old triangle's normal. 30 degrees lets flips run freely across the smooth parts (a
  /// flip across an edge of dihedral angle delta changes normals by about delta) while a fold
  /// (a new triangle turned over, 180 degrees) or a flip across a strong crease is refused.
  double beta = 30;
  /// gamma of §6.1: a flip is refused when the dihedral angle at the edge changes by more than
  /// gamma; with beta, it keeps flips from pinching thin parts (tails, legs).
  double gamma = 30;
  /// a removal is refused when a new triangle's normal is more than this away from the mean
  /// normal of the removed vertex's star (of its side, on a feature curve): no fold-overs.
  /// (a larger bound leaves fewer input vertices but more folds)
  double max_removal_normal_deviation = 60;
  /// when a pass removes nothing, the bound above is raised to this one for the vertices left
  /// (mostly tips of thin parts, where a kept original vertex causes more self-intersections than
  /// a steeper triangle does); set it equal to max_removal_normal_deviation to disable the
  /// escalation.
  double max_removal_normal_deviation_last_resort = 120;
  /// after the paper's steps, flip edges of self-intersecting faces when that removes crossings
  /// (thin parts sampled with few samples across; not in the paper).
  bool repair_self_intersections = true;
  /// passes of removal (each followed by flips) before the leftovers are reported.
  std::size_t max_removal_passes = 30;
  /// (beyond the paper) an original vertex the passes could not remove is collapsed onto one of
  /// its sample neighbours (along its feature curve if it is on one) when the link condition
  /// holds (the topology is kept) and no triangle turns by more than the last-resort deviation:
  /// typically the ring of a sharp tip, whose removal folds the star
  bool collapse_leftovers = true;
};

/// What the tessellation did, and what each output vertex is.
template <class TriangleMesh>
struct Mutual_tessellation_result
{
  /// the mesh's vertex descriptor
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  /// a point of the input: a face and barycentric coordinates
  typedef CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> Face_location;
  /// the `sample` of an output vertex that is no sample (a leftover input vertex)
  static constexpr std::size_t no_sample = std::size_t(-1);

  /// One output vertex: the sample it is (no_sample for a leftover original vertex) and where it
  /// lies on the input (the sample's location, or the input vertex's).
  struct Vertex
  {
    vertex_descriptor vertex;            ///< in `output`
    std::size_t sample = no_sample;      ///< index in the sample range
    Face_location location;              ///< on `input`
  };

  std::vector<Vertex> vertices;                     ///< one per output vertex, in vertices(output) order
  std::vector<vertex_descriptor> sample_vertices;   ///< output vertex of sample i
  std::vector<vertex_descriptor> leftover_vertices; ///< input vertices that could not be removed
  std::size_t number_of_inserted_samples = 0;       ///< samples inserted by a split
  std::size_t number_of_vertex_samples = 0;         ///< samples that were an input vertex
  /// (i, j): sample i fell on the vertex of sample j and was merged into it (only seen inside
  /// nearly zero-area input faces); sample_vertices[i] is that of j
  std::vector<std::pair<std::size_t, std::size_t>> merged_samples;
  std::size_t number_of_flips = 0;                  ///< flips that raised the smallest angle (§6.1)
  std::size_t number_of_repair_flips = 0;           ///< flips that removed self-intersections (last step)
  std::size_t number_of_removed_vertices = 0;       ///< input vertices removed
  std::size_t number_of_removal_passes = 0;         ///< passes of removals and flips
  std::size_t number_of_collapsed_vertices = 0;     ///< original vertices removed by a collapse (fallback)
  std::size_t number_of_refused_removals = 0;       ///< attempts refused (a vertex may be tried again)
  /// why the last pass (and the retry after the repair) refused the leftovers: a star that is
  /// not a simple (half) disk (repeated ring vertex, feature degree not 2, two border fans), the
  /// feature edge already there, a pocket (the ring triangle already a face), no triangulation
  /// of a side without an existing edge or a fold-over.
  /// @{
  std::size_t refused_star = 0, refused_feature_edge = 0, refused_pocket = 0, refused_triangulation = 0;
  /// @}
};


namespace internal {

// Step 1 of §6.1: copies `input` into T.tm and inserts every sample by splitting the triangle it
// lies in, or the edge it lies on (both triangles); a sample on an input vertex marks it. Every
// input face keeps the list of the triangles it is split into ("sub-faces", located in the input
// face's plane). Returns the input vertices by index (for the locations of leftovers).
template <class TriangleMesh, class InputVPM, class SampleRange, class Tess, class Result>
std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>
insert_samples(const TriangleMesh& input, InputVPM in_vpm, const SampleRange& samples,
               const Feature_set<TriangleMesh>& features, Tess& T, Result& result)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename Tess::Point_3 Point_3;
  TriangleMesh& work = T.tm;
  auto vpm = T.vpm;

  auto vim = CGAL::get_initialized_vertex_index_map(input);
  auto fim = CGAL::get_initialized_face_index_map(input);
  std::vector<vertex_descriptor> v2v(num_vertices(input), GT::null_vertex()), input_vertex(num_vertices(input), GT::null_vertex());
  std::vector<face_descriptor> f2f(num_faces(input));
  std::vector<std::pair<halfedge_descriptor, halfedge_descriptor>> h2h;
  CGAL::copy_face_graph(input, work,
    CGAL::parameters::vertex_point_map(in_vpm)
      .vertex_to_vertex_output_iterator(boost::make_function_output_iterator(
        [&](const std::pair<vertex_descriptor, vertex_descriptor>& p) { v2v[get(vim, p.first)] = p.second; input_vertex[get(vim, p.first)] = p.first; }))
      .face_to_face_output_iterator(boost::make_function_output_iterator(
        [&](const std::pair<face_descriptor, face_descriptor>& p) { f2f[get(fim, p.first)] = p.second; }))
      .halfedge_to_halfedge_output_iterator(std::back_inserter(h2h)),
    CGAL::parameters::vertex_point_map(vpm));
  // (isolated input vertices are not copied: they are no part of the surface)
  for(auto v : vertices(input))
    if(v2v[get(vim, v)] != GT::null_vertex()) put(T.origin, v2v[get(vim, v)], -long(get(vim, v)) - 1);
  for(auto e : edges(work)) put(T.feature, e, false);
  for(const auto& hh : h2h) if(features.is_feature(edge(hh.first, input))) put(T.feature, edge(hh.second, work), true);
  std::vector<std::vector<face_descriptor>> sub_faces(num_faces(input));
  for(auto f : faces(input)) {
    const std::size_t i = get(fim, f);
    put(T.owner, f2f[i], i);
    sub_faces[i].push_back(f2f[i]);
  }

  const std::size_t ns = std::size_t(std::distance(samples.begin(), samples.end()));
  result.sample_vertices.assign(ns, GT::null_vertex());
  // A sample that lands on the vertex of an earlier one (only inside (nearly) zero-area input
  // faces, where the geodesic separation has no planar meaning) is merged into it and counted.
  auto mark = [&](vertex_descriptor w, std::size_t i) {
    result.sample_vertices[i] = w;
    if(T.is_sample(w)) {
      result.merged_samples.emplace_back(i, std::size_t(get(T.origin, w)));
      return false;
    }
    put(T.origin, w, long(i));
    return true;
  };
  auto add_sub_face = [&](face_descriptor f, std::size_t own) {
    put(T.owner, f, own);
    sub_faces[own].push_back(f);
  };
  // splits face(h)'s triangles after the split of one of its edges: h points to the new vertex
  auto close_split = [&](halfedge_descriptor h) {
    if(is_border(h, work)) return;
    const std::size_t own = get(T.owner, face(h, work));
    const halfedge_descriptor hn = CGAL::Euler::split_face(h, next(next(h, work), work), work);
    put(T.feature, edge(hn, work), false);
    add_sub_face(face(opposite(hn, work), work), own);
  };

  std::size_t si = 0;
  for(const auto& s : samples) {
    const std::size_t i = si++;
    const face_descriptor fin = s.location.first;
    const auto& b = s.location.second;
    const halfedge_descriptor hin = halfedge(fin, input);
    const vertex_descriptor fv[3] = {source(hin, input), target(hin, input), target(next(hin, input), input)};
    const int kmax = int(std::max_element(b.begin(), b.end()) - b.begin());
    if(b[kmax] >= 1 - 1e-12) {   // on an input vertex: that vertex is the sample
      mark(v2v[get(vim, fv[kmax])], i);
      ++result.number_of_vertex_samples;
      continue;
    }
    // 2D frame of the input face: sub-faces lie in its plane
    const internal::Vec3 o = T.xyz(v2v[get(vim, fv[0])]);
    const internal::Vec3 e1r = internal::sub3(T.xyz(v2v[get(vim, fv[1])]), o);
    const internal::Vec3 nrm = internal::cross3(e1r, internal::sub3(T.xyz(v2v[get(vim, fv[2])]), o));
    const double l1 = internal::norm3(e1r), ln = internal::norm3(nrm);
    const internal::Vec3 e1 = {e1r[0] / l1, e1r[1] / l1, e1r[2] / l1};
    const internal::Vec3 e2r = internal::cross3({nrm[0] / ln, nrm[1] / ln, nrm[2] / ln}, e1);
    auto to2 = [&](const internal::Vec3& p) {
      const internal::Vec3 d = internal::sub3(p, o);
      return std::array<double, 2>{internal::dot3(d, e1), internal::dot3(d, e2r)};
    };
    const Point_3 p = s.point;
    const internal::Vec3 p3 = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    const auto q = to2(p3);
    // the sub-face containing p: largest smallest barycentric coordinate
    double best = -std::numeric_limits<double>::infinity();
    halfedge_descriptor best_h = GT::null_halfedge();
    std::array<double, 3> best_b = {0, 0, 0};
    for(face_descriptor f : sub_faces[get(fim, fin)]) {
      const halfedge_descriptor h = halfedge(f, work);
      const auto a = to2(T.xyz(source(h, work))), bb = to2(T.xyz(target(h, work))), c = to2(T.xyz(target(next(h, work), work)));
      const double area = (bb[0] - a[0]) * (c[1] - a[1]) - (bb[1] - a[1]) * (c[0] - a[0]);
      if(!(area > 0)) continue;
      auto cr = [](const std::array<double, 2>& u, const std::array<double, 2>& v, const std::array<double, 2>& w) {
        return (v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0]);
      };
      // coordinate of vertex k = area of the triangle opposite to it
      const std::array<double, 3> l = {cr(bb, c, q) / area, cr(c, a, q) / area, cr(a, bb, q) / area};
      const double lmin = std::min({l[0], l[1], l[2]});
      if(lmin > best) { best = lmin; best_h = h; best_b = l; }
    }
    if(best_h == GT::null_halfedge()) {
      // no sub-face with an area in the face's plane: the input face has (nearly) none, and the
      // sample is taken by the closest vertex of its sub-faces (it lies within the face's size)
      vertex_descriptor w = GT::null_vertex();
      double dmin = std::numeric_limits<double>::infinity();
      for(face_descriptor f : sub_faces[get(fim, fin)])
        for(vertex_descriptor x : CGAL::vertices_around_face(halfedge(f, work), work)) {
          const double d = internal::norm3(internal::sub3(T.xyz(x), p3));
          if(d < dmin) { dmin = d; w = x; }
        }
      if(w == GT::null_vertex()) throw std::logic_error("mutual_tessellation: a sample's face has no sub-face");
      mark(w, i);
      ++result.number_of_vertex_samples;
      continue;
    }
    const double on_edge = 1e-10;
    int small = 0, kmin = 0, kbig = 0;
    for(int k = 0; k < 3; ++k) {
      if(best_b[k] < on_edge) ++small;
      if(best_b[k] < best_b[kmin]) kmin = k;
      if(best_b[k] > best_b[kbig]) kbig = k;
    }
    // vertex k of the sub-face: 0 = source(best_h), 1 = target(best_h), 2 = target(next(best_h))
    const halfedge_descriptor hk[3] = {prev(best_h, work), best_h, next(best_h, work)}; // target = vertex k
    if(small >= 2) {   // on an existing vertex of the tessellation
      if(mark(target(hk[kbig], work), i)) put(vpm, target(hk[kbig], work), p);
      ++result.number_of_vertex_samples;
      continue;
    }
    vertex_descriptor w;
    if(small == 1) {   // on the edge opposite vertex kmin: split it and both triangles
      const halfedge_descriptor h = hk[(kmin + 2) % 3];   // from vertex kmin+1 to kmin+2
      const bool was_feature = T.is_feature(h);
      const halfedge_descriptor hnew = CGAL::Euler::split_edge(h, work);   // target(hnew) is new
      w = target(hnew, work);
      put(T.feature, edge(hnew, work), was_feature);
      close_split(hnew);
      close_split(opposite(h, work));
    } else {           // inside the triangle
      const face_descriptor f = face(best_h, work);
      const std::size_t own = get(T.owner, f);
      const halfedge_descriptor hnew = CGAL::Euler::add_center_vertex(best_h, work);
      w = target(hnew, work);
      for(halfedge_descriptor g : CGAL::halfedges_around_target(hnew, work)) {
        put(T.feature, edge(g, work), false);
        if(!is_border(g, work) && face(g, work) != f) add_sub_face(face(g, work), own);
      }
    }
    put(vpm, w, p);
    put(T.origin, w, std::numeric_limits<long>::min());   // new: not yet anything
    mark(w, i);
    ++result.number_of_inserted_samples;
  }
  for(std::size_t i = 0; i < ns; ++i)
    if(result.sample_vertices[i] == GT::null_vertex()) throw std::logic_error("mutual_tessellation: a sample was not inserted");

  return input_vertex;
}

// Steps 2 and 3 of §6.1: flips, then passes of removal of the original vertices with flips in
// between, until a pass removes nothing (the fold-over guard is raised once before giving up);
// then the repair flips. Fills the counters of `result`.
template <class ConcurrencyTag, class Tess, class Settings, class Result>
void remove_original_vertices(Tess& T, const Settings& settings, Result& result)
{
  typedef typename Tess::vertex_descriptor vertex_descriptor;
  auto& work = T.tm;

  T.flip_edges();
  std::vector<vertex_descriptor> originals;
  for(auto v : vertices(work)) if(!T.is_sample(v)) originals.push_back(v);
  for(std::size_t pass = 0; pass < settings.max_removal_passes && !originals.empty(); ++pass) {
    ++result.number_of_removal_passes;
    std::vector<vertex_descriptor> left;
    T.refusals = {{0, 0, 0, 0}};
    for(vertex_descriptor v : originals) {
      if(T.try_remove(v)) ++result.number_of_removed_vertices;
      else { left.push_back(v); ++result.number_of_refused_removals; }
    }
    const bool progress = left.size() < originals.size();
    originals.swap(left);
    const std::size_t flipped = T.flip_changed_edges();
    if(!progress && flipped == 0) {
      if(T.last_resort || settings.max_removal_normal_deviation_last_resort <= settings.max_removal_normal_deviation) break;
      T.last_resort = true;
    }
  }
  T.flip_changed_edges();
  result.number_of_flips = T.flips;
  if(settings.repair_self_intersections) {
    result.number_of_repair_flips = T.template repair_self_intersections<ConcurrencyTag>();
    // the repair changed some rings: one more chance for the vertices left, then repair again
    if(result.number_of_repair_flips > 0 && !originals.empty()) {
      std::vector<vertex_descriptor> left;
      for(vertex_descriptor v : originals) {
        if(T.try_remove(v)) ++result.number_of_removed_vertices;
        else left.push_back(v);
      }
      if(left.size() < originals.size()) result.number_of_repair_flips += T.template repair_self_intersections<ConcurrencyTag>();
      originals.swap(left);
    }
  }
  if(settings.collapse_leftovers && !originals.empty()) {
    std::vector<vertex_descriptor> left;
    for(vertex_descriptor v : originals) {
      if(T.try_collapse(v)) { ++result.number_of_removed_vertices; ++result.number_of_collapsed_vertices; }
      else left.push_back(v);
    }
    originals.swap(left);
    if(result.number_of_collapsed_vertices > 0) {
      T.flip_changed_edges();
      result.number_of_flips = T.flips;
      if(settings.repair_self_intersections) result.number_of_repair_flips += T.template repair_self_intersections<ConcurrencyTag>();
    }
  }
  result.refused_star = T.refusals[0];
  result.refused_feature_edge = T.refusals[1];
  result.refused_pocket = T.refusals[2];
  result.refused_triangulation = T.refusals[3];

}

} // namespace internal

/*!
  builds the mutual tessellation (paper §6.1) of `input` and the `samples` (a range of
  Poisson_sample: location on `input`, point, kind), written to `output` (cleared first): a
  triangle mesh whose vertices are the samples, with the input's topology, the corners kept and
  consecutive feature samples joined along the feature curves of `features` (detect_features on
  `input`). Vertices that could not be removed are listed in the result, never silently kept.

  Named parameters: `vertex_point_map` of `input` (CGAL; default the internal one). The output
  uses its internal point map. The guards are in `settings` (see Mutual_tessellation_settings).
  `ConcurrencyTag`: CGAL::Sequential_tag (the default) or CGAL::Parallel_tag, which runs the
  whole-mesh crossing searches of the repair flips on TBB's threads (the same result).
*/
template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleMesh, class SampleRange, class NamedParameters = parameters::Default_named_parameters>
Mutual_tessellation_result<TriangleMesh>
mutual_tessellation(const TriangleMesh& input, const SampleRange& samples, const Feature_set<TriangleMesh>& features,
                    TriangleMesh& output, const NamedParameters& np = parameters::default_values(),
                    const Mutual_tessellation_settings& settings = Mutual_tessellation_settings())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  typedef Mutual_tessellation_result<TriangleMesh> Result;

  auto in_vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, input));
  TriangleMesh work;
  auto vpm = get(CGAL::vertex_point, work);
  internal::Tessellator<TriangleMesh, decltype(vpm), Mutual_tessellation_settings> T(work, vpm, settings);
  Result result;

  // §6.1, step by step
  const std::vector<vertex_descriptor> input_vertex = internal::insert_samples(input, in_vpm, samples, features, T, result);
  internal::remove_original_vertices<ConcurrencyTag>(T, settings, result);

  // ---- the output: a compact copy, and what each vertex is ------------------------------------------
  clear(output);
  std::vector<std::pair<vertex_descriptor, vertex_descriptor>> w2o;
  CGAL::copy_face_graph(work, output, CGAL::parameters::vertex_to_vertex_output_iterator(std::back_inserter(w2o)));
  for(const auto& pr : w2o) {
    const long org = get(T.origin, pr.first);
    typename Result::Vertex rv;
    rv.vertex = pr.second;
    if(org >= 0) {
      rv.sample = std::size_t(org);
      auto it = samples.begin();
      std::advance(it, org);
      rv.location = it->location;
      result.sample_vertices[std::size_t(org)] = pr.second;
    } else {
      const vertex_descriptor vin = input_vertex[std::size_t(-org - 1)];
      result.leftover_vertices.push_back(vin);
      rv.location = location_on_halfedge(halfedge(vin, input), 1.0, input);
    }
    result.vertices.push_back(rv);
  }
  for(const auto& m : result.merged_samples) result.sample_vertices[m.first] = result.sample_vertices[m.second];
  return result;
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_TESSELLATION_MUTUAL_TESSELLATION_H
