// Poisson_remesh/Relaxation/Relaxation_statistics.h
//
// What the relaxation did: counts of the moves, flips and changes of each step.

#ifndef POISSON_REMESH_RELAXATION_RELAXATION_STATISTICS_H
#define POISSON_REMESH_RELAXATION_RELAXATION_STATISTICS_H

#include <cstddef>

namespace Poisson_remesh {

/// What `Lloyd_relaxer::relax()` did.
struct Relaxation_statistics
{
  /// Lloyd moves made and refused, Delaunay and valence flips, sliver collapses, long-edge splits
  /// @{
  std::size_t moves = 0, refused_moves = 0, delaunay_flips = 0, valence_flips = 0, collapses = 0, splits = 0;
  /// @}
  std::size_t angle_moves = 0;   ///< moves of the final angle optimization
  std::size_t fidelity_insertions = 0;   ///< input vertices inserted where the mesh cut across the input
  std::size_t refinement_insertions = 0;   ///< vertices inserted beside triangles still sharper than sliver_angle
  /// the other changes of the refinement: flips and vertex removals
  /// @{
  std::size_t refinement_flips = 0, refinement_removals = 0;
  /// @}
  std::size_t untangle_changes = 0;   ///< moves and flips that left fewer crossing face pairs
};

} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_RELAXATION_STATISTICS_H
