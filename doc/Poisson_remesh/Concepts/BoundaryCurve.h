// Concept documentation (pseudo-class, not compiled).
//
// The available boundary of "Direct Sampling on Surfaces for High Quality Remeshing",
// §4.1 and §4.2.3 (uniform density: circular arcs) and §5.1 (adaptive density: conic arcs).

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept

A `BoundaryCurve` stores the available boundary of boundary sampling: the parts of the samples'
iso-distance curves (at 2r from each sample) that no other sample's expellant disk D(s, 2r)
covers -- the boundary of the union of the disks. Each piece is an arc inside one face of the
input mesh, in that face's 2D frame (see `GeodesicOracle`). New samples are drawn on it, and each
new sample's curve updates it, until it is empty: then the samples form a maximal Poisson-disk set.

With adaptive density (§5.1) the curve of a sample p is where d(p, x) = r(p) + r(x) and the
region is {x : d(p, x) < r(p) + r(x)}; its pieces are conic arcs.

It is the fourth template parameter of `Poisson_remesh::Boundary_sampler` (default
`Circular_available_boundary<TriangleMesh, GeodesicOracle::Iso_arc>`), which calls exactly the
members below.

\cgalHasModel `Poisson_remesh::Circular_available_boundary<TriangleMesh, Arc>` (uniform density:
the circular `Iso_arc`s of `Exact_geodesic_oracle`; adaptive density: its conic `Iso_arc`s, those
with a non-zero `gradient`, whose crossings it finds numerically)
*/
class BoundaryCurve
{
public:
  /// the arc type, e.g. `Poisson_remesh::Iso_arc<face_descriptor, Point_3>`
  typedef unspecified_type Arc;
  /// `CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>`
  typedef unspecified_type Face_location;

  /// built on the input mesh
  BoundaryCurve(const TriangleMesh& tm);

  /// true when no available boundary is left (the sample set is maximal)
  bool empty() const;
  /// total length of the available boundary
  double length() const;
  /// removes every arc (a new level of detail starts from scratch)
  void clear();

  /// a point drawn uniformly by arc length; `u01()` returns uniform numbers in [0, 1); `arc`
  /// receives the index of the arc it lies on (for remove_arc())
  template <class Uniform01> Face_location pick(Uniform01&& u01, std::size_t& arc);
  /// removes the arc of index `arc` (one that gives no usable sample point)
  void remove_arc(std::size_t arc);
  /// arcs shorter than `length` are not stored (the sampler sets 1e-9 r)
  void set_minimum_length(double length);

  /// Adds the iso-curve `chains` (ordered chains of arcs, as `GeodesicOracle::iso_curve()` returns
  /// them) of a new sample `sample`: stored arcs inside the new disk are cut away, and the parts of
  /// the new curve inside earlier disks are left out.
  /// `faces`: every face the new disk can meet; `in_new_disk(loc)`: is `loc` closer than 2r to the
  /// new sample; `in_old_disks(loc)`: is `loc` closer than 2r to an earlier sample.
  template <class Chains, class FaceRange, class InNewDisk, class InOldDisks>
  void update(const Chains& chains, std::size_t sample, const FaceRange& faces,
              InNewDisk in_new_disk, InOldDisks in_old_disks);

  /// optional, with the oracle's `iso_curve_outside()`: whether a live arc lies in face `f`
  bool has_arcs_in(face_descriptor f) const;
  /// optional: update() with chains that leave out faces inside the earlier disks;
  /// `ends_in_covered_face(arc, at_end)` tells whether the open chain that begins (`at_end`
  /// false) or ends (true) with `arc` breaks there at such a face: the run of the new curve that
  /// reaches the break without meeting the stored boundary is inside the earlier disks
  template <class Chains, class FaceRange, class InNewDisk, class InOldDisks, class EndsInCoveredFace>
  void update(const Chains& chains, std::size_t sample, const FaceRange& faces,
              InNewDisk in_new_disk, InOldDisks in_old_disks, EndsInCoveredFace ends_in_covered_face);

  /// the live arcs, each with the sample that owns it
  template <class OutputIterator> OutputIterator arcs(OutputIterator out) const;
};
