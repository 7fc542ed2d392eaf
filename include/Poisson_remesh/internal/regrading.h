// Poisson_remesh/internal/regrading.h
//
// (beyond the paper) A remesh whose result still cuts itself, or keeps a smallest angle under 30
// degrees away from the input's sharp corners, is made again with the sampling finer around the
// places at fault, graded back to the spacing: a posteriori grading, used by poisson_remesh()
// (`regrading_attempts`, default 6). A remesh that is fine the first time is not touched.
//
// Why: an input crumpled below the spacing -- a surface stacked from slices, whose seams are pleats
// folded back over it -- has places where no placement of the samples on the input at the
// spacing avoids folded triangles: the tessellation's result already crosses itself there, and no
// move of a vertex to an input point within its star's edge length undoes it. Where the samples
// are finer than the pleats, the triangles follow them.
//
// When: the output has face pairs that cut each other away from the input's own crossings (both
// centroids within two mean edge lengths of the output of an input triangle that cuts another, as
// the quality report counts them), or its smallest angle away from the input's sharp corners (the
// quality report's min_angle_away_from_sharp_corners) is under `min_angle`.
// Where: the centroids of those crossing faces and of the triangles under `min_angle` none of
// whose vertices is fixed. Each input vertex within `reach` r of such a place (r: the uniform
// disk radius, or the median one) gets the disk radius `first_ratio` r, or half its radius when
// that is `first_ratio` r or less already (a place met again, or near a graded tip), no less than
// `smallest_ratio` r; then the radius grows back by at most `grading` per unit of length (as
// around the tips of internal/feature_grading.h).
// Also, from the second attempt on: each attempt samples with its own seed (random_seed + k
// `seed_step`: a triangle left sharp at a fixed vertex is a matter of the draw), and the corners
// left on no feature edge of the output (their curves dropped as crowded, or unsampled; not the
// pointed tips) and the input vertices the tessellation could not remove are free to move.
// The best attempt is kept: fewest crossings, then the largest smallest angle (up to the floor),
// then the fewest triangles under `min_angle` at no pointed tip.
// No remake follows an attempt with no place to sample finer that left the very same fault as
// the attempt before it (Regrading_places::remake_wanted): a fault that a new draw reproduces
// does not depend on the draw.
// Nor does one follow `max_attempts_without_gain` attempts in a row that did not beat the best
// attempt so far, when the best cuts itself nowhere (remakes_stop_for_want_of_gain): a sharp
// triangle that finer radii and new draws have not mended twice is seldom mended by the next
// remakes, each of which costs a whole remesh; a crossing is worth every attempt.


#ifndef POISSON_REMESH_INTERNAL_REGRADING_H
#define POISSON_REMESH_INTERNAL_REGRADING_H

#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/Relaxation/Lloyd_relaxer.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/internal/near_points.h>
#include <Poisson_remesh/internal/parallel.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/Kernel_traits.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <optional>
#include <vector>

namespace Poisson_remesh {
namespace internal {

struct Regrading_settings
{
  double min_angle = 30;        ///< degrees: a triangle of free vertices under this is a place to regrade
  double reach = 2;             ///< disk radii around a place within which the input's vertices are lowered
  double first_ratio = 0.25;    ///< the radius there the first time (times r)
  double smallest_ratio = 1.0 / 16;   ///< the radius is never lowered under this (times r)
  double grading = 0.25;        ///< the largest growth of the radius per unit of length
  unsigned int seed_step = 1000003;   ///< attempt k samples with the seed random_seed + k seed_step
  /// no remake after an attempt with more than this times the first attempt's vertices: finer
  /// radii around a few places at fault are to mend them, not to turn into a much finer mesh
  /// (where nearly every place is at fault, each remake would make the whole mesh finer)
  double max_growth = 1.5;
  /// no remake after this many attempts in a row that did not beat the best one so far, when the
  /// best cuts itself nowhere: finer radii and new draws that have not mended a sharp triangle
  /// that many times are not worth the time of the others (0: no such limit)
  unsigned int max_attempts_without_gain = 2;
};

/// The places of a remesh to regrade: see the file's comment. `is_fixed(v)` tells the output's
/// vertices that may not move, `is_tip(v)` the pointed tips among them (their triangles are no
/// places). The input's crossing triangles are looked for once, and only when the output crosses
/// itself (`input_crossings` keeps them between calls).
template <class Point_3>
struct Regrading_places
{
  std::vector<Point_3> places;
  /// the centroids of the triangles under the angle with a fixed vertex (at no pointed tip): no
  /// place to sample finer, but one to draw anew (internal/local_remake.h)
  std::vector<Point_3> fixed_places;
  std::size_t crossing_pairs = 0;    ///< face pairs of the output that cut each other, away from the input's own
  std::size_t sharp_free = 0;        ///< triangles under the angle none of whose vertices is fixed
  std::size_t sharp = 0;             ///< triangles under the angle at no pointed tip (fixed vertices or not)
  /// the smallest angle (degrees) away from the input's corners whose own angle is smaller, as
  /// the quality report measures it (min_angle_away_from_sharp_corners)
  double min_angle_away = 180;
  double floor = 30;
  /// whether the remesh is at fault (it cuts itself, or keeps an angle under the floor)
  bool wanted() const { return crossing_pairs > 0 || min_angle_away < floor; }
  /// whether this attempt, at fault, is worth making again, given the attempt before it (none:
  /// this is the first). A remake samples finer around the places; with no place (no crossing,
  /// every triangle under the floor at a fixed vertex) it keeps the radii and is a new draw
  /// alone. A first draw may be unlucky, so that remake is made (it also frees the corners left
  /// on no feature edge and the input vertices the tessellation kept); but when the attempt
  /// before this one left the very same fault (no crossing and the same smallest angle), the
  /// fault does not depend on the draw, and no remake follows.
  bool remake_wanted(const Regrading_places* before) const
  {
    if(!wanted()) return false;
    if(!places.empty() || before == nullptr) return true;
    return !(crossing_pairs == 0 && before->crossing_pairs == 0 && min_angle_away == before->min_angle_away);
  }
  /// lexicographic: fewer crossings, then the smallest angle away from corners (up to the floor),
  /// then fewer sharp triangles (at no tip: counted alike in every attempt, whatever is fixed)
  bool better_than(const Regrading_places& o) const
  {
    if(crossing_pairs != o.crossing_pairs) return crossing_pairs < o.crossing_pairs;
    const double a = std::min(min_angle_away, floor), b = std::min(o.min_angle_away, o.floor);
    if(a != b) return a > b;
    return sharp < o.sharp;
  }
};

/// Whether the remakes stop for want of gain: `without_gain` attempts in a row have not beaten
/// `best`, the best attempt so far, which cuts itself nowhere (see the file's comment).
template <class Point_3>
bool remakes_stop_for_want_of_gain(unsigned int without_gain, const Regrading_places<Point_3>& best, const Regrading_settings& s)
{
  return s.max_attempts_without_gain > 0 && without_gain >= s.max_attempts_without_gain && best.crossing_pairs == 0;
}

template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleMesh, class InputMesh, class IsFixed, class IsTip,
          class Point_3 = typename boost::property_traits<typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type>::value_type>
Regrading_places<Point_3>
regrading_places(const TriangleMesh& tm, const InputMesh& input, IsFixed is_fixed, IsTip is_tip,
                 std::optional<Reference_crossings<InputMesh>>& input_crossings,
                 const Regrading_settings& s = Regrading_settings())
{
  Regrading_places<Point_3> r;
  r.floor = s.min_angle;
  auto vpm = get(CGAL::vertex_point, tm);
  auto centroid_of = [&](typename boost::graph_traits<TriangleMesh>::face_descriptor f) {
    const auto h = halfedge(f, tm);
    return CGAL::centroid(get(vpm, source(h, tm)), get(vpm, target(h, tm)), get(vpm, target(next(h, tm), tm)));
  };
  // the smallest angle away from sharp corners and the crossing pairs, at once with
  // CGAL::Parallel_tag (both only read the meshes; the first adds its maps to the input alone, the
  // second to tm alone, whose point map is read above)
  Face_pairs<TriangleMesh> pairs;
  for_each_index<ConcurrencyTag>(2, [&](std::size_t task) {
    if(task == 1) { pairs = intersecting_pairs<ConcurrencyTag>(tm); return; }
    Quality_report q;
    fill_min_angle_away_from_sharp_corners(tm, vpm, input, 60.0, q);
    if(q.min_angle_away_from_sharp_corners) r.min_angle_away = *q.min_angle_away_from_sharp_corners;
  }, 1);
  if(!pairs.empty()) {
    if(!input_crossings) input_crossings.emplace(input);
    const double reach = 2 * mean_edge_length(tm, vpm);   // (as the quality report's)
    for(const auto& fp : pairs) {
      if(input_crossings->near(tm, vpm, fp.first, reach) && input_crossings->near(tm, vpm, fp.second, reach)) continue;
      ++r.crossing_pairs;
      r.places.push_back(centroid_of(fp.first));
      r.places.push_back(centroid_of(fp.second));
    }
  }
  const double limit = std::cos(s.min_angle * CGAL_PI / 180);
  for(auto f : faces(tm)) {
    bool fixed = false, tip = false;
    for(auto v : CGAL::vertices_around_face(halfedge(f, tm), tm)) {
      if(is_fixed(v)) fixed = true;
      if(is_tip(v)) tip = true;
    }
    if(tip) continue;
    const auto h = halfedge(f, tm);
    const Point_3 p[3] = {get(vpm, source(h, tm)), get(vpm, target(h, tm)), get(vpm, target(next(h, tm), tm))};
    bool sharp = false;
    for(int k = 0; k < 3 && !sharp; ++k) {
      const auto u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
      const double lu = CGAL::to_double(u.squared_length()), lw = CGAL::to_double(w.squared_length());
      // (the angle at p[k] under min_angle: its cosine over cos(min_angle); a degenerate triangle is sharp)
      const double uw = CGAL::to_double(u * w);
      sharp = !(lu > 0 && lw > 0) || (uw > 0 && uw * uw > limit * limit * lu * lw);
    }
    if(!sharp) continue;
    ++r.sharp;
    if(fixed) { r.fixed_places.push_back(centroid_of(f)); continue; }
    ++r.sharp_free;
    r.places.push_back(centroid_of(f));
  }
  return r;
}

// "Within d of one of the points" for a point set (cells of side `cell`, d <= cell).
// whether corner v of m need not stay fixed in a remake: it lies on no feature or border edge
// (its curves were dropped or left unsampled) and is no pointed tip
template <class Mesh, class IsTip, class IsFeature>
bool is_loose_corner(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, IsTip is_tip, IsFeature is_feature)
{
  if(is_tip(v)) return false;
  for(auto h : CGAL::halfedges_around_target(v, m))
    if(is_border(edge(h, m), m) || is_feature(edge(h, m))) return false;
  return true;
}

/// Lowers `radii` (by vertex index of `input`; filled with `radius` when empty) around `places`:
/// see the file's comment.
template <class InputMesh, class VPM, class Point_3>
void regrade_radii(const InputMesh& input, VPM vpm, double radius, const std::vector<Point_3>& places, std::vector<double>& radii,
                   const Regrading_settings& s = Regrading_settings())
{
  auto vim = CGAL::get_initialized_vertex_index_map(input);
  if(radii.empty()) radii.assign(vertex_index_bound(input), radius);
  const double reach = s.reach * radius, reach2 = reach * reach;
  const double first = s.first_ratio * radius, smallest = s.smallest_ratio * radius;
  // (a folded input may have thousands of places)
  const Near_points<Point_3> near_places(places, reach);
  auto near = [&](const Point_3& p) { return near_places.squared_distance(p) < reach2; };
  Radius_queue queue;
  for(auto v : vertices(input)) {
    if(!near(get(vpm, v))) continue;
    double& x = radii[get(vim, v)];
    const double lowered = x > first ? first : std::max(smallest, 0.5 * x);
    if(lowered < x) { x = lowered; queue.push({x, std::size_t(get(vim, v))}); }
  }
  limit_radius_growth(radii, edge_adjacency(input, vpm), s.grading, queue);
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_REGRADING_H
