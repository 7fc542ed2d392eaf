// Poisson_remesh/Sampling/internal/slab_sampling.h
//
// The parallel mode of the boundary sampler (internal): the surface is cut into slabs across its
// longest side, and the slabs fill in two phases, the even ones at once, then the odd ones, each
// slab once (fill_by_slabs says why once is enough). As in the parallel Poisson-disk
// literature, two slabs that fill at the same time are farther apart than anything a sample can
// read or change, so the result does not depend on the number of threads (nor on their timing):
// each slab draws from its own generator, and the samples are gathered in slab order after each
// phase. It is another maximal set than the sequential sampler's for the same seed.
//
// A slab's sampler works on a copy of the faces near the slab (a submesh): it draws only on the
// available boundary in the faces the slab owns (those whose centroid lies in it), and it knows
// every sample, its own and its neighbours', that can decide that boundary. With r the largest
// disk radius and R the owned faces' extent along the cut axis:
//   - a new sample p lies in R; its disk, its iso-curve at 2r and the points its update tests lie
//     within 2r of R, in the faces meeting R +- 2r, whose extent we call E;
//   - what the boundary is in E depends on the samples within 2r of E: those are inserted into the
//     slab's sampler ("the reach", E +- 2r);
//   - their disks must be exact in E: geodesic paths no longer than 2r from a point stay within
//     the ball of radius 2r around it, so the submesh holds every face meeting E +- 4r.
// Two slabs fill at once only when neither one's reach meets the other's faces, and each slab is
// wide enough for its reach: the thin slabs take the first listed share for which that holds, four
// slabs are tried before three (three at least, else the sequential sampler runs).
// Each slab starts with one sample drawn in its faces when no arc of the boundary is there yet
// (refused where an earlier sample covers it), so that the slabs start at once instead of waiting
// for a front to travel over the surface; the final set is maximal wherever they fall: each slab
// ends with no arc on its faces, and no later sample opens one there.

#ifndef POISSON_REMESH_SAMPLING_INTERNAL_SLAB_SAMPLING_H
#define POISSON_REMESH_SAMPLING_INTERNAL_SLAB_SAMPLING_H

#include <Poisson_remesh/Sampling/Boundary_sampler.h>
#include <Poisson_remesh/internal/parallel.h>

#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/locate.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// The settings of the slab decomposition.
struct Slab_sampling_settings
{
  /// The thin slabs' share of the area each, the first for which every slab is wide enough and the
  /// slabs of a phase out of each other's reach: two large slabs fill at once, then the thin ones.
  /// (Each sample within the reach of a slab's border is propagated again by its neighbour: the
  /// slabs are as few as keep both threads busy in both phases.)
  std::vector<double> thin_shares = {0.06, 0.1, 0.15, 0.2, 0.3};
  /// Four slabs (large, thin, large, thin) where they fit, the two thin ones filling at once;
  /// false: three (large, thin, large), the thin one filling alone.
  bool four_slabs = true;
  /// A slab is at least this many times as wide as its reach beyond its faces.
  double min_width_in_reaches = 2.0;
};

/// Fills `samples` (the fixed samples -- corners, feature points, component seeds -- on input;
/// all samples on output, the fixed ones first, in order) to a maximal set by slabs, as the file's
/// comment says. `radius`: the disk radius; `vertex_radii`: the adaptive radii by vertex index
/// (empty: uniform density). Returns false, leaving `samples` as it was, when the surface cannot
/// be cut into enough slabs; the caller then fills with the sequential sampler. `on_phase(n)` is
/// called after each phase with the number of samples so far.
template <class ConcurrencyTag, class TriangleMesh, class VPM, class Sample, class OnPhase>
bool fill_by_slabs(const TriangleMesh& tm, VPM vpm, double radius, const std::vector<double>& vertex_radii, std::uint64_t seed,
                   std::vector<Sample>& samples, Sampling_statistics& stats, OnPhase on_phase,
                   const Slab_sampling_settings& settings = Slab_sampling_settings())
{
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::property_traits<VPM>::value_type Point_3;
  typedef CGAL::Surface_mesh<Point_3> Sub_mesh;
  typedef typename Sub_mesh::Vertex_index Sub_vertex;
  typedef typename Sub_mesh::Face_index Sub_face;
  typedef Boundary_sampler<Sub_mesh> Sub_sampler;
  namespace PMP = CGAL::Polygon_mesh_processing;

  if(faces(tm).empty()) return false;
  auto vim = CGAL::get_initialized_vertex_index_map(tm);
  auto fim = CGAL::get_initialized_face_index_map(tm);
  auto xyz = [&](vertex_descriptor v) {
    const Point_3& p = get(vpm, v);
    return std::array<double, 3>{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  };
  // the cut axis: the longest side of the bounding box
  std::array<double, 3> lo{{HUGE_VAL, HUGE_VAL, HUGE_VAL}}, hi{{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
  for(vertex_descriptor v : vertices(tm)) {
    const auto p = xyz(v);
    for(int i = 0; i < 3; ++i) { lo[i] = std::min(lo[i], p[i]); hi[i] = std::max(hi[i], p[i]); }
  }
  int axis = 0;
  for(int i = 1; i < 3; ++i) if(hi[i] - lo[i] > hi[axis] - lo[axis]) axis = i;
  const double length = hi[axis] - lo[axis];
  const double r = vertex_radii.empty() ? radius : *std::max_element(vertex_radii.begin(), vertex_radii.end());
  if(!(length > 0) || !(r > 0) || !std::isfinite(length)) return false;

  // the faces: by index, with their extent and centroid along the axis
  std::size_t face_bound = 0;
  for(face_descriptor f : faces(tm)) face_bound = std::max(face_bound, std::size_t(get(fim, f)) + 1);
  std::vector<face_descriptor> face_of(face_bound);
  std::vector<double> fmin(face_bound, HUGE_VAL), fmax(face_bound, -HUGE_VAL), fmid(face_bound, 0);
  std::vector<char> is_face(face_bound, 0);
  for(face_descriptor f : faces(tm)) {
    const std::size_t i = std::size_t(get(fim, f));
    face_of[i] = f;
    is_face[i] = 1;
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, tm), tm)) {
      const double x = xyz(v)[axis];
      fmin[i] = std::min(fmin[i], x);
      fmax[i] = std::max(fmax[i], x);
      fmid[i] += x / 3;
    }
  }
  // the extent of the faces meeting [a, b]
  auto extent_of_faces_meeting = [&](double a, double b) {
    std::pair<double, double> e(a, b);
    for(std::size_t i = 0; i < face_bound; ++i)
      if(is_face[i] && fmax[i] >= a && fmin[i] <= b) { e.first = std::min(e.first, fmin[i]); e.second = std::max(e.second, fmax[i]); }
    return e;
  };

  struct Slab
  {
    std::vector<std::size_t> owned;         // the faces it owns (centroid in the slab), by index
    double a = 0, b = 0;                    // their extent
    double reach_a = 0, reach_b = 0;        // samples there are inserted
    double mesh_a = 0, mesh_b = 0;          // faces meeting it are in the submesh
  };
  // the faces by centroid along the axis, with their areas (slabs are cut by shares of the area)
  std::vector<std::pair<double, std::size_t>> by_centroid;
  std::vector<double> area(face_bound, 0.0);
  double total_area = 0;
  for(std::size_t i = 0; i < face_bound; ++i)
    if(is_face[i]) {
      by_centroid.emplace_back(fmid[i], i);
      area[i] = CGAL::to_double(PMP::face_area(face_of[i], tm, CGAL::parameters::vertex_point_map(vpm)));
      total_area += area[i];
    }
  std::sort(by_centroid.begin(), by_centroid.end());
  // (the slabs for the shares of the area `share`, or none when they do not fit)
  auto cut = [&](const std::vector<double>& share) {
    const std::size_t k = share.size();
    std::vector<Slab> slabs(k);
    std::vector<double> start(k + 1, lo[axis]);   // slab s: centroids in [start[s], start[s + 1])
    double sum = 0, until = share[0];
    std::size_t s = 0;
    for(const auto& [x, i] : by_centroid) {
      // (a slab closes where its share of the area is reached, between two centroids)
      while(s + 1 < k && sum >= total_area * until) { start[++s] = x; until += share[s]; }
      slabs[s].owned.push_back(i);
      sum += area[i];
    }
    start[k] = hi[axis];
    for(std::size_t t = 0; t < k; ++t) {
      Slab& s = slabs[t];
      const double width = start[t + 1] - start[t];
      if(s.owned.empty()) return std::vector<Slab>();
      s.a = HUGE_VAL; s.b = -HUGE_VAL;
      for(std::size_t i : s.owned) { s.a = std::min(s.a, fmin[i]); s.b = std::max(s.b, fmax[i]); }
      const auto e = extent_of_faces_meeting(s.a - 2 * r, s.b + 2 * r);
      s.reach_a = e.first - 2 * r;
      s.reach_b = e.second + 2 * r;
      s.mesh_a = e.first - 4 * r;
      s.mesh_b = e.second + 4 * r;
      // (too narrow for its reach)
      if(settings.min_width_in_reaches * std::max(s.a - s.reach_a, s.reach_b - s.b) > width) return std::vector<Slab>();
    }
    // two slabs of a phase (same parity) must not reach each other's faces
    for(std::size_t i = 0; i + 2 < k; ++i)
      for(std::size_t j = i + 2; j < k; j += 2)
        if(slabs[i].reach_b >= slabs[j].a || slabs[j].reach_a <= slabs[i].b) return std::vector<Slab>();
    return slabs;
  };
  // Four slabs where they fit: two large ones that fill at once, then two thin ones, one between
  // them (keeping them out of each other's reach) and one at the far end, at once too (on two
  // threads neither phase leaves one idle, whatever the thin share). Else three:
  // the two large ones, then the thin one between them alone (its share of the area then runs on
  // one thread).
  std::vector<Slab> layout;
  for(const int count : {4, 3}) {
    if(count == 4 && !settings.four_slabs) continue;
    for(double thin : settings.thin_shares) {
      layout = count == 4 ? cut({0.5 - thin, thin, 0.5 - thin, thin}) : cut({0.5 * (1 - thin), thin, 0.5 * (1 - thin)});
      if(!layout.empty()) break;
    }
    if(!layout.empty()) break;
  }
  if(layout.empty()) return false;
  const std::size_t k = layout.size();

  // each slab's submesh, sampler and state
  struct Slab_sampler
  {
    Sub_mesh mesh;
    std::vector<face_descriptor> original;      // by submesh face index
    std::vector<unsigned char> rotation;        // the submesh face's first corner, in the original's order
    std::unordered_map<std::size_t, std::size_t> sub_of;   // original face index -> submesh face index
    // the owned faces by connected piece, with their cumulative areas (seeds)
    std::vector<std::vector<Sub_face>> pieces;
    std::vector<std::vector<double>> piece_area;
    std::unique_ptr<Sub_sampler> sampler;
    std::vector<Sample> made;                   // its new samples of the phase
  };
  std::vector<std::unique_ptr<Slab_sampler>> slab(k);
  std::atomic<bool> built(true);
  auto sub_face = [](std::size_t j) { return Sub_face(typename Sub_mesh::size_type(j)); };
  auto sub_vertex = [](std::size_t j) { return Sub_vertex(typename Sub_mesh::size_type(j)); };
  // (each slab built by its thread: the input is only read)
  for_each_index<ConcurrencyTag>(k, [&](std::size_t s) {
    auto x = std::make_unique<Slab_sampler>();
    const Slab& layer = layout[s];
    std::vector<std::size_t> chosen;
    for(std::size_t i = 0; i < face_bound; ++i)
      if(is_face[i] && fmax[i] >= layer.mesh_a && fmin[i] <= layer.mesh_b) chosen.push_back(i);
    for(std::size_t j = 0; j < chosen.size(); ++j) x->sub_of.emplace(chosen[j], j);
    // submesh vertices: one per fan of chosen faces around an input vertex (a vertex whose chosen
    // faces form two fans -- far from the slab, at the submesh's edge -- is split, which keeps
    // the submesh a manifold)
    std::vector<std::array<std::size_t, 3>> corner(chosen.size(), {{0, 0, 0}});
    std::vector<Point_3> points;
    std::vector<double> radii;
    std::unordered_set<std::size_t> done;   // input vertices already split into fans
    auto chosen_face = [&](halfedge_descriptor h) -> long {
      if(is_border(h, tm)) return -1;
      const auto it = x->sub_of.find(std::size_t(get(fim, face(h, tm))));
      return it == x->sub_of.end() ? -1 : long(it->second);
    };
    // the corner of v in face j (0, 1, 2 in the order source, target, target(next) of halfedge(f))
    auto corner_of = [&](std::size_t j, vertex_descriptor v) {
      const halfedge_descriptor h0 = halfedge(face_of[chosen[j]], tm);
      if(source(h0, tm) == v) return 0;
      if(target(h0, tm) == v) return 1;
      return 2;
    };
    for(std::size_t j = 0; j < chosen.size(); ++j) {
      for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(face_of[chosen[j]], tm), tm)) {
        const std::size_t vi = std::size_t(get(vim, v));
        if(!done.insert(vi).second) continue;
        std::vector<halfedge_descriptor> ring;
        for(halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, tm), tm)) ring.push_back(h);
        const std::size_t n = ring.size();
        // start after a gap (a halfedge without a chosen face), if any
        std::size_t start = 0;
        for(std::size_t i = 0; i < n; ++i) if(chosen_face(ring[i]) < 0) { start = (i + 1) % n; break; }
        long current = -1;   // the submesh vertex of the fan being walked
        for(std::size_t t = 0; t < n; ++t) {
          const halfedge_descriptor h = ring[(start + t) % n];
          const long fj = chosen_face(h);
          if(fj < 0) { current = -1; continue; }
          if(current < 0) {
            current = long(points.size());
            points.push_back(get(vpm, v));
            radii.push_back(vertex_radii.empty() ? radius : vertex_radii[vi]);
          }
          corner[std::size_t(fj)][std::size_t(corner_of(std::size_t(fj), v))] = std::size_t(current);
        }
      }
    }
    for(const Point_3& p : points) x->mesh.add_vertex(p);
    x->original.reserve(chosen.size());
    x->rotation.reserve(chosen.size());
    std::vector<char> pickable(chosen.size(), 0);
    for(std::size_t j = 0; j < chosen.size(); ++j) {
      const Sub_vertex w[3] = {sub_vertex(corner[j][0]), sub_vertex(corner[j][1]), sub_vertex(corner[j][2])};
      const Sub_face g = x->mesh.add_face(w[0], w[1], w[2]);
      if(g == Sub_mesh::null_face() || std::size_t(g) != j) { built = false; return; }
      const Sub_vertex first = source(halfedge(g, x->mesh), x->mesh);
      x->rotation.push_back(first == w[0] ? 0 : first == w[1] ? 1 : 2);
      x->original.push_back(face_of[chosen[j]]);
    }
    for(std::size_t i : layer.owned) pickable[x->sub_of.at(i)] = 1;
    // the connected pieces of the owned faces (a slab cut across separate parts of the surface
    // holds several)
    std::vector<long> piece(chosen.size(), -1);
    for(std::size_t i : layer.owned) {
      const std::size_t j0 = x->sub_of.at(i);
      if(piece[j0] >= 0) continue;
      piece[j0] = long(x->pieces.size());
      x->pieces.emplace_back();
      x->piece_area.emplace_back();
      std::vector<std::size_t> stack(1, j0);
      while(!stack.empty()) {
        const std::size_t j = stack.back();
        stack.pop_back();
        x->pieces.back().push_back(sub_face(j));
        const double a = CGAL::to_double(PMP::face_area(sub_face(j), x->mesh));
        x->piece_area.back().push_back((x->piece_area.back().empty() ? 0.0 : x->piece_area.back().back()) + a);
        for(auto h : CGAL::halfedges_around_face(halfedge(sub_face(j), x->mesh), x->mesh)) {
          const auto o = opposite(h, x->mesh);
          if(is_border(o, x->mesh)) continue;
          const std::size_t n = std::size_t(face(o, x->mesh));
          if(pickable[n] && piece[n] < 0) { piece[n] = piece[j0]; stack.push_back(n); }
        }
      }
    }
    // each slab its own generator, from the seed and the slab's number
    x->sampler = std::make_unique<Sub_sampler>(x->mesh, get(CGAL::vertex_point, static_cast<const Sub_mesh&>(x->mesh)),
                                               seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull * (s + 1));
    if(vertex_radii.empty()) {
      x->sampler->set_radius(radius);
    } else {
      x->sampler->set_radius_field([&](Sub_vertex w) { return radii[std::size_t(w)]; });
    }
    x->sampler->restrict_draws_to(std::move(pickable));
    slab[s] = std::move(x);
  }, 1);
  if(!built) return false;

  // a location of the input as a location of slab x's submesh, and back
  auto to_sub = [&](const Slab_sampler& x, const decltype(Sample::location)& loc) {
    const std::size_t j = x.sub_of.at(std::size_t(get(fim, loc.first)));
    const unsigned s = x.rotation[j];
    typename Sub_sampler::Face_location out;
    out.first = sub_face(j);
    for(unsigned t = 0; t < 3; ++t) out.second[t] = loc.second[(s + t) % 3];
    return out;
  };
  auto from_sub = [&](const Slab_sampler& x, const typename Sub_sampler::Sample& p) {
    const std::size_t j = std::size_t(p.location.first);
    const unsigned s = x.rotation[j];
    Sample out;
    out.location.first = x.original[j];
    for(unsigned t = 0; t < 3; ++t) out.location.second[(s + t) % 3] = p.location.second[t];
    out.point = PMP::construct_point(out.location, tm, CGAL::parameters::vertex_point_map(vpm));
    out.kind = p.kind;
    out.level = p.level;
    out.radius = p.radius;
    return out;
  };
  auto along = [&](const Sample& p) { return CGAL::to_double(p.point[axis]); };
  // slab s takes in the samples of its reach (the first n: none of them its own, made only now),
  // seeds its pieces and fills its faces
  auto fill_slab = [&](std::size_t s, std::size_t n) {
    Slab_sampler& x = *slab[s];
    for(std::size_t i = 0; i < n; ++i)
      if(along(samples[i]) >= layout[s].reach_a && along(samples[i]) <= layout[s].reach_b)
        x.sampler->insert(to_sub(x, samples[i].location), samples[i].kind, false);
    const std::size_t first_own = x.sampler->samples().size();
    // a seed in each piece of its faces (refused where a sample covers it)
    for(std::size_t c = 0; c < x.pieces.size(); ++c)
      if(x.piece_area[c].back() > 0)
        x.sampler->insert(x.sampler->random_location(x.pieces[c], x.piece_area[c]), Sample_kind::surface, true);
    x.sampler->fill();
    for(std::size_t i = first_own; i < x.sampler->samples().size(); ++i) x.made.push_back(from_sub(x, x.sampler->samples()[i]));
  };
  // Each slab fills once, in its phase: the even ones, then the odd ones. A fill leaves no arc on
  // the slab's faces, so each point of them is covered by a disk of a sample it knows (an uncovered
  // region's boundary would be an arc there, unless the region were a whole piece of the faces, which
  // its seed starts), up to the arcs a sampler drops (runs shorter than its minimum length; adaptive
  // arcs whose drawn point is covered). A later sample only covers more: the even slabs need not take
  // the odd ones' samples, and the odd slabs, which take every earlier sample of their reach, end it.
  for(std::size_t parity = 0; parity < 2; ++parity) {
    const std::size_t n = samples.size();
    std::vector<std::size_t> todo;
    for(std::size_t s = parity; s < k; s += 2) todo.push_back(s);
    for_each_index<ConcurrencyTag>(todo.size(), [&](std::size_t t) { fill_slab(todo[t], n); }, 1);
    for(std::size_t s : todo) {
      for(Sample& p : slab[s]->made) samples.push_back(std::move(p));
      slab[s]->made.clear();
    }
    on_phase(samples.size());
  }
  for(const auto& x : slab) {
    const Sampling_statistics& t = x->sampler->statistics();
    stats.propagations += t.propagations;
    stats.classification_propagations += t.classification_propagations;
    stats.open_iso_curves += t.open_iso_curves;
    stats.dropped_arcs += t.dropped_arcs;
    stats.covered_faces += t.covered_faces;
  }
  stats.slabs = k;
  return true;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_SAMPLING_INTERNAL_SLAB_SAMPLING_H
