// Poisson_remesh/internal/feature_grading.h
//
// (beyond the paper) The remesher samples finer around a pointed tip -- a horn, a claw: a corner
// on at most one feature curve where the surface is too thin for the spacing -- graded back to
// the spacing, because a tip cannot be meshed well at a spacing wider than its girth.
//
// A tip kept as a vertex with k neighbours at distance d has apex angles of at most c(d) / k, c(d)
// the cone angle within d (360 degrees minus the angle defects there), and three neighbours fit
// around it only where the geodesic circle of radius d, of length L(d) = integral of c(t) dt from 0
// to d (c d on a cone, the girth on a tube), holds three disks (a flat surface has L(s) = 2 pi s at
// the spacing s = 2r; a horn tip can have a third of that).
// A needle -- a tip whose own cone angle (its vertex's angle sum) is under 90 degrees, so that no
// sampling makes its apex angles 30 -- is left alone. Where L(s) < 2 `ring_samples` r, the disk radius within `tip_reach` spacings of the tip becomes L(d) / (2
// `ring_samples`) (at least `smallest_ratio` of the radius there) -- `ring_samples` = 4 rather
// than 3, because a maximal disk set on a circle of length 6r may hold only two -- and then grows
// by at most `grading` per unit of length along the edges, up to the given radius.


#ifndef POISSON_REMESH_INTERNAL_FEATURE_GRADING_H
#define POISSON_REMESH_INTERNAL_FEATURE_GRADING_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/density_fields.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

struct Feature_grading_settings
{
  double grading = 0.25;          ///< the largest growth of the disk radius per unit of length
  double ring_samples = 4;        ///< disks that should fit on the geodesic circles around a tip
  double tip_reach = 6;           ///< spacings around a tip within which its girth is measured
  double smallest_ratio = 0.125;  ///< the disk radius is lowered to no less than this share
  double lowered_ratio = 0.95;    ///< a vertex's radius lowered by less than this share is kept
  double needle_angle = 90;       ///< degrees: a tip whose own cone angle is under this is left as is
};

/// The disk radius at each vertex (by vertex index) for the uniform `radius`, graded around the
/// pointed tips of `fs`; empty when no tip needs it. `graded_tips` is set to the number of tips
/// that lowered it.
template <class TriangleMesh, class VPM>
std::vector<double> feature_graded_radii(const TriangleMesh& tm, VPM vpm, const Feature_set<TriangleMesh>& fs,
                                         double radius, std::size_t& graded_tips,
                                         const Feature_grading_settings& settings = Feature_grading_settings())
{
  graded_tips = 0;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  if(!(radius > 0) || fs.corners.empty()) return {};
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  const std::size_t n = vertex_index_bound(tm);
  std::vector<double> radii(n, radius);
  std::vector<vertex_descriptor> lowered;   // the vertices whose radius a tip lowers

  // the vertices within reach of a tip, nearest first
  Vertex_ball<TriangleMesh, VPM> ball(tm, vpm, n);
  std::vector<std::pair<double, vertex_descriptor>> reached;
  std::vector<double> ring_lengths;
  for(vertex_descriptor v : fs.corners) {
    if(halfedge(v, tm) == GT::null_halfedge() || is_border(v, tm)) continue;
    std::size_t curves = 0;   // a tip may end one crease (a horn's ridge); more make a crease corner
    for(halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, tm), tm))
      if(fs.is_feature(edge(h, tm))) ++curves;
    if(curves > 1) continue;
    // a needle -- the cone at the tip itself under `needle_angle` -- is a corner whose own angle is
    // smaller than any finer sampling could help (the star's apex angles are c / 3 at any scale)
    if(2 * CGAL_PI - angle_defect(v, tm, vpm) < settings.needle_angle * CGAL_PI / 180) continue;
    // L(d) at each vertex within reach, the cone angle piecewise constant between them
    const double s = 2 * radius;
    reached.clear();
    ball.visit(v, settings.tip_reach * s, [&](vertex_descriptor w, double d2) { reached.push_back({std::sqrt(d2), w}); });
    std::sort(reached.begin(), reached.end(), [&](const auto& a, const auto& b) {
      return a.first < b.first || (a.first == b.first && get(vim, a.second) < get(vim, b.second));
    });
    double cone = 2 * CGAL_PI, length = 0, before = 0, at_spacing = -1;
    ring_lengths.clear();
    for(const auto& [d, w] : reached) {
      if(at_spacing < 0 && d > s) at_spacing = length + cone * (s - before);
      length += cone * (d - before);
      before = d;
      ring_lengths.push_back(length);
      cone = std::max(0.0, cone - angle_defect(w, tm, vpm));
    }
    if(at_spacing < 0) at_spacing = length + cone * (s - before);
    if(at_spacing >= 2 * settings.ring_samples * radius) continue;   // the disks fit around v at the spacing
    bool graded = false;
    for(std::size_t i = 0; i < reached.size(); ++i) {
      const vertex_descriptor w = reached[i].second;
      const double target = std::max(settings.smallest_ratio * radius, ring_lengths[i] / (2 * settings.ring_samples));
      double& x = radii[get(vim, w)];
      if(target < settings.lowered_ratio * x) { x = target; lowered.push_back(w); graded = true; }
    }
    if(graded) ++graded_tips;
  }
  if(lowered.empty()) return {};

  // from those, the radius grows by at most `grading` per unit of length along the edges
  // (Dijkstra): a tip's girth may widen faster than the mesh can grade
  Radius_queue queue;
  for(vertex_descriptor v : lowered) queue.push({radii[get(vim, v)], std::size_t(get(vim, v))});
  limit_radius_growth(radii, edge_adjacency(tm, vpm), settings.grading, queue);
  return radii;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_FEATURE_GRADING_H
