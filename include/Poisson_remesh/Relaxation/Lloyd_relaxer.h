// Poisson_remesh/Relaxation/Lloyd_relaxer.h
//
// The Relaxer model of paper §6.2 and §6.3. relax() runs the paper's rounds -- the Lloyd step with
// projection onto the input (Relaxation/lloyd_step.h), 3D Delaunay flips (Relaxation/
// delaunay_flips.h) and connectivity flips towards the angle-based ideal valence (Relaxation/
// valence_flips.h) -- for `iterations` rounds, then the operators beyond the paper, one header
// each in Postprocessing/, each with its own settings in Relaxation_settings:
//   - Lloyd guard (lloyd_guard.h): Lloyd moves that would make a sharp triangle go half way or not;
//   - sliver collapse (sliver_collapse.h);
//   - fidelity insertions (fidelity_insertion.h): input points far from the mesh inserted, pinned;
//   - angle smoothing (angle_smoothing.h) and angle optimization (angle_optimization.h);
//   - regularity flips (regularity_flips.h);
//   - refinement at the triangles still sharp (refinement.h);
//   - untangling of the crossings left (untangling.h);
//   - local repair of the triangles still sharp (local_repair.h).
// Each works locally under the same constraints -- no topology change, every vertex on the input,
// no new self-intersection (a crossing near the input's own is not new) -- and takes back its own
// changes. The schedule is relax() below.

#ifndef POISSON_REMESH_RELAXATION_LLOYD_RELAXER_H
#define POISSON_REMESH_RELAXATION_LLOYD_RELAXER_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Relaxation/Relaxation_statistics.h>
#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <Poisson_remesh/Relaxation/lloyd_step.h>
#include <Poisson_remesh/Relaxation/delaunay_flips.h>
#include <Poisson_remesh/Relaxation/valence_flips.h>
#include <Poisson_remesh/Postprocessing/lloyd_guard.h>
#include <Poisson_remesh/Postprocessing/sliver_collapse.h>
#include <Poisson_remesh/Postprocessing/fidelity_insertion.h>
#include <Poisson_remesh/Postprocessing/angle_smoothing.h>
#include <Poisson_remesh/Postprocessing/angle_optimization.h>
#include <Poisson_remesh/Postprocessing/regularity_flips.h>
#include <Poisson_remesh/Postprocessing/refinement.h>
#include <Poisson_remesh/Postprocessing/untangling.h>
#include <Poisson_remesh/Postprocessing/local_repair.h>

#include <algorithm>
#include <functional>
#include <map>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {

/// The rounds and switches of `Lloyd_relaxer::relax()` (angles in degrees): the paper's rounds
/// (§6.2, §6.3), then the settings of each operator beyond the paper (see the user manual,
/// "Beyond the paper"). poisson_remesh() sets `iterations` from the named parameter
/// `number_of_iterations` and `fidelity.max_deviation` from `fidelity_tolerance`, or takes the
/// whole struct from `relaxation_settings`.
struct Relaxation_settings
{
  /// rounds of Lloyd + Delaunay flips + valence flips. The paper finds about 3 enough for the
  /// points; the connectivity keeps improving to about 10
  unsigned int iterations = 10;
  bool delaunay_flips = true;              ///< Delaunay flips after each Lloyd pass
  bool valence_flips = true;               ///< valence flips (§6.3, Eq. 7-8) after each Lloyd pass
  double max_flip_normal_change = 35;      ///< degrees between the old and the new triangles' normals
  /// a valence flip may not make the smallest angle of its two triangles worse than this ratio of
  /// it (0 lets slivers through, values near 1 leave almost every valence flip undone)
  double valence_flip_min_angle_ratio = 0.6;
  bool final_delaunay = true;              ///< Delaunay flips after the passes beyond the paper too
  /// a triangle with a smaller angle is a sliver: the target of the operators beyond the paper
  double sliver_angle = 30;
  /// relaxation rounds after the sliver collapses and fidelity insertions
  unsigned int rounds_after_collapse = 3;

  /// the operators beyond the paper
  /// @{
  Postprocessing::Lloyd_guard_settings lloyd_guard;
  Postprocessing::Sliver_collapse_settings sliver_collapse;
  Postprocessing::Fidelity_settings fidelity;
  Postprocessing::Angle_smoothing_settings angle_smoothing;
  Postprocessing::Regularity_settings regularity;
  Postprocessing::Angle_optimization_settings angle_optimization;
  Postprocessing::Refinement_settings refinement;
  Postprocessing::Untangling_settings untangling;
  Postprocessing::Local_repair_settings local_repair;
  /// @}
};

/// The relaxation of paper §6.2 and §6.3, a model of the concept `Relaxer`: local Lloyd steps with
/// projection onto the input, Delaunay and valence flips, then the operators beyond the paper
/// (`Relaxation_settings`). Built on the input mesh and its features; relax() works in place on
/// a mesh whose vertices lie on the input (the mutual tessellation). `GeomTraits`: the kernel of
/// the input's points. `ConcurrencyTag`: CGAL::Sequential_tag (the default), or CGAL::Parallel_tag
/// (CGAL::Parallel_if_available_tag: when TBB is linked) for the parallel mode, in which the
/// vertex passes (Lloyd steps, angle smoothing and optimization) and the fidelity distance queries
/// run on TBB's threads; the result is the same in both modes and for any number of threads.
template <class InputMesh, class GeomTraits, class ConcurrencyTag = CGAL::Sequential_tag>
class Lloyd_relaxer
{
  typedef typename GeomTraits::Point_3 Point_3;
  typedef internal::Relaxation_context<InputMesh, GeomTraits> Context;

public:
  /// `features`: the input's features (their edges are where feature vertices may slide).
  Lloyd_relaxer(const InputMesh& input, const Feature_set<InputMesh>& features) : context_(input, features) {}

  /// Relaxes `mesh` (its vertices on the input) in place. `is_feature(e)` tells the output's
  /// feature edges (never flipped), `is_corner(v)` its corners (never moved).
  template <class Mesh, class IsFeatureEdge, class IsCorner>
  Relaxation_statistics relax(Mesh& mesh, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s = {}) const
  {
    return relax(mesh, is_feature, is_corner, s, No_new_vertex());
  }

  /// The default model's rounds and switches, used by the concept's relax() below (the other
  /// overloads take them as an argument).
  Relaxation_settings settings;

  /// The `Relaxer` concept's call (doc/Poisson_remesh/Concepts/Relaxer.h): relaxes `mesh` on the
  /// input given at construction (`input` must be it; `input_vpm` its points as the relaxer was
  /// built on them), with the property maps `is_feature` (edge -> bool), `is_fixed` (vertex ->
  /// bool) and `density` (vertex -> double > 0, Eq. 6 weights), `iterations` Lloyd rounds and
  /// `settings` for the rest; `new_vertex(v, on_feature)` is told each vertex it adds.
  template <class InputMeshArg, class InputVPM, class Mesh, class IsFeatureMap, class IsFixedMap, class DensityMap, class NewVertex>
  Relaxation_statistics relax(const InputMeshArg& input, InputVPM input_vpm, Mesh& mesh, IsFeatureMap is_feature, IsFixedMap is_fixed,
                              DensityMap density, unsigned int iterations, NewVertex new_vertex) const
  {
    CGAL_precondition(static_cast<const void*>(&input) == static_cast<const void*>(&context_.input()));
    Relaxation_settings s = settings;
    s.iterations = iterations;
    typedef typename boost::graph_traits<Mesh>::edge_descriptor edge_descriptor;
    typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
    return relax(mesh, [is_feature](edge_descriptor e) { return bool(get(is_feature, e)); },
                 [is_fixed](vertex_descriptor v) { return bool(get(is_fixed, v)); }, s, new_vertex,
                 [density](vertex_descriptor v) { return double(get(density, v)); });
  }

  /// `progress(stage, done, total)` is told how far relax() is: "relaxation" for the Lloyd rounds
  /// (done of `iterations`), "optimization" for the passes after them (done of their number).
  /// It may throw to stop the relaxation (the mesh is then valid but not finished).
  void set_progress(std::function<void(const char*, std::size_t, std::size_t)> progress) { progress_ = std::move(progress); }

  /// The `new_vertex` callback of the short relax(): no vertex may be added (no fidelity
  /// insertions or refinement).
  struct No_new_vertex
  {
    /// does nothing
    template <class V> void operator()(V, bool) const {}
    static constexpr bool splits = false;   ///< no vertex may be added
  };

  /// As above; `new_vertex(v, on_feature)` is called for each vertex the fidelity insertions and refinement add
  /// (on_feature: a feature vertex between two feature or corner vertices, on the input's
  /// features; else a free vertex on the input surface), so that the caller's `is_feature` and
  /// `is_corner` know it. Without it, no vertex is added.
  template <class Mesh, class IsFeatureEdge, class IsCorner, class NewVertex>
  Relaxation_statistics relax(Mesh& mesh, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s,
                              NewVertex new_vertex) const
  {
    return relax(mesh, is_feature, is_corner, s, new_vertex, Unit_density());
  }

  /// Uniform density for the Lloyd centroids.
  typedef Relaxation::Unit_density Unit_density;

  /// As above with a density (adaptive remeshing, Eq. 6): `vertex_density(v)` > 0 at the output's
  /// vertices, linear over each triangle; the Lloyd target of a vertex is the centroid of its
  /// triangles' centroids weighted by area times their mean density.
  template <class Mesh, class IsFeatureEdge, class IsCorner, class NewVertex, class VertexDensity>
  Relaxation_statistics relax(Mesh& mesh, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s,
                              NewVertex new_vertex, VertexDensity vertex_density) const
  {
    namespace P = Postprocessing;
    typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
    // (the steps that add vertices need the caller's new_vertex callback)
    constexpr bool may_add = !std::is_same<NewVertex, No_new_vertex>::value;
    const Context& ctx = context_;
    Relaxation_statistics stats;
    internal::Step_clock clock;   // (each step's time: stats.seconds)
    Relaxation_times& T = stats.seconds;
    std::vector<vertex_descriptor> pinned;   // the vertices of the fidelity insertions stay where they are put
    auto is_fixed = [&](vertex_descriptor v) { return is_corner(v) || std::binary_search(pinned.begin(), pinned.end(), v); };
    // (but near a sliver, they may move a little from there: P::optimize_pinned_vertices)
    std::map<vertex_descriptor, Point_3> pin_positions;
    auto pin_position = [&](vertex_descriptor v) -> const Point_3* {
      if(!std::binary_search(pinned.begin(), pinned.end(), v)) return nullptr;
      return &pin_positions.emplace(v, get(get(CGAL::vertex_point, mesh), v)).first->second;
    };
    // a vertex added may take the descriptor of one removed before it (a Surface_mesh recycles
    // indices, a Polyhedron_3 memory): it is no pinned vertex, and has no recorded pin position,
    // until the step that adds it says so (the whole list is searched: the fidelity insertions
    // append to it before they sort it)
    auto added_vertex = [&](vertex_descriptor v, bool on_feature) {
      pinned.erase(std::remove(pinned.begin(), pinned.end(), v), pinned.end());
      pin_positions.erase(v);
      new_vertex(v, on_feature);
    };
    const double tolerance = s.fidelity.max_deviation, optimized = s.angle_optimization.optimized_angle;
    const bool keep_regularity = s.regularity.keep_regularity;

    // the paper's steps
    auto lloyd = [&](auto fixed) {
      clock.timed(T.lloyd, [&] { Relaxation::lloyd_pass<ConcurrencyTag>(ctx, mesh, is_feature, fixed, stats, vertex_density, area_weighted_, P::Lloyd_guard<Context>{ctx, s.lloyd_guard}); });
    };
    auto delaunay = [&](bool keep) {
      clock.timed(T.delaunay_flips, [&] { Relaxation::delaunay_flips(ctx, mesh, is_feature, s.max_flip_normal_change, s.sliver_angle, stats, keep); });
    };
    auto valence = [&] {
      clock.timed(T.valence_flips, [&] { Relaxation::valence_flips<ConcurrencyTag>(ctx, mesh, is_feature, s.max_flip_normal_change, s.valence_flip_min_angle_ratio, stats); });
    };
    auto paper_round = [&](auto fixed) {
      lloyd(fixed);
      if(s.delaunay_flips) delaunay(false);
      if(s.valence_flips) valence();
    };
    // (after an operator beyond the paper)
    auto final_delaunay = [&](bool keep) { if(s.delaunay_flips && s.final_delaunay) delaunay(keep); };

    // the operators beyond the paper, each a round of its own
    auto fidelity = [&]() -> std::size_t {
      if constexpr(may_add)
        return tolerance > 0 ? clock.timed(T.fidelity, [&] { return P::insert_far_input_points<ConcurrencyTag>(ctx, mesh, is_feature, added_vertex, s.fidelity, stats, pinned, &fidelity_points_); }) : 0;
      else return 0;
    };
    auto optimize_angles = [&] {
      for(unsigned int it = 0; it < s.angle_optimization.rounds; ++it) {
        if(clock.timed(T.angle_optimization, [&] { return P::optimize_angles<ConcurrencyTag>(ctx, mesh, is_feature, is_fixed, s.angle_optimization, s.sliver_angle, tolerance, stats); }) == 0) break;
        final_delaunay(keep_regularity);
      }
    };
    auto refine = [&] {
      if constexpr(may_add)
        for(unsigned int round = 0; round < s.refinement.rounds; ++round) {
          if(clock.timed(T.refinement, [&] { return P::refine_sharp_triangles(ctx, mesh, is_feature, is_corner, added_vertex, s.refinement, s.sliver_angle, tolerance, stats, pinned); }) == 0) break;
          final_delaunay(keep_regularity);
          optimize_angles();
        }
    };
    P::Angle_smoothing_memory<Mesh> smoothing_memory;   // (no vertex is added or removed between the smoothing rounds)
    auto smooth = [&] { return clock.timed(T.angle_smoothing, [&] { return P::smooth_angles<ConcurrencyTag>(ctx, mesh, is_feature, is_fixed, stats, &smoothing_memory); }); };
    auto untangle = [&](std::size_t* collapses) {
      for(unsigned int round = 0; round < s.untangling.rounds; ++round)
        if(clock.timed(T.untangling, [&] { return P::untangle<ConcurrencyTag>(ctx, mesh, is_feature, is_fixed, s.untangling, stats, collapses); }) == 0) break;
    };
    auto report = [&](const char* stage, std::size_t done, std::size_t total) { if(progress_) progress_(stage, done, total); };
    const std::size_t optimization_steps = 8;   // (the reports of the steps after the Lloyd rounds)

    // the schedule
    for(unsigned int it = 0; it < s.iterations; ++it) {
      report("relaxation", it, s.iterations);
      paper_round(is_corner);
    }
    report("optimization", 0, optimization_steps);
    std::size_t changed = 0;
    if(s.sliver_collapse.enabled)
      changed += clock.timed(T.sliver_collapse, [&] { return P::collapse_slivers(ctx, mesh, is_feature, is_corner, s.sliver_collapse, s.sliver_angle, stats); });
    changed += fidelity();
    if(changed > 0)
      for(unsigned int it = 0; it < s.rounds_after_collapse; ++it) paper_round(is_fixed);
    if(fidelity() > 0) {
      if(s.delaunay_flips) delaunay(false);
      if(s.valence_flips) valence();
    }
    report("optimization", 1, optimization_steps);
    lloyd(is_fixed);   // end the paper's part on geometry: a last Lloyd pass and Delaunay flips
    final_delaunay(false);
    report("optimization", 2, optimization_steps);
    for(unsigned int it = 0; it < s.angle_smoothing.rounds; ++it) {
      if(smooth() == 0) break;
      final_delaunay(false);
    }
    report("optimization", 3, optimization_steps);
    for(unsigned int it = 0; it < s.regularity.rounds; ++it) {
      if(clock.timed(T.regularity, [&] { return P::regularity_flips(ctx, mesh, is_feature, s.regularity, s.max_flip_normal_change, stats); }) == 0) break;
      if(s.angle_smoothing.rounds > 0) smooth();   // (rounds = 0 switches the smoothing off here too)
    }
    report("optimization", 4, optimization_steps);
    optimize_angles();
    if(s.fidelity.final_pass && fidelity() > 0) {   // (the angle moves may cut a crest again)
      final_delaunay(keep_regularity);
      optimize_angles();
    }
    report("optimization", 5, optimization_steps);
    refine();
    clock.timed(T.final_regularity, [&] { P::final_regularity_flips<ConcurrencyTag>(ctx, mesh, is_feature, s.regularity, s.max_flip_normal_change, optimized, stats); });
    report("optimization", 6, optimization_steps);
    if(!pinned.empty())
      for(unsigned int it = 0; it < s.angle_optimization.rounds; ++it)
        if(clock.timed(T.pinned_optimization, [&] { return P::optimize_pinned_vertices<ConcurrencyTag>(ctx, mesh, is_feature, is_fixed, s.angle_optimization, s.sliver_angle, tolerance, stats, pin_position); }) == 0)
          break;
    report("optimization", 7, optimization_steps);
    std::size_t collapses = 0;
    untangle(s.untangling.collapse_min_angle > 0 ? &collapses : nullptr);
    if(collapses > 0) {   // (the collapsed vertices' triangles: their angles optimized again)
      optimize_angles();
      refine();
      untangle(nullptr);
    }
    if constexpr(may_add)
      for(unsigned int round = 0; round < s.local_repair.rounds; ++round)
        if(clock.timed(T.local_repair, [&] { return P::repair_sharp_triangles(ctx, mesh, is_feature, is_fixed, added_vertex, s.local_repair, s.sliver_angle, stats); }) == 0)
          break;
    report("optimization", optimization_steps, optimization_steps);
    return stats;
  }

  /// the point of the input surface closest to `p`
  Point_3 project_on_surface(const Point_3& p) const { return context_.project_on_surface(p); }
  /// the point of the input's feature edges closest to `p` (of the surface, without features)
  Point_3 project_on_features(const Point_3& p) const { return context_.project_on_features(p); }
  /// the same when it is closer to `p` than `start` (any point), else `start`: the search passes
  /// over every part of the features farther than `start`
  Point_3 project_on_features(const Point_3& p, const Point_3& start) const { return context_.project_on_features(p, start); }

  /// the Lloyd step weights each ring triangle's centroid by its area (Eq. 6; the default), or
  /// all alike (false)
  bool area_weighted_ = true;

private:
  std::function<void(const char*, std::size_t, std::size_t)> progress_;
  Context context_;
  // the input's points that each fidelity pass measures, read at the first (the input does not
  // change: the remakes' relaxations use them too; relax() is not called from two threads at once);
  // kept while the relaxer lives: about six points per input vertex, and their grid
  mutable Postprocessing::Fidelity_input_points<InputMesh, Point_3> fidelity_points_;
};

} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_LLOYD_RELAXER_H
