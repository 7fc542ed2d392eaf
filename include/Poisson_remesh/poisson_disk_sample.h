// Poisson_remesh/poisson_disk_sample.h
//
// Entry points: poisson_disk_sample(mesh, out, np) and poisson_disk_sample_levels(mesh, radii, out, np)
// -- a maximal geodesic Poisson-disk set on a triangle surface (paper §4), usable alone for object
// distribution on surfaces, or as the vertices of a remesh; and progressive levels of detail (§8).
// Features are sampled first (§4.2.4): corners, then feature curves at even intervals no shorter
// than 2r, then the surface by boundary sampling (Boundary_sampler).

#ifndef POISSON_REMESH_POISSON_DISK_SAMPLE_H
#define POISSON_REMESH_POISSON_DISK_SAMPLE_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Sampling/Boundary_sampler.h>
#include <Poisson_remesh/Sampling/internal/slab_sampling.h>
#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/parameters.h>
#include <Poisson_remesh/progress.h>
#include <Poisson_remesh/sizing.h>

#include <CGAL/Polygon_mesh_processing/measure.h>

#include <functional>
#include <optional>
#include <stdexcept>
#include <vector>

namespace Poisson_remesh {

/// What a sampling run did.
struct Poisson_disk_sampling_result
{
  double radius = 0;                 ///< r: samples are at least 2r apart (geodesic); adaptive: the median disk radius
  /// the range of the disk radius (equal to r for uniform density)
  /// @{
  double min_radius = 0, max_radius = 0;
  /// @}
  std::size_t number_of_samples = 0;  ///< all samples (corners and feature samples included)
  std::size_t number_of_corners = 0;  ///< samples at corners
  std::size_t number_of_feature_samples = 0;  ///< (poisson_remesh(): without those of the dropped curves)
  Sampling_statistics statistics;     ///< the sampler's counters
};

/// The default `minimum_feature_length` of the sampler and the remesher, in sampling radii r:
/// a dangling crease shorter than two sample spacings (4r) is noise at the scale of the output.
constexpr double feature_length_in_radii = 4.0;

namespace internal {

// r from the named parameters: sampling_radius, else target_edge_length (spacing 2r = edge
// length), else target_vertex_count through Eq. 1 (rho = 0.844), else the input's vertex count.
template <class TriangleMesh, class VPM, class NamedParameters>
double sampling_radius_from_parameters(const TriangleMesh& tm, VPM vpm, const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const double r = choose_parameter(get_parameter(np, internal_np::sampling_radius), 0.0);
  if(r > 0) return r;
  const double l = choose_parameter(get_parameter(np, internal_np::target_edge_length), 0.0);
  if(l > 0) return 0.5 * l;
  double n = double(choose_parameter(get_parameter(np, internal_np::target_vertex_count), 0));
  if(!(n > 0)) n = double(vertices(tm).size());
  const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(tm, CGAL::parameters::vertex_point_map(vpm)));
  return disk_radius_from_vertex_count(area, n);
}

// the features as the sampler sees them at radius r: detect_features() with
// `minimum_feature_length` defaulting to feature_length_in_radii * r
template <class TriangleMesh, class NamedParameters>
Feature_set<TriangleMesh> detect_features_at_radius(const TriangleMesh& tm, double r, const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const double length = choose_parameter(get_parameter(np, internal_np::minimum_feature_length), feature_length_in_radii * r);
  return detect_features(tm, Named_function_parameters<double, internal_np::minimum_feature_length_t, NamedParameters>(length, np));
}

// the disk radius at each vertex for the `density` named parameter; empty for uniform density.
// The field is scaled to the target vertex count (target_vertex_count, else the count that
// target_edge_length or sampling_radius gives with uniform density, else the input's count).
template <class TriangleMesh, class VPM, class NamedParameters>
std::vector<double> vertex_radii_from_parameters(const TriangleMesh& tm, VPM vpm, const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const auto density = choose_parameter(get_parameter(np, internal_np::density), Uniform_density());
  if constexpr(is_uniform_density<decltype(density)>::value) {
    return {};
  } else {
    const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(tm, CGAL::parameters::vertex_point_map(vpm)));
    double n = double(choose_parameter(get_parameter(np, internal_np::target_vertex_count), 0));
    if(!(n > 0)) {
      const double r = sampling_radius_from_parameters(tm, vpm, np);
      n = paper_rho * paper_rho * area / (2 * std::sqrt(3.0) * r * r);   // Eq. 1 solved for N
    }
    if constexpr(std::is_same<typename std::decay<decltype(density)>::type, Curvature_density>::value) {
      // the feature edges that are no border: the remesh keeps them, the curvature density is
      // measured beside them (Curvature_density::beside_creases); found as the sampler finds
      // them, at the radius of the uniform density (the adaptive one's median is not known yet)
      std::optional<Feature_set<TriangleMesh>> features;
      if(density.beside_creases) features.emplace(detect_features_at_radius(tm, sampling_radius_from_parameters(tm, vpm, np), np));
      const auto creases = boost::make_function_property_map<typename boost::graph_traits<TriangleMesh>::edge_descriptor>(
        [&](typename boost::graph_traits<TriangleMesh>::edge_descriptor e) { return features && features->is_feature(e) && !is_border(e, tm); });
      return vertex_disk_radii(tm, vpm, vertex_densities(density, tm, vpm, creases), n, density.min_edge, density.max_edge);
    } else {
      return vertex_disk_radii(tm, vpm, vertex_densities(density, tm, vpm), n);
    }
  }
}


// A feature curve whose samples are refused -- closer than the spacing to an earlier sample --
// this many times in a row runs beside another curve (the corners and the curve's own samples
// cannot refuse three in a row, but a tip's disk or a hairpin turn could): the output cannot keep
// both at this spacing (the triangles between them would be slivers, and the curve's output edge
// would span the whole run). The remesher drops such a curve, whole, from the features
// (sample_features()); its samples stay, as surface samples. A curve of fewer than three
// planned samples is never dropped.
constexpr std::size_t crowded_curve_run = 3;

// corners, then the samples along the curves (§4.2.4). With `crowded`, the (non-border) curves
// with crowded_curve_run refused samples in a row are appended to it, and the indices (in the
// sampler's order) of the samples of those curves that were taken to `crowded_samples`.
template <class Sampler, class TriangleMesh, class VPM>
void sample_features(Sampler& sampler, const TriangleMesh& tm, VPM vpm, const Feature_set<TriangleMesh>& fs,
                     bool first_level, Poisson_disk_sampling_result& result,
                     std::vector<std::size_t>* crowded = nullptr, std::vector<std::size_t>* crowded_samples = nullptr)
{
  for(auto v : fs.corners) {
    // a location of the corner in one of its faces
    auto h = halfedge(v, tm);
    if(is_border(h, tm)) h = prev(opposite(h, tm), tm);
    // corners are always kept; on a finer level they are already there and are refused
    if(sampler.insert(location_on_halfedge(h, 1.0, tm), Sample_kind::corner, !first_level)) ++result.number_of_corners;
  }
  const auto locations = sampler.adaptive()
    ? feature_sample_locations_with_spacing(tm, vpm, fs, [&](auto v) { return 2 * sampler.radius_at(v); })
    : feature_sample_locations(tm, vpm, fs, 2 * sampler.radius());
  // (the locations come curve by curve)
  std::size_t run = 0, longest = 0;
  std::vector<std::size_t> taken;
  for(std::size_t i = 0; i < locations.size(); ++i) {
    const auto& s = locations[i];
    if(sampler.insert(s.location, Sample_kind::feature, true)) {
      ++result.number_of_feature_samples;
      taken.push_back(sampler.samples().size() - 1);
      run = 0;
    } else {
      longest = std::max(longest, ++run);
    }
    if(i + 1 == locations.size() || locations[i + 1].curve != s.curve) {
      if(crowded && longest >= crowded_curve_run && !fs.curves[s.curve].border) {
        crowded->push_back(s.curve);
        if(crowded_samples) crowded_samples->insert(crowded_samples->end(), taken.begin(), taken.end());
      }
      run = longest = 0;
      taken.clear();
    }
  }
}

// drops the curves `which` (indices in fs.curves) from the features: their edges are no feature
// edges any more; the corners stay corners
template <class TriangleMesh>
void drop_feature_curves(Feature_set<TriangleMesh>& fs, std::vector<std::size_t> which, const TriangleMesh& tm)
{
  std::sort(which.begin(), which.end());
  which.erase(std::unique(which.begin(), which.end()), which.end());
  for(auto it = which.rbegin(); it != which.rend(); ++it) {
    for(auto h : fs.curves[*it].halfedges) {
      const std::size_t e = std::size_t(get(fs.eim, edge(h, tm)));
      if(fs.feature_edge[e]) { fs.feature_edge[e] = false; --fs.number_of_feature_edges; }
    }
    fs.curves.erase(fs.curves.begin() + std::ptrdiff_t(*it));
  }
}

// A named parameter left at its default (`sampler`, `relaxer`, `geodesic_oracle`): the package's
// own model runs. model_pointer(v), v = get_parameter(np, tag) kept alive: the user's model (the
// object itself when CGAL keeps it as a std::reference_wrapper: one it cannot copy, a std::ref), or
// a null Default_model pointer.
struct Default_model {};
inline const Default_model* model_pointer(const CGAL::internal_np::Param_not_found&) { return nullptr; }
template <class T> const T* model_pointer(const T& t) { return &t; }
template <class T> T* model_pointer(const std::reference_wrapper<T>& t) { return &t.get(); }

// f(oracle) with the user's geodesic oracle (a model of GeodesicOracle built on tm), else with an
// Exact_geodesic_oracle on tm
template <class TriangleMesh, class VPM, class Oracle, class F>
decltype(auto) with_geodesic_oracle(const TriangleMesh& tm, VPM vpm, const Oracle* oracle, F f)
{
  if constexpr(std::is_same<Oracle, Default_model>::value)
    return f(Exact_geodesic_oracle<TriangleMesh, VPM>(tm, vpm));
  else
    return f(*oracle);
}

// the same with the oracle of the named parameters (`geodesic_oracle`)
template <class TriangleMesh, class VPM, class NamedParameters, class F>
decltype(auto) with_geodesic_oracle(const TriangleMesh& tm, VPM vpm, const NamedParameters& np, F f)
{
  const auto oracle = parameters::get_parameter(np, internal_np::geodesic_oracle);
  return with_geodesic_oracle(tm, vpm, model_pointer(oracle), f);
}

// poisson_disk_sample() with the features already detected (the remesher shares them with the
// tessellation)
// (vertex_radii not empty: adaptive density, the disk radius at each vertex by vertex index;
// `radius` is then their median)
// (ConcurrencyTag: with CGAL::Parallel_tag and the default oracle, the surface fills by slabs in
// parallel, Sampling/internal/slab_sampling.h, when it is long enough to cut)
template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleMesh, class VPM, class OutputIterator,
          class GeodesicOracle = Exact_geodesic_oracle<TriangleMesh, VPM>>
Poisson_disk_sampling_result poisson_disk_sample(const TriangleMesh& tm, VPM vpm, const Feature_set<TriangleMesh>& fs,
                                                 double radius, unsigned int seed, OutputIterator out,
                                                 const std::vector<double>& vertex_radii = std::vector<double>(),
                                                 std::vector<std::size_t>* crowded_curves = nullptr,
                                                 Progress_reporter* progress = nullptr,
                                                 const GeodesicOracle* oracle = nullptr)
{
  Poisson_disk_sampling_result result;
  result.radius = result.min_radius = result.max_radius = radius;
  Boundary_sampler<TriangleMesh, VPM, GeodesicOracle> sampler(tm, vpm, seed, oracle ? *oracle : GeodesicOracle(tm, vpm));
  if(vertex_radii.empty()) {
    sampler.set_radius(result.radius);
  } else {
    auto vim = CGAL::get_initialized_vertex_index_map(tm);
    sampler.set_radius_field([&](typename boost::graph_traits<TriangleMesh>::vertex_descriptor v) { return vertex_radii[get(vim, v)]; });
    result.min_radius = *std::min_element(vertex_radii.begin(), vertex_radii.end());
    result.max_radius = *std::max_element(vertex_radii.begin(), vertex_radii.end());
  }
  std::vector<std::size_t> crowded_samples;
  internal::sample_features(sampler, tm, vpm, fs, true, result, crowded_curves, &crowded_samples);
  sampler.seed_components();
  const bool report = progress != nullptr && progress->active();
  std::size_t expected = 0;
  if(report) {
    // the count Eq. 1 expects at the median radius (adaptive: roughly)
    const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(tm, CGAL::parameters::vertex_point_map(vpm)));
    expected = std::size_t(paper_rho * paper_rho * area / (2 * std::sqrt(3.0) * radius * radius)) + 1;
    (*progress)("sampling", sampler.samples().size(), expected);
  }
  auto on_sample = [&](std::size_t n) { if(report) (*progress)("sampling", n, expected); };
  // (the samples: the sampler's, or those of the slabs in parallel mode)
  std::vector<typename decltype(sampler)::Sample> by_slabs;
  const auto* all = &sampler.samples();
  result.statistics = sampler.statistics();
  if constexpr(is_parallel<ConcurrencyTag>() && std::is_same<GeodesicOracle, Exact_geodesic_oracle<TriangleMesh, VPM>>::value) {
    by_slabs = sampler.samples();
    if(fill_by_slabs<ConcurrencyTag>(tm, vpm, radius, vertex_radii, seed, by_slabs, result.statistics, on_sample)) all = &by_slabs;
  }
  if(all != &by_slabs) {
    sampler.fill(on_sample);
    result.statistics = sampler.statistics();
  }
  const auto& samples = *all;
  // the samples of crowded curves are surface samples (the caller drops those curves)
  std::sort(crowded_samples.begin(), crowded_samples.end());
  for(std::size_t i = 0; i < samples.size(); ++i) {
    auto s = samples[i];
    if(std::binary_search(crowded_samples.begin(), crowded_samples.end(), i)) { s.kind = Sample_kind::surface; --result.number_of_feature_samples; }
    *out++ = s;
  }
  result.number_of_samples = samples.size();
  return result;
}


} // namespace internal

/*!
  The default model of the `Sampler` concept of poisson_remesh() (named parameter `sampler`):
  geodesic Poisson-disk boundary sampling (§4, §5), the features first -- what
  poisson_disk_sample() does, on features already detected and with the disk radius given.
*/
struct Poisson_disk_sampler
{
  /// writes to `out` the samples (`Poisson_sample<TriangleMesh, Point_3>`) of `tm` read through
  /// `vpm`: the corners and feature-curve points of `features` first, then a maximal set at
  /// disk radius `radius` (or, when `vertex_radii` is not empty, at the radius `vertex_radii[i]`
  /// at the vertex of index i of `CGAL::get_initialized_vertex_index_map(tm)`), drawn from `seed`
  template <class TriangleMesh, class VertexPointMap, class OutputIterator>
  Poisson_disk_sampling_result operator()(const TriangleMesh& tm, VertexPointMap vpm, const Feature_set<TriangleMesh>& features,
                                          double radius, const std::vector<double>& vertex_radii, unsigned int seed,
                                          OutputIterator out) const
  {
    return internal::poisson_disk_sample(tm, vpm, features, radius, seed, out, vertex_radii);
  }
};

/*!
  The disk radius at each vertex of `tm` (indexed by `CGAL::get_initialized_vertex_index_map(tm)`)
  that poisson_disk_sample() and poisson_remesh() sample with for the named parameters `np`: the
  size (`sampling_radius`, `target_edge_length`, `target_vertex_count`), the `density` field
  scaled to that size by Eq. 1 (a Curvature_density measured beside the feature edges that the
  feature parameters give), and `vertex_point_map`; the same radius everywhere for a uniform
  density. (poisson_remesh() may then lower it around pointed tips and where a remake is asked.)
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
std::vector<double> disk_radii(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  std::vector<double> radii = internal::vertex_radii_from_parameters(tm, vpm, np);
  if(radii.empty()) radii.assign(internal::vertex_index_bound(tm), internal::sampling_radius_from_parameters(tm, vpm, np));
  return radii;
}

/*!
  computes a maximal geodesic Poisson-disk sample set of `tm` (a triangle mesh, any FaceGraph)
  and writes its `Poisson_sample`s (location, point, kind) to `out`.

  Named parameters (all optional):
  - size, first given wins: `sampling_radius` (r), `target_edge_length` (2r), `target_vertex_count`
    (r from Eq. 1 with rho = 0.844); default: the input's vertex count
  - `density` (default Uniform_density()): Curvature_density{...}, vertex_density(map) or
    point_density(function) for adaptive sampling (§5): samples p, q at least r(p) + r(q) apart,
    the field scaled to the target vertex count (see density_fields.h)
  - `random_seed` (CGAL, default 0): the same seed gives the same samples
  - features: `feature_policy` (default Feature_policy::detect), `sharp_angle` (60),
    `corner_angle` (60), `minimum_feature_length` (default feature_length_in_radii * r),
    `edge_is_constrained_map` (CGAL; implies Feature_policy::user_map)
  - `vertex_point_map` (CGAL)
  - `geodesic_oracle`: a model of `GeodesicOracle` built on `tm` and read through the same point
    map (default: an `Exact_geodesic_oracle`); the sampler works on a copy of it
  - `progress` (a callable `bool(const Progress&)`) and `callback` (CGAL; `bool(double)`): told
    how far the sampling is; returning false stops it with Cancelled (progress.h); in parallel
    mode the counts come after each phase of the slabs

  `ConcurrencyTag`: CGAL::Sequential_tag (the default), or CGAL::Parallel_tag (needs TBB) /
  CGAL::Parallel_if_available_tag: the surface is cut into four slabs across its longest side
  (large, thin, large, thin), or three where four do not fit (large, thin, large), which fill on
  TBB's threads in two phases, each slab once: the large ones at once, then the thin ones
  (`Poisson_disk_sampling_result::statistics.slabs` tells how many). The set is as maximal and as
  separated as the sequential one, but another one, the same for any number of
  threads. A surface too short for three slabs at its sampling radius (fewer than about 25
  spacings along its longest side), or a user's `geodesic_oracle`, is sampled sequentially.
*/
template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleMesh, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
Poisson_disk_sampling_result poisson_disk_sample(const TriangleMesh& tm, OutputIterator out,
                                                 const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  const unsigned int seed = choose_parameter(get_parameter(np, CGAL::internal_np::random_seed), 0u);
  if(faces(tm).empty()) throw std::invalid_argument("poisson_disk_sample: the mesh has no faces");

  const std::vector<double> vertex_radii = internal::vertex_radii_from_parameters(tm, vpm, np);
  const double radius = vertex_radii.empty() ? internal::sampling_radius_from_parameters(tm, vpm, np)
                                             : internal::quantile(vertex_radii, 0.5);
  internal::Progress_reporter progress(np);
  progress("features", 0, 1);
  const Feature_set<TriangleMesh> features = internal::detect_features_at_radius(tm, radius, np);
  progress.set_span(0.05, 1.0);
  return internal::with_geodesic_oracle(tm, vpm, np, [&](const auto& oracle) {
    return internal::poisson_disk_sample<ConcurrencyTag>(tm, vpm, features, radius, seed, out, vertex_radii, nullptr, &progress, &oracle);
  });
}


/*!
  progressive multi-level sampling (§8): one maximal set per radius of `radii` (decreasing), each
  containing all samples of the coarser ones. Writes every sample once, with `level` = the index
  of the radius that added it; the samples of level k and below form the set at radius radii[k].
  Named parameters as poisson_disk_sample() (the size parameters are ignored).
*/
template <class TriangleMesh, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
std::vector<Poisson_disk_sampling_result>
poisson_disk_sample_levels(const TriangleMesh& tm, const std::vector<double>& radii, OutputIterator out,
                           const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  const unsigned int seed = choose_parameter(get_parameter(np, CGAL::internal_np::random_seed), 0u);
  for(std::size_t i = 0; i < radii.size(); ++i)
    if(!(radii[i] > 0) || (i > 0 && radii[i] >= radii[i - 1]))
      throw std::invalid_argument("poisson_disk_sample_levels: radii must be positive and decreasing");

  std::vector<Poisson_disk_sampling_result> results;
  Boundary_sampler<TriangleMesh, decltype(vpm)> sampler(tm, vpm, seed);
  // one feature set for every level (judged at the coarsest radius), so that the corners and
  // curves of a level are those of the levels below
  const Feature_set<TriangleMesh> features = radii.empty() ? Feature_set<TriangleMesh>() : internal::detect_features_at_radius(tm, radii.front(), np);
  for(double r : radii) {
    Poisson_disk_sampling_result result;
    result.radius = r;
    sampler.set_radius(r);
    internal::sample_features(sampler, tm, vpm, features, results.empty(), result);
    sampler.seed_components();
    sampler.fill();
    result.number_of_samples = sampler.samples().size();
    result.statistics = sampler.statistics();
    results.push_back(result);
  }
  for(const auto& s : sampler.samples()) *out++ = s;
  return results;
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POISSON_DISK_SAMPLE_H
