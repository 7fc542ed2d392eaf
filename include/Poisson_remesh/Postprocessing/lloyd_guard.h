// Poisson_remesh/Postprocessing/lloyd_guard.h
//
// (beyond the paper) The Lloyd guard. Objective: the smallest angle in the vertex's star. On thin
// parts and near graded tips a centroid projected back onto the input can line a vertex up with two
// neighbours, a little more at each round, and the later rounds do not undo that. A Lloyd move that
// would make one of the vertex's triangles sharper than `min_angle` (and sharper than it is) goes
// half the way (on the input, or on its curve); if that still does, it is refused. Constraints: it
// only shortens or refuses moves of the Lloyd step, which keeps the vertices on the input.

#ifndef POISSON_REMESH_POSTPROCESSING_LLOYD_GUARD_H
#define POISSON_REMESH_POSTPROCESSING_LLOYD_GUARD_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <CGAL/number_utils.h>

namespace Poisson_remesh {

namespace Postprocessing {

/// The Lloyd guard's settings.
struct Lloyd_guard_settings
{
  /// degrees; 0 disables the guard
  double min_angle = 25;
};

/// The guard, a callable for Relaxation::lloyd_pass().
template <class Context>
struct Lloyd_guard
{
  const Context& ctx;      ///< the input surface and the shared predicates
  Lloyd_guard_settings s;  ///< the guard's settings

  /// whether `v` may move to `target` (which it may move half the way back to where `v` is);
  /// `feature_degree`: 0 for a free vertex, 2 on a curve; `max_jump`: how far a free vertex's
  /// projection may land from the point it projects
  template <class Mesh>
  bool operator()(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, std::size_t feature_degree,
                  double max_jump, typename Context::Point_3& target) const
  {
    typedef typename Context::Point_3 Point_3;
    const double floor = s.min_angle * CGAL_PI / 180;
    if(!(floor > 0)) return true;
    const std::size_t fd = feature_degree;
    const Point_3 from = get(get(CGAL::vertex_point, m), v);
    double after = ctx.smallest_angles_around(v, m, target).first;
    if(!(after < floor)) return true;   // (most moves: the star as it is need not be measured)
    const double before = ctx.smallest_angles_around(v, m, from).first;
    if(after < before) {   // half the way, on the input (on the curve)
      const Point_3 half = CGAL::midpoint(from, target);
      target = fd == 0 ? ctx.project_on_surface(half, from) : ctx.project_on_features(half, from);
      if(fd == 0 && CGAL::to_double(CGAL::squared_distance(target, half)) > CGAL::square(max_jump)) return false;
      after = ctx.smallest_angles_around(v, m, target).first;
    }
    return !(after < floor && after < before);
  }
};

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_LLOYD_GUARD_H
