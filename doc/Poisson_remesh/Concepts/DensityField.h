// Concept documentation (pseudo-class, not compiled).
//
// The density of "Direct Sampling on Surfaces for High Quality Remeshing", §5.1: a sampling
// density given at the input's vertices and interpolated linearly inside faces (Eq. 3, which the
// package applies to the disk radius that Eq. 1 derives from the density).

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept

A `DensityField` tells how densely to sample each part of the input: a relative number of samples
per unit area at each vertex of the input (only ratios matter: the field is scaled so that the
sample count meets the target vertex count). It is passed to `poisson_disk_sample()` and
`poisson_remesh()` with the named parameter `density`; the function
`Poisson_remesh::vertex_densities(field, tm, vpm)` turns it into one positive value per vertex
(indexed by the vertex index map), and `Poisson_remesh::vertex_disk_radii()` turns those values
into disk radii (Eq. 1, scaled to the target count, gradient limited to 1/2).

A new model is a type with an overload of `vertex_densities` in namespace `Poisson_remesh`.

\cgalHasModel `Poisson_remesh::Uniform_density` (the default: every part alike)
\cgalHasModel `Poisson_remesh::Curvature_density` (gamma, min_edge, max_edge, edge_ratio, smoothing,
beside_creases; its overload `vertex_densities(field, tm, vpm, creases)` takes the feature edges
too, which the sampler and the remesher pass: no normal curvature is counted across them, a
curved crease's own bend is)
\cgalHasModel `Poisson_remesh::Vertex_density<VertexDensityMap>` (made by `vertex_density(map)`)
\cgalHasModel `Poisson_remesh::Point_density<Function>` (made by `point_density(f)`, `f(point)`)
*/
class DensityField
{
};

/// The relative density at each vertex of `tm` (by vertex index), all positive and finite.
template <class TriangleMesh, class VertexPointMap>
std::vector<double> vertex_densities(const DensityField& field, const TriangleMesh& tm, VertexPointMap vpm);
