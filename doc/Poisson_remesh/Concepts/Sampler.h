// Concept documentation (pseudo-class, not compiled).
//
// The sampler of "Direct Sampling on Surfaces for High Quality Remeshing", §4.2 (uniform),
// §4.2.4 (features first) and §8 (progressive levels of detail).

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept

A `Sampler` produces a maximal geodesic Poisson-disk set on a triangle mesh: fixed samples first
(corners and feature-curve points), a seed in every component left without one, then samples
drawn on the available boundary (a `BoundaryCurve`) until it is empty, each with its geodesic
disk computed by a `GeodesicOracle`. All randomness comes from the seed given at construction.

\cgalHasModel `Poisson_remesh::Boundary_sampler<TriangleMesh, VertexPointMap, GeodesicOracle>`
*/
class Sampler
{
public:
  /// `Poisson_remesh::Poisson_sample<TriangleMesh, Point_3>`: location on the input, point, kind, level
  typedef unspecified_type Sample;
  /// `CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>`: a face and barycentric
  /// coordinates
  typedef unspecified_type Face_location;

  /// a sampler of the surface `tm` (read through `vpm`), all its random draws from `seed`
  Sampler(const TriangleMesh& tm, VertexPointMap vpm, std::uint64_t seed);

  /// sets the expellant-disk radius r (samples >= 2r apart); a smaller radius than the current one
  /// starts a new level of detail that keeps every existing sample
  void set_radius(double r);
  /// the current disk radius r
  double radius() const;

  /// inserts a sample whatever the available boundary says (corners, feature points); with
  /// `require_separation`, refuses a location closer than 2r to an earlier sample
  bool insert(const Face_location& loc, Sample_kind kind, bool require_separation);
  /// one random sample in every connected component that has none
  void seed_components();
  /// draws samples on the available boundary until it is empty
  void fill();

  /// the samples so far, in the order they were added
  const std::vector<Sample>& samples() const;
  /// counters of the run (`Poisson_remesh::Sampling_statistics`)
  const Sampling_statistics& statistics() const;
};
