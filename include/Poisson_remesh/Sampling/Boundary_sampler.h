// Poisson_remesh/Sampling/Boundary_sampler.h
//
// The boundary sampler of paper §4.2, a model of the concept Sampler: Dunbar and Humphreys'
// boundary sampling moved onto a surface with geodesic distance.
//   1. fixed samples first: corners, then feature-curve samples (§4.2.4), each with its disk;
//   2. every connected component still without a sample gets a random seed;
//   3. repeat until the available boundary is empty: draw a point uniformly by arc length on it,
//      make it a sample, propagate its exact geodesic field to 2r (the GeodesicOracle), extract
//      its iso-curve at 2r and update the available boundary (BoundaryCurve).
// When the boundary is empty the set is maximal: no two samples closer than 2r (geodesic), every
// surface point within 2r of a sample. Levels of detail (§8): set_radius() with a smaller radius
// rebuilds the available boundary around the existing samples, and filling again adds samples
// without removing any, so each level contains the coarser ones.
//
// Adaptive density (§5): with set_radius_field() the disk radius r(x) varies over the surface
// (linear inside faces, Eq. 3); the available boundary of a sample p is where d(p, x) = r(p) + r(x),
// made of conic arcs (Eq. 4-5), and the set is maximal for the rule d(p, q) >= r(p) + r(q).
//
// Beyond the paper, for speed: the faces found to lie inside the union of the disks so far are
// left out of each new iso-curve (its arcs there would all be dropped); the available boundary is
// the same (see add_sample() and mark_covered_faces()).
//
// Determinism: all randomness comes from one std::mt19937_64 seeded by the caller.

#ifndef POISSON_REMESH_SAMPLING_BOUNDARY_SAMPLER_H
#define POISSON_REMESH_SAMPLING_BOUNDARY_SAMPLER_H

#include <Poisson_remesh/Boundary/Circular_available_boundary.h>
#include <Poisson_remesh/Geodesic/Exact_geodesic_oracle.h>
#include <Poisson_remesh/density_fields.h>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace Poisson_remesh {

/// Why a sample is there.
enum class Sample_kind { corner, feature, surface };

/// A sample: where it lies on the input (face + barycentric coordinates), its point, its kind.
template <class TriangleMesh, class Point_3>
struct Poisson_sample
{
  CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> location;   ///< a face and barycentric coordinates
  Point_3 point;                             ///< its 3D point
  Sample_kind kind = Sample_kind::surface;   ///< corner, feature-curve or surface sample
  unsigned int level = 0;   ///< the level of detail that added it (0: the first)
  double radius = 0;        ///< its disk radius r (samples p, q are at least r(p) + r(q) apart)
};

/// Counters of a sampling run.
struct Sampling_statistics
{
  std::size_t propagations = 0;            ///< forward propagations (one per sample)
  std::size_t classification_propagations = 0; ///< propagations from boundary midpoints (§4.2.3 decisions)
  std::size_t rejected_feature_samples = 0; ///< feature-curve points closer than 2r to an earlier sample
  std::size_t open_iso_curves = 0;         ///< iso-curves left open away from a border and from the edges of faces left out (inside earlier disks)
  std::size_t dropped_arcs = 0;            ///< boundary arcs found inside an earlier sample's region (adaptive density) or with no finite point (zero-area faces)
  std::size_t slabs = 0;                   ///< the slabs of the parallel mode (0: the sequential sampler ran)
  std::size_t covered_faces = 0;           ///< faces found inside the union of the disks, whose new arcs are not made
};

namespace internal {

// whether the oracle makes iso-curves without given faces (both levels) and the boundary tells the
// faces that hold arcs and takes the chains' breaks (Exact_geodesic_oracle,
// Circular_available_boundary): what the sampler's skipping of covered faces needs
template <class Oracle, class Boundary, class Face, class Vertex, class Location, class = void>
struct Skips_covered_faces : std::false_type {};
template <class Oracle, class Boundary, class Face, class Vertex, class Location>
struct Skips_covered_faces<
  Oracle, Boundary, Face, Vertex, Location,
  std::void_t<decltype(std::declval<const Oracle&>().iso_curve_outside(1.0, std::declval<bool (*)(Face)>())),
              decltype(std::declval<const Oracle&>().iso_curve_outside(1.0, std::declval<double (*)(Vertex)>(), std::declval<bool (*)(Face)>())),
              decltype(std::declval<const Boundary&>().has_arcs_in(std::declval<Face>())),
              decltype(std::declval<Boundary&>().update(std::declval<const std::vector<typename Oracle::Iso_curve>&>(), std::size_t(0),
                                                        std::declval<const std::vector<Face>&>(), std::declval<bool (*)(const Location&)>(),
                                                        std::declval<bool (*)(const Location&)>(),
                                                        std::declval<bool (*)(const typename Oracle::Iso_arc&, bool)>()))>> : std::true_type {};

/// Uniform hash grid of sample points for "which samples are within Euclidean distance d".
class Point_grid
{
public:
  void reset(double cell) { cell_ = cell; cells_.clear(); }
  void insert(std::size_t id, const std::array<double, 3>& p) { cells_[key(p, 0, 0, 0)].push_back(id); }
  template <class F>
  void for_each_near(const std::array<double, 3>& p, F f) const
  {
    for(int i = -1; i <= 1; ++i)
      for(int j = -1; j <= 1; ++j)
        for(int k = -1; k <= 1; ++k) {
          auto it = cells_.find(key(p, i, j, k));
          if(it != cells_.end()) for(std::size_t id : it->second) f(id);
        }
  }
private:
  std::uint64_t key(const std::array<double, 3>& p, int di, int dj, int dk) const
  {
    auto c = [&](double x, int d) { return std::uint64_t(std::int64_t(std::floor(x / cell_)) + d + (1 << 20)) & 0x1fffff; };
    return (c(p[0], di) << 42) | (c(p[1], dj) << 21) | c(p[2], dk);
  }
  double cell_ = 1;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

} // namespace internal

/// The boundary sampler of paper §4.2 (Dunbar and Humphreys' boundary sampling on the surface,
/// with geodesic distances), a model of the concept `Sampler`: fixed samples first (insert()),
/// a seed in every component left without one (seed_components()), then samples drawn on the
/// available boundary until it is empty (fill()), which makes the set maximal. Uniform density
/// with set_radius() (several calls with decreasing radii: levels of detail), adaptive density with
/// set_radius_field() (§5). All randomness comes from the seed given at construction.
///
/// `GeodesicOracle`: a model of `GeodesicOracle` whose `Iso_arc`s the available boundary
/// (`Circular_available_boundary`) handles: circular or conic arcs, as those of
/// `Exact_geodesic_oracle` (the default, and the only model that fits today).
template <class TriangleMesh,
          class VertexPointMap = typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type,
          class GeodesicOracle = Exact_geodesic_oracle<TriangleMesh, VertexPointMap>,
          class BoundaryCurve = Circular_available_boundary<TriangleMesh, typename GeodesicOracle::Iso_arc>>
class Boundary_sampler
{
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename GT::vertex_descriptor vertex_descriptor;

public:
  /// the point type
  typedef typename boost::property_traits<VertexPointMap>::value_type Point_3;
  /// a surface point: a face and barycentric coordinates
  typedef CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> Face_location;
  /// a sample
  typedef Poisson_sample<TriangleMesh, Point_3> Sample;
  /// the oracle's arc type
  typedef typename GeodesicOracle::Iso_arc Arc;
  /// the available boundary (a model of `BoundaryCurve`)
  typedef BoundaryCurve Boundary;

  /// Closer than 2r * (1 - separation_tolerance) counts as inside a disk.
  static constexpr double separation_tolerance = 1e-9;

  /// A sampler of `tm` (read through `vpm`, which must outlive the sampler), its draws from `seed`.
  Boundary_sampler(const TriangleMesh& tm, VertexPointMap vpm, std::uint64_t seed)
    : Boundary_sampler(tm, vpm, seed, GeodesicOracle(tm, vpm))
  {}

  /// As above, with the geodesic oracle `oracle` (a model of `GeodesicOracle` built on `tm`, read
  /// through `vpm`; the sampler keeps a copy and propagates with it).
  Boundary_sampler(const TriangleMesh& tm, VertexPointMap vpm, std::uint64_t seed, GeodesicOracle oracle)
    : tm_(tm), vpm_(vpm), vim_(CGAL::get_initialized_vertex_index_map(tm)), oracle_(std::move(oracle)), classifier_(oracle_),
      boundary_(tm), rng_(seed), fim_(CGAL::get_initialized_face_index_map(tm))
  {}

  /// The expellant-disk radius r (samples are at least 2r apart). A smaller radius than the
  /// current one starts a new level of detail: the available boundary is rebuilt around the
  /// existing samples (which all stay).
  void set_radius(double r)
  {
    if(!(r > 0)) throw std::invalid_argument("Boundary_sampler: the radius must be positive");
    if(r_ > 0 && r > r_) throw std::invalid_argument("Boundary_sampler: a new level needs a smaller radius");
    if(!vertex_radius_.empty()) throw std::logic_error("Boundary_sampler: levels of detail need a uniform radius");
    const bool rebuild = r_ > 0;
    r_ = r;
    boundary_.clear();
    covered_.clear();
    boundary_.set_minimum_length(1e-9 * r);
    grid_.reset(2 * r);
    if(rebuild) ++level_;
    const std::vector<Sample> previous = std::move(samples_);
    samples_.clear();
    for(const Sample& s : previous) add_sample(s.location, s.kind, false, s.level);
  }
  /// The largest disk radius (the radius, for uniform density).
  double radius() const { return r_; }

  /// Adaptive density (§5): the disk radius at vertex v is `vertex_radius(v)` (> 0), interpolated
  /// linearly inside faces (Eq. 3); samples p, q will be at least r(p) + r(q) apart (geodesic) and
  /// every surface point x within r(p) + r(x) of a sample p. Replaces set_radius(); one level only.
  /// The radius should not change faster than the distance (|grad r| < 1; the density fields of
  /// the package limit it to 0.5).
  template <class VertexRadius>
  void set_radius_field(VertexRadius vertex_radius)
  {
    if(!samples_.empty()) throw std::logic_error("Boundary_sampler: set the radius field before sampling");
    vertex_radius_.assign(internal::vertex_index_bound(tm_), 0.0);
    double rmin = std::numeric_limits<double>::infinity(), rmax = 0;
    for(vertex_descriptor v : vertices(tm_)) {
      const double r = vertex_radius(v);
      if(!(r > 0) || !std::isfinite(r)) throw std::invalid_argument("Boundary_sampler: radii must be positive and finite");
      vertex_radius_[get(vim_, v)] = r;
      rmin = std::min(rmin, r);
      rmax = std::max(rmax, r);
    }
    r_ = rmax;
    boundary_.clear();
    covered_.clear();
    boundary_.set_minimum_length(1e-9 * rmin);
    grid_.reset(2 * rmax);
  }
  /// true after set_radius_field() (adaptive density)
  bool adaptive() const { return !vertex_radius_.empty(); }

  /// The disk radius at a surface location (r for uniform density).
  double radius_at(const Face_location& loc) const
  {
    if(vertex_radius_.empty()) return r_;
    const auto h0 = halfedge(loc.first, tm_);
    const vertex_descriptor v[3] = {source(h0, tm_), target(h0, tm_), target(next(h0, tm_), tm_)};
    double r = 0;
    for(int i = 0; i < 3; ++i) r += loc.second[i] * vertex_radius_[get(vim_, v[i])];
    return r;
  }
  /// The disk radius at vertex v.
  double radius_at(vertex_descriptor v) const
  {
    if(vertex_radius_.empty()) return r_;
    return vertex_radius_[get(vim_, v)];
  }

  /// Inserts a sample at `loc` whatever the available boundary says (corners, feature points).
  /// With `require_separation`, a location closer than 2r to an earlier sample is refused.
  bool insert(const Face_location& loc, Sample_kind kind, bool require_separation)
  {
    return add_sample(loc, kind, require_separation, level_);
  }

  /// Seeds every connected component that has no sample yet with a random point (area-uniform).
  void seed_components()
  {
    auto fim = CGAL::get_initialized_face_index_map(tm_);
    std::vector<std::size_t> component(num_faces(tm_), 0);
    auto fcc = boost::make_iterator_property_map(component.begin(), fim);
    const std::size_t nc = CGAL::Polygon_mesh_processing::connected_components(tm_, fcc, CGAL::parameters::face_index_map(fim));
    std::vector<char> has_sample(nc, 0);
    for(const Sample& s : samples_) has_sample[get(fcc, s.location.first)] = 1;
    std::vector<std::vector<face_descriptor>> faces_of(nc);
    std::vector<std::vector<double>> cumulative(nc);
    for(face_descriptor f : faces(tm_)) {
      const std::size_t c = get(fcc, f);
      if(has_sample[c]) continue;
      const double a = CGAL::to_double(CGAL::Polygon_mesh_processing::face_area(f, tm_, CGAL::parameters::vertex_point_map(vpm_)));
      faces_of[c].push_back(f);
      cumulative[c].push_back((cumulative[c].empty() ? 0.0 : cumulative[c].back()) + a);
    }
    for(std::size_t c = 0; c < nc; ++c) {
      if(has_sample[c] || faces_of[c].empty()) continue;
      add_sample(random_location(faces_of[c], cumulative[c]), Sample_kind::surface, false, level_);
    }
  }

  /// A point drawn uniformly by area from the sampler's generator on the faces `fs`, whose
  /// cumulative areas are `cumulative` (non-empty, the last one positive).
  Face_location random_location(const std::vector<face_descriptor>& fs, const std::vector<double>& cumulative)
  {
    const double u = uniform01() * cumulative.back();
    const std::size_t i = std::min<std::size_t>(fs.size() - 1,
      std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin()));
    double b1 = uniform01(), b2 = uniform01();
    if(b1 + b2 > 1) { b1 = 1 - b1; b2 = 1 - b2; }
    return {fs[i], {{1 - b1 - b2, b1, b2}}};
  }

  /// Draws samples on the available boundary until it is empty (§4.2, steps 3-5).
  void fill() { fill([](std::size_t) {}); }

  /// As fill(); `on_sample(n)` is called after each new sample, with the number of samples so far
  /// (progress reports; an exception it throws stops the filling, the samples so far kept).
  template <class OnSample>
  void fill(OnSample on_sample)
  {
    while(!boundary_.empty()) {
      std::size_t arc = 0;
      const Face_location loc = boundary_.pick([this] { return uniform01(); }, arc);
      // an arc in a (nearly) zero-area face can give no finite point: it is dropped, and counted
      const Face_location s = snapped(loc);
      if(!(std::isfinite(s.second[0]) && std::isfinite(s.second[1]) && std::isfinite(s.second[2]))) {
        boundary_.remove_arc(arc);
        never_cover(loc.first);
        ++stats_.dropped_arcs;
        continue;
      }
      // adaptive density: a point already inside an earlier sample's region (d < r(p) + r(x))
      // means its arc was left behind by an update (a conic arc where the radius changes faster
      // than the distance on a needle face): the arc is dropped, and counted
      if(!vertex_radius_.empty() && covered_by_earlier_adaptive_samples(s)) {
        boundary_.remove_arc(arc);
        never_cover(loc.first);
        ++stats_.dropped_arcs;
        continue;
      }
      add_sample(loc, Sample_kind::surface, false, level_);
      on_sample(samples_.size());
    }
  }

  /// Whether the faces found inside the union of the disks are left out of the new iso-curves
  /// (default true; with an oracle and a boundary that support it, as the defaults do, and on a
  /// mesh without nearly zero-area faces): the same available boundary, for less work, its arcs
  /// added in another order, so that the points drawn on it differ (see add_sample()).
  void set_skip_covered_faces(bool skip) { skip_covered_ = skip; covered_.clear(); }

  /// fill() draws only in the faces f with `pickable[fim(f)]` (fim: the mesh's initialized face
  /// index map; an empty vector: everywhere), the rest of the boundary still kept and updated;
  /// fill() then stops when no arc is left in those faces. (The parallel sampler gives each slab
  /// of the surface a sampler that draws in the slab alone: Sampling/internal/slab_sampling.h.)
  void restrict_draws_to(std::vector<char> pickable) { boundary_.set_pickable_faces(std::move(pickable)); }

  /// the samples so far, in the order they were added
  const std::vector<Sample>& samples() const { return samples_; }
  /// the available boundary (empty when the set is maximal)
  const Boundary& available_boundary() const { return boundary_; }
  /// counters of the run
  const Sampling_statistics& statistics() const { return stats_; }
  /// the oracle that propagates each new sample's disk
  GeodesicOracle& oracle() { return oracle_; }

  /// A number in [0, 1) from the sampler's generator (53 random bits; the same on every platform).
  double uniform01() { return double(rng_() >> 11) * (1.0 / 9007199254740992.0); }

private:
  std::array<double, 3> coords(const Point_3& p) const
  {
    return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  }

  // Barycentric coordinates within rounding of 0 are made 0: a location a hair's breadth off a
  // vertex or an edge is on it (propagations from such near-vertex sources lost windows).
  static Face_location snapped(Face_location loc)
  {
    double sum = 0;
    for(double& b : loc.second) { if(b < 1e-12) b = 0; sum += b; }
    for(double& b : loc.second) b /= sum;
    return loc;
  }

  bool add_sample(const Face_location& unsnapped, Sample_kind kind, bool require_separation, unsigned int level)
  {
    if(!vertex_radius_.empty()) return add_adaptive_sample(snapped(unsnapped), kind, require_separation, level);
    const Face_location loc = snapped(unsnapped);
    if(!(r_ > 0)) throw std::logic_error("Boundary_sampler: set_radius() first");
    const double two_r = 2 * r_, inside = two_r * (1 - separation_tolerance);
    const Point_3 p = CGAL::Polygon_mesh_processing::construct_point(loc, tm_, CGAL::parameters::vertex_point_map(vpm_));
    const std::array<double, 3> pc = coords(p);

    oracle_.propagate(loc, two_r);
    ++stats_.propagations;
    if(require_separation) {
      bool too_close = false;
      grid_.for_each_near(pc, [&](std::size_t id) {
        if(too_close) return;
        const auto d = oracle_.distance(samples_[id].location);
        too_close = d && *d < inside;
      });
      if(too_close) { ++stats_.rejected_feature_samples; return false; }
    }

    // the new iso-curve at 2r (without the faces inside the earlier disks), and the faces the new
    // disk meets
    const auto chains = iso_curve_outside_covered_faces([&](auto skip) { return oracle_.iso_curve_outside(two_r, skip); },
                                                        [&] { return oracle_.iso_curve(two_r); });
    const std::vector<face_descriptor>& disk_faces =
      faces_of_new_disk(loc, chains, [](vertex_descriptor, double) { return true; }, [&](vertex_descriptor, double d) { return d < inside; });

    const std::size_t id = samples_.size();
    update_boundary(chains, id, disk_faces,
      [&](const Face_location& x) {
        const auto d = oracle_.distance(x);
        return d && *d < inside;
      },
      [&](const Face_location& x) { return covered_by_earlier_samples(x, inside); });
    mark_covered_faces();

    samples_.push_back({loc, p, kind, level, r_});
    grid_.insert(id, pc);
    return true;
  }

  // add_sample() with a radius field: the same steps with the rule d(p, q) < r(p) + r(q)
  bool add_adaptive_sample(const Face_location& loc, Sample_kind kind, bool require_separation, unsigned int level)
  {
    const double rp = radius_at(loc), keep = 1 - separation_tolerance;
    const Point_3 p = CGAL::Polygon_mesh_processing::construct_point(loc, tm_, CGAL::parameters::vertex_point_map(vpm_));
    const std::array<double, 3> pc = coords(p);
    // propagate far enough to see every x with d(p, x) <= rp + r(x): until the radius covers rp
    // plus the largest radius met (with a margin for faces reaching beyond the last vertices)
    double R = 2 * rp;
    for(int round = 0;; ++round) {
      oracle_.propagate(loc, R);
      ++stats_.propagations;
      double met = rp;
      // (the vertices around the reached ones too: their faces reach beyond the last vertices)
      oracle_.reached_vertices(boost::make_function_output_iterator([&](const std::pair<vertex_descriptor, double>& vd) {
        met = std::max(met, radius_at(vd.first));
        for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(vd.first, tm_), tm_)) met = std::max(met, radius_at(w));
      }));
      const double needed = std::min(rp + r_, rp + 1.25 * met);
      if(R >= needed * (1 - 1e-12) || round == 8) break;
      R = needed;
    }
    if(require_separation) {
      bool too_close = false;
      grid_.for_each_near(pc, [&](std::size_t id) {
        if(too_close) return;
        const auto d = oracle_.distance(samples_[id].location);
        too_close = d && *d < (rp + samples_[id].radius) * keep;
      });
      if(too_close) { ++stats_.rejected_feature_samples; return false; }
    }

    auto vertex_radius = [&](vertex_descriptor v) { return radius_at(v); };
    const auto chains = iso_curve_outside_covered_faces([&](auto skip) { return oracle_.iso_curve_outside(rp, vertex_radius, skip); },
                                                        [&] { return oracle_.iso_curve(rp, vertex_radius); });
    const std::vector<face_descriptor>& disk_faces =
      faces_of_new_disk(loc, chains, [&](vertex_descriptor v, double d) { return d <= rp + radius_at(v); },
                        [&](vertex_descriptor v, double d) { return d < (rp + radius_at(v)) * keep; });

    const std::size_t id = samples_.size();
    update_boundary(chains, id, disk_faces,
      [&](const Face_location& x) {
        const auto d = oracle_.distance(x);
        return d && *d < (rp + radius_at(x)) * keep;
      },
      [&](const Face_location& x) { return covered_by_earlier_adaptive_samples(x); });
    mark_covered_faces();

    samples_.push_back({loc, p, kind, level, rp});
    grid_.insert(id, pc);
    return true;
  }

  // Faces inside the union of the disks. A face that holds no arc of the available boundary -- the
  // boundary of that union -- lies either wholly inside the union or wholly outside it (its points
  // are joined within it without meeting the boundary); with a point inside a disk, it is inside,
  // and stays so as disks are added. A new iso-curve's arcs in such a face all lie in earlier
  // disks and would be dropped: the oracle does not make them (extracting the arcs is the largest
  // share of a sample's work, and much of a new curve lies in such faces), and the boundary
  // is told where a chain breaks at one, so that the run it ends is known to be inside. Arcs
  // shorter than the boundary's minimum length are not stored, so a face is counted inside within
  // that length, as the boundary already counts it.
  static constexpr bool skips_covered_faces =
    internal::Skips_covered_faces<GeodesicOracle, Boundary, face_descriptor, vertex_descriptor, Face_location>::value;

  // covered_'s values: not known to be covered, covered, never to be taken as covered (a face one
  // of whose arcs gave no usable point, fill())
  enum : char { not_covered = 0, covered = 1, never_covered = 2 };

  bool is_covered(face_descriptor f) const { return !covered_.empty() && covered_[get(fim_, f)] == covered; }

  // an arc of face f was dropped (fill()): f is never taken as covered
  void never_cover(face_descriptor f)
  {
    if(!covered_.empty()) covered_[get(fim_, f)] = never_covered;
  }

  // whether face f is too thin for its arcs to be stored surely (its height under 1e-9 of its
  // longest edge): its lack of arcs would tell nothing, and the arcs of its neighbours' curves
  // through it may give no usable point (they are dropped in fill()); on a mesh with such a face
  // the covered faces are not skipped (poisson_remesh() removes zero-area faces first)
  bool nearly_flat(face_descriptor f) const
  {
    const auto h = halfedge(f, tm_);
    const std::array<double, 3> a = coords(get(vpm_, source(h, tm_))), b = coords(get(vpm_, target(h, tm_))),
                                c = coords(get(vpm_, target(next(h, tm_), tm_)));
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
                 x[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double area2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];   // (twice the area, squared)
    const double longest = (std::max)({u[0] * u[0] + u[1] * u[1] + u[2] * u[2], w[0] * w[0] + w[1] * w[1] + w[2] * w[2],
                                       x[0] * x[0] + x[1] * x[1] + x[2] * x[2]});
    // (the height is twice the area over the longest edge)
    return !(area2 > 1e-18 * longest * longest);
  }

  // the new iso-curve: `outside(skip)` without the covered faces, or `whole()` when they are not
  // skipped
  template <class Outside, class Whole>
  auto iso_curve_outside_covered_faces(Outside outside, Whole whole)
  {
    if constexpr(skips_covered_faces) {
      if(skip_covered_ && covered_.empty()) {
        // (a mesh with nearly zero-area faces: every arc is made, see nearly_flat())
        for(face_descriptor f : faces(tm_))
          if(nearly_flat(f)) { skip_covered_ = false; break; }
        if(skip_covered_) covered_.assign(internal::index_bound(faces(tm_), fim_), not_covered);
      }
      if(skip_covered_) return outside([this](face_descriptor f) { return is_covered(f); });
    }
    return whole();
  }

  // the boundary's update, told where the chains break at covered faces
  template <class Chains, class FaceRange, class InNewDisk, class InOldDisks>
  void update_boundary(const Chains& chains, std::size_t id, const FaceRange& faces, InNewDisk in_new_disk, InOldDisks in_old_disks)
  {
    if constexpr(skips_covered_faces) {
      if(skip_covered_) {
        boundary_.update(chains, id, faces, in_new_disk, in_old_disks,
                         [&](const Arc& a, bool at_end) { return breaks_at_covered_face(a, at_end); });
        return;
      }
    }
    boundary_.update(chains, id, faces, in_new_disk, in_old_disks);
  }

  // whether the start (`at_end` false) or end of arc `a` lies on an edge whose other face is covered
  // (a barycentric coordinate within 1e-9 of 0: on the edge opposite that vertex)
  bool breaks_at_covered_face(const Arc& a, bool at_end) const
  {
    const std::array<double, 3> b = a.barycentric(at_end ? 1.0 : 0.0);
    const auto h0 = halfedge(a.face, tm_);
    // (the face's vertices are source(h0), target(h0), target(next(h0)); the edge opposite vertex i is
    // the halfedge after the one that starts at it)
    const typename GT::halfedge_descriptor opposite_edge[3] = {next(h0, tm_), prev(h0, tm_), h0};
    for(int i = 0; i < 3; ++i) {
      if(!(b[i] <= 1e-9)) continue;   // (NaN: no end known)
      const auto o = opposite(opposite_edge[i], tm_);
      if(!is_border(o, tm_) && is_covered(face(o, tm_))) return true;
    }
    return false;
  }

  // whether an open curve begins and ends at covered faces (it was cut there, not left open)
  template <class Curve>
  bool breaks_at_covered_faces(const Curve& c) const
  {
    if constexpr(skips_covered_faces) return skip_covered_ && breaks_at_covered_face(c.arcs.front(), false) && breaks_at_covered_face(c.arcs.back(), true);
    else return false;
  }

  // after the update: the faces without arcs around the vertices the propagation reached strictly
  // inside the new disk (faces_of_new_disk() gathered them) are covered
  void mark_covered_faces()
  {
    if constexpr(skips_covered_faces)
      for(face_descriptor f : faces_to_mark_) {
        if(covered_[get(fim_, f)] != not_covered || boundary_.has_arcs_in(f)) continue;
        covered_[get(fim_, f)] = covered;
        ++stats_.covered_faces;
      }
  }

  // The faces the new disk meets, sorted: a face meeting it holds the sample, is crossed by its
  // iso-curve `chains`, or has a vertex inside it (a vertex v the propagation reached at distance
  // d with inside(v, d)); counts the open iso-curves on the way. When covered faces are skipped,
  // the faces around the vertices strictly inside (`strictly_inside(v, d)`) are kept for
  // mark_covered_faces().
  template <class Chains, class Inside, class StrictlyInside>
  const std::vector<face_descriptor>& faces_of_new_disk(const Face_location& loc, const Chains& chains, Inside inside,
                                                        StrictlyInside strictly_inside)
  {
    std::vector<face_descriptor>& faces = disk_faces_;
    faces.assign(1, loc.first);
    faces_to_mark_.clear();
    const bool marking = skips_covered_faces && skip_covered_ && !covered_.empty();
    for(const auto& curve : chains) {
      if(!curve.closed && !curve.arcs.empty() && !touches_border(curve) && !breaks_at_covered_faces(curve)) ++stats_.open_iso_curves;
      for(const Arc& a : curve.arcs) faces.push_back(a.face);
    }
    oracle_.reached_vertices(boost::make_function_output_iterator([&](const std::pair<vertex_descriptor, double>& vd) {
      if(!inside(vd.first, vd.second)) return;
      const bool mark = marking && strictly_inside(vd.first, vd.second);
      for(face_descriptor f : CGAL::faces_around_target(halfedge(vd.first, tm_), tm_))
        if(f != GT::null_face()) {
          faces.push_back(f);
          if(mark) faces_to_mark_.push_back(f);
        }
    }));
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
  }

  bool covered_by_earlier_adaptive_samples(const Face_location& x)
  {
    const double rx = radius_at(x), keep = 1 - separation_tolerance;
    const Point_3 px = CGAL::Polygon_mesh_processing::construct_point(x, tm_, CGAL::parameters::vertex_point_map(vpm_));
    const std::array<double, 3> xc = coords(px);
    std::vector<std::size_t>& near = near_;
    near.clear();
    double reach = 0;
    grid_.for_each_near(xc, [&](std::size_t id) {
      const std::array<double, 3> s = coords(samples_[id].point);
      const double d2 = (s[0] - xc[0]) * (s[0] - xc[0]) + (s[1] - xc[1]) * (s[1] - xc[1]) + (s[2] - xc[2]) * (s[2] - xc[2]);
      const double lim = (rx + samples_[id].radius) * keep;
      if(d2 < lim * lim) { near.push_back(id); reach = std::max(reach, lim); }
    });
    if(near.empty()) return false;
    classifier_.propagate(x, reach);
    ++stats_.classification_propagations;
    for(std::size_t id : near) {
      const auto d = classifier_.distance(samples_[id].location);
      if(d && *d < (rx + samples_[id].radius) * keep) return true;
    }
    return false;
  }

  // Is x closer than `inside` to an earlier sample? Only samples within Euclidean distance
  // `inside` can be (geodesic >= Euclidean); the exact test propagates from x.
  bool covered_by_earlier_samples(const Face_location& x, double inside)
  {
    const Point_3 px = CGAL::Polygon_mesh_processing::construct_point(x, tm_, CGAL::parameters::vertex_point_map(vpm_));
    const std::array<double, 3> xc = coords(px);
    std::vector<std::size_t>& near = near_;
    near.clear();
    grid_.for_each_near(xc, [&](std::size_t id) {
      const std::array<double, 3> s = coords(samples_[id].point);
      const double d2 = (s[0] - xc[0]) * (s[0] - xc[0]) + (s[1] - xc[1]) * (s[1] - xc[1]) + (s[2] - xc[2]) * (s[2] - xc[2]);
      if(d2 < inside * inside) near.push_back(id);
    });
    if(near.empty()) return false;
    classifier_.propagate(x, inside);
    ++stats_.classification_propagations;
    for(std::size_t id : near) {
      const auto d = classifier_.distance(samples_[id].location);
      if(d && *d < inside) return true;
    }
    return false;
  }

  template <class Curve>
  bool touches_border(const Curve& c) const
  {
    for(const Arc& a : c.arcs)
      for(auto h : CGAL::halfedges_around_face(halfedge(a.face, tm_), tm_))
        if(is_border(opposite(h, tm_), tm_)) return true;
    return false;
  }

  const TriangleMesh& tm_;
  VertexPointMap vpm_;
  // the index map is fetched once: radius_at() runs for every reached vertex and boundary test
  typename CGAL::GetInitializedVertexIndexMap<TriangleMesh>::const_type vim_;
  GeodesicOracle oracle_, classifier_;
  Boundary boundary_;
  std::mt19937_64 rng_;
  internal::Point_grid grid_;
  std::vector<Sample> samples_;
  std::vector<face_descriptor> disk_faces_;   // (the faces a new disk meets; kept to reuse its storage)
  std::vector<std::size_t> near_;   // (the samples near a point of a new curve; kept likewise)
  std::vector<double> vertex_radius_;   // adaptive density: radius per vertex (by vertex index)
  typename CGAL::GetInitializedFaceIndexMap<TriangleMesh>::const_type fim_;
  std::vector<char> covered_;   // by face index: inside the union of the disks (is_covered()); empty until the first sample
  std::vector<face_descriptor> faces_to_mark_;   // (faces_of_new_disk() for mark_covered_faces(); kept to reuse its storage)
  bool skip_covered_ = true;
  Sampling_statistics stats_;
  double r_ = 0;
  unsigned int level_ = 0;
};

} // namespace Poisson_remesh

#endif // POISSON_REMESH_SAMPLING_BOUNDARY_SAMPLER_H
