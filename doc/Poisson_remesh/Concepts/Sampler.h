// Concept documentation (pseudo-class, not compiled).
//
// The sampling stage of "Direct Sampling on Surfaces for High Quality Remeshing": §4.2 (uniform),
// §4.2.4 (features first), §5 (adaptive density).

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept

A `Sampler` places the vertices of a remesh on the input surface: `poisson_remesh()` calls it once
per attempt (named parameter `sampler`), then tessellates the input with its samples (§6.1) and
relaxes the result (§6.2-6.3).

What the remesher expects, and what it does when a sampler does not deliver it:
- every sample lies on the input (a face location, and its point); samples of kind
  `Sample_kind::corner` at the corners of `features` and of kind `Sample_kind::feature` on its
  feature curves keep those features in the output: a curve without feature samples is not kept as
  a feature, and a corner without a corner sample is cut;
- samples are about twice the disk radius apart (the radius, or the per-vertex radii, given):
  samples at the same point are merged by the tessellation
  (`Poisson_remesh_result::number_of_merged_samples`); samples much closer than the spacing make
  short edges that the relaxation spreads out, and gaps much wider make large triangles that the
  relaxation's fidelity insertions fill only where the mesh leaves the input;
- each component of the input has at least one sample, or it is left out of the output.
With a user's sampler the remesher does not remake a failed result (`regrading_attempts` defaults
to 0), since a remake asks for finer radii that the sampler may not follow.

\cgalHasModel `Poisson_remesh::Poisson_disk_sampler` (the default: maximal geodesic Poisson-disk
boundary sampling, corners and feature curves first; it uses a `GeodesicOracle` and a
`BoundaryCurve` through `Poisson_remesh::Boundary_sampler`)
*/
class Sampler
{
public:
  /// writes to `out` the samples (`Poisson_remesh::Poisson_sample<TriangleMesh, Point_3>`: face
  /// location, point, kind) of the surface `tm` read through `vpm`.
  /// - `features`: the input's corners and feature curves (`detect_features()` at the sampling
  ///   scale; the remesher keeps exactly these as output features);
  /// - `radius`: the disk radius r (samples about 2r apart); with adaptive density the median of
  ///   `vertex_radii`;
  /// - `vertex_radii`: empty for a uniform density; else the disk radius at each vertex, indexed by
  ///   `CGAL::get_initialized_vertex_index_map(tm)` (linear inside faces, Eq. 3);
  /// - `seed`: all random draws come from it (each remake passes another).
  /// Returns what it did; the remesher reads `number_of_samples` (it counts them itself too).
  template <class TriangleMesh, class VertexPointMap, class OutputIterator>
  Poisson_remesh::Poisson_disk_sampling_result
  operator()(const TriangleMesh& tm, VertexPointMap vpm, const Poisson_remesh::Feature_set<TriangleMesh>& features,
             double radius, const std::vector<double>& vertex_radii, unsigned int seed, OutputIterator out) const;
};
