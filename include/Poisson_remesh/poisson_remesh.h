// Poisson_remesh/poisson_remesh.h
//
// Entry point: poisson_remesh(input, output, np) -- the whole method of the paper:
//   detect_features (§3) -> poisson_disk_sample (§4, features first) -> mutual_tessellation (§6.1)
//   -> Lloyd_relaxer::relax (§6.2 local Lloyd with projection onto the input, Delaunay flips,
//   §6.3 connectivity flips).
// The output's vertices are the samples (moved by the relaxation, always on the input surface);
// the output keeps the input's topology (input vertices that the tessellation could not remove
// are reported, never silently kept).

#ifndef POISSON_REMESH_POISSON_REMESH_H
#define POISSON_REMESH_POISSON_REMESH_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Relaxation/Lloyd_relaxer.h>
#include <Poisson_remesh/Tessellation/mutual_tessellation.h>
#include <Poisson_remesh/internal/feature_grading.h>
#include <Poisson_remesh/internal/repair_degenerate_faces.h>
#include <Poisson_remesh/internal/local_remake.h>
#include <Poisson_remesh/internal/parallel.h>
#include <Poisson_remesh/internal/regrading.h>
#include <Poisson_remesh/parameters.h>
#include <Poisson_remesh/poisson_disk_sample.h>
#include <Poisson_remesh/progress.h>

#include <Poisson_remesh/internal/feature_curves.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Kernel_traits.h>
#include <boost/property_map/function_property_map.hpp>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {

namespace internal {
// the relaxer's collapses and removals leave removed elements in a Surface_mesh (its BGL
// num_vertices() and friends count them, and its indices have gaps); the output has none
template <class Mesh> void collect_garbage(Mesh&) {}
template <class P> void collect_garbage(CGAL::Surface_mesh<P>& m) { m.collect_garbage(); }
} // namespace internal

/// What poisson_remesh() did, stage by stage.
struct Poisson_remesh_result
{
  Poisson_disk_sampling_result sampling;   ///< the sampling's counts (of the kept attempt)
  /// zero-area input faces removed before remeshing (on a copy of the input), and the vertices
  /// that their removal left pinched, split (0 with `strict_input`, which refuses such input)
  /// @{
  std::size_t number_of_repaired_faces = 0, number_of_split_vertices = 0;
  /// @}
  std::size_t number_of_leftover_input_vertices = 0;  ///< input vertices the tessellation could not remove
  std::size_t number_of_merged_samples = 0;  ///< samples on the vertex of another (nearly zero-area input faces)
  std::size_t number_of_graded_tips = 0;     ///< pointed tips sampled finer (`feature_grading`)
  /// feature curves not kept: closer than a spacing beside another curve for several spacings,
  /// their samples were refused (internal::crowded_curve_run in a row)
  std::size_t number_of_dropped_feature_curves = 0;
  /// remeshes made again, finer where the last one crossed itself or kept triangles under 30
  /// degrees (`regrading_attempts`, internal/regrading.h)
  unsigned int number_of_regrading_attempts = 0;
  /// in the output (the best attempt; also measured without remakes): face pairs that cut each
  /// other away from the input's own crossings, triangles under 30 degrees at no pointed tip, and
  /// the smallest angle away from the input's corners whose own angle is smaller (degrees, as
  /// quality_report() measures it with its default sharp angle, 60)
  /// @{
  std::size_t crossing_pairs_left = 0, sharp_triangles_left = 0;
  double min_angle_away_from_corners = 180;
  /// @}
  Relaxation_statistics relaxation;   ///< what the relaxation did (of the kept attempt)
  /// the time of each stage in seconds, summed over the remakes (the relaxation's includes their
  /// checks and copies; the tessellation's, the construction of the relaxer's search structures on
  /// the input, which runs beside it in the parallel mode)
  /// @{
  double seconds_features = 0, seconds_sampling = 0, seconds_tessellation = 0, seconds_relaxation = 0;
  /// @}
  /// the default relaxer's time by step, summed over the remakes (part of seconds_relaxation, which
  /// adds the remakes' checks and copies)
  Relaxation_times seconds_by_step;
  /// the time of the whole run in seconds
  double seconds() const { return seconds_features + seconds_sampling + seconds_tessellation + seconds_relaxation; }
};

namespace internal {

// The closest point of the input's feature curves, or of its surface when it has none, as
// Lloyd_relaxer::project_on_features() gives it: the remesher's own when a user's relaxer runs.
template <class TriangleMesh, class K>
class Feature_projector
{
  typedef typename K::Point_3 Point_3;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<TriangleMesh>>> Face_tree;

public:
  // (`tm` read through its own point map)
  Feature_projector(const TriangleMesh& tm, const Feature_set<TriangleMesh>& features) : curves_(tm, features)
  {
    if(!curves_.empty()) return;
    faces_.insert(faces(tm).first, faces(tm).second, tm);
    faces_.do_not_accelerate_distance_queries();   // (internal/closest_point.h needs no k-d tree)
  }
  Point_3 project(const Point_3& p) const { return curves_.empty() ? internal::closest_point(faces_, p) : curves_.closest_point(p); }
  // the same when it is closer to p than `start` (any point), else `start`
  Point_3 project(const Point_3& p, const Point_3& start) const
  {
    return curves_.empty() ? internal::closest_point(faces_, p, start) : curves_.closest_point(p, start);
  }

private:
  Feature_curves<K> curves_;
  Face_tree faces_;
};

// What the stages take from the named parameters, read once by read_remesh_options(): the
// pipeline below is compiled once per mesh type and choice of models, not once per combination
// of named parameters (each of which is a type of its own).
template <class TriangleMesh>
struct Remesh_options
{
  std::vector<double> vertex_radii;   // the disk radius at each vertex (adaptive density); empty: uniform
  double radius = 0;                  // the disk radius (adaptive: the median of vertex_radii)
  Feature_set<TriangleMesh> features;
  bool feature_grading = true;
  unsigned int regrading_attempts = 0;
  bool local_remakes = false;
  unsigned int seed = 0;
  Relaxation_settings settings;
  double seconds_features = 0;
};

template <class TriangleMesh, class VPM, class NamedParameters>
Remesh_options<TriangleMesh> read_remesh_options(const TriangleMesh& input, VPM in_vpm, const NamedParameters& np, Progress_reporter& progress)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using parameters::is_default_parameter;
  const auto start = std::chrono::steady_clock::now();
  Remesh_options<TriangleMesh> o;
  progress.set_span(0, 0.02);
  progress("features", 0, 1);
  o.vertex_radii = vertex_radii_from_parameters(input, in_vpm, np);
  o.radius = o.vertex_radii.empty() ? sampling_radius_from_parameters(input, in_vpm, np) : quantile(o.vertex_radii, 0.5);
  // one feature set for the sampler and the tessellation
  o.features = detect_features_at_radius(input, o.radius, np);
  o.feature_grading = choose_parameter(get_parameter(np, internal_np::feature_grading), true);
  // (the remakes, by default only for a uniform density and the default relaxer: an adaptive
  // density is the user's choice of where to be finer, a user's relaxer may not aim at 30
  // degrees, and a user's sampler may not follow the finer radii)
  const bool own_models = is_default_parameter<NamedParameters, internal_np::relaxer_t>::value &&
                          is_default_parameter<NamedParameters, internal_np::sampler_t>::value;
  o.regrading_attempts = choose_parameter(get_parameter(np, internal_np::regrading_attempts), o.vertex_radii.empty() && own_models ? 6u : 0u);
  o.local_remakes = own_models && choose_parameter(get_parameter(np, internal_np::local_remakes), false);
  o.seed = choose_parameter(get_parameter(np, CGAL::internal_np::random_seed), 0u);
  // (the operators' switches: Relaxation_settings' defaults unless given whole; the two named
  // parameters below override their members)
  o.settings = choose_parameter(get_parameter(np, internal_np::relaxation_settings), Relaxation_settings());
  o.settings.iterations = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), o.settings.iterations);
  o.settings.fidelity.max_deviation = choose_parameter(get_parameter(np, internal_np::fidelity_tolerance), o.settings.fidelity.max_deviation);
  if(!(o.settings.fidelity.max_deviation >= 0)) throw std::invalid_argument("poisson_remesh: fidelity_tolerance must be >= 0");
  o.seconds_features = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return o;
}

// poisson_remesh() on an input without zero-area faces, read through `in_vpm`, with the options
// read from the named parameters. Sampler, Relaxer, Oracle: the user's models, or Default_model
// (then the pointer is null). LocalRemakes: the local remakes are compiled in (only where the
// `local_remakes` named parameter is given: they instantiate the tessellation and the relaxation
// once more, for the patches).
template <class ConcurrencyTag, bool LocalRemakes, class TriangleMesh, class VPM, class Sampler, class Relaxer, class Oracle>
Poisson_remesh_result poisson_remesh_impl(const TriangleMesh& input, VPM in_vpm, TriangleMesh& output, const Remesh_options<TriangleMesh>& options,
                                          Progress_reporter& progress, const Sampler* user_sampler, Relaxer* user_relaxer, const Oracle* user_oracle)
{
  typedef typename boost::property_traits<VPM>::value_type Point_3;
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel K;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::edge_descriptor edge_descriptor;
  constexpr bool default_sampler = std::is_same<std::remove_const_t<Sampler>, Default_model>::value;
  constexpr bool default_relaxer = std::is_same<std::remove_const_t<Relaxer>, Default_model>::value;
  auto now = [] { return std::chrono::steady_clock::now(); };
  auto since = [&](std::chrono::steady_clock::time_point t) { return std::chrono::duration<double>(now() - t).count(); };
  // the geodesic oracle of the default sampler: the user's, or an exact one on the input
  auto with_oracle = [&](auto f) -> decltype(auto) { return internal::with_geodesic_oracle(input, in_vpm, user_oracle, f); };

  Poisson_remesh_result result;
  result.seconds_features = options.seconds_features;
  const std::vector<double>& vertex_radii = options.vertex_radii;
  const double radius = options.radius;
  const Feature_set<TriangleMesh>& detected_features = options.features;   // (the sampling drops crowded curves from its copy)
  Feature_set<TriangleMesh> features;   // (the attempt's)
  // uniform density: finer around pointed tips (internal/feature_grading.h; an adaptive density
  // is finer there already, and both together over-refine them)
  auto t = now();
  std::vector<double> radii =
      vertex_radii.empty() && options.feature_grading
        ? internal::feature_graded_radii(input, in_vpm, detected_features, radius, result.number_of_graded_tips)
        : vertex_radii;
  result.seconds_features += since(t);

  // (a posteriori) the remesh is made again, finer where its result still cuts itself or keeps
  // triangles under 30 degrees (internal/regrading.h); the best one is kept
  const unsigned int regrading_attempts = options.regrading_attempts;
  const internal::Regrading_settings regrading;
  const bool use_local_remakes = options.local_remakes;
  const internal::Local_remake_settings local_remake;
  std::optional<internal::Reference_crossings<TriangleMesh>> input_crossings;   // (found when first needed)
  const Poisson_remesh_result first = result;
  TriangleMesh best;
  Poisson_remesh_result best_result;
  internal::Regrading_places<Point_3> best_places;
  internal::Regrading_places<Point_3> previous_places;   // (of the attempt before)
  bool output_is_best = true;
  const unsigned int seed = options.seed;
  double seconds[3] = {0, 0, 0};   // sampling, tessellation, relaxation: of all attempts
  Relaxation_times seconds_by_step;
  unsigned int regraded = 0;
  std::size_t first_count = 0;   // (the first attempt's vertices)
  unsigned int attempts_without_gain = 0;   // (attempts in a row that did not beat the best)
  // the pointed tips (the last corners of the feature set)
  std::vector<Point_3> tips;
  for(std::size_t i = detected_features.corners.size() - detected_features.number_of_tips; i < detected_features.corners.size(); ++i)
    tips.push_back(get(in_vpm, detected_features.corners[i]));
  std::sort(tips.begin(), tips.end());
  for(unsigned int attempt = 0;; ++attempt) {
    result = first;
    features = detected_features;
    auto is_tip = [&](vertex_descriptor v) { return std::binary_search(tips.begin(), tips.end(), get(get(CGAL::vertex_point, output), v)); };
    t = now();
    std::vector<Poisson_sample<TriangleMesh, Point_3>> samples;
    std::vector<std::size_t> crowded;
    // (each attempt draws anew: a triangle left sharp at a corner is a matter of the draw)
    const unsigned int attempt_seed = seed + regrading.seed_step * attempt;
    // (the shares of the run, for CGAL's callback: sampling, tessellation, relaxation; each
    // remake spans the whole range again)
    progress.set_span(0.02, 0.3);
    if constexpr(default_sampler) {
      result.sampling = with_oracle([&](const auto& oracle) {
        return internal::poisson_disk_sample<ConcurrencyTag>(input, in_vpm, features, radius, attempt_seed, std::back_inserter(samples), radii, &crowded, &progress, &oracle);
      });
    } else {   // the user's model of the Sampler concept
      const Feature_set<TriangleMesh>& fs = features;
      result.sampling = (*user_sampler)(input, in_vpm, fs, radius, static_cast<const std::vector<double>&>(radii),
                                                                attempt_seed, std::back_inserter(samples));
      result.sampling.number_of_samples = samples.size();
    }
    // a feature curve that runs closer than a spacing beside another (its samples refused in a
    // row) is no feature of the output: its samples are surface samples already
    result.number_of_dropped_feature_curves = crowded.size();
    if(!crowded.empty()) internal::drop_feature_curves(features, crowded, input);
    seconds[0] += since(t);

    t = now();
    progress.set_span(0.3, 0.4);
    progress("tessellation", 0, 1);
    clear(output);
    // the default relaxer, or the projection onto the input's features it would give (a user's
    // relaxer): one of them is built, from the input and its features alone -- in the parallel
    // mode on another thread while the tessellation, which is sequential, runs
    std::optional<Lloyd_relaxer<TriangleMesh, K, ConcurrencyTag>> relaxer;
    std::optional<internal::Feature_projector<TriangleMesh, K>> projector;
    std::optional<decltype(mutual_tessellation<ConcurrencyTag>(input, samples, features, output, CGAL::parameters::vertex_point_map(in_vpm)))> tessellated;
    internal::run_beside<ConcurrencyTag>(
      [&] {
        if constexpr(default_relaxer) relaxer.emplace(input, features);
        else projector.emplace(input, features);
      },
      [&] { tessellated.emplace(mutual_tessellation<ConcurrencyTag>(input, samples, features, output, CGAL::parameters::vertex_point_map(in_vpm))); });
    const auto& tessellation = *tessellated;
    result.number_of_leftover_input_vertices = tessellation.leftover_vertices.size();
    result.number_of_merged_samples = tessellation.merged_samples.size();
    seconds[1] += since(t);

    t = now();
    // what each output vertex is: corner, feature or surface sample (leftover input vertices are fixed)
    // (a dynamic map: the relaxer may add feature vertices)
    auto kind_map = get(CGAL::dynamic_vertex_property_t<int>(), output);
    for(vertex_descriptor v : vertices(output)) put(kind_map, v, -1);
    for(const auto& v : tessellation.vertices)
      if(v.sample != tessellation.no_sample) put(kind_map, v.vertex, int(samples[v.sample].kind));
    auto kind = [&](vertex_descriptor v) { return get(kind_map, v); };
    auto project_on_features = [&](const Point_3& p) { return relaxer ? relaxer->project_on_features(p) : projector->project(p); };
    auto project_on_features_from = [&](const Point_3& p, const Point_3& start) {
      return relaxer ? relaxer->project_on_features(p, start) : projector->project(p, start);
    };
    progress.set_span(0.4, 1.0);
    auto point = [&](vertex_descriptor v) { return get(get(CGAL::vertex_point, output), v); };
    // an output feature edge joins two feature (or corner) samples along an input feature curve
    auto is_feature = [&](edge_descriptor e) {
      const vertex_descriptor a = source(halfedge(e, output), output), b = target(halfedge(e, output), output);
      const int ka = kind(a), kb = kind(b);
      if(ka != int(Sample_kind::corner) && ka != int(Sample_kind::feature)) return false;
      if(kb != int(Sample_kind::corner) && kb != int(Sample_kind::feature)) return false;
      const Point_3 mid = CGAL::midpoint(point(a), point(b));
      const double limit = 0.0025 * CGAL::to_double(CGAL::squared_distance(point(a), point(b)));
      // (only a closest point within sqrt(limit) of mid counts: the search starts from a point just
      // beyond that distance and passes over every part of the curves farther than it, most of
      // them; where that point rounds back to within it, the whole search)
      const Point_3 beyond = mid + typename K::Vector_3(1.000001 * std::sqrt(limit), 0, 0);
      const bool bounded = CGAL::to_double(CGAL::squared_distance(mid, beyond)) > limit;
      const double d2 = CGAL::to_double(CGAL::squared_distance(mid, bounded ? project_on_features_from(mid, beyond) : project_on_features(mid)));
      if(!(d2 < limit)) return false;
      // a chord of a straight feature curve is no feature edge: when the vertex opposite it in one
      // of its triangles lies on the curve between a and b (the triangle is flat, a-c-b is the
      // curve), the edge may be flipped away
      for(auto h : {halfedge(e, output), opposite(halfedge(e, output), output)}) {
        if(is_border(h, output)) continue;
        const vertex_descriptor c = target(next(h, output), output);
        const int kc = kind(c);
        if(kc != int(Sample_kind::corner) && kc != int(Sample_kind::feature)) continue;
        const auto u = point(a) - point(c), w = point(b) - point(c);
        const double uw = CGAL::to_double(u * w);
        if(uw < 0 && uw * uw > 0.75 * CGAL::to_double(u.squared_length()) * CGAL::to_double(w.squared_length())) return false;   // angle at c > 150 degrees
      }
      return true;
    };
    if(attempt > 0) {
      // a second attempt also frees what need not stay: the corners left on no feature edge (their
      // curves dropped or unsampled; not the pointed tips, the last corners of the set) and the
      // input vertices the tessellation could not remove (they move on the input like the samples)
      for(vertex_descriptor v : vertices(output)) {
        const int k = kind(v);
        if(k < 0) { put(kind_map, v, int(Sample_kind::surface)); continue; }
        if(k == int(Sample_kind::corner) && internal::is_loose_corner(v, output, is_tip, is_feature)) put(kind_map, v, int(Sample_kind::surface));
      }
    }
    auto is_fixed = [&](vertex_descriptor v) { const int k = kind(v); return k < 0 || k == int(Sample_kind::corner); };
    const Relaxation_settings& settings = options.settings;
    // the sampling density at each vertex, for the Eq. 6 weights (Eq. 1: ~ 1 / r^2 at each sample's
    // radius; 1 for a uniform density); a vertex the relaxer adds takes its neighbours' mean
    auto density_map = get(CGAL::dynamic_vertex_property_t<double>(), output);
    for(vertex_descriptor v : vertices(output)) put(density_map, v, 0.0);
    // a vertex the relaxer adds may take the descriptor of one it removed (a Surface_mesh recycles
    // indices, a Polyhedron_3 memory): what the maps held for that one is forgotten
    auto new_vertex = [&](vertex_descriptor v, bool on_feature) {
      put(kind_map, v, int(on_feature ? Sample_kind::feature : Sample_kind::surface));
      put(density_map, v, 0.0);
    };
    for(const auto& v : tessellation.vertices)
      if(v.sample != tessellation.no_sample)
        put(density_map, v.vertex, radii.empty() ? 1.0 : 1.0 / (samples[v.sample].radius * samples[v.sample].radius));
    auto density = [&](vertex_descriptor v) {
      const double d = get(density_map, v);
      if(d > 0) return d;
      double sum = 0;
      int n = 0;
      if(halfedge(v, output) != boost::graph_traits<TriangleMesh>::null_halfedge())
        for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, output), output))
          if(get(density_map, w) > 0) { sum += get(density_map, w); ++n; }
      const double mean = n ? sum / n : 1.0;
      put(density_map, v, mean);
      return mean;
    };
    if constexpr(default_relaxer) {
      if(progress.active())
        relaxer->set_progress([&](const char* stage, std::size_t done, std::size_t total) {
          // (the Lloyd rounds take about half of the relaxation, the passes after them the rest)
          const bool lloyd = stage[0] == 'r';
          progress.set_span(lloyd ? 0.4 : 0.7, lloyd ? 0.7 : 1.0);
          progress(stage, done, total);
        });
      // (a uniform density: the relaxer's unit weights; adaptive or graded: the density above)
      if(radii.empty()) result.relaxation = relaxer->relax(output, is_feature, is_fixed, settings, new_vertex);
      else result.relaxation = relaxer->relax(output, is_feature, is_fixed, settings, new_vertex, density);
    } else {   // the user's model of the Relaxer concept: the maps and the density
      result.relaxation = user_relaxer->relax(
        input, in_vpm, output, boost::make_function_property_map<edge_descriptor, bool>(is_feature),
        boost::make_function_property_map<vertex_descriptor, bool>(is_fixed),
        boost::make_function_property_map<vertex_descriptor, double>(density), settings.iterations, new_vertex);
    }
    seconds_by_step += result.relaxation.seconds;
    internal::collect_garbage(output);
    // (the check, the copy of the best attempt and the new radii count with the relaxation)
    const auto places = internal::regrading_places<ConcurrencyTag>(output, input, is_fixed, is_tip, input_crossings, regrading);
    if(attempt == 0) first_count = num_vertices(output);
    const bool last_by_fault = !places.remake_wanted(attempt == 0 ? nullptr : &previous_places) || attempt >= regrading_attempts ||
                               double(num_vertices(output)) > regrading.max_growth * double(first_count);
    output_is_best = attempt == 0 || places.better_than(best_places);
    attempts_without_gain = output_is_best ? 0 : attempts_without_gain + 1;
    const bool last = last_by_fault || internal::remakes_stop_for_want_of_gain(attempts_without_gain, best_places, regrading);
    // (a result that cuts itself is made again whole: the crossings of a crumpled input follow its
    // pleats, features and all, beyond any one region)
    const bool remake_locally = use_local_remakes && attempt == 0 && places.crossing_pairs == 0;
    if(output_is_best) {
      best_places = places;
      if(!last && !remake_locally) { clear(best); CGAL::copy_face_graph(output, best); best_result = result; }
    }
    if constexpr(default_relaxer && default_sampler && LocalRemakes) {
      if(remake_locally && !last) {
        // the remakes redo the regions at fault alone (internal/local_remake.h), each on the best
        // output so far: a remake that does not make it better is taken back
        seconds[2] += since(t);
        internal::Local_remake_undo<TriangleMesh> undo;
        t = now();
        with_oracle([&](const auto& oracle) {   // (one oracle for all the remakes)
          for(unsigned int k = 1;; ++k) {
            internal::regrade_radii(input, in_vpm, radius, best_places.places, radii, regrading);
            ++regraded;
            internal::Local_remake_statistics remake;
            // (around the triangles at fault at a fixed vertex too: drawn anew, not finer)
            std::vector<Point_3> around = best_places.places;
            around.insert(around.end(), best_places.fixed_places.begin(), best_places.fixed_places.end());
            const bool changed = internal::remake_regions(input, in_vpm, oracle, *relaxer, settings, output, kind_map, is_feature, is_tip, around,
                                                          radius, radii, seed + regrading.seed_step * k, local_remake, remake, undo);
            bool stop = remake.region_vertices == 0 || k >= regrading_attempts;
            if(changed) {
              const auto current = internal::regrading_places<ConcurrencyTag>(output, input, is_fixed, is_tip, input_crossings, regrading);
              if(current.better_than(best_places)) best_places = current;
              else internal::undo_remake(output, kind_map, undo);
              internal::collect_garbage(output);
              stop = stop || !best_places.wanted() || double(num_vertices(output)) > regrading.max_growth * double(first_count);
            }
            if(stop) break;
          }
        });
        seconds[2] += since(t);
        output_is_best = true;
        break;
      }
    }
    if(!last) {
      internal::regrade_radii(input, in_vpm, radius, places.places, radii, regrading);
      ++regraded;
    }
    previous_places = places;
    seconds[2] += since(t);
    if(last) break;
  }
  if(!output_is_best) {   // an earlier attempt was better: it is the output
    t = now();
    clear(output);
    CGAL::copy_face_graph(best, output);
    result = best_result;
    seconds[2] += since(t);
  }
  result.number_of_regrading_attempts = regraded;
  result.crossing_pairs_left = best_places.crossing_pairs;
  result.sharp_triangles_left = best_places.sharp;
  result.min_angle_away_from_corners = best_places.min_angle_away;
  result.seconds_sampling = seconds[0];
  result.seconds_tessellation = seconds[1];
  result.seconds_relaxation = seconds[2];
  result.seconds_by_step = seconds_by_step;
  return result;
}

} // namespace internal

/*!
  remeshes `input` (a closed or open triangle mesh, any `FaceListGraph`) into `output` (any
  `MutableFaceGraph`, of the input's type or another; cleared first; a `Surface_mesh` output has
  no removed elements left: its garbage is collected). The output's vertices lie on the surface
  that `vertex_point_map` describes. With a user `vertex_point_map`, an output of another type or
  zero-area faces to remove, the stages run on a copy of the input in the output's type.

  Named parameters: those of poisson_disk_sample() (size: `target_vertex_count`,
  `target_edge_length`, `sampling_radius`; `random_seed`; features: `feature_policy`,
  `sharp_angle`, `corner_angle`, `minimum_feature_length`, `edge_is_constrained_map`),
  `density` (Uniform_density() by default; Curvature_density{...}, vertex_density(map) or
  point_density(function) for an adaptive remesh, §5: see density_fields.h),
  `number_of_iterations` (CGAL; relaxation rounds, default 10: see Relaxation_settings),
  `fidelity_tolerance` (default 0.008: after the rounds, input vertices farther than this times
  the input's bounding-box diagonal from the mesh -- rims and crests finer than the sample
  spacing -- are inserted, at most 1% of the vertex count; 0 disables: see
  Relaxation_settings::fidelity),
  `feature_grading` (default true; uniform density only: finer sampling around pointed tips --
  horns, claws thinner than the spacing -- graded back to it, where the spacing leaves sharp
  triangles; the output has a few more vertices there: see internal/feature_grading.h),
  `regrading_attempts` (default 6 for a uniform density and the default relaxer, else 0; 0: off;
  a result that cuts itself, or keeps a smallest angle
  under 30 degrees away from the input's sharp corners -- an input crumpled finer than the
  spacing -- is remeshed again, at most this many times, with the sampling finer around the
  places at fault and a new draw, until two attempts in a row do not beat the best one (when it
  cuts itself nowhere); the best result is kept: see internal/regrading.h) and
  `sampler` (a model of the Sampler concept, default Poisson_disk_sampler: see
  doc/Poisson_remesh/Concepts/Sampler.h), `geodesic_oracle` (the default sampler's oracle, a model of
  GeodesicOracle built on `input`),
  `relaxer` (a model of the Relaxer concept, default Lloyd_relaxer on the input and its features;
  see doc/Poisson_remesh/Concepts/Relaxer.h),
  `progress` and `callback` (CGAL) (told how far the run is; returning false stops it with
  Cancelled: see progress.h) and `strict_input` (default false: zero-area input faces are
  removed, on a copy of the input, before remeshing, and counted in
  `Poisson_remesh_result::number_of_repaired_faces`; true: such input throws std::invalid_argument).

  `ConcurrencyTag`: CGAL::Sequential_tag (the default) or CGAL::Parallel_tag (needs TBB;
  CGAL::Parallel_if_available_tag falls back to Sequential_tag without it). In the parallel mode
  the sampling runs by slabs of the surface, and the default relaxer's vertex passes (Lloyd steps,
  angle smoothing and optimization), its fidelity distance queries, the valence flips' ideal
  valences and the whole-mesh self-intersection searches run on TBB's threads (as many as TBB is
  allowed: tbb::global_control); the tessellation and the flips themselves stay sequential. For a
  given `random_seed` the output is the same for any number of threads; it is not the
  sequential mode's (the slabs draw another maximal sample set, as another seed would).
*/
template <class ConcurrencyTag = CGAL::Sequential_tag, class InputMesh, class OutputMesh, class NamedParameters = parameters::Default_named_parameters>
Poisson_remesh_result poisson_remesh(const InputMesh& input, OutputMesh& output,
                                     const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  auto in_vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, input));
  if(faces(input).empty()) throw std::invalid_argument("poisson_remesh: the mesh has no faces");
  // zero-area faces have no sampling, tessellation or angle to speak of: a remesher exists to
  // replace them, so they are removed first (on a copy: the input is the caller's)
  const std::size_t degenerate = internal::count_degenerate_faces(input, in_vpm);
  if(degenerate > 0 && choose_parameter(get_parameter(np, internal_np::strict_input), false))
    throw std::invalid_argument("poisson_remesh: the input has " + std::to_string(degenerate) +
                                " zero-area faces (strict_input: not repaired)");
  // The stages read the input through its own point map and build the output in the input's
  // type. The input is used as it is when that fits; otherwise the stages run on a copy of it in
  // the output's type, read through the user's point map: a user vertex_point_map (every stage
  // then sees the surface it describes), an output of another type, or faces to repair.
  constexpr bool same_type = std::is_same<InputMesh, OutputMesh>::value;
  constexpr bool own_points = parameters::is_default_parameter<NamedParameters, CGAL::internal_np::vertex_point_t>::value;
  // the user's models (copies, as CGAL keeps them, or the objects of a std::ref), else none
  const auto sampler = get_parameter(np, internal_np::sampler);
  const auto relaxer = get_parameter(np, internal_np::relaxer);
  const auto oracle = get_parameter(np, internal_np::geodesic_oracle);
  constexpr bool local_remakes = !parameters::is_default_parameter<NamedParameters, internal_np::local_remakes_t>::value;
  internal::Progress_reporter progress(np);
  if constexpr(same_type && own_points) {
    if(degenerate == 0) {
      const auto options = internal::read_remesh_options(input, in_vpm, np, progress);
      return internal::poisson_remesh_impl<ConcurrencyTag, local_remakes>(input, in_vpm, output, options, progress, internal::model_pointer(sampler),
                                                                          internal::model_pointer(relaxer), internal::model_pointer(oracle));
    }
  }
  // (a user's geodesic oracle is built on the input itself: it cannot follow a copy)
  if constexpr(!parameters::is_default_parameter<NamedParameters, internal_np::geodesic_oracle_t>::value) {
    throw std::invalid_argument("poisson_remesh: a geodesic_oracle works on the input itself: give no vertex_point_map "
                                "of your own, an output of the input's type and an input without zero-area faces");
  } else {
    OutputMesh work;
    CGAL::copy_face_graph(input, work, CGAL::parameters::vertex_point_map(in_vpm));
    std::size_t split = 0;
    if(degenerate > 0) {
      const internal::Degenerate_face_repair repaired = internal::remove_degenerate_faces(work, get(CGAL::vertex_point, work));
      if(!repaired.complete)
        throw std::invalid_argument("poisson_remesh: the input's " + std::to_string(degenerate) +
                                    " zero-area faces could not all be removed");
      split = repaired.split_vertices;
      internal::collect_garbage(work);
    }
    const auto work_vpm = get_const_property_map(CGAL::vertex_point, work);
    const auto options = internal::read_remesh_options(work, work_vpm, np.vertex_point_map(work_vpm), progress);
    Poisson_remesh_result result =
      internal::poisson_remesh_impl<ConcurrencyTag, local_remakes>(work, work_vpm, output, options, progress, internal::model_pointer(sampler),
                                                                   internal::model_pointer(relaxer), internal::model_pointer(oracle));
    result.number_of_repaired_faces = degenerate;
    result.number_of_split_vertices = split;
    return result;
  }
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_POISSON_REMESH_H
