// Poisson_remesh/Relaxation/Lloyd_relaxer.h
//
// The Relaxer model of paper §6.2 and §6.3: local Lloyd relaxation with projection onto the input,
// 3D Delaunay flips, and connectivity flips towards the angle-based ideal valence.
//   - Lloyd step (§6.2, Eq. 6): the one-ring of a free vertex is laid out in the plane (the
//     exponential-map layout of §6.1: radial lengths kept, angles scaled to sum to 2 pi); the vertex
//     moves to the density-weighted mean of its triangles' centroids (uniform density: their mean),
//     mapped back through the ring triangle that contains it, then projected onto the INPUT surface
//     (closest point, CGAL AABB tree), so vertices always lie on the input.
//   - feature vertices (two incident feature edges) slide along the feature curve: they move to
//     the midpoint of their two feature neighbours, projected onto the input's feature edges;
//     corners and vertices where features meet do not move.
//   - a move that would fold an incident triangle is refused.
//   - Delaunay flips: a non-feature edge whose two opposite angles sum to more than 180 degrees is
//     flipped when the new edge does not exist yet and the two new triangles stay close to the
//     surface (normal change under `max_flip_normal_change`).
//   - connectivity flips (§6.3, Eq. 7-8): a non-feature edge is flipped when that lowers
//     sum (d(v) - o(v))^2 over its four vertices, o(v) = (angle sum at v) / 60 degrees (+1 on a
//     border), under the same guards and without making the smallest angle much worse.
// The three alternate for `iterations` rounds (default 10; see Relaxation_settings). Then, beyond
// the paper, slivers whose short edge no move can lengthen (pinned by corners or feature samples)
// lose that edge by a guarded collapse onto its more constrained end (two corners too close are
// merged), input points far from the mesh (and the input points nearest the mesh's triangles and
// edges that are far from the input) are inserted and pinned (fidelity insertions), and a
// few rounds follow; at the very end the vertices of the triangles still under optimized_angle move
// to raise their smallest angle (angle optimization), after a smoothing of all vertices and
// regularity flips; last, the triangles still sharper than that get a flip, a vertex removal or
// a vertex insertion beside them (refinement), a last round of regularity flips keeps the
// smallest angle, the pinned vertices still at such triangles move a little (a quarter of the
// fidelity tolerance at most), and the crossings left from the tessellation and the Lloyd passes
// get vertex moves, flips and collapses that leave fewer of them (untangling). Moves and insertions that
// make the mesh cut itself anew are taken back (not for a crossing near the input's own: an
// input that cuts itself, as where one part runs through another).

#ifndef POISSON_REMESH_RELAXATION_LLOYD_RELAXER_H
#define POISSON_REMESH_RELAXATION_LLOYD_RELAXER_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/internal/feature_curves.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <algorithm>
#include <functional>
#include <array>
#include <map>
#include <set>
#include <cmath>
#include <tuple>
#include <iterator>
#include <limits>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {

/// The rounds and switches of `Lloyd_relaxer::relax()` (angles in degrees): the paper's Lloyd
/// rounds and flips (§6.2, §6.3), then the operators beyond the paper (see the user manual,
/// "Beyond the paper"). poisson_remesh() sets `iterations` from the named parameter
/// `number_of_iterations` and `max_deviation` from `fidelity_tolerance`.
struct Relaxation_settings
{
  /// rounds of Lloyd + Delaunay flips + valence flips. The paper finds about 3 enough for the
  /// points; the connectivity keeps improving to about 10, at a cost small beside the sampling.
  unsigned int iterations = 10;
  bool delaunay_flips = true;              ///< Delaunay flips after each Lloyd pass
  bool valence_flips = true;               ///< valence flips (§6.3, Eq. 7-8) after each Lloyd pass
  double max_flip_normal_change = 35;      ///< degrees between the old and the new triangles' normals
  /// a valence flip may not make the smallest angle of its two triangles worse than this ratio
  /// (0.6: about 1% more irregular vertices than 0.3 but 0.6-0.9 degrees more mean smallest angle
  /// on the benchmark models; 0.9 leaves almost every valence flip undone, 0 lets slivers through)
  double valence_flip_min_angle_ratio = 0.6;
  bool final_delaunay = true;              ///< end with Delaunay flips (after the last Lloyd pass)
  /// (beyond the paper) collapse the short edge of a triangle sharper than `sliver_angle` whose
  /// shortest edge is under `sliver_edge_ratio` of its longest, onto its more constrained end,
  /// then relax `rounds_after_collapse` more rounds: the slivers pinned by corners and feature
  /// samples that no vertex move can mend
  bool collapse_slivers = true;
  double sliver_angle = 30;   ///< a triangle with a smaller angle is a sliver (collapses, refinement)
  /// a sliver's shortest edge must be under this share of its longest to be collapsed (a triangle
  /// of three corners closer than the spacing has about half)
  double sliver_edge_ratio = 0.5;
  unsigned int rounds_after_collapse = 3;   ///< relaxation rounds after the sliver collapses
  /// (beyond the paper) an input vertex farther than this (times the input's bounding-box
  /// diagonal) from the relaxed mesh -- a rim or a crest finer than the sample spacing, cut
  /// across by the triangles -- is inserted there (the nearest triangle split at it), at most
  /// one per triangle and its neighbours; 0 disables. Needs the new-vertex callback of relax().
  /// An insertion that would make the mesh cut itself is taken back and tried as a split of an
  /// edge of that triangle instead (at the side of a tip, the nearest triangle's three new ones
  /// may cut the next ones). Checked are the input's vertices, edge midpoints and triangle
  /// centroids (the distance often peaks inside a triangle), and the other way the mesh's
  /// triangle centroids (their nearest input point goes in) and edge midpoints (the edge is
  /// split at the input point nearest its midpoint: an edge spanning a groove). After the Lloyd
  /// rounds and after the rounds that follow the collapses.
  double max_deviation = 0.008;
  /// and once more after the angle optimization, whose moves may cut a crest again (new vertices
  /// there are followed by Delaunay flips and angle optimization rounds)
  bool final_fidelity_pass = true;
  /// at most this share of the vertex count is inserted so in one pass, farthest first, and as
  /// many far edges split (a mesh much too coarse for its input everywhere is not mended by
  /// pinned vertices)
  double max_deviation_insertions = 0.01;
  /// the sliver collapses may also merge two corners joined by the sliver's short edge
  bool merge_close_corners = true;
  /// (beyond the paper) rounds of local angle optimization at the end: each movable vertex of a
  /// triangle sharper than `optimized_angle` moves (on the input; a feature vertex along its curve)
  /// to raise the smallest angle of its triangles, by a pattern search; 0 disables. Lloyd's
  /// centroids leave slivers beside vertices that may not move (corners, tips, feature samples)
  unsigned int angle_rounds = 4;
  /// (beyond the paper) rounds of angle smoothing before those: every movable vertex moves (a
  /// free one in its tangent plane, then onto the input; a feature vertex along its curve) to
  /// raise the sum of its triangles' smallest angles without lowering the smallest of them, by a
  /// short pattern search; then Delaunay flips. Lloyd's centroids are not the best angles for a
  /// given connectivity: two rounds add 1.2 to 1.5 degrees to the mean smallest angle of the
  /// benchmark models (one round about 1.1); 0 disables.
  unsigned int smoothing_rounds = 2;
  /// (beyond the paper) a feature or border edge longer than this times the mean length of the
  /// other edges at its ends (a feature sample was refused there, too close to another curve's)
  /// is split at its midpoint projected onto the input's features, unless the curve bends away
  /// from the edge or a new triangle would turn; 0 disables. Needs the callback that tells the
  /// caller about the new vertex (see relax()).
  double long_edge_ratio = 1.6;
  /// (beyond the paper) rounds of refinement at the very end: a triangle still sharper than
  /// `sliver_angle` (its vertices could not move enough: corners, feature samples) gets the best
  /// of three local changes when it beats the old triangles' smallest angle by a degree: a flip of
  /// one of its edges; the removal of a vertex of degree 3 of it off the features, free or pinned by
  /// the fidelity pass (when the vertex is within half of max_deviation of the new triangle); or a
  /// new vertex on one of the two edges at its smallest angle, placed on the input (on the
  /// features for a feature edge) where the four new triangles have the largest smallest angle --
  /// the small angle's wedge is shared with the neighbour's angle, as Ruppert's refinement does.
  /// Changes that make the mesh cut itself are taken back; Delaunay flips and the angle
  /// optimization follow. 0 disables. Needs the new-vertex callback of relax().
  unsigned int refinement_rounds = 3;
  /// (beyond the paper) rounds of regularity flips after the smoothing: a flip is made when fewer
  /// of its four vertices are irregular after it and both new triangles keep their smallest angle
  /// over `regularity_min_angle`; each round is followed by a smoothing round; 0 disables. The
  /// rounds stop when a round flips nothing (two or three rounds on the benchmark models).
  unsigned int regularity_rounds = 4;
  /// the smallest angle a regularity flip's triangles keep: a degree under the 30 degree floor,
  /// which the angle optimization and the refinement that follow lift back
  double regularity_min_angle = 29;
  /// (beyond the paper) after the refinement, one more round of regularity flips (no look-ahead)
  /// whose new triangles keep this smallest angle, or the mesh's smallest angle if larger (up to
  /// optimized_angle); the round is taken back whole if it makes the mesh cut itself anew; 0
  /// disables
  double final_regularity_min_angle = 30;
  /// (beyond the paper) rounds of untangling at the very end: the crossings left (the
  /// tessellation and the Lloyd passes do not check for them: bumps finer than the spacing) lose a free vertex
  /// of a crossing face moved onto the input below its neighbours' centroid (or halfway there), or
  /// an edge of a crossing face flipped, when fewer crossing pairs involve the faces it changes and
  /// their smallest angle stays over `untangle_min_angle` (or what it was); 0 disables
  unsigned int untangle_rounds = 3;
  /// (with untangle_rounds) the smallest angle the triangles of a collapse of the untangling keep
  /// (degrees; 0: no collapse)
  double untangle_collapse_min_angle = 15;
  /// (with untangle_rounds) the smallest angle the triangles of a move or flip of the untangling
  /// keep, or what it was if smaller (degrees)
  double untangle_min_angle = 30;
  /// (beyond the paper) a Lloyd move that would make one of the vertex's triangles sharper than
  /// this (degrees) and sharper than they are goes half the way; if that still does, it is
  /// refused: on thin parts and near graded tips a centroid projected back onto the input can
  /// line a vertex up with two neighbours, and the later rounds do not undo that; 0 disables
  double lloyd_min_angle = 25;
  /// a regularity flip that leaves as many irregular vertices (it moves one: a 5-7 pair glides) is
  /// made when a flip of an edge at one of its four vertices then makes fewer; both flips under
  /// the same guards. Irregular vertices 1.3-3.0 points fewer on the benchmark models.
  bool regularity_lookahead = true;
  /// after the regularity flips, a Delaunay flip that would make more irregular vertices is made
  /// only at a triangle sharper than `sliver_angle` whose smallest angle it raises (else the
  /// Delaunay flips of the angle optimization undo most regularity flips)
  bool keep_regularity = true;
  /// the angle optimization (angle_rounds) moves the vertices of the triangles sharper than this
  /// (degrees; the regularity flips leave triangles down to regularity_min_angle)
  double optimized_angle = 35;
};

/// What `Lloyd_relaxer::relax()` did.
struct Relaxation_statistics
{
  /// Lloyd moves made and refused, Delaunay and valence flips, sliver collapses, long-edge splits
  /// @{
  std::size_t moves = 0, refused_moves = 0, delaunay_flips = 0, valence_flips = 0, collapses = 0, splits = 0;
  /// @}
  std::size_t angle_moves = 0;   ///< moves of the final angle optimization
  std::size_t fidelity_insertions = 0;   ///< input vertices inserted where the mesh cut across the input
  std::size_t refinement_insertions = 0;   ///< vertices inserted beside triangles still sharper than sliver_angle
  /// the other changes of the refinement: flips and vertex removals
  /// @{
  std::size_t refinement_flips = 0, refinement_removals = 0;
  /// @}
  std::size_t untangle_changes = 0;   ///< moves and flips that left fewer crossing face pairs
};

namespace internal {

template <class Mesh>
using Face_pairs = std::vector<std::pair<typename boost::graph_traits<Mesh>::face_descriptor, typename boost::graph_traits<Mesh>::face_descriptor>>;

// the intersecting face pairs among the faces of `range` (all of m's by default), each (smaller,
// larger), sorted; the search stops past twice the face count (a mesh that cuts itself
// everywhere: folded input)
template <class Mesh, class FaceRange>
Face_pairs<Mesh> intersecting_pairs(const Mesh& m, const FaceRange& range)
{
  Face_pairs<Mesh> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(range, m, std::back_inserter(pairs),
                                                    CGAL::parameters::maximum_number(unsigned(2 * num_faces(m) + 1)));
  for(auto& fp : pairs) if(fp.second < fp.first) std::swap(fp.first, fp.second);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}
template <class Mesh>
Face_pairs<Mesh> intersecting_pairs(const Mesh& m) { return intersecting_pairs(m, faces(m)); }

// the intersecting face pairs (as above) that involve a face of `changed` or a face whose box
// meets the box of one: all the pairs that can differ from an earlier check when only the faces
// of `changed` moved or are new. A box search of the changed faces against all faces, then
// CGAL's exact test on that neighbourhood alone (a whole-mesh check per undo round was a tenth of
// the remesh's time); when most faces changed, the whole mesh's pairs (a superset: the box
// search would only repeat self_intersections' own).
template <class Mesh, class FaceRange>
Face_pairs<Mesh> intersecting_pairs_near(const Mesh& m, const FaceRange& changed)
{
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  typedef CGAL::Box_intersection_d::Box_with_info_d<double, 3, face_descriptor> Box;
  auto vpm = get(CGAL::vertex_point, m);
  auto box_of = [&](face_descriptor f) {
    const auto h = halfedge(f, m);
    return Box(get(vpm, source(h, m)).bbox() + get(vpm, target(h, m)).bbox() + get(vpm, target(next(h, m), m)).bbox(), f);
  };
  const auto n = std::size_t(std::distance(std::begin(changed), std::end(changed)));
  if(n == 0) return {};
  if(2 * n > num_faces(m)) return intersecting_pairs(m);
  std::vector<Box> mine, all;
  for(face_descriptor f : changed) mine.push_back(box_of(f));
  all.reserve(num_faces(m));
  for(face_descriptor f : faces(m)) all.push_back(box_of(f));
  // (each changed face meets its own box in `all`, so it is in `near` too)
  std::vector<face_descriptor> near;
  CGAL::box_intersection_d(mine.begin(), mine.end(), all.begin(), all.end(),
                           [&](const Box&, const Box& b) { near.push_back(b.info()); });
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  return intersecting_pairs(m, near);
}

// the faces around the vertices of a range, sorted, each once
template <class Mesh, class VertexRange>
std::vector<typename boost::graph_traits<Mesh>::face_descriptor> faces_around(const Mesh& m, const VertexRange& vs)
{
  std::vector<typename boost::graph_traits<Mesh>::face_descriptor> out;
  for(auto v : vs)
    for(auto h : CGAL::halfedges_around_target(halfedge(v, m), m))
      if(!is_border(h, m)) out.push_back(face(h, m));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

} // namespace internal

/// The relaxation of paper §6.2 and §6.3, a model of the concept `Relaxer`: local Lloyd steps with
/// projection onto the input, Delaunay and valence flips, then the operators beyond the paper
/// (`Relaxation_settings`). Built on the input mesh and its features; relax() works in place on
/// a mesh whose vertices lie on the input (the mutual tessellation). `GeomTraits`: the kernel of
/// the input's points.
template <class InputMesh, class GeomTraits>
class Lloyd_relaxer
{
  typedef typename GeomTraits::Point_3 Point_3;
  typedef typename GeomTraits::Vector_3 Vector_3;
  typedef typename GeomTraits::Segment_3 Segment_3;
  typedef CGAL::AABB_face_graph_triangle_primitive<InputMesh> Face_primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GeomTraits, Face_primitive>> Face_tree;

public:
  /// `features`: the input's features (their edges are where feature vertices may slide).
  Lloyd_relaxer(const InputMesh& input, const Feature_set<InputMesh>& features)
    : input_(input), faces_(faces(input).first, faces(input).second, input), curves_(input, features)
  {
    faces_.accelerate_distance_queries();
    const auto& pts = get(CGAL::vertex_point, input);
    if(!vertices(input).empty()) {
      CGAL::Bbox_3 box;
      for(auto v : vertices(input)) box += get(pts, v).bbox();
      diagonal_ = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) + CGAL::square(box.zmax() - box.zmin()));
    }
  }

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
    CGAL_precondition(static_cast<const void*>(&input) == static_cast<const void*>(&input_));
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

  /// The `new_vertex` callback of the short relax(): no vertex may be added (no splits,
  /// insertions or refinement).
  struct No_new_vertex
  {
    /// does nothing
    template <class V> void operator()(V, bool) const {}
    static constexpr bool splits = false;   ///< no vertex may be added
  };

  /// As above; `new_vertex(v, on_feature)` is called for each vertex the long-edge splits add
  /// (on_feature: a feature vertex between two feature or corner vertices, on the input's
  /// features; else a free vertex on the input surface), so that the caller's `is_feature` and
  /// `is_corner` know it. Without it, no edge is split.
  template <class Mesh, class IsFeatureEdge, class IsCorner, class NewVertex>
  Relaxation_statistics relax(Mesh& mesh, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s,
                              NewVertex new_vertex) const
  {
    return relax(mesh, is_feature, is_corner, s, new_vertex, Unit_density());
  }

  /// Uniform density for the Lloyd centroids.
  struct Unit_density
  {
    /// 1 at every vertex
    template <class V> double operator()(V) const { return 1.0; }
  };

  /// As above with a density (adaptive remeshing, Eq. 6): `vertex_density(v)` > 0 at the output's
  /// vertices, linear over each triangle; the Lloyd target of a vertex is the centroid of its
  /// triangles' centroids weighted by area times their mean density.
  template <class Mesh, class IsFeatureEdge, class IsCorner, class NewVertex, class VertexDensity>
  Relaxation_statistics relax(Mesh& mesh, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s,
                              NewVertex new_vertex, VertexDensity vertex_density) const
  {
    auto lloyd_pass = [&](Mesh& m, IsFeatureEdge f, auto c, Relaxation_statistics& st) {
      this->lloyd_pass(m, f, c, st, vertex_density, s.lloyd_min_angle);
    };
    typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
    std::vector<vertex_descriptor> pinned;   // the vertices of the fidelity pass stay where they are put
    auto is_fixed = [&](vertex_descriptor v) { return is_corner(v) || std::binary_search(pinned.begin(), pinned.end(), v); };
    // (but near a sliver, they may move a little from there: see angle_pass)
    std::map<vertex_descriptor, Point_3> anchors;
    auto pin_anchor = [&](vertex_descriptor v) -> const Point_3* {
      if(!std::binary_search(pinned.begin(), pinned.end(), v)) return nullptr;
      return &anchors.emplace(v, get(get(CGAL::vertex_point, mesh), v)).first->second;
    };
    Relaxation_statistics stats;
    // the angle optimization rounds, each followed by Delaunay flips
    auto optimize_angles = [&] {
      for(unsigned int it = 0; it < s.angle_rounds; ++it) {
        if(angle_pass(mesh, is_feature, is_fixed, s, stats, Angle_goal::smallest) == 0) break;
        if(s.delaunay_flips && s.final_delaunay) delaunay_pass(mesh, is_feature, s, stats, s.keep_regularity);
      }
    };
    auto report = [&](const char* stage, std::size_t done, std::size_t total) { if(progress_) progress_(stage, done, total); };
    // (the passes after the Lloyd rounds, for the progress reports)
    const std::size_t optimization_steps = 8;
    for(unsigned int it = 0; it < s.iterations; ++it) {
      report("relaxation", it, s.iterations);
      lloyd_pass(mesh, is_feature, is_corner, stats);
      if(s.delaunay_flips) delaunay_pass(mesh, is_feature, s, stats);
      if(s.valence_flips) valence_pass(mesh, is_feature, s, stats);
    }
    report("optimization", 0, optimization_steps);
    std::size_t changed = 0;
    if constexpr(!std::is_same<NewVertex, No_new_vertex>::value)
      if(s.long_edge_ratio > 0) changed += split_pass(mesh, is_feature, new_vertex, s, stats);
    if(s.collapse_slivers) changed += collapse_pass(mesh, is_feature, is_corner, s, stats);
    if constexpr(!std::is_same<NewVertex, No_new_vertex>::value)
      if(s.max_deviation > 0) changed += fidelity_pass(mesh, is_feature, new_vertex, s, stats, pinned);
    if(changed > 0)
      for(unsigned int it = 0; it < s.rounds_after_collapse; ++it) {
        lloyd_pass(mesh, is_feature, is_fixed, stats);
        if(s.delaunay_flips) delaunay_pass(mesh, is_feature, s, stats);
        if(s.valence_flips) valence_pass(mesh, is_feature, s, stats);
      }
    if constexpr(!std::is_same<NewVertex, No_new_vertex>::value)
      if(s.max_deviation > 0 && fidelity_pass(mesh, is_feature, new_vertex, s, stats, pinned) > 0) {
        if(s.delaunay_flips) delaunay_pass(mesh, is_feature, s, stats);
        if(s.valence_flips) valence_pass(mesh, is_feature, s, stats);
      }
    report("optimization", 1, optimization_steps);
    // end on geometry: a last Lloyd pass and Delaunay flips
    lloyd_pass(mesh, is_feature, is_fixed, stats);
    if(s.delaunay_flips && s.final_delaunay) delaunay_pass(mesh, is_feature, s, stats);
    // then every vertex raises the angles of its triangles, and those of the triangles still
    // sharper than sliver_angle (next to vertices that may not move) the smallest angle around them
    report("optimization", 2, optimization_steps);
    for(unsigned int it = 0; it < s.smoothing_rounds; ++it) {
      if(angle_pass(mesh, is_feature, is_fixed, s, stats, Angle_goal::sum_of_smallest) == 0) break;
      if(s.delaunay_flips && s.final_delaunay) delaunay_pass(mesh, is_feature, s, stats);
    }
    report("optimization", 3, optimization_steps);
    for(unsigned int it = 0; it < s.regularity_rounds; ++it) {
      if(regularity_pass(mesh, is_feature, s, stats) == 0) break;
      angle_pass(mesh, is_feature, is_fixed, s, stats, Angle_goal::sum_of_smallest);
    }
    report("optimization", 4, optimization_steps);
    optimize_angles();
    // the angle moves may cut a crest again: its input vertices are inserted there too
    if constexpr(!std::is_same<NewVertex, No_new_vertex>::value)
      if(s.final_fidelity_pass && s.max_deviation > 0 && fidelity_pass(mesh, is_feature, new_vertex, s, stats, pinned) > 0) {
        if(s.delaunay_flips && s.final_delaunay) delaunay_pass(mesh, is_feature, s, stats, s.keep_regularity);
        optimize_angles();
      }
    // and where the angles are still too small, the connectivity changes there (a flip, a vertex
    // removed or inserted)
    auto refine = [&] {
      if constexpr(!std::is_same<NewVertex, No_new_vertex>::value)
        for(unsigned int round = 0; round < s.refinement_rounds; ++round) {
          if(refinement_pass(mesh, is_feature, is_corner, new_vertex, s, stats, pinned) == 0) break;
          if(s.delaunay_flips && s.final_delaunay) delaunay_pass(mesh, is_feature, s, stats, s.keep_regularity);
          optimize_angles();
        }
    };
    report("optimization", 5, optimization_steps);
    refine();
    // a last round of regularity flips whose triangles all keep final_regularity_min_angle; all
    // taken back if one makes the mesh cut itself anew
    if(s.final_regularity_min_angle > 0) {
      const auto before = internal::intersecting_pairs(mesh);
      std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> flipped;
      // (nor under the mesh's smallest angle, up to optimized_angle: these flips trade little
      // regularity, 0.01-0.1 points, for the smallest angle, 35 -> 30 degrees on half the models)
      const auto vpm = get(CGAL::vertex_point, mesh);
      double smallest = CGAL_PI;
      for(auto f : faces(mesh)) {
        const auto h = halfedge(f, mesh);
        smallest = std::min(smallest, min_angle(get(vpm, source(h, mesh)), get(vpm, target(h, mesh)), get(vpm, target(next(h, mesh), mesh))));
      }
      const double floor_degrees = std::max(s.final_regularity_min_angle, std::min(smallest * 180 / CGAL_PI, s.optimized_angle));
      if(before.size() <= num_faces(mesh) && regularity_pass(mesh, is_feature, s, stats, floor_degrees, &flipped) > 0) {
        std::vector<typename boost::graph_traits<Mesh>::face_descriptor> changed;
        for(auto h : flipped) { changed.push_back(face(h, mesh)); changed.push_back(face(opposite(h, mesh), mesh)); }
        std::sort(changed.begin(), changed.end());
        changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
        bool cut = false;
        for_vertices_of_new_intersections(mesh, before, changed, [&](vertex_descriptor) { cut = true; });
        if(cut) {
          for(auto it = flipped.rbegin(); it != flipped.rend(); ++it) CGAL::Euler::flip_edge(*it, mesh);
          stats.valence_flips -= std::min(stats.valence_flips, flipped.size());
        }
      }
    }
    report("optimization", 6, optimization_steps);
    // then the vertices of the fidelity pass still at such triangles move a little (see angle_pass)
    if(!pinned.empty())
      for(unsigned int it = 0; it < s.angle_rounds; ++it)
        if(angle_pass(mesh, is_feature, is_fixed, s, stats, Angle_goal::smallest, pin_anchor, true) == 0) break;
    report("optimization", 7, optimization_steps);
    std::size_t collapses = 0;
    for(unsigned int round = 0; round < s.untangle_rounds; ++round)
      if(untangle_pass(mesh, is_feature, is_fixed, s, stats, s.untangle_collapse_min_angle > 0 ? &collapses : nullptr) == 0) break;
    if(collapses > 0) {   // (the collapsed vertices' triangles: their angles optimized again)
      optimize_angles();
      refine();
      for(unsigned int round = 0; round < s.untangle_rounds; ++round)
        if(untangle_pass(mesh, is_feature, is_fixed, s, stats) == 0) break;
    }
    report("optimization", optimization_steps, optimization_steps);
    return stats;
  }

  /// the point of the input surface closest to `p`
  Point_3 project_on_surface(const Point_3& p) const { return faces_.closest_point(p); }
  /// the point of the input's feature edges closest to `p` (of the surface, without features)
  Point_3 project_on_features(const Point_3& p) const { return curves_.empty() ? project_on_surface(p) : curves_.closest_point(p); }
  /// The same with `hint`, a point known to lie on the input surface (on a feature curve for
  /// project_on_features), near p: the search starts from it instead of a k-d tree query, which
  /// makes projections of moving vertices cheaper (the result is the same closest point).
  /// @{
  Point_3 project_on_surface(const Point_3& p, const Point_3& hint) const { return faces_.closest_point(p, hint); }
  Point_3 project_on_features(const Point_3& p, const Point_3& hint) const
  {
    return curves_.empty() ? project_on_surface(p, hint) : curves_.closest_point(p, hint);
  }
  /// @}

private:
  static double angle(const Point_3& a, const Point_3& o, const Point_3& b)
  {
    const Vector_3 u = a - o, v = b - o;
    return std::atan2(std::sqrt(CGAL::to_double(CGAL::cross_product(u, v).squared_length())), CGAL::to_double(u * v));
  }
  // the smallest angle lies opposite the shortest edge: one atan2 instead of three (the relaxer's
  // angle searches spend most of their time here)
  static double min_angle(const Point_3& a, const Point_3& b, const Point_3& c)
  {
    const double ab = CGAL::to_double(CGAL::squared_distance(a, b));
    const double bc = CGAL::to_double(CGAL::squared_distance(b, c));
    const double ca = CGAL::to_double(CGAL::squared_distance(c, a));
    if(bc <= ab && bc <= ca) return angle(b, a, c);
    if(ca <= ab) return angle(a, b, c);
    return angle(a, c, b);
  }
  static Vector_3 normal(const Point_3& a, const Point_3& b, const Point_3& c) { return CGAL::cross_product(b - a, c - a); }
  static double cos_between(const Vector_3& a, const Vector_3& b)
  {
    const double la = std::sqrt(CGAL::to_double(a.squared_length())), lb = std::sqrt(CGAL::to_double(b.squared_length()));
    return (la > 0 && lb > 0) ? CGAL::to_double(a * b) / (la * lb) : -1;
  }

  template <class Mesh, class IsFeatureEdge>
  std::size_t feature_degree(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, IsFeatureEdge is_feature) const
  {
    std::size_t d = 0;
    for(auto h : CGAL::halfedges_around_target(v, m)) if(is_feature(edge(h, m)) || is_border(edge(h, m), m)) ++d;
    return d;
  }

  // Eq. 6 in the exponential-map layout of the one-ring, mapped back to 3D
  template <class Mesh>
  bool lloyd_target(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, Point_3& target) const
  {
    return lloyd_target(v, m, target, Unit_density());
  }

  template <class Mesh, class VertexDensity>
  bool lloyd_target(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, Point_3& target,
                    VertexDensity vertex_density) const
  {
    constexpr bool uniform = std::is_same<VertexDensity, Unit_density>::value;
    std::vector<Point_3> ring;
    std::vector<double> ring_density;
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      ring.push_back(get(get(CGAL::vertex_point, m), source(h, m)));
      if constexpr(!uniform) ring_density.push_back(vertex_density(source(h, m)));
    }
    std::reverse(ring.begin(), ring.end());  // counter-clockwise around v
    std::reverse(ring_density.begin(), ring_density.end());
    double own_density = 1;
    if constexpr(!uniform) own_density = vertex_density(v);
    const std::size_t n = ring.size();
    if(n < 3) return false;
    const Point_3& p = get(get(CGAL::vertex_point, m), v);
    std::vector<double> theta(n), len(n);
    double total = 0;
    for(std::size_t i = 0; i < n; ++i) {
      theta[i] = angle(ring[i], p, ring[(i + 1) % n]);
      len[i] = std::sqrt(CGAL::to_double(CGAL::squared_distance(ring[i], p)));
      total += theta[i];
    }
    if(!(total > 0)) return false;
    std::vector<std::array<double, 2>> q(n);
    double phi = 0;
    for(std::size_t i = 0; i < n; ++i) {
      q[i] = {{len[i] * std::cos(phi), len[i] * std::sin(phi)}};
      phi += 2 * CGAL_PI * theta[i] / total;
    }
    double cx = 0, cy = 0, wsum = 0;
    for(std::size_t i = 0; i < n; ++i) {
      const auto& a = q[i];
      const auto& b = q[(i + 1) % n];
      double w = area_weighted_ ? 0.5 * std::abs(a[0] * b[1] - a[1] * b[0]) : 1.0;
      if constexpr(!uniform) w *= (own_density + ring_density[i] + ring_density[(i + 1) % n]) / 3.0;
      cx += w * (a[0] + b[0]) / 3.0;
      cy += w * (a[1] + b[1]) / 3.0;
      wsum += w;
    }
    if(!(wsum > 0)) return false;
    cx /= wsum;
    cy /= wsum;
    // the ring triangle (0, q_i, q_i+1) that contains (cx, cy)
    for(int shrink = 0; shrink < 8; ++shrink) {
      for(std::size_t i = 0; i < n; ++i) {
        const auto& a = q[i];
        const auto& b = q[(i + 1) % n];
        const double det = a[0] * b[1] - a[1] * b[0];
        if(!(std::abs(det) > 0)) continue;
        const double u = (cx * b[1] - cy * b[0]) / det, w = (a[0] * cy - a[1] * cx) / det;
        if(u >= -1e-12 && w >= -1e-12 && u + w <= 1 + 1e-12) {
          const Point_3& A = ring[i];
          const Point_3& B = ring[(i + 1) % n];
          target = p + u * (A - p) + w * (B - p);
          return true;
        }
      }
      cx *= 0.5;  // concave ring: pull towards the vertex until inside
      cy *= 0.5;
    }
    return false;
  }

  template <class Mesh>
  bool folds(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, const Point_3& to) const
  {
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      if(is_border(h, m)) continue;
      const Point_3& a = get(get(CGAL::vertex_point, m), source(h, m));
      const Point_3& b = get(get(CGAL::vertex_point, m), target(next(h, m), m));
      // triangle (a, v, b) in this order around the face
      const Vector_3 before = normal(a, get(get(CGAL::vertex_point, m), v), b), after = normal(a, to, b);
      if(cos_between(before, after) < 0.5) return true;
    }
    return false;
  }

  template <class Mesh, class IsFeatureEdge, class IsCorner>
  void lloyd_pass(Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, Relaxation_statistics& stats) const
  {
    lloyd_pass(m, is_feature, is_corner, stats, Unit_density());
  }

  template <class Mesh, class IsFeatureEdge, class IsCorner, class VertexDensity>
  void lloyd_pass(Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, Relaxation_statistics& stats,
                  VertexDensity vertex_density, double min_angle_degrees = 0) const
  {
    const double floor = min_angle_degrees * CGAL_PI / 180;
    for(auto v : vertices(m)) {
      if(is_corner(v)) continue;
      const std::size_t fd = feature_degree(v, m, is_feature);
      Point_3 target;
      double max_jump = 0;   // (a free vertex: how far its projection onto the input may jump)
      if(fd == 0) {
        if(!lloyd_target(v, m, target, vertex_density)) continue;
        // the closest point of the input must be the local one: in thin parts (horns, legs, tails)
        // the other side can be closer; a projection farther than a fraction of the ring's size
        // is refused (the paper projects through a local parameterization for the same reason)
        const Point_3 projected = project_on_surface(target, get(get(CGAL::vertex_point, m), v));
        double ring = 0;
        std::size_t nr = 0;
        for(auto h : CGAL::halfedges_around_target(v, m)) {
          ring += std::sqrt(CGAL::to_double(CGAL::squared_distance(get(get(CGAL::vertex_point, m), source(h, m)), get(get(CGAL::vertex_point, m), v))));
          ++nr;
        }
        if(nr > 0) max_jump = 0.25 * ring / double(nr);
        if(nr == 0 || CGAL::to_double(CGAL::squared_distance(projected, target)) > CGAL::square(max_jump)) {
          ++stats.refused_moves;
          continue;
        }
        target = projected;
      } else if(fd == 2) {
        std::vector<Point_3> ends;
        for(auto h : CGAL::halfedges_around_target(v, m))
          if(is_feature(edge(h, m)) || is_border(edge(h, m), m)) ends.push_back(get(get(CGAL::vertex_point, m), source(h, m)));
        target = project_on_features(CGAL::midpoint(ends[0], ends[1]), get(get(CGAL::vertex_point, m), v));
      } else {
        continue;
      }
      if(folds(v, m, target)) { ++stats.refused_moves; continue; }
      if(floor > 0) {   // (Relaxation_settings::lloyd_min_angle)
        const Point_3 from = get(get(CGAL::vertex_point, m), v);
        const double before = smallest_angles_around(v, m, from).first;
        double after = smallest_angles_around(v, m, target).first;
        if(after < floor && after < before) {   // half the way, on the input (on the curve)
          const Point_3 half = CGAL::midpoint(from, target);
          target = fd == 0 ? project_on_surface(half, from) : project_on_features(half, from);
          if(fd == 0 && CGAL::to_double(CGAL::squared_distance(target, half)) > CGAL::square(max_jump)) { ++stats.refused_moves; continue; }
          after = smallest_angles_around(v, m, target).first;
        }
        if(after < floor && after < before) { ++stats.refused_moves; continue; }
      }
      put(get(CGAL::vertex_point, m), v, target);
      ++stats.moves;
    }
  }

  // the two new triangles of a flip stay close to the old ones
  template <class Mesh>
  bool flip_is_safe(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m, double cos_max) const
  {
    const auto p = source(h, m), q = target(h, m);
    const auto r = target(next(h, m), m), s = target(next(opposite(h, m), m), m);
    if(r == s || halfedge(r, s, m).second) return false;
    if(degree(p, m) <= 3 || degree(q, m) <= 3) return false;
    const Point_3 &P = get(get(CGAL::vertex_point, m), p), &Q = get(get(CGAL::vertex_point, m), q), &R = get(get(CGAL::vertex_point, m), r), &S = get(get(CGAL::vertex_point, m), s);
    const Vector_3 n1 = normal(P, Q, R), n2 = normal(Q, P, S);
    const Vector_3 m1 = normal(R, S, Q), m2 = normal(S, R, P);   // new triangles (r, s, q), (s, r, p)
    // (area-weighted: the normal of a nearly flat triangle is noise)
    const Vector_3 avg = n1 + n2;
    return cos_between(m1, avg) > cos_max && cos_between(m2, avg) > cos_max && cos_between(m1, m2) > cos_max;
  }

  // how many more of its four vertices a flip of h makes irregular (valence not 6, not 4 on a
  // border): negative when fewer
  template <class Mesh>
  static int irregular_change(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m)
  {
    auto irregular = [&](auto v, int change) { return int(degree(v, m)) + change != (is_border(v, m) ? 4 : 6) ? 1 : 0; };
    const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
    return irregular(p, -1) + irregular(q, -1) + irregular(r, 1) + irregular(t, 1)
         - (irregular(p, 0) + irregular(q, 0) + irregular(r, 0) + irregular(t, 0));
  }
  // the smallest angle of the two triangles of h, and of the two a flip of h would make
  template <class Mesh>
  static double min_angle_of_faces(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m)
  {
    auto vpm = get(CGAL::vertex_point, m);
    const Point_3 &P = get(vpm, source(h, m)), &Q = get(vpm, target(h, m));
    const Point_3 &R = get(vpm, target(next(h, m), m)), &T = get(vpm, target(next(opposite(h, m), m), m));
    return std::min(min_angle(P, Q, R), min_angle(Q, P, T));
  }
  template <class Mesh>
  static double min_angle_after_flip(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Mesh& m)
  {
    auto vpm = get(CGAL::vertex_point, m);
    const Point_3 &P = get(vpm, source(h, m)), &Q = get(vpm, target(h, m));
    const Point_3 &R = get(vpm, target(next(h, m), m)), &T = get(vpm, target(next(opposite(h, m), m), m));
    return std::min(min_angle(R, T, Q), min_angle(T, R, P));
  }

  template <class Mesh, class IsFeatureEdge>
  void delaunay_pass(Mesh& m, IsFeatureEdge is_feature, const Relaxation_settings& s, Relaxation_statistics& stats,
                     bool keep_regularity = false) const
  {
    const double cos_max = std::cos(s.max_flip_normal_change * CGAL_PI / 180);
    const double sliver = s.sliver_angle * CGAL_PI / 180;
    for(int round = 0; round < 4; ++round) {
      std::size_t flips = 0;
      for(auto e : edges(m)) {
        if(is_feature(e) || is_border(e, m)) continue;
        auto h = halfedge(e, m);
        const Point_3 &P = get(get(CGAL::vertex_point, m), source(h, m)), &Q = get(get(CGAL::vertex_point, m), target(h, m));
        const Point_3 &R = get(get(CGAL::vertex_point, m), target(next(h, m), m)), &S = get(get(CGAL::vertex_point, m), target(next(opposite(h, m), m), m));
        if(angle(P, R, Q) + angle(P, S, Q) <= CGAL_PI + 1e-9) continue;
        if(keep_regularity && irregular_change(h, m) > 0) {
          const double old_min = min_angle_of_faces(h, m);
          if(old_min >= sliver || min_angle_after_flip(h, m) <= old_min) continue;
        }
        if(!flip_is_safe(h, m, cos_max)) continue;
        CGAL::Euler::flip_edge(h, m);
        ++flips;
      }
      stats.delaunay_flips += flips;
      if(flips == 0) break;
    }
  }

  template <class Mesh>
  double ideal_valence(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m) const
  {
    double sum = 0;
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      if(is_border(h, m)) continue;
      sum += angle(get(get(CGAL::vertex_point, m), source(h, m)), get(get(CGAL::vertex_point, m), v), get(get(CGAL::vertex_point, m), target(next(h, m), m)));
    }
    return sum * 180 / CGAL_PI / 60 + (is_border(v, m) ? 1 : 0);
  }

  // flips that make fewer of their four vertices irregular (valence not 6, not 4 on a border),
  // keeping both new triangles' smallest angle over regularity_min_angle
  template <class Mesh, class IsFeatureEdge>
  std::size_t regularity_pass(Mesh& m, IsFeatureEdge is_feature, const Relaxation_settings& s, Relaxation_statistics& stats,
                              double min_angle_degrees = -1,   // (< 0: regularity_min_angle)
                              // (given, it gets the flipped edges, and no look-ahead flip is made:
                              // single flips can be undone in reverse order)
                              std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor>* flipped = nullptr) const
  {
    const double cos_max = std::cos(s.max_flip_normal_change * CGAL_PI / 180);
    const double floor = (min_angle_degrees < 0 ? s.regularity_min_angle : min_angle_degrees) * CGAL_PI / 180;
    typedef typename boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
    const int no = 99;
    // the change of the number of irregular vertices a flip of h makes, or `no` when it may not be made
    auto gain = [&](halfedge_descriptor h) {
      if(is_feature(edge(h, m)) || is_border(edge(h, m), m)) return no;
      const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
      if(degree(p, m) <= 3 || degree(q, m) <= 3 || halfedge(r, t, m).second) return no;
      const int change = irregular_change(h, m);
      if(change > 0) return no;
      if(min_angle_after_flip(h, m) < floor) return no;
      if(!flip_is_safe(h, m, cos_max)) return no;
      return change;
    };
    const bool lookahead = s.regularity_lookahead;
    std::size_t flips = 0;
    std::vector<halfedge_descriptor> around;
    for(auto e : edges(m)) {
      auto h = halfedge(e, m);
      const int g = gain(h);
      if(g == no || g > 0) continue;
      if(g < 0) { CGAL::Euler::flip_edge(h, m); ++flips; if(flipped) flipped->push_back(h); continue; }
      if(!lookahead || flipped) continue;
      // a flip that only moves an irregular vertex, when a second flip next to it then removes one
      const auto p = source(h, m), q = target(h, m);
      CGAL::Euler::flip_edge(h, m);
      around.clear();
      for(auto x : {p, q, source(h, m), target(h, m)})
        for(auto k : CGAL::halfedges_around_target(x, m))
          if(edge(k, m) != edge(h, m)) around.push_back(k);
      bool done = false;
      for(auto k : around)
        if(gain(k) < 0) { CGAL::Euler::flip_edge(k, m); flips += 2; done = true; break; }
      if(!done) CGAL::Euler::flip_edge(h, m);
    }
    stats.valence_flips += flips;
    return flips;
  }

  template <class Mesh, class IsFeatureEdge>
  void valence_pass(Mesh& m, IsFeatureEdge is_feature, const Relaxation_settings& s, Relaxation_statistics& stats) const
  {
    const double cos_max = std::cos(s.max_flip_normal_change * CGAL_PI / 180);
    // the ideal valences, computed once per vertex and again only after a flip at the vertex
    auto cache = get(CGAL::dynamic_vertex_property_t<double>(), m);
    for(auto v : vertices(m)) put(cache, v, -1.0);
    auto ideal = [&](typename boost::graph_traits<Mesh>::vertex_descriptor v) {
      double o = get(cache, v);
      if(o < 0) { o = ideal_valence(v, m); put(cache, v, o); }
      return o;
    };
    for(auto e : edges(m)) {
      if(is_feature(e) || is_border(e, m)) continue;
      auto h = halfedge(e, m);
      const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
      const double dp = double(degree(p, m)), dq = double(degree(q, m)), dr = double(degree(r, m)), dt = double(degree(t, m));
      const double op = ideal(p), oq = ideal(q), orr = ideal(r), ot = ideal(t);
      auto sq = [](double x) { return x * x; };
      const double before = sq(dp - op) + sq(dq - oq) + sq(dr - orr) + sq(dt - ot);
      const double after = sq(dp - 1 - op) + sq(dq - 1 - oq) + sq(dr + 1 - orr) + sq(dt + 1 - ot);
      if(after >= before - 1e-9) continue;
      if(min_angle_after_flip(h, m) < s.valence_flip_min_angle_ratio * min_angle_of_faces(h, m)) continue;
      if(!flip_is_safe(h, m, cos_max)) continue;
      CGAL::Euler::flip_edge(h, m);
      for(auto x : {p, q, r, t}) put(cache, x, -1.0);
      ++stats.valence_flips;
    }
  }


  // calls f(x) for each vertex of the faces that intersect now but not in `before` (sorted pairs),
  // where only the faces of `changed` moved or are new since `before` was taken
  template <class Mesh, class Pairs, class FaceRange, class F>
  void for_vertices_of_new_intersections(const Mesh& m, const Pairs& before, const FaceRange& changed, F f) const
  {
    for(const auto& fp : internal::intersecting_pairs_near(m, changed)) {
      if(std::binary_search(before.begin(), before.end(), fp)) continue;
      if(near_input_crossing(fp.first, m) && near_input_crossing(fp.second, m)) continue;
      for(auto face : {fp.first, fp.second})
        for(auto x : CGAL::vertices_around_face(halfedge(face, m), m)) f(x);
    }
  }

  // whether the centroid of face f of m lies within two of f's longest edge's lengths of the
  // centroid of a face of the input that cuts the input (one part of it runs through another): the
  // mesh follows the input there, and a crossing of it is the input's own (the quality report
  // leaves out such crossings too, by its own measure: two mean edge lengths of tm to the face)
  template <class Mesh>
  bool near_input_crossing(typename boost::graph_traits<Mesh>::face_descriptor f, const Mesh& m) const
  {
    if(!input_crossings_known_) {
      input_crossings_known_ = true;
      const auto pairs = internal::intersecting_pairs(input_);
      const auto vpm = get(CGAL::vertex_point, input_);
      std::vector<typename boost::graph_traits<InputMesh>::face_descriptor> crossing;
      for(const auto& fp : pairs) { crossing.push_back(fp.first); crossing.push_back(fp.second); }
      std::sort(crossing.begin(), crossing.end());
      crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
      for(auto g : crossing) {
        const auto h = halfedge(g, input_);
        input_crossings_.push_back(CGAL::centroid(get(vpm, source(h, input_)), get(vpm, target(h, input_)), get(vpm, target(next(h, input_), input_))));
      }
    }
    if(input_crossings_.empty()) return false;
    const auto vpm = get(CGAL::vertex_point, m);
    const auto h = halfedge(f, m);
    const Point_3 &a = get(vpm, source(h, m)), &b = get(vpm, target(h, m)), &c = get(vpm, target(next(h, m), m));
    const double reach2 = 4 * std::max({CGAL::to_double(CGAL::squared_distance(a, b)), CGAL::to_double(CGAL::squared_distance(b, c)),
                                        CGAL::to_double(CGAL::squared_distance(c, a))});
    const Point_3 x = CGAL::centroid(a, b, c);
    for(const Point_3& p : input_crossings_)
      if(CGAL::to_double(CGAL::squared_distance(p, x)) <= reach2) return true;
    return false;
  }

  // the smallest angle of the triangles around v with v at `at`, and the sum of their smallest
  // angles; (-1, -1) when one of them would turn over (its normal more than 60 degrees away from
  // the current one)
  template <class Mesh>
  std::pair<double, double> smallest_angles_around(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m,
                                                   const Point_3& at) const
  {
    return smallest_angles_around(v, m, at, [](typename boost::graph_traits<Mesh>::vertex_descriptor) { return 1.0; });
  }
  // the same with the angles at each other vertex x of the triangles scaled by tip_scale(x)
  template <class Mesh, class TipScale>
  std::pair<double, double> smallest_angles_around(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m,
                                                   const Point_3& at, TipScale tip_scale) const
  {
    auto vpm = get(CGAL::vertex_point, m);
    double worst = CGAL_PI, sum = 0;
    for(auto h : CGAL::halfedges_around_target(v, m)) {
      if(is_border(h, m)) continue;
      const Point_3& a = get(vpm, source(h, m));
      const Point_3& b = get(vpm, target(next(h, m), m));
      if(cos_between(normal(a, get(vpm, v), b), normal(a, at, b)) < 0.5) return {-1, -1};
      const double sa = tip_scale(source(h, m)), sb = tip_scale(target(next(h, m), m));
      const double x = sa == 1 && sb == 1 ? min_angle(a, at, b)
                                          : std::min({angle(at, a, b) * sa, angle(a, at, b), angle(a, b, at) * sb});
      worst = std::min(worst, x);
      sum += x;
    }
    return {worst, sum};
  }

  enum class Angle_goal { smallest, sum_of_smallest };

  // moves vertices by a pattern search on the input (feature vertices along their curves): with
  // Angle_goal::smallest, the movable vertices of the triangles sharper than optimized_angle, to raise
  // the smallest angle around them; with Angle_goal::sum_of_smallest, every movable vertex, to
  // raise the sum of its triangles' smallest angles without lowering the smallest (free vertices
  // search in their tangent plane and are projected once: it is a smoothing of vertices already
  // well placed, with a shorter search). Returns the number of vertices moved.
  template <class Mesh, class IsFeatureEdge, class IsCorner>
  std::size_t angle_pass(Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s,
                         Relaxation_statistics& stats, Angle_goal goal) const
  {
    return angle_pass(m, is_feature, is_corner, s, stats, goal, [](typename boost::graph_traits<Mesh>::vertex_descriptor) -> const Point_3* { return nullptr; }, false);
  }
  // the same; with `pinned_only` (Angle_goal::smallest), only the vertices of the fidelity pass
  // (fixed for is_corner) at a triangle sharper than sliver_angle move, by a quarter of the
  // fidelity tolerance at most from where they were put, `pin_anchor(x)` (nullptr for the others):
  // they still hold the mesh near the input
  template <class Mesh, class IsFeatureEdge, class IsCorner, class PinAnchor>
  std::size_t angle_pass(Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s,
                         Relaxation_statistics& stats, Angle_goal goal, PinAnchor pin_anchor, bool pinned_only) const
  {
    typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
    auto vpm = get(CGAL::vertex_point, m);
    const bool smoothing = goal == Angle_goal::sum_of_smallest;
    const double sharp = s.optimized_angle * CGAL_PI / 180;   // (Angle_goal::smallest only)
    std::vector<vertex_descriptor> todo;
    // a feature vertex with one feature edge (the output's edge along its curve is a chord too far
    // from the curve to count) slides along the curve too when it is at a sliver
    const double pin_reach = 0.25 * s.max_deviation * diagonal_, sliver = s.sliver_angle * CGAL_PI / 180;
    auto movability = [&](vertex_descriptor x) {
      if(pinned_only)
        return pin_reach > 0 && pin_anchor(x) != nullptr && feature_degree(x, m, is_feature) == 0 && !is_border(x, m) &&
               smallest_angles_around(x, m, get(vpm, x)).first < sliver ? 0 : 2;
      const int c = constraint(x, m, is_feature, is_corner);
      return !smoothing && c == 2 && !is_corner(x) && feature_degree(x, m, is_feature) == 1 ? 1 : c;
    };
    if(smoothing) {
      for(vertex_descriptor x : vertices(m)) if(movability(x) < 2) todo.push_back(x);
    } else {
      for(auto f : faces(m)) {
        const auto h = halfedge(f, m);
        const vertex_descriptor v[3] = {source(h, m), target(h, m), target(next(h, m), m)};
        if(min_angle(get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2])) >= sharp) continue;
        for(vertex_descriptor x : v) if(movability(x) < 2) todo.push_back(x);
      }
      std::sort(todo.begin(), todo.end());
      todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
    }
    // a tip -- a fixed vertex on no feature curve whose angles sum to less than 90 degrees -- has
    // triangles sharper than 30 degrees whatever its neighbours do: its angles count times 90
    // degrees over its angle sum (a third of the sum counts as 30), so that the neighbours raise
    // their own angles (a cone tip of 83 degrees: its three triangles at best 27.7 degrees there,
    // the other two angles of each then depend on the neighbours)
    std::map<vertex_descriptor, double> tips;
    std::set<vertex_descriptor> checked;
    for(vertex_descriptor x : todo)
      for(auto h : CGAL::halfedges_around_target(x, m)) {
        const vertex_descriptor t = source(h, m);
        if(!is_corner(t) || !checked.insert(t).second || is_border(t, m) || feature_degree(t, m, is_feature) != 0) continue;
        double sum = 0;
        for(auto g : CGAL::halfedges_around_target(t, m))
          sum += angle(get(vpm, source(g, m)), get(vpm, t), get(vpm, target(next(g, m), m)));
        if(sum > 0 && sum < CGAL_PI / 2) tips[t] = CGAL_PI / 2 / sum;
      }
    auto tip_scale = [&](vertex_descriptor x) {
      if(tips.empty()) return 1.0;
      const auto it = tips.find(x);
      return it == tips.end() ? 1.0 : it->second;
    };
    typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
    std::vector<std::pair<face_descriptor, face_descriptor>> before;   // intersections there already
    if(!todo.empty()) {
      // (only the faces around `todo` can move: around a few slivers, their neighbourhood is
      // enough; the smoothing moves every vertex)
      before = smoothing ? internal::intersecting_pairs(m) : internal::intersecting_pairs_near(m, internal::faces_around(m, todo));
      // (a mesh that cuts itself everywhere -- folded input -- is not worth the checks)
      if(before.size() > num_faces(m)) return 0;
    }
    std::size_t moved = 0;
    std::vector<std::pair<vertex_descriptor, Point_3>> from;   // where the moved vertices were
    for(vertex_descriptor v : todo) {
      const int c = movability(v);
      const Point_3* anchor = pinned_only ? pin_anchor(v) : nullptr;
      const Point_3 start = get(vpm, v);
      Point_3 p = start;
      const double floor = smallest_angles_around(v, m, p, tip_scale).first;
      auto objective = [&](const Point_3& q) {
        const auto [smallest, sum] = smallest_angles_around(v, m, q, tip_scale);
        if(!smoothing || smallest < 0) return smallest;
        return smallest < floor ? -1.0 : sum;
      };
      double best = objective(p);
      if(best < 0) continue;
      // directions: the tangent plane (8 of them), or along the feature curve (2)
      std::vector<Vector_3> dirs;
      double mean = 0;
      std::size_t n = 0;
      Vector_3 nv(0, 0, 0);
      for(auto h : CGAL::halfedges_around_target(v, m)) {
        const Point_3& a = get(vpm, source(h, m));
        mean += std::sqrt(CGAL::to_double(CGAL::squared_distance(a, p)));
        ++n;
        if(c == 1 && (is_feature(edge(h, m)) || is_border(edge(h, m), m))) {
          const Vector_3 d = a - p;
          dirs.push_back(d / std::sqrt(CGAL::to_double(d.squared_length())));
        }
        if(!is_border(h, m)) nv = nv + normal(a, p, get(vpm, target(next(h, m), m)));
      }
      if(n == 0) continue;
      mean /= double(n);
      // (one feature edge: the vertex may be the loose end of a curve at a tip, it moves little)
      const bool loose_end = c == 1 && dirs.size() == 1;
      if(loose_end) dirs.push_back(-dirs[0]);
      if(c == 0) {
        const double ln = std::sqrt(CGAL::to_double(nv.squared_length()));
        if(!(ln > 0)) continue;
        const Vector_3 nn = nv / ln;
        Vector_3 u = CGAL::cross_product(nn, Vector_3(1, 0, 0));
        if(CGAL::to_double(u.squared_length()) < 0.1) u = CGAL::cross_product(nn, Vector_3(0, 1, 0));
        u = u / std::sqrt(CGAL::to_double(u.squared_length()));
        const Vector_3 w = CGAL::cross_product(nn, u);
        for(int k = 0; k < 8; ++k) dirs.push_back(std::cos(k * CGAL_PI / 4) * u + std::sin(k * CGAL_PI / 4) * w);
      }
      if(dirs.empty()) continue;
      // (at most 40 steps: gains that never stop, however small -- a flat double-sided sheet
      // found by fuzzing -- kept the step from shrinking)
      const bool in_plane = smoothing && c == 0;
      double step = (smoothing ? 0.1 : 0.2) * mean;
      for(int iteration = 0; iteration < (smoothing ? 10 : 40) && step > 0.01 * mean; ++iteration) {
        Point_3 best_q = p;
        double best_here = best;
        for(const Vector_3& d : dirs) {
          const Point_3 t = p + step * d;
          const Point_3 q = in_plane ? t : c == 0 ? project_on_surface(t, p) : project_on_features(t, p);
          if(CGAL::to_double(CGAL::squared_distance(q, t)) > CGAL::square(0.25 * mean)) continue;   // thin parts
          if(loose_end && CGAL::to_double(CGAL::squared_distance(q, start)) > CGAL::square(0.25 * mean)) continue;
          if(anchor != nullptr && CGAL::to_double(CGAL::squared_distance(q, *anchor)) > pin_reach * pin_reach) continue;
          const double a = objective(q);
          if(a > best_here + 1e-9) { best_here = a; best_q = q; }
        }
        if(best_here > best + 1e-6) { best = best_here; p = best_q; }
        else step *= 0.5;
      }
      if(in_plane && p != start) {   // onto the input; kept if still better there
        p = project_on_surface(p, start);
        if(!(objective(p) > objective(start))) p = start;
      }
      if(p != start) { put(vpm, v, p); from.push_back({v, start}); ++moved; }
    }
    // a move may not make the mesh cut itself (thin parts): the moved vertices of triangles
    // that intersect anew go back, until no new intersection is left
    if(moved > 0) {
      std::sort(from.begin(), from.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      std::vector<vertex_descriptor> movers;
      for(const auto& x : from) movers.push_back(x.first);
      const auto changed = internal::faces_around(m, movers);
      for(int round = 0; round < 8; ++round) {
        std::size_t back = 0;
        for_vertices_of_new_intersections(m, before, changed, [&](vertex_descriptor x) {
          auto it = std::lower_bound(from.begin(), from.end(), x, [](const auto& y, vertex_descriptor z) { return y.first < z; });
          if(it != from.end() && it->first == x && get(vpm, x) != it->second) { put(vpm, x, it->second); ++back; }
        });
        if(back == 0) break;
        moved -= std::min(moved, back);
        stats.refused_moves += back;
      }
    }
    stats.angle_moves += moved;
    return moved;
  }

  // what a vertex may do: 2 fixed (a corner, or where features meet), 1 slide on a feature, 0 free
  template <class Mesh, class IsFeatureEdge, class IsCorner>
  int constraint(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner) const
  {
    if(is_corner(v)) return 2;
    const std::size_t fd = feature_degree(v, m, is_feature);
    return fd == 0 ? 0 : fd == 2 ? 1 : 2;
  }

  // splits the edge of h at `at` and its (one or two) triangles: the new vertex, of degree 3 or 4
  template <class Mesh>
  static typename boost::graph_traits<Mesh>::vertex_descriptor
  insert_vertex_on_edge(typename boost::graph_traits<Mesh>::halfedge_descriptor h, const Point_3& at, Mesh& m)
  {
    const auto g0 = opposite(h, m);
    const auto hnew = CGAL::Euler::split_edge(h, m);   // hnew points to the new vertex, followed by h
    const auto v = target(hnew, m);
    put(get(CGAL::vertex_point, m), v, at);
    for(auto g : {hnew, g0})
      if(!is_border(g, m)) CGAL::Euler::split_face(g, next(next(g, m), m), m);
    return v;
  }

  // the inverse of insert_vertex_on_edge for an interior edge (a, b): v's four triangles become two
  template <class Mesh>
  static void remove_vertex_on_edge(typename boost::graph_traits<Mesh>::vertex_descriptor v,
                                    typename boost::graph_traits<Mesh>::vertex_descriptor a,
                                    typename boost::graph_traits<Mesh>::vertex_descriptor b, Mesh& m)
  {
    const auto g = CGAL::Euler::remove_center_vertex(halfedge(v, m), m);
    auto to_a = boost::graph_traits<Mesh>::null_halfedge(), to_b = boost::graph_traits<Mesh>::null_halfedge();
    for(auto x : CGAL::halfedges_around_face(g, m)) {
      if(target(x, m) == a) to_a = x;
      if(target(x, m) == b) to_b = x;
    }
    CGAL::Euler::split_face(to_a, to_b, m);
  }

  template <class Mesh, class IsFeatureEdge, class NewVertex>
  std::size_t split_pass(Mesh& m, IsFeatureEdge is_feature, NewVertex new_vertex, const Relaxation_settings& s,
                         Relaxation_statistics& stats) const
  {
    typedef boost::graph_traits<Mesh> GT;
    typedef typename GT::vertex_descriptor vertex_descriptor;
    typedef typename GT::halfedge_descriptor halfedge_descriptor;
    auto vpm = get(CGAL::vertex_point, m);
    auto length = [&](vertex_descriptor a, vertex_descriptor b) { return std::sqrt(CGAL::to_double(CGAL::squared_distance(get(vpm, a), get(vpm, b)))); };
    std::vector<std::pair<vertex_descriptor, vertex_descriptor>> long_edges;
    for(auto e : edges(m)) {
      if(!is_feature(e) && !is_border(e, m)) continue;   // (free edges: the Lloyd rounds even them out)
      const vertex_descriptor a = source(halfedge(e, m), m), b = target(halfedge(e, m), m);
      double sum = 0;
      std::size_t n = 0;
      for(vertex_descriptor x : {a, b})
        for(auto h : CGAL::halfedges_around_target(x, m))
          if(edge(h, m) != e && !is_feature(edge(h, m)) && !is_border(edge(h, m), m)) { sum += length(source(h, m), x); ++n; }
      if(n > 0 && length(a, b) > s.long_edge_ratio * sum / double(n)) long_edges.push_back({a, b});
    }
    std::size_t done = 0;
    for(const auto& ab : long_edges) {
      const auto h = halfedge(ab.first, ab.second, m);
      if(!h.second) continue;
      const bool on_feature = is_feature(edge(h.first, m)) || is_border(edge(h.first, m), m);
      const Point_3 chord_mid = CGAL::midpoint(get(vpm, ab.first), get(vpm, ab.second));
      const Point_3 mid = on_feature ? project_on_features(chord_mid) : project_on_surface(chord_mid);
      // the feature must run along the edge: a curve that bends away (the projection lands far
      // from the chord) would fold the new triangles
      if(CGAL::to_double(CGAL::squared_distance(mid, chord_mid)) > CGAL::square(0.1 * length(ab.first, ab.second))) continue;
      // and the four new triangles stay close to the two old ones (no fold on thin parts)
      bool folds = false;
      for(halfedge_descriptor g : {h.first, opposite(h.first, m)}) {
        if(is_border(g, m)) continue;
        const Point_3 &P = get(vpm, source(g, m)), &Q = get(vpm, target(g, m)), &R = get(vpm, target(next(g, m), m));
        const Vector_3 n = normal(P, Q, R);
        if(cos_between(normal(P, mid, R), n) < 0.8 || cos_between(normal(mid, Q, R), n) < 0.8) folds = true;
      }
      if(folds) continue;
      const vertex_descriptor v = insert_vertex_on_edge(h.first, mid, m);
      new_vertex(v, on_feature);
      ++done;
    }
    stats.splits += done;
    return done;
  }

  // a vertex on an edge of each triangle sharper than sliver_angle (see refinement_rounds)
  template <class Mesh, class IsFeatureEdge, class IsCorner, class NewVertex>
  std::size_t refinement_pass(Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, NewVertex new_vertex, const Relaxation_settings& s,
                              Relaxation_statistics& stats,
                              std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>& pinned) const   // (sorted)
  {
    typedef boost::graph_traits<Mesh> GT;
    typedef typename GT::vertex_descriptor vertex_descriptor;
    typedef typename GT::halfedge_descriptor halfedge_descriptor;
    typedef typename GT::face_descriptor face_descriptor;
    auto vpm = get(CGAL::vertex_point, m);
    const double sliver = s.sliver_angle * CGAL_PI / 180, gain = CGAL_PI / 180;
    // a new vertex on the edge of h, a flip of that edge, or the removal of the free vertex
    // target(h) of degree 3
    enum class Operation { split, flip, remove };
    struct Candidate
    {
      double gain;
      halfedge_descriptor h;
      Point_3 at;
      bool on_feature;
      Operation op;
      std::vector<face_descriptor> faces;   // the faces the change replaces (checked before h is used)
    };
    const double cos_refine = 0.5;
    std::vector<Candidate> candidates;
    for(face_descriptor f : faces(m)) {
      const halfedge_descriptor hf = halfedge(f, m);
      const vertex_descriptor v[3] = {source(hf, m), target(hf, m), target(next(hf, m), m)};
      const Point_3 p[3] = {get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2])};
      const double old_f = min_angle(p[0], p[1], p[2]);
      if(!(old_f < sliver)) continue;
      // the vertex of the smallest angle, and the two edges there
      const double a[3] = {angle(p[1], p[0], p[2]), angle(p[0], p[1], p[2]), angle(p[0], p[2], p[1])};
      const int k = int(std::min_element(a, a + 3) - a);
      Candidate best{0, GT::null_halfedge(), Point_3(), false, Operation::split, {}};
      for(halfedge_descriptor h : CGAL::halfedges_around_face(hf, m)) {
        // flip: the two new triangles beat the two old ones
        if(!is_feature(edge(h, m)) && !is_border(edge(h, m), m)) {
          const Point_3 &A = get(vpm, source(h, m)), &B = get(vpm, target(h, m));
          const Point_3 &C = get(vpm, target(next(h, m), m)), &D = get(vpm, target(next(opposite(h, m), m), m));
          // (the guards of the Delaunay flips, with the looser normal change of the tessellation's
          // removals, 60 degrees: the triangles here are the worst of the mesh, their normals noisy)
          if(flip_is_safe(h, m, cos_refine)) {
            const double old = std::min(old_f, min_angle(B, A, D));
            const double value = std::min(min_angle(C, A, D), min_angle(D, B, C));
            if(value > old + gain && value - old > best.gain) best = {value - old, h, Point_3(), false, Operation::flip, {f, face(opposite(h, m), m)}};
          }
        }
        // removal of target(h), a vertex of degree 3 off the features: its three triangles become
        // one (a pinned vertex of the fidelity pass too: the new triangle passes near it, see below)
        const vertex_descriptor x = target(h, m);
        // (constraint 0: no corner, no feature or border edge)
        if(degree(x, m) == 3 && constraint(x, m, is_feature, is_corner) == 0) {
          double old = CGAL_PI;
          Vector_3 n(0, 0, 0);
          std::vector<face_descriptor> star;
          bool closed = false;   // the three neighbours bound a face already (a tetrahedron)
          for(halfedge_descriptor g : CGAL::halfedges_around_target(x, m)) {
            const Point_3 &P = get(vpm, source(g, m)), &Q = get(vpm, target(next(g, m), m));
            old = std::min(old, min_angle(P, get(vpm, x), Q));
            n = n + normal(P, get(vpm, x), Q);
            star.push_back(face(g, m));
            // the link edge (b, a) of face (a, x, b): the face across it must not be (a, b, c)
            const halfedge_descriptor across = opposite(next(next(g, m), m), m);
            if(!is_border(across, m)) {
              const vertex_descriptor w = target(next(across, m), m);
              for(halfedge_descriptor k : CGAL::halfedges_around_target(x, m))
                if(source(k, m) == w && w != source(g, m) && w != target(next(g, m), m)) closed = true;
            }
          }
          // the new triangle runs along the link edges next(next(g)) = (b, a) of the faces (a, x, b)
          const halfedge_descriptor link = next(next(halfedge(x, m), m), m);
          // (the next link edge, from target(link), is in the face across the edge (x, target(link)))
          const Point_3 &P = get(vpm, source(link, m)), &Q = get(vpm, target(link, m));
          const Point_3& third = get(vpm, target(next(opposite(next(link, m), m), m), m));
          if(closed) continue;
          // (and the removed vertex is close to the new triangle, within half the fidelity tolerance:
          // a tip is not cut off)
          const double tol = (s.max_deviation > 0 ? 0.5 * s.max_deviation : 0.002) * diagonal_;
          if(cos_between(normal(P, Q, third), n) > 0.5 &&
             CGAL::to_double(CGAL::squared_distance(get(vpm, x), typename GeomTraits::Triangle_3(P, Q, third))) <= tol * tol) {
            const double value = min_angle(P, Q, third);
            if(value > old + gain && value - old > best.gain) best = {value - old, h, Point_3(), false, Operation::remove, star};
          }
        }
      }
      for(halfedge_descriptor h : CGAL::halfedges_around_face(hf, m)) {
        if(source(h, m) != v[k] && target(h, m) != v[k]) continue;
        if(is_border(opposite(h, m), m)) continue;
        const Point_3 &A = get(vpm, source(h, m)), &B = get(vpm, target(h, m));
        const Point_3 &C = get(vpm, target(next(h, m), m)), &D = get(vpm, target(next(opposite(h, m), m), m));
        const double old = std::min(old_f, min_angle(B, A, D));
        const bool on_feature = is_feature(edge(h, m));
        const Vector_3 n1 = normal(A, B, C), n2 = normal(B, A, D);
        // the four triangles (A, q, C), (q, B, C), (B, q, D), (q, A, D): the smallest angle, or -1
        // when one turns over
        auto objective = [&](const Point_3& q) {
          if(cos_between(normal(A, q, C), n1) < 0.5 || cos_between(normal(q, B, C), n1) < 0.5 ||
             cos_between(normal(B, q, D), n2) < 0.5 || cos_between(normal(q, A, D), n2) < 0.5) return -1.0;
          return std::min({min_angle(A, q, C), min_angle(q, B, C), min_angle(B, q, D), min_angle(q, A, D)});
        };
        const Point_3 mid = CGAL::midpoint(A, B);
        const double length = std::sqrt(CGAL::to_double(CGAL::squared_distance(A, B)));
        Point_3 q = on_feature ? project_on_features(mid) : project_on_surface(mid);
        if(CGAL::to_double(CGAL::squared_distance(q, mid)) > CGAL::square(0.25 * length)) continue;   // thin parts
        double value = objective(q);
        if(value < 0) continue;
        // pattern search: along the edge for a feature edge, else in the plane of the two faces
        std::vector<Vector_3> dirs;
        const Vector_3 ab = (B - A) / length;
        dirs.push_back(ab);
        dirs.push_back(-ab);
        if(!on_feature) {
          Vector_3 nn = n1 / std::sqrt(CGAL::to_double(n1.squared_length())) + n2 / std::sqrt(CGAL::to_double(n2.squared_length()));
          const Vector_3 w = CGAL::cross_product(nn, ab);
          const double lw = std::sqrt(CGAL::to_double(w.squared_length()));
          if(!(lw > 0)) continue;
          for(int sign : {1, -1}) {
            dirs.push_back(double(sign) * w / lw);
            dirs.push_back(std::sqrt(0.5) * (ab + double(sign) * w / lw));
            dirs.push_back(std::sqrt(0.5) * (-ab + double(sign) * w / lw));
          }
        }
        double step = 0.2 * length;
        for(int iteration = 0; iteration < 30 && step > 0.01 * length; ++iteration) {
          Point_3 best_q = q;
          double best_here = value;
          for(const Vector_3& d : dirs) {
            const Point_3 t = q + step * d;
            const Point_3 r = on_feature ? project_on_features(t, q) : project_on_surface(t, q);
            if(CGAL::to_double(CGAL::squared_distance(r, t)) > CGAL::square(0.25 * length)) continue;
            const double x = objective(r);
            if(x > best_here + 1e-9) { best_here = x; best_q = r; }
          }
          if(best_here > value + 1e-6) { value = best_here; q = best_q; }
          else step *= 0.5;
        }
        if(value > old + gain && value - old > best.gain) best = {value - old, h, q, on_feature, Operation::split, {f, face(opposite(h, m), m)}};
      }
      if(best.h != GT::null_halfedge()) candidates.push_back(best);
    }
    if(candidates.empty()) return 0;
    const auto before = internal::intersecting_pairs(m);
    if(before.size() > num_faces(m)) return 0;   // (folded everywhere: see angle_pass)
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) { return x.gain > y.gain; });
    std::set<face_descriptor> touched;
    struct Inserted { vertex_descriptor v; bool on_feature; vertex_descriptor a, b; };   // on the old edge (a, b)
    std::vector<Inserted> mine;
    std::vector<halfedge_descriptor> flipped;
    struct Removed { halfedge_descriptor h; Point_3 at; bool pinned; };   // a halfedge of the new triangle, where the vertex was, pinned
    std::vector<Removed> removed;
    // (the removals last: the faces they free are not reused by a split of this pass, which would
    // pair them with the old faces' intersections in `before`)
    std::stable_partition(candidates.begin(), candidates.end(), [](const Candidate& c) { return c.op != Operation::remove; });
    for(const Candidate& c : candidates) {
      // the faces changed and their neighbours take one change at most; a candidate whose faces
      // are untouched still has valid descriptors
      if(std::any_of(c.faces.begin(), c.faces.end(), [&](face_descriptor f) { return touched.count(f) > 0; })) continue;
      if(c.op == Operation::flip && !flip_is_safe(c.h, m, cos_refine)) continue;
      for(face_descriptor f : c.faces) {
        touched.insert(f);
        for(halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(f, m), m))
          if(!is_border(opposite(g, m), m)) touched.insert(face(opposite(g, m), m));
      }
      if(c.op == Operation::flip) {
        CGAL::Euler::flip_edge(c.h, m);
        flipped.push_back(c.h);
        continue;
      }
      if(c.op == Operation::remove) {
        const vertex_descriptor x = target(c.h, m);
        const Point_3 at = get(vpm, x);
        const auto it = std::lower_bound(pinned.begin(), pinned.end(), x);
        const bool was_pinned = it != pinned.end() && *it == x;
        if(was_pinned) pinned.erase(it);
        removed.push_back({CGAL::Euler::remove_center_vertex(halfedge(x, m), m), at, was_pinned});
        continue;
      }
      const vertex_descriptor a = source(c.h, m), b = target(c.h, m);
      mine.push_back({insert_vertex_on_edge(c.h, c.at, m), c.on_feature, a, b});
    }
    // a change that makes the mesh cut itself is taken back: an inserted vertex's four triangles
    // become the two old ones, a flip is flipped back, a removed vertex comes back
    std::vector<face_descriptor> cut;   // the faces of the new intersections
    std::vector<vertex_descriptor> inserted;
    for(const Inserted& x : mine) inserted.push_back(x.v);
    std::vector<face_descriptor> new_faces = internal::faces_around(m, inserted);   // the faces that are new
    for(halfedge_descriptor h : flipped)
      for(halfedge_descriptor g : {h, opposite(h, m)}) if(!is_border(g, m)) new_faces.push_back(face(g, m));
    for(const Removed& r : removed) new_faces.push_back(face(r.h, m));
    std::sort(new_faces.begin(), new_faces.end());
    new_faces.erase(std::unique(new_faces.begin(), new_faces.end()), new_faces.end());
    for(const auto& fp : internal::intersecting_pairs_near(m, new_faces))
      if(!std::binary_search(before.begin(), before.end(), fp)) { cut.push_back(fp.first); cut.push_back(fp.second); }
    std::sort(cut.begin(), cut.end());
    auto is_cut = [&](face_descriptor f) { return std::binary_search(cut.begin(), cut.end(), f); };
    std::size_t changed = 0;
    for(halfedge_descriptor h : flipped) {
      if(is_cut(face(h, m)) || is_cut(face(opposite(h, m), m))) { CGAL::Euler::flip_edge(h, m); ++stats.refused_moves; }
      else { ++changed; ++stats.refinement_flips; }
    }
    for(const Removed& r : removed) {
      if(is_cut(face(r.h, m))) {
        const vertex_descriptor v = target(CGAL::Euler::add_center_vertex(r.h, m), m);   // a new descriptor
        put(vpm, v, r.at);
        new_vertex(v, false);
        if(r.pinned) pinned.insert(std::lower_bound(pinned.begin(), pinned.end(), v), v);
        ++stats.refused_moves;
      } else {
        ++changed;
        ++stats.refinement_removals;
      }
    }
    std::vector<Inserted> undo;
    for(const Inserted& x : mine)
      for(halfedge_descriptor g : CGAL::halfedges_around_target(x.v, m))
        if(is_cut(face(g, m))) { undo.push_back(x); break; }
    auto by_vertex = [](const Inserted& x, const Inserted& y) { return x.v < y.v; };
    std::sort(undo.begin(), undo.end(), by_vertex);
    for(const Inserted& u : undo) {
      remove_vertex_on_edge(u.v, u.a, u.b, m);
      ++stats.refused_moves;
    }
    std::size_t done = 0;
    for(const Inserted& x : mine)
      if(!std::binary_search(undo.begin(), undo.end(), x, by_vertex)) { new_vertex(x.v, x.on_feature); ++done; }
    stats.refinement_insertions += done;
    return done + changed;
  }

  template <class Mesh, class IsFeatureEdge, class NewVertex>
  std::size_t fidelity_pass(Mesh& m, IsFeatureEdge is_feature, NewVertex new_vertex, const Relaxation_settings& s, Relaxation_statistics& stats,
                            std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>& added) const   // (kept sorted)
  {
    typedef boost::graph_traits<Mesh> GT;
    typedef typename GT::face_descriptor face_descriptor;
    typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
    typedef CGAL::AABB_tree<CGAL::AABB_traits<GeomTraits, Primitive>> Tree;
    auto vpm = get(CGAL::vertex_point, m);
    auto in_vpm = get(CGAL::vertex_point, input_);
    const double tol = s.max_deviation * diagonal_;
    if(!(tol > 0) || faces(m).empty()) return 0;
    Tree tree(faces(m).first, faces(m).second, m);
    tree.accelerate_distance_queries();
    // the input's vertices, edge midpoints and face centroids (all on the input: the distance
    // from the input to the mesh peaks inside the input's triangles as often as at its vertices)
    std::vector<std::pair<double, Point_3>> far;
    auto check = [&](const Point_3& p) {
      const double d2 = CGAL::to_double(tree.squared_distance(p));
      if(d2 > tol * tol) far.push_back({d2, p});
      return d2;
    };
    // (the distance is 1-Lipschitz: a midpoint or centroid within tol of the mesh by way of one
    // of its vertices is not queried)
    auto vertex_distance = get(CGAL::dynamic_vertex_property_t<double>(), input_);
    for(auto v : vertices(input_)) {
      put(vertex_distance, v, std::numeric_limits<double>::infinity());
      if(halfedge(v, input_) != boost::graph_traits<InputMesh>::null_halfedge()) put(vertex_distance, v, std::sqrt(check(get(in_vpm, v))));
    }
    auto near_by_way_of = [&](const Point_3& x, auto v) {
      return get(vertex_distance, v) + std::sqrt(CGAL::to_double(CGAL::squared_distance(x, get(in_vpm, v)))) <= tol;
    };
    for(auto e : edges(input_)) {
      const auto a = source(e, input_), b = target(e, input_);
      const Point_3 x = CGAL::midpoint(get(in_vpm, a), get(in_vpm, b));
      if(!near_by_way_of(x, a) && !near_by_way_of(x, b)) check(x);
    }
    for(auto f : faces(input_)) {
      const auto h = halfedge(f, input_);
      const auto a = source(h, input_), b = target(h, input_), c = target(next(h, input_), input_);
      const Point_3 x = CGAL::centroid(get(in_vpm, a), get(in_vpm, b), get(in_vpm, c));
      if(!near_by_way_of(x, a) && !near_by_way_of(x, b) && !near_by_way_of(x, c)) check(x);
    }
    // and the other way: a triangle of the mesh whose centroid is far from the input (it spans a
    // groove) takes the input's point nearest to it; an edge whose midpoint is, is split there
    // (the input point nearest c, and its squared distance to c)
    auto nearest_on_input = [&](const Point_3& c) {
      const Point_3 p = project_on_surface(c);
      return std::make_pair(CGAL::to_double(CGAL::squared_distance(c, p)), p);
    };
    for(face_descriptor f : faces(m)) {
      const auto h = halfedge(f, m);
      const auto [d2, p] = nearest_on_input(CGAL::centroid(get(vpm, source(h, m)), get(vpm, target(h, m)), get(vpm, target(next(h, m), m))));
      // (not when that input point is near the mesh elsewhere: the other side of a thin part)
      if(d2 > tol * tol && CGAL::to_double(tree.squared_distance(p)) > tol * tol) far.push_back({d2, p});
    }
    typedef typename GT::halfedge_descriptor halfedge_descriptor;
    typedef typename GT::vertex_descriptor vertex_descriptor;
    std::vector<std::tuple<double, Point_3, vertex_descriptor, vertex_descriptor>> far_edges;
    for(auto e : edges(m)) {
      const halfedge_descriptor h = halfedge(e, m);
      if(is_border_edge(h, m) || is_feature(e)) continue;
      const auto [d2, p] = nearest_on_input(CGAL::midpoint(get(vpm, source(h, m)), get(vpm, target(h, m))));
      if(d2 > tol * tol) far_edges.push_back({d2, p, source(h, m), target(h, m)});
    }
    if(far.empty() && far_edges.empty()) return 0;
    std::sort(far.begin(), far.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const auto before = internal::intersecting_pairs(m);   // intersections there already
    if(before.size() > num_faces(m)) return 0;   // (folded everywhere: see angle_pass)
    std::set<face_descriptor> touched;
    std::vector<vertex_descriptor> mine;
    std::size_t done = 0;
    const std::size_t cap = std::max<std::size_t>(1, std::size_t(s.max_deviation_insertions * double(num_vertices(m))));
    for(const auto& fp : far) {
      if(mine.size() >= cap) break;
      const face_descriptor f = tree.closest_point_and_primitive(fp.second).second;
      if(touched.count(f)) continue;
      // the triangle and its neighbours take one new vertex at most
      touched.insert(f);
      for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m))
        if(!is_border(opposite(h, m), m)) touched.insert(face(opposite(h, m), m));
      const auto hnew = CGAL::Euler::add_center_vertex(halfedge(f, m), m);
      const auto v = target(hnew, m);
      put(vpm, v, fp.second);
      mine.push_back(v);
    }
    // an insertion that makes the mesh cut itself is taken back (its vertex still has degree 3)
    std::sort(mine.begin(), mine.end());
    std::vector<vertex_descriptor> undo;
    for_vertices_of_new_intersections(m, before, internal::faces_around(m, mine), [&](vertex_descriptor x) {
      if(std::binary_search(mine.begin(), mine.end(), x)) undo.push_back(x);
    });
    std::sort(undo.begin(), undo.end());
    undo.erase(std::unique(undo.begin(), undo.end()), undo.end());
    std::vector<std::pair<Point_3, typename GT::halfedge_descriptor>> retry;   // (a halfedge of the triangle it was in)
    for(vertex_descriptor v : undo) {
      const Point_3 p = get(vpm, v);
      retry.push_back({p, CGAL::Euler::remove_center_vertex(halfedge(v, m), m)});
    }
    for(vertex_descriptor v : mine)
      if(!std::binary_search(undo.begin(), undo.end(), v)) {
        new_vertex(v, false);
        added.push_back(v);
        ++done;
      }
    // a split of an edge of `order` at p (the first that works) is kept if it makes the mesh cut
    // itself nowhere new and turns no triangle by more than acos(min_cos) from both old ones
    auto try_split = [&](const Point_3& p, const std::vector<std::pair<double, halfedge_descriptor>>& order, double min_cos) {
      for(const auto& candidate : order) {
        const auto x = candidate.second;
        const vertex_descriptor a = source(x, m), b = target(x, m);
        const Vector_3 n1 = normal(get(vpm, a), get(vpm, b), get(vpm, target(next(x, m), m)));
        const Vector_3 n2 = normal(get(vpm, b), get(vpm, a), get(vpm, target(next(opposite(x, m), m), m)));
        const vertex_descriptor v = insert_vertex_on_edge(x, p, m);
        bool ok = true;
        for(auto h : CGAL::halfedges_around_target(v, m)) {
          const Vector_3 n = normal(get(vpm, source(h, m)), p, get(vpm, target(next(h, m), m)));
          ok = ok && (cos_between(n, n1) >= min_cos || cos_between(n, n2) >= min_cos);
        }
        // (every crossing of a triangle at v is new; `before` is not used here: its face indices
        // may have been recycled by the removals above)
        if(ok)
          for_vertices_of_new_intersections(m, decltype(before)(), internal::faces_around(m, std::vector<vertex_descriptor>(1, v)),
                                            [&](vertex_descriptor y) { if(y == v) ok = false; });
        if(!ok) { remove_vertex_on_edge(v, a, b, m); continue; }
        new_vertex(v, false);
        added.push_back(v);
        ++done;
        return true;
      }
      return false;
    };
    // one taken back splits an edge of that triangle instead, the nearest edge first (not a
    // feature edge: it would lose its feature), turning a triangle by 75 degrees at most: it
    // follows the input there (a horn thinner than the spacing turns that much)
    for(const auto& [p, g] : retry) {
      std::vector<std::pair<double, halfedge_descriptor>> order;
      for(auto x : CGAL::halfedges_around_face(g, m)) {
        if(is_border(opposite(x, m), m) || is_feature(edge(x, m))) continue;
        order.push_back({CGAL::to_double(CGAL::squared_distance(p, typename GeomTraits::Segment_3(get(vpm, source(x, m)), get(vpm, target(x, m))))), x});
      }
      std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      try_split(p, order, 0.26);
    }
    // the edges far from the input (those still in the mesh), each triangle split once at most,
    // turning a triangle by 60 degrees at most (the limit of folds())
    std::sort(far_edges.begin(), far_edges.end(), [](const auto& x, const auto& y) { return std::get<0>(x) > std::get<0>(y); });
    std::set<vertex_descriptor> split_near;
    std::size_t edge_splits = 0;
    for(const auto& [d2, p, a, b] : far_edges) {
      if(edge_splits >= cap) break;
      const auto [h, exists] = halfedge(a, b, m);
      if(!exists || split_near.count(a) || split_near.count(b)) continue;
      for(auto x : {h, opposite(h, m)})
        for(vertex_descriptor y : CGAL::vertices_around_face(x, m)) split_near.insert(y);
      if(try_split(p, std::vector<std::pair<double, halfedge_descriptor>>(1, {d2, h}), 0.5)) ++edge_splits;
    }
    std::sort(added.begin(), added.end());   // (the caller looks its pinned vertices up)
    stats.fidelity_insertions += done;
    return done;
  }

  // see Relaxation_settings::untangle_rounds; returns the number of changes made
  template <class Mesh, class IsFeatureEdge, class IsCorner>
  std::size_t untangle_pass(Mesh& m, IsFeatureEdge is_feature, IsCorner is_fixed, const Relaxation_settings& s,
                            Relaxation_statistics& stats, std::size_t* collapses = nullptr) const
  {
    typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
    typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
    auto pairs = internal::intersecting_pairs(m);
    if(pairs.empty() || pairs.size() > num_faces(m)) return 0;
    auto vpm = get(CGAL::vertex_point, m);
    // the faces' boxes, kept up to date by `refresh` after each change (taken back or not); the
    // crossing pairs that involve one of the faces of `fs` (sorted) are looked for among the
    // faces whose boxes meet theirs (intersecting_pairs_near would box the whole mesh each time)
    auto box = get(CGAL::dynamic_face_property_t<CGAL::Bbox_3>(), m);
    auto box_of = [&](face_descriptor f) {
      CGAL::Bbox_3 b;
      for(vertex_descriptor x : CGAL::vertices_around_face(halfedge(f, m), m)) b += get(vpm, x).bbox();
      return b;
    };
    for(face_descriptor f : faces(m)) put(box, f, box_of(f));
    auto refresh = [&](const std::vector<face_descriptor>& fs) { for(face_descriptor f : fs) put(box, f, box_of(f)); };
    std::vector<face_descriptor> near;
    auto crossings = [&](const std::vector<face_descriptor>& fs) {
      refresh(fs);
      near = fs;
      for(face_descriptor g : faces(m))
        for(face_descriptor f : fs)
          if(g != f && CGAL::do_overlap(get(box, g), get(box, f))) { near.push_back(g); break; }
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
      std::size_t n = 0;
      for(const auto& fp : internal::intersecting_pairs(m, near))
        if(std::binary_search(fs.begin(), fs.end(), fp.first) || std::binary_search(fs.begin(), fs.end(), fp.second)) ++n;
      return n;
    };
    const double floor = s.untangle_min_angle * CGAL_PI / 180;
    std::size_t done = 0;
    std::vector<vertex_descriptor> vs;
    for(const auto& fp : pairs)
      for(face_descriptor f : {fp.first, fp.second})
        for(vertex_descriptor x : CGAL::vertices_around_face(halfedge(f, m), m)) vs.push_back(x);
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    // moves of the free vertices
    for(vertex_descriptor v : vs) {
      const int c_v = constraint(v, m, is_feature, is_fixed);   // 0 free, 1 on a curve, 2 fixed
      if(c_v == 2) continue;   // (a border vertex is on a curve: border edges count as features)
      const std::vector<face_descriptor> fs = internal::faces_around(m, std::array<vertex_descriptor, 1>{{v}});
      const std::size_t before = crossings(fs);
      if(before == 0) continue;
      const Point_3 start = get(vpm, v);
      // (a triangle of zero area around v makes the angles -1: then no triangle may get worse than 0)
      const double limit = std::min(std::max(smallest_angles_around(v, m, start).first, 0.0), floor);
      double x = 0, y = 0, z = 0, mean = 0;
      std::size_t n = 0;
      for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, m), m)) {
        const Point_3& q = get(vpm, w);
        x += CGAL::to_double(q.x()); y += CGAL::to_double(q.y()); z += CGAL::to_double(q.z());
        mean += std::sqrt(CGAL::to_double(CGAL::squared_distance(q, start)));
        ++n;
      }
      if(n == 0) continue;
      mean /= double(n);
      const Point_3 c(x / double(n), y / double(n), z / double(n));
      // toward the centroid, and a third of the way toward each neighbour: the one that leaves
      // the fewest crossings
      std::vector<Point_3> tries;
      if(c_v == 0) tries = {c, CGAL::midpoint(start, c)};
      for(auto g : CGAL::halfedges_around_target(v, m))   // (a vertex on a curve slides along it)
        if(c_v == 0 || is_feature(edge(g, m)) || is_border(edge(g, m), m)) tries.push_back(start + (get(vpm, source(g, m)) - start) / 3.0);
      std::size_t best = before;
      Point_3 best_q = start;
      for(const Point_3& t : tries) {
        const Point_3 q = c_v == 0 ? project_on_surface(t, start) : project_on_features(t, start);
        if(CGAL::to_double(CGAL::squared_distance(q, t)) > CGAL::square(0.25 * mean)) continue;   // thin parts
        const double new_min = smallest_angles_around(v, m, q).first;
        if(new_min < 0 || new_min < limit) continue;
        put(vpm, v, q);
        const std::size_t after = crossings(fs);
        if(after < best) { best = after; best_q = q; }
        put(vpm, v, start);
        refresh(fs);
        if(best == 0) break;
      }
      if(best < before) {
        put(vpm, v, best_q);
        refresh(fs);
        ++done;
        ++stats.untangle_changes;
      }
    }
    // flips of the edges of the faces still crossing
    pairs = internal::intersecting_pairs(m);
    const double cos_max = std::cos(60 * CGAL_PI / 180);
    std::vector<typename boost::graph_traits<Mesh>::edge_descriptor> es;
    for(const auto& fp : pairs)
      for(face_descriptor f : {fp.first, fp.second})
        for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m)) es.push_back(edge(h, m));
    std::sort(es.begin(), es.end());
    es.erase(std::unique(es.begin(), es.end()), es.end());
    for(auto e : es) {
      if(is_feature(e) || is_border(e, m)) continue;
      const auto h = halfedge(e, m);
      const auto p = source(h, m), q = target(h, m), r = target(next(h, m), m), t = target(next(opposite(h, m), m), m);
      if(degree(p, m) <= 3 || degree(q, m) <= 3 || r == t || halfedge(r, t, m).second) continue;
      if(!flip_is_safe(h, m, cos_max)) continue;
      std::vector<face_descriptor> fs = {face(h, m), face(opposite(h, m), m)};
      std::sort(fs.begin(), fs.end());
      const std::size_t before = crossings(fs);
      if(before == 0) continue;
      if(min_angle_after_flip(h, m) < std::min(min_angle_of_faces(h, m), floor)) continue;
      CGAL::Euler::flip_edge(h, m);
      std::vector<face_descriptor> gs = {face(h, m), face(opposite(h, m), m)};
      std::sort(gs.begin(), gs.end());
      if(crossings(gs) < before) { ++done; ++stats.untangle_changes; }
      else {
        CGAL::Euler::flip_edge(h, m);
        std::vector<face_descriptor> back = {face(h, m), face(opposite(h, m), m)};
        refresh(back);
      }
    }
    // (with `collapses`) a free vertex shared by two faces still crossing -- its fan folded over on
    // a part thinner than the triangles, a claw -- goes into a free neighbour, which keeps
    // its place, when the triangles around it cross fewer others and keep untangle_collapse_min_angle;
    // tried on a copy of the mesh; the caller optimizes the angles there again
    if(collapses != nullptr) {
      typedef typename boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
      pairs = internal::intersecting_pairs(m);
      std::vector<vertex_descriptor> shared;
      for(const auto& fp : pairs)
        for(vertex_descriptor x : CGAL::vertices_around_face(halfedge(fp.first, m), m))
          for(vertex_descriptor y : CGAL::vertices_around_face(halfedge(fp.second, m), m))
            if(x == y) shared.push_back(x);
      std::sort(shared.begin(), shared.end());
      shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
      const double collapse_floor = s.untangle_collapse_min_angle * CGAL_PI / 180;
      std::set<vertex_descriptor> gone;
      // (each trial copies the whole mesh: at most 64 per pass, a large input folded in many
      // places would spend its time there)
      std::size_t trials = 0;
      const std::size_t max_trials = 64;
      // the crossings of the faces around the vertices `around` (in m, or in a copy of it)
      auto crossings_near = [](const Mesh& g, const std::vector<vertex_descriptor>& around) {
        const auto fs = internal::faces_around(g, around);
        std::size_t n = 0;
        for(const auto& fp : internal::intersecting_pairs_near(g, fs))
          if(std::binary_search(fs.begin(), fs.end(), fp.first) || std::binary_search(fs.begin(), fs.end(), fp.second)) ++n;
        return n;
      };
      for(vertex_descriptor x : shared) {
        if(gone.count(x) || constraint(x, m, is_feature, is_fixed) != 0) continue;
        halfedge_descriptor best_h = boost::graph_traits<Mesh>::null_halfedge();
        std::size_t best_gain = 0;
        for(halfedge_descriptor h : CGAL::halfedges_around_target(x, m)) {   // h: y -> x
          const vertex_descriptor y = source(h, m);
          if(gone.count(y) || constraint(y, m, is_feature, is_fixed) != 0 || !CGAL::Euler::does_satisfy_link_condition(edge(h, m), m)) continue;
          std::vector<vertex_descriptor> xy = {x, y};
          std::sort(xy.begin(), xy.end());
          const std::size_t before = crossings_near(m, xy);
          if(before == 0 || trials >= max_trials) continue;
          ++trials;
          Mesh copy;
          std::map<halfedge_descriptor, typename boost::graph_traits<Mesh>::halfedge_descriptor> h2h;
          CGAL::copy_face_graph(m, copy, CGAL::parameters::halfedge_to_halfedge_output_iterator(std::inserter(h2h, h2h.end())));
          const Point_3 at = get(vpm, y);
          const auto z = CGAL::Euler::collapse_edge(edge(h2h[h], copy), copy);
          put(get(CGAL::vertex_point, copy), z, at);
          if(!(smallest_angles_around(z, copy, at).first >= collapse_floor)) continue;
          const std::size_t after = crossings_near(copy, std::vector<vertex_descriptor>(1, z));
          if(after < before && before - after > best_gain) { best_gain = before - after; best_h = h; }
        }
        if(best_h == boost::graph_traits<Mesh>::null_halfedge()) continue;
        const vertex_descriptor y = source(best_h, m);
        const Point_3 at = get(vpm, y);
        const vertex_descriptor z = CGAL::Euler::collapse_edge(edge(best_h, m), m);
        put(vpm, z, at);
        gone.insert(z == x ? y : x);
        ++done;
        ++*collapses;
        ++stats.untangle_changes;
      }
    }
    return done;
  }

  template <class Mesh, class IsFeatureEdge, class IsCorner>
  std::size_t collapse_pass(Mesh& m, IsFeatureEdge is_feature, IsCorner is_corner, const Relaxation_settings& s, Relaxation_statistics& stats) const
  {
    typedef boost::graph_traits<Mesh> GT;
    typedef typename GT::vertex_descriptor vertex_descriptor;
    auto vpm = get(CGAL::vertex_point, m);
    const double sliver = s.sliver_angle * CGAL_PI / 180;
    // the short edges of the slivers, shortest first
    std::vector<std::pair<double, std::pair<vertex_descriptor, vertex_descriptor>>> candidates;
    for(auto f : faces(m)) {
      const auto h = halfedge(f, m);
      const vertex_descriptor v[3] = {source(h, m), target(h, m), target(next(h, m), m)};
      const Point_3 p[3] = {get(vpm, v[0]), get(vpm, v[1]), get(vpm, v[2])};
      if(min_angle(p[0], p[1], p[2]) >= sliver) continue;
      double l[3];
      for(int i = 0; i < 3; ++i) l[i] = std::sqrt(CGAL::to_double(CGAL::squared_distance(p[i], p[(i + 1) % 3])));
      const int k = int(std::min_element(l, l + 3) - l);
      if(l[k] < s.sliver_edge_ratio * std::max({l[0], l[1], l[2]})) candidates.push_back({l[k], {v[k], v[(k + 1) % 3]}});
    }
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<vertex_descriptor> removed;
    std::size_t done = 0;
    for(const auto& c : candidates) {
      vertex_descriptor a = c.second.first, b = c.second.second;
      if(std::find(removed.begin(), removed.end(), a) != removed.end() || std::find(removed.begin(), removed.end(), b) != removed.end()) continue;
      const auto ab = halfedge(a, b, m);
      if(!ab.second) continue;
      const auto e = edge(ab.first, m);
      const int ca = constraint(a, m, is_feature, is_corner), cb = constraint(b, m, is_feature, is_corner);
      if(ca < cb) std::swap(a, b);   // a is kept, b goes
      const int cr = std::min(ca, cb);
      // two fixed ends: two corners closer than the sampling allows are merged (the junction of
      // more curves stays; the merged one moves by less than the sliver's short edge)
      if(cr == 2) {
        if(!s.merge_close_corners) continue;
        if(feature_degree(b, m, is_feature) > feature_degree(a, m, is_feature)) std::swap(a, b);
      }
      if(cr == 1 && !is_feature(e) && !is_border(e, m)) continue;   // a feature vertex leaves only along its curve
      if(!CGAL::Euler::does_satisfy_link_condition(e, m)) continue;
      const auto hba = halfedge(b, a, m).first;
      bool ok = true;
      for(auto g : {hba, opposite(hba, m)})
        if(!is_border(g, m) && degree(target(next(g, m), m), m) <= 3) ok = false;
      if(!ok) continue;
      // the faces around b take a's place: no fold, and a better smallest angle around
      const Point_3 pa = get(vpm, a);
      double before = CGAL_PI, after = CGAL_PI;
      for(vertex_descriptor x : {a, b})
        for(auto g : CGAL::halfedges_around_target(x, m)) {
          if(is_border(g, m)) continue;
          before = std::min(before, min_angle(get(vpm, source(g, m)), get(vpm, x), get(vpm, target(next(g, m), m))));
        }
      for(auto g : CGAL::halfedges_around_target(b, m)) {
        if(is_border(g, m)) continue;
        const vertex_descriptor x = source(g, m), y = target(next(g, m), m);
        if(x == a || y == a) continue;   // one of the two faces that go
        const Point_3 px = get(vpm, x), py = get(vpm, y);
        if(cos_between(normal(px, get(vpm, b), py), normal(px, pa, py)) < 0.5) { ok = false; break; }
        after = std::min(after, min_angle(px, pa, py));
      }
      if(!ok) continue;
      for(auto g : CGAL::halfedges_around_target(a, m)) {
        if(is_border(g, m)) continue;
        const vertex_descriptor x = source(g, m), y = target(next(g, m), m);
        if(x == b || y == b) continue;
        after = std::min(after, min_angle(get(vpm, x), pa, get(vpm, y)));
      }
      if(!(after > before)) continue;
      // collapse_edge(e) keeps target(halfedge(e)): a must be that vertex
      if(target(halfedge(edge(hba, m), m), m) != a) continue;
      const vertex_descriptor kept = CGAL::Euler::collapse_edge(edge(hba, m), m);
      put(vpm, kept, pa);
      removed.push_back(b);
      ++done;
    }
    stats.collapses += done;
    return done;
  }

public:
  /// the Lloyd step weights each ring triangle's centroid by its area (Eq. 6; the default), or
  /// all alike (false)
  bool area_weighted_ = true;
private:
  std::function<void(const char*, std::size_t, std::size_t)> progress_;
  const InputMesh& input_;
  double diagonal_ = 0;
  Face_tree faces_;
  // the centroids of the input's faces that cut another of its faces, found the first time a new
  // crossing of the mesh is met (see near_input_crossing)
  mutable bool input_crossings_known_ = false;
  mutable std::vector<Point_3> input_crossings_;
  internal::Feature_curves<GeomTraits> curves_;
};

} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_LLOYD_RELAXER_H
