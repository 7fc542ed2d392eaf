// Poisson_remesh/Postprocessing/angle_smoothing.h
//
// (beyond the paper) Angle smoothing. Objective: the smallest angles in each vertex star. Lloyd's
// centroids are the best positions for the energy of §6.2, not for the angles of a given
// connectivity: every movable vertex moves (a free one in its tangent plane, then onto the input;
// a feature vertex along its curve) to raise the sum of its triangles' smallest angles without
// lowering the smallest of them: a free vertex by steps up the gradient of that sum (halved
// while they do not gain), a feature vertex by a short compass search along its curve.
// Constraints: vertices on the input; moves only; a move that makes the mesh cut itself anew is
// taken back.

#ifndef POISSON_REMESH_POSTPROCESSING_ANGLE_SMOOTHING_H
#define POISSON_REMESH_POSTPROCESSING_ANGLE_SMOOTHING_H

#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/Postprocessing/internal/vertex_angle_search.h>

namespace Poisson_remesh {

namespace Postprocessing {

/// The angle smoothing's settings.
struct Angle_smoothing_settings
{
  /// rounds of smoothing (each followed by Delaunay flips); they stop when a round moves nothing;
  /// 0 disables
  unsigned int rounds = 2;
};

/// What a smoothing round leaves for the next ones: the vertices whose search moved nothing, with
/// a digest of their star. A vertex whose star is the same at the next round is not searched
/// again (its search would find the same nothing): the rounds after the first, and those after
/// the regularity flips, search where something changed. Vertices must not be added or removed
/// between the rounds that share one.
template <class Mesh>
using Angle_smoothing_memory = std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, std::uint64_t>;

/// One round of angle smoothing of `m` (the vertices for which `is_fixed` holds stay), with the
/// memory of the earlier rounds (`memory`; nullptr: every movable vertex is searched); in parallel
/// with `ConcurrencyTag` = CGAL::Parallel_tag, with the same result (internal::vertex_angle_search).
/// Returns the number of vertices moved.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Context, class Mesh, class IsFeatureEdge, class IsFixed>
std::size_t smooth_angles(const Context& ctx, Mesh& m, IsFeatureEdge is_feature, IsFixed is_fixed, Relaxation_statistics& stats,
                          Angle_smoothing_memory<Mesh>* memory = nullptr)
{
  // (the search's angle thresholds and pin reach serve the other goals only)
  return Postprocessing::internal::vertex_angle_search<ConcurrencyTag>(ctx, m, is_feature, is_fixed, Angle_goal::sum_of_smallest, 0, 0, 0, stats, memory);
}

} // namespace Postprocessing

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_ANGLE_SMOOTHING_H
