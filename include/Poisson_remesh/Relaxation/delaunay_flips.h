// Poisson_remesh/Relaxation/delaunay_flips.h
//
// The 3D Delaunay flips of paper §6.2: a non-feature edge whose two opposite angles sum to more
// than 180 degrees is flipped when the new edge does not exist yet and the two new triangles stay
// close to the surface (their normals within `max_normal_change` degrees of the old triangles'
// area-weighted normal). Rounds until no flip is left (at most 4).

#ifndef POISSON_REMESH_RELAXATION_DELAUNAY_FLIPS_H
#define POISSON_REMESH_RELAXATION_DELAUNAY_FLIPS_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <cmath>

namespace Poisson_remesh {

namespace Relaxation {

/// Delaunay flips of `m` (feature and border edges are never flipped). With `keep_regularity`
/// (Postprocessing/regularity_flips.h), a flip that makes more irregular vertices is made only at a
/// triangle sharper than `sliver_angle` (degrees) whose smallest angle it raises.
template <class Context, class Mesh, class IsFeatureEdge>
void delaunay_flips(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, double max_normal_change, double sliver_angle,
                    Relaxation_statistics& stats, bool keep_regularity = false)
{
  typedef typename Context::Point_3 Point_3;
  const double cos_max = std::cos(max_normal_change * CGAL_PI / 180);
  const double sliver = sliver_angle * CGAL_PI / 180;
  for(int round = 0; round < 4; ++round) {
    std::size_t flips = 0;
    for(auto e : edges(m)) {
      if(is_feature(e) || is_border(e, m)) continue;
      auto h = halfedge(e, m);
      const Point_3 &P = get(get(CGAL::vertex_point, m), source(h, m)), &Q = get(get(CGAL::vertex_point, m), target(h, m));
      const Point_3 &R = get(get(CGAL::vertex_point, m), target(next(h, m), m)), &S = get(get(CGAL::vertex_point, m), target(next(opposite(h, m), m), m));
      // (two acute opposite angles cannot sum to more than 180 degrees: most edges end here,
      // without the angles; the signs are those of the angles' own cosine terms)
      if(CGAL::to_double((P - R) * (Q - R)) > 0 && CGAL::to_double((P - S) * (Q - S)) > 0) continue;
      if(ctx.angle(P, R, Q) + ctx.angle(P, S, Q) <= CGAL_PI + 1e-9) continue;
      if(keep_regularity && ctx.irregular_change(h, m) > 0) {
        const double old_min = ctx.min_angle_of_faces(h, m);
        if(old_min >= sliver || ctx.min_angle_after_flip(h, m) <= old_min) continue;
      }
      if(!ctx.flip_is_safe(h, m, cos_max)) continue;
      CGAL::Euler::flip_edge(h, m);
      ++flips;
    }
    stats.delaunay_flips += flips;
    if(flips == 0) break;
  }
}

} // namespace Relaxation

} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_DELAUNAY_FLIPS_H
