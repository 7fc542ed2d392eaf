// Concept documentation (pseudo-class, not compiled).
//
// The relaxation of "Direct Sampling on Surfaces for High Quality Remeshing", §6.2 (local Lloyd
// relaxation with projection onto the input) and §6.3 (connectivity optimization).

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept

A `Relaxer` improves, in place, a triangle mesh whose vertices lie on the input surface (the
mutual tessellation of the samples). It may move vertices (keeping them on the input surface),
flip edges, and add or remove vertices; it should never move a fixed vertex, never flip a feature
edge, keep feature vertices on the input's feature curves and keep the mesh's topology. It is
passed to `poisson_remesh()` with the named parameter `relaxer`, constructed by the user; the
remesher calls relax() once per attempt with everything it knows, as property maps: the interface
does not depend on the default model's settings.

With a user's relaxer the remesher does not remake a failed result (`regrading_attempts`
defaults to 0: a remake aims at 30 degrees, which a user's relaxer may not) unless asked; the
remakes, when asked for, work with it as with the default.

\cgalHasModel `Poisson_remesh::Lloyd_relaxer<InputMesh, GeomTraits, ConcurrencyTag>` (the default; its
`Relaxation_settings` are its own business: the member `settings`; `ConcurrencyTag`
`CGAL::Parallel_tag` runs its vertex passes on TBB's threads, with the same result)
*/
class Relaxer
{
public:
  /// Relaxes `mesh`, whose vertices lie on the surface of `input` read through `input_vpm` (the
  /// mesh the remesher works on: the user's input, or a copy of it in the output's type).
  /// - `is_feature`: readable property map, `edge_descriptor` of `Mesh` -> `bool`: the edge lies
  ///   on a feature curve of the input (never flipped; its ends slide along the curve);
  /// - `is_fixed`: readable property map, `vertex_descriptor` -> `bool`: the vertex must not move
  ///   (a corner, a pointed tip, an input vertex the tessellation could not remove);
  /// - `density`: readable property map, `vertex_descriptor` -> `double` > 0: the sampling
  ///   density at the vertex, for the weights of Eq. 6: 1 everywhere for a uniform density; else
  ///   1 / r^2 at the disk radius r of the vertex's sample (Eq. 1), adaptive density or the finer
  ///   sampling around pointed tips (`feature_grading`); a vertex without a sample takes its
  ///   neighbours' mean;
  /// - `iterations`: the rounds asked for (named parameter `number_of_iterations`, default 10);
  /// - `new_vertex(v, on_feature)`: to be called for each vertex the relaxer adds (on a feature
  ///   curve or not), so that `is_feature` and `is_fixed` answer for it afterwards.
  /// Returns what it did (`Poisson_remesh::Relaxation_statistics`, counters that may stay 0).
  template <class InputMesh, class InputVertexPointMap, class Mesh, class EdgeIsFeatureMap, class VertexIsFixedMap,
            class VertexDensityMap, class NewVertex>
  Poisson_remesh::Relaxation_statistics relax(const InputMesh& input, InputVertexPointMap input_vpm, Mesh& mesh,
                                              EdgeIsFeatureMap is_feature, VertexIsFixedMap is_fixed,
                                              VertexDensityMap density, unsigned int iterations, NewVertex new_vertex) const;
};
