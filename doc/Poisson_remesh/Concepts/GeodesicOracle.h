// Concept documentation (pseudo-class, not compiled).
//
// Describes the geodesic distance oracle used by the sampler of "Direct
// Sampling on Surfaces for High Quality Remeshing": Section 4.2.2 (one
// truncated propagation of radius 2r per new sample, and the geodesic
// equidistant curve at 2r that becomes part of the available boundary) and
// Section 5.2 (predicate-driven propagation for adaptive sampling).

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept

The concept `GeodesicOracle` describes a truncated single-source geodesic
distance computation on a triangulated surface mesh, together with the
extraction of the iso-distance curve of a given radius.

A propagation is started from a point of the surface given as a face location
(a face and barycentric coordinates, possibly on an edge or a vertex of that
face).  Only the part of the surface within the propagation radius is
explored, so that the cost of a propagation depends on the size of the
geodesic disk and not on the size of the mesh.  Results of a propagation stay
valid until the next call to `propagate()`.

All distances are expressed in the unit of the coordinates of the mesh points.

<b>Face-local 2D frame.</b> For a face `f`, let `h0 = halfedge(f)`,
`v0 = source(h0)`, `v1 = target(h0)` and `v2 = target(next(h0))`.  The face
is laid out isometrically in the plane with `v0 = (0,0)`, `v1 = (|v0 v1|, 0)`
and `v2` in the upper half plane.  Barycentric coordinates of face locations
refer to `(v0, v1, v2)` in this order (the convention of
`CGAL::Polygon_mesh_processing::Face_location`).

The sampler (`Boundary_sampler`, and through it `poisson_disk_sample()` and `poisson_remesh()`
with the named parameter `geodesic_oracle`) calls exactly the members below, and keeps copies of
the oracle it is given (a model is `CopyConstructible`; the copies propagate independently).
`iso_curve(r0, vertex_radius)` is needed for adaptive density only. The two `iso_curve_outside()`
members are optional: when a model has them (and the `BoundaryCurve` has `has_arcs_in()`), the
sampler leaves out of each new curve the faces it knows to lie inside earlier samples' disks,
whose arcs it would drop; without them it asks for the whole curve (the same available boundary
after each sample, but its arcs found in another order: other sample sets for a seed).

`Poisson_remesh::Approximate_geodesic_oracle` answers the same distance queries cheaply, but its
iso-curves are straight segments, which the circular available boundary does not take: it is not
a model of this concept (not for the sampler).

\cgalHasModel `Poisson_remesh::Exact_geodesic_oracle<TriangleMesh, VertexPointMap, GeomTraits>`
*/
class GeodesicOracle
{
public:
  /// \name Types
  /// @{

  /// a model of `FaceGraph` whose faces are triangles (for example
  /// `CGAL::Surface_mesh<Point_3>` or `CGAL::Polyhedron_3<K>`)
  typedef unspecified_type TriangleMesh;

  /// `boost::graph_traits<TriangleMesh>::vertex_descriptor`
  typedef unspecified_type vertex_descriptor;

  /// `boost::graph_traits<TriangleMesh>::face_descriptor`
  typedef unspecified_type face_descriptor;

  /// the point type of the vertex point map
  typedef unspecified_type Point_3;

  /// `CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>`, that is
  /// `std::pair<face_descriptor, std::array<double,3> >`
  typedef unspecified_type Face_location;

  /// `Poisson_remesh::Iso_arc<face_descriptor, Point_3>`: a piece of an
  /// iso-distance curve contained in one face.  It has the public members
  /// `face`, `center` (the unfolded (pseudo-)source in the face frame),
  /// `radius` (`R - sigma`), `sigma`, `theta_start <= theta_end` (a
  /// counter-clockwise angular range in the face frame), `is_segment`,
  /// `segment_start`, `segment_end` (for straight pieces, then the circle
  /// fields are unused), and the functions `point_2(t)`, `barycentric(t)`,
  /// `point(t)` (2D point, barycentric coordinates and 3D point at parameter
  /// `t` in [0,1]) and `length()`.
  typedef unspecified_type Iso_arc;

  /// `Poisson_remesh::Iso_curve<face_descriptor, Point_3>`: an ordered chain of
  /// `Iso_arc` (member `arcs`), the end of each arc being the start of the
  /// next one; `closed` is `true` when the last arc ends at the start of the
  /// first one, otherwise both ends of the chain lie on the mesh border.  The
  /// region closer than `R` to the source lies on the left of the curve.
  typedef unspecified_type Iso_curve;

  /// @}

  /// \name Creation
  /// @{

  /// precomputes the per-mesh data (edge lengths, face layouts, ...); the mesh
  /// must outlive the oracle and must not be modified while the oracle is used.
  /// Throws `std::invalid_argument` if `tm` has a non-triangular face.
  GeodesicOracle(const TriangleMesh& tm);

  /// same with an explicit vertex point map
  GeodesicOracle(const TriangleMesh& tm, VertexPointMap vpm);

  /// @}

  /// \name Propagation
  /// @{

  /// computes the geodesic distances from `source` up to `radius`.  After the
  /// call, every vertex and every surface point at distance at most `radius`
  /// from `source` is reached.
  void propagate(const Face_location& source, double radius);

  /// @}

  /// \name Queries (about the last propagation)
  /// @{

  /// the radius of the last propagation
  double radius() const;

  /// the geodesic distance from the source to `v`, or `std::nullopt` if it is
  /// larger than the propagation radius (never an infinite value).
  std::optional<double> distance(vertex_descriptor v) const;

  /// the geodesic distance from the source to the surface point `p`, or
  /// `std::nullopt` if it is larger than the propagation radius.
  std::optional<double> distance(const Face_location& p) const;

  /// writes `std::pair<vertex_descriptor, double>` for every vertex at distance
  /// at most the propagation radius (in no particular order).
  template <class OutputIterator>
  OutputIterator reached_vertices(OutputIterator out) const;

  /// the iso-distance curve at distance `R` (`R` must not exceed the
  /// propagation radius): one closed chain per connected component, or open
  /// chains ending on the mesh border.
  std::vector<Iso_curve> iso_curve(double R) const;

  /// adaptive density (§5.1, Eq. 4-5): the curve of the points x with
  /// d(x) = r0 + r(x), r linear inside each face from `vertex_radius(v)` at its
  /// vertices (conic arcs, `Iso_arc::gradient` not zero); the propagation radius
  /// must be at least r0 + max r(x) over the region d(x) <= r0 + r(x).
  template <class VertexRadius>
  std::vector<Iso_curve> iso_curve(double r0, VertexRadius vertex_radius) const;

  /// optional: `iso_curve(R)` without the arcs in the faces `f` for which `skip(f)` is true; the
  /// chains break where they enter such a face
  template <class SkipFace>
  std::vector<Iso_curve> iso_curve_outside(double R, SkipFace skip) const;

  /// optional: `iso_curve(r0, vertex_radius)` likewise without the faces `skip` tells
  template <class VertexRadius, class SkipFace>
  std::vector<Iso_curve> iso_curve_outside(double r0, VertexRadius vertex_radius, SkipFace skip) const;

  /// @}
};

/*!
\ingroup PkgPoissonRemeshConcepts
\cgalConcept
\cgalRefines `GeodesicOracle`

An oracle whose propagation can be driven by a predicate on windows, as needed
by the adaptive sampling of Section 5.2 of the paper (the termination test uses
the conic of the source and the triangle formed by the unfolded source and the
window endpoints).

\cgalHasModel `Poisson_remesh::Exact_geodesic_oracle<TriangleMesh, VertexPointMap, GeomTraits>`
*/
class WindowPropagationGeodesicOracle
{
public:
  /// the geometry of a window: members `halfedge` (the window lies on
  /// `edge(halfedge)` and is about to enter `face(halfedge)`), `source`
  /// (unfolded (pseudo-)source in the halfedge frame: origin at
  /// `source(halfedge)`, x axis along the halfedge, y axis towards the face;
  /// the source has y <= 0), `sigma` (distance from the source to the
  /// pseudo-source), `b0 <= b1` (extent of the window along the halfedge),
  /// `p0`, `p1` (3D endpoints) and `min_distance`, `max_distance` (extreme
  /// distances on the window).
  typedef unspecified_type Window_geometry;

  /// propagates from `source`; `stop(w)` (with `w` a `Window_geometry`) is
  /// called for every new window and returns `true` if the window must not be
  /// propagated further.  Distances larger than `report_radius` are reported
  /// as not reached.  `propagate(source, radius)` is equivalent to a predicate
  /// returning `w.min_distance > radius` with `report_radius = radius`.
  template <class StopPredicate>
  void propagate(const Face_location& source, StopPredicate stop,
                 double report_radius = std::numeric_limits<double>::infinity());
};
