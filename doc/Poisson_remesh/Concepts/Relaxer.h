// Concept documentation (pseudo-class, not compiled).
//
// The relaxation of "Direct Sampling on Surfaces for High Quality Remeshing", §6.2 (local Lloyd
// relaxation with projection onto the input) and §6.3 (connectivity optimization).

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept

A `Relaxer` improves, in place, a triangle mesh whose vertices lie on the input surface (the
mutual tessellation of the samples): it may move vertices (keeping them on the input surface),
flip edges, and add or remove vertices, but it never moves a fixed vertex, never flips a feature
edge, keeps feature vertices on the input's feature curves and keeps the mesh's topology. It is
passed to `poisson_remesh()` with the named parameter `relaxer`; it is constructed by the user
(typically on the input mesh and its `Feature_set`).

\cgalHasModel `Poisson_remesh::Lloyd_relaxer<InputMesh, GeomTraits>`
*/
class Relaxer
{
public:
  /// Relaxes `mesh`.
  /// - `is_feature(e)`: whether the edge `e` of `mesh` lies on a feature curve of the input
  ///   (never flipped; its ends slide along the curve);
  /// - `is_fixed(v)`: whether the vertex `v` must not move (a corner, a tip, an input vertex the
  ///   tessellation could not remove);
  /// - `settings`: rounds and switches (`Relaxation_settings`; `iterations` comes from the named
  ///   parameter `number_of_iterations`);
  /// - `new_vertex(v, on_feature)`: to be called for each vertex the relaxer adds (on a feature
  ///   curve or not), so that `is_feature` and `is_fixed` answer for it afterwards.
  /// Returns what it did.
  template <class Mesh, class IsFeatureEdge, class IsFixed, class NewVertex>
  Relaxation_statistics relax(Mesh& mesh, IsFeatureEdge is_feature, IsFixed is_fixed,
                              const Relaxation_settings& settings, NewVertex new_vertex) const;
};
