// Poisson_remesh/Postprocessing/angle_optimization.h
//
// (beyond the paper) Angle optimization. Objective: the smallest angle in the stars of the
// triangles sharper than `optimized_angle`. Lloyd's centroids leave slivers beside vertices that
// may not move (corners, tips, feature samples): each movable vertex of such a triangle moves (on
// the input; a feature vertex along its curve) to raise the smallest angle of its triangles, by a
// pattern search. At a tip whose angles add up to less than 90 degrees, where three triangles cannot
// all reach 30 degrees, the neighbours raise their own angles instead of the tip's. The vertices of
// the fidelity insertions at a sliver may move too, by a quarter of the tolerance at most
// (optimize_pinned_vertices). Constraints: vertices on the input; moves only; a move that makes the
// mesh cut itself anew is taken back; with a fidelity tolerance (`max_deviation` > 0), a trial
// point wins only if each edge of the moving vertex ends within the tolerance of the input (its
// midpoint), or no farther than it was: these moves follow the last fidelity insertions, and an
// edge stretched across a groove or around a bend would undo them (not guaranteed where a vertex
// is taken back for a crossing: its neighbours' moves were checked with it where it had moved).

#ifndef POISSON_REMESH_POSTPROCESSING_ANGLE_OPTIMIZATION_H
#define POISSON_REMESH_POSTPROCESSING_ANGLE_OPTIMIZATION_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/Postprocessing/internal/vertex_angle_search.h>

namespace Poisson_remesh {

namespace Postprocessing {

/// The angle optimization's settings.
struct Angle_optimization_settings
{
  /// rounds of optimization (each followed by Delaunay flips); they stop when a round moves
  /// nothing; 0 disables
  unsigned int rounds = 4;
  /// the vertices of the triangles sharper than this move (degrees; the regularity flips leave
  /// triangles down to their min_angle)
  double optimized_angle = 35;
};

/// One round of angle optimization of `m` (`ConcurrencyTag`: see internal::vertex_angle_search). Returns the number of vertices moved.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge, class IsFixed>
std::size_t optimize_angles(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsFixed is_fixed, const Angle_optimization_settings& s,
                            double sliver_angle, double max_deviation, Relaxation_statistics& stats)
{
  return Postprocessing::internal::vertex_angle_search<ConcurrencyTag>(ctx, m, is_feature, is_fixed, Angle_goal::smallest, s.optimized_angle, sliver_angle,
                                                       max_deviation, stats);
}

/// One round in which only the pinned vertices of the fidelity insertions (`pin_position(x)`: where
/// x was put, nullptr for the others) at a triangle sharper than `sliver_angle` move, within a
/// quarter of the tolerance of where they were put. Returns the number of vertices moved.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge, class IsFixed, class PinPosition>
std::size_t optimize_pinned_vertices(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsFixed is_fixed, const Angle_optimization_settings& s,
                                     double sliver_angle, double max_deviation, Relaxation_statistics& stats, PinPosition pin_position)
{
  return Postprocessing::internal::vertex_angle_search<ConcurrencyTag>(ctx, m, is_feature, is_fixed, Angle_goal::smallest, s.optimized_angle, sliver_angle,
                                                       max_deviation, stats, pin_position, true);
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_ANGLE_OPTIMIZATION_H
