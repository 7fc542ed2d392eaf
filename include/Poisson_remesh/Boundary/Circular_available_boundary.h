// Poisson_remesh/Boundary/Circular_available_boundary.h
//
// The available boundary of uniform geodesic Poisson-disk sampling (paper §4.1, §4.2.3), a model
// of the concept BoundaryCurve: the parts of the samples' iso-distance curves at 2r that are not
// inside the expellant disk D(s, 2r) of any other sample -- the boundary of the union of the
// disks. Each piece is a circular arc inside one face (in that face's 2D frame, see
// Geodesic/Exact_geodesic_oracle.h), owned by the sample whose curve it belongs to.
//
// Updating with a new sample q (§4.2.3) splits arcs where the new curve B_new crosses the stored
// boundary B_whole -- the computation is local to each face, as in the paper -- and then decides
// for every resulting piece whether it is kept. Instead of the paper's ordering and parity rules,
// each piece is decided by evaluating exact distances at its midpoint (a way the issue allows,
// and one that gives the same set while needing no global orientation bookkeeping):
//   - a stored piece is dropped when d(q, midpoint) < 2r (q's field, just propagated);
//   - a new piece is dropped when d(s, midpoint) < 2r for an earlier sample s (the caller's
//     predicate, which propagates from the midpoint only when some sample is close enough).
// Random points are drawn uniformly by arc length with a Fenwick tree over arc lengths.

#ifndef POISSON_REMESH_BOUNDARY_CIRCULAR_AVAILABLE_BOUNDARY_H
#define POISSON_REMESH_BOUNDARY_CIRCULAR_AVAILABLE_BOUNDARY_H

#include <Poisson_remesh/Geodesic/internal/conic_geometry.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Polygon_mesh_processing/locate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

constexpr double two_pi = 6.28318530717958647692;

/// Fenwick (binary indexed) tree of non-negative weights, growing on demand.
class Fenwick_tree
{
public:
  void resize(std::size_t n)
  {
    if(n <= weights_.size()) return;
    std::size_t cap = std::max<std::size_t>(16, weights_.size());
    while(cap < n) cap *= 2;
    weights_.resize(cap, 0.0);
    rebuild();
  }
  void set(std::size_t i, double w)
  {
    resize(i + 1);
    const double delta = w - weights_[i];
    weights_[i] = w;
    for(std::size_t k = i + 1; k <= tree_.size(); k += k & (~k + 1)) tree_[k - 1] += delta;
  }
  double weight(std::size_t i) const { return i < weights_.size() ? weights_[i] : 0.0; }
  double total() const
  {
    double s = 0;
    for(std::size_t k = tree_.size(); k > 0; k -= k & (~k + 1)) s += tree_[k - 1];
    return s;
  }
  /// the index i with prefix(i) <= u < prefix(i + 1), for 0 <= u < total()
  std::size_t find(double u, double& rest) const
  {
    std::size_t pos = 0;
    std::size_t step = 1;
    while(step * 2 <= tree_.size()) step *= 2;
    for(; step > 0; step /= 2)
      if(pos + step <= tree_.size() && tree_[pos + step - 1] <= u) { pos += step; u -= tree_[pos - 1]; }
    rest = u;
    return std::min(pos, weights_.size() - 1);
  }
  void rebuild()
  {
    tree_.assign(weights_.size(), 0.0);
    for(std::size_t i = 0; i < weights_.size(); ++i) {
      tree_[i] += weights_[i];
      const std::size_t parent = (i + 1) + ((i + 1) & (~(i + 1) + 1));
      if(parent <= tree_.size()) tree_[parent - 1] += tree_[i];
    }
  }
  void clear() { weights_.clear(); tree_.clear(); }
private:
  std::vector<double> weights_, tree_;
};

/// Where arc `a` meets arc `b`: the parameter on `a`, and whether `a`, running forward, enters the
/// disk that `b` bounds (the region closer to `b`'s source lies on the left of `b`, which runs
/// counter-clockwise around its center). `reliable` is false for grazing crossings.
struct Arc_crossing
{
  double t;
  bool entering;
  bool reliable;
};

/// The parameter in [0, 1] of the point `delta` radians (counter-clockwise) past an arc's start on
/// an arc spanning `span`, or -1 when the point is not on it (1e-12 radians of slack at both ends)
inline double arc_parameter(double delta, double span)
{
  const double tol = 1e-12;
  delta -= two_pi * std::floor(delta / two_pi);
  if(delta > span + tol && delta < two_pi - tol) return -1.0;
  return (delta > span + tol) ? 0.0 : (span > 0 ? std::min(1.0, delta / span) : 0.0);
}

/// The same for conic arcs (adaptive density, §5.1) with the same gradient: the arcs of one face,
/// whose level r0 + r(x) has the face's radius gradient whatever the sample. Their conics meet in
/// at most two points, found in closed form (Geodesic/internal/conic_geometry.h); each is kept
/// when it lies on both arcs, and a enters b's region where b's level function decreases along a.
template <class Arc>
void same_gradient_conic_arc_crossings(const Arc& a, const Arc& b, std::vector<Arc_crossing>& out)
{
  const double span_a = a.theta_end - a.theta_start, span_b = b.theta_end - b.theta_start;
  if(!(span_a > 0)) return;
  const Vec2 g{a.gradient[0], a.gradient[1]};
  thread_local std::vector<double> angles;
  angles.clear();
  conic_conic_angles(Vec2{a.center[0], a.center[1]}, a.radius, Vec2{b.center[0], b.center[1]}, b.radius, g, angles);
  for(const double th : angles) {
    const double t = arc_parameter(th - a.theta_start, span_a);
    if(t < 0) continue;   // not on a
    const Vec2 u{std::cos(th), std::sin(th)}, v{-u.y, u.x};
    const double rho = a.radius / (1. - dot(g, u));
    const Vec2 p = Vec2{a.center[0], a.center[1]} + rho * u;
    const Vec2 x = p - Vec2{b.center[0], b.center[1]};
    if(arc_parameter(std::atan2(x.y, x.x) - b.theta_start, span_b) < 0) continue;   // not on b
    // a's forward tangent d(rho u)/dtheta, and the gradient of b's level function |x| - g . x - radius
    const Vec2 tangent = (rho * rho * dot(g, v) / a.radius) * u + rho * v;
    const double d = norm(x);
    const Vec2 grad = (d > 0 ? (1. / d) * x : Vec2{0., 0.}) - g;
    const double slope = dot(tangent, grad), norms = norm(tangent) * norm(grad);
    const double sine = norms > 0 ? std::abs(slope) / norms : 0;
    out.push_back({t, slope < 0, sine > 1e-6});   // b's level falls along a: into b's region
  }
}

/// The same for arcs of which one at least is a conic, with different gradients (a user's oracle:
/// ours gives every arc of a face that face's radius gradient): no closed form worth having (two
/// such conics meet in up to four points, a quartic), so the level function of b is followed
/// along a, sign changes are bracketed on 64 steps per turn and refined by bisection to 1e-15 of
/// a's parameter.
template <class Arc>
void conic_arc_crossings(const Arc& a, const Arc& b, std::vector<Arc_crossing>& out)
{
  if(a.gradient == b.gradient && !a.is_segment && !b.is_segment) {
    same_gradient_conic_arc_crossings(a, b, out);
    return;
  }
  const double span = a.theta_end - a.theta_start;
  if(!(span > 0)) return;
  const int n = std::max(8, int(std::ceil(span / (two_pi / 64))));
  auto f = [&](double t) { return b.level_function(a.point_2(t)); };
  const double span_b = b.theta_end - b.theta_start;
  double t0 = 0, f0 = f(0.0);
  for(int i = 1; i <= n; ++i) {
    const double t1 = double(i) / double(n), f1 = f(t1);
    if((f0 < 0) != (f1 < 0)) {
      double lo = t0, hi = t1, flo = f0;
      for(int it = 0; it < 64 && hi - lo > 1e-15; ++it) {
        const double mid = 0.5 * (lo + hi), fm = f(mid);
        if((fm < 0) == (flo < 0)) { lo = mid; flo = fm; } else hi = mid;
      }
      const double t = 0.5 * (lo + hi);
      const std::array<double, 2> p = a.point_2(t);
      if(arc_parameter(std::atan2(p[1] - b.center[1], p[0] - b.center[0]) - b.theta_start, span_b) >= 0) {   // on b
        const double e = 1e-7;
        const std::array<double, 2> p0 = a.point_2(std::max(0.0, t - e)), p1 = a.point_2(std::min(1.0, t + e));
        const double tx = p1[0] - p0[0], ty = p1[1] - p0[1];
        const double dx = p[0] - b.center[0], dy = p[1] - b.center[1], d = std::sqrt(dx * dx + dy * dy);
        const double gx = (d > 0 ? dx / d : 0) - b.gradient[0], gy = (d > 0 ? dy / d : 0) - b.gradient[1];
        const double norms = std::sqrt((tx * tx + ty * ty) * (gx * gx + gy * gy));
        const double sine = norms > 0 ? std::abs(tx * gx + ty * gy) / norms : 0;
        out.push_back({t, f0 >= 0, sine > 1e-6});   // from outside b (f > 0) to inside: entering
      }
    }
    t0 = t1;
    f0 = f1;
  }
}

/// Where arcs `a` and `b` meet: the crossings seen from `a` (its parameter; entering: into b's
/// disk) go to `on_a`, the same points seen from `b` to `on_b` (either may be null).
template <class Arc>
void arc_crossings(const Arc& a, const Arc& b, std::vector<Arc_crossing>* on_a, std::vector<Arc_crossing>* on_b)
{
  if(a.is_conic() || b.is_conic()) {
    // a conic arc lies within radius / (1 - |gradient|) of its focus: two arcs whose such disks
    // are apart cannot meet (the common case in a face holding many arcs, on a coarse input)
    auto reach = [](const Arc& c) {
      const double g = std::sqrt(c.gradient[0] * c.gradient[0] + c.gradient[1] * c.gradient[1]);
      return g < 1 ? c.radius / (1 - g) : std::numeric_limits<double>::infinity();
    };
    const double dx = b.center[0] - a.center[0], dy = b.center[1] - a.center[1], r = reach(a) + reach(b);
    if(dx * dx + dy * dy > r * r) return;
    if(on_a) conic_arc_crossings(a, b, *on_a);
    if(on_b) conic_arc_crossings(b, a, *on_b);
    return;
  }
  const double dx = b.center[0] - a.center[0], dy = b.center[1] - a.center[1];
  const double d2 = dx * dx + dy * dy, d = std::sqrt(d2);
  const double ra = a.radius, rb = b.radius;
  if(!(d > 0) || d > ra + rb || d < std::abs(ra - rb)) return;
  const double x = (d2 + ra * ra - rb * rb) / (2 * d);     // along the center line, from a's center
  const double h = std::sqrt(std::max(0.0, ra * ra - x * x));
  const double ux = dx / d, uy = dy / d;
  const double span_a = a.theta_end - a.theta_start, span_b = b.theta_end - b.theta_start;
  for(int sgn : {-1, 1}) {
    const double px = a.center[0] + x * ux - sgn * h * uy, py = a.center[1] + x * uy + sgn * h * ux;
    const double tb = arc_parameter(std::atan2(py - b.center[1], px - b.center[0]) - b.theta_start, span_b);
    if(tb >= 0) {
      const double ta = arc_parameter(std::atan2(py - a.center[1], px - a.center[0]) - a.theta_start, span_a);
      if(ta >= 0) {
        // forward directions (counter-clockwise tangents) of a and b at the crossing
        const double ta_x = -(py - a.center[1]), ta_y = px - a.center[0];
        const double tb_x = -(py - b.center[1]), tb_y = px - b.center[0];
        const double cross = tb_x * ta_y - tb_y * ta_x;   // > 0: a turns to b's left, into b's disk
        const bool reliable = std::abs(cross / (ra * rb)) > 1e-6;
        if(on_a) on_a->push_back({ta, cross > 0, reliable});
        if(on_b) on_b->push_back({tb, cross < 0, reliable});
      }
    }
    if(h == 0) break;
  }
}

/// Arc `a` restricted to parameters [t0, t1].
template <class Arc>
Arc sub_arc(const Arc& a, double t0, double t1)
{
  Arc r = a;
  const double span = a.theta_end - a.theta_start;
  r.theta_start = a.theta_start + t0 * span;
  r.theta_end = a.theta_start + t1 * span;
  return r;
}

} // namespace internal

/// The available boundary of circular arcs (BoundaryCurve model for uniform density) and of
/// conic arcs (adaptive density, §5.1: arcs whose `gradient` is not zero).
template <class TriangleMesh, class Arc>
class Circular_available_boundary
{
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename CGAL::GetInitializedFaceIndexMap<TriangleMesh>::const_type FIM;

public:
  /// a point of the surface: a face and barycentric coordinates
  typedef CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> Face_location;

  /// A live arc of the boundary and the sample whose iso-curve it belongs to.
  struct Stored_arc
  {
    Arc arc;              ///< the arc, in the frame of its face
    std::size_t sample;   ///< the index of the sample that owns it
  };

  /// An empty boundary on the faces of `tm`.
  explicit Circular_available_boundary(const TriangleMesh& tm)
    : tm_(tm), fim_(CGAL::get_initialized_face_index_map(tm)), arcs_in_face_(num_faces(tm))
  {}

  /// Pieces shorter than this are dropped (set to a tiny fraction of r by the sampler).
  void set_minimum_length(double l) { min_length_ = l; }

  /// Draws only on the arcs of the faces f with `pickable[fim(f)]` (the parallel sampler's slab:
  /// its samples are drawn in the faces it owns, the arcs of the faces around them are kept to
  /// update); an empty vector (the default) makes every face pickable. empty() and length() then
  /// count the pickable arcs alone.
  void set_pickable_faces(std::vector<char> pickable)
  {
    pickable_ = std::move(pickable);
    pickable_count_ = 0;
    for(std::size_t i = 0; i < alive_.size(); ++i) {
      if(!alive_[i]) continue;
      const bool p = is_pickable(stored(i).arc.face);
      fenwick_.set(i, p ? stored(i).arc.length() : 0.0);
      if(p) ++pickable_count_;
    }
  }

  /// true when no arc is left (the sample set is maximal), or no pickable one (set_pickable_faces())
  bool empty() const { return pickable_count_ == 0; }
  /// the number of live arcs
  std::size_t number_of_arcs() const { return alive_count_; }
  /// the total length of the live arcs
  double length() const { return fenwick_.total(); }

  /// All live arcs, for inspection and tests.
  template <class OutputIterator>
  OutputIterator arcs(OutputIterator out) const
  {
    for(std::size_t i = 0; i < alive_.size(); ++i) if(alive_[i]) *out++ = stored(i);
    return out;
  }

  /// removes every arc (a new level of detail starts from scratch)
  void clear()
  {
    arcs_.clear();
    alive_.clear();
    slot_of_.clear();
    free_.clear();
    fenwick_.clear();
    for(auto& l : arcs_in_face_) l.clear();
    alive_count_ = 0;
    pickable_count_ = 0;
  }

  /// A point drawn uniformly by arc length on the live arcs; `u01` returns uniform numbers in [0, 1).
  template <class Uniform01>
  Face_location pick(Uniform01&& u01)
  {
    std::size_t arc;
    return pick(u01, arc);
  }

  /// The same, telling which arc the point is on (for remove_arc()).
  template <class Uniform01>
  Face_location pick(Uniform01&& u01, std::size_t& arc)
  {
    for(int attempt = 0;; ++attempt) {
      const double total = fenwick_.total();
      double rest = 0;
      const std::size_t i = fenwick_.find(u01() * total, rest);
      if(i < alive_.size() && alive_[i] && is_pickable(stored(i).arc.face)) {
        const double len = fenwick_.weight(i);
        const double t = len > 0 ? std::min(1.0, std::max(0.0, rest / len)) : 0.5;
        arc = i;
        return location(stored(i).arc, t);
      }
      fenwick_.rebuild(); // rounding drift: rebuild and draw again
      if(attempt > 3) {   // fall back to the first live arc
        for(std::size_t k = 0; k < alive_.size(); ++k) if(alive_[k] && is_pickable(stored(k).arc.face)) { arc = k; return location(stored(k).arc, u01()); }
      }
    }
  }

  /// The update of §4.2.3 with the iso-curve `chains` of sample `sample` (ordered chains of arcs,
  /// as the oracle returns them):
  ///   faces                   the faces the new disk D(q, 2r) can meet (the sampler passes the
  ///                           faces around the vertices the propagation reached, the faces of
  ///                           the new arcs and q's face: a face meeting the disk contains q, is
  ///                           crossed by its boundary, or has a vertex inside it);
  ///   in_new_disk(location)   true when the location is closer than 2r to the new sample;
  ///   in_old_disks(location)  true when the location is closer than 2r to an earlier sample.
  /// A run of the new curve between two crossings with the stored boundary lies inside the union
  /// of the earlier disks when, at its first crossing, it turns into the disk of the stored arc it
  /// crosses, and then leaves at its last crossing (the region a stored arc bounds is on its
  /// left); a run whose two ends disagree, that has a grazing crossing, or a chain that crosses
  /// nothing, is decided by in_old_disks at its midpoint.
  template <class Chains, class FaceRange, class InNewDisk, class InOldDisks>
  void update(const Chains& chains, std::size_t sample, const FaceRange& faces,
              InNewDisk in_new_disk, InOldDisks in_old_disks)
  {
    update(chains, sample, faces, in_new_disk, in_old_disks, [](const Arc&, bool) { return false; });
  }

  /// The same, where the chains leave out faces inside the earlier disks (the oracle's
  /// iso_curve_outside): `ends_in_covered_face(arc, at_end)` tells whether the chain that begins
  /// (`at_end` false) or ends (true) with `arc` breaks there because it enters such a face. A run
  /// that reaches such a break without meeting the stored boundary is inside the earlier disks
  /// (it goes on inside that face), and is left out without a distance query; where its crossings
  /// say otherwise (rounding), in_old_disks decides as above.
  template <class Chains, class FaceRange, class InNewDisk, class InOldDisks, class EndsInCoveredFace>
  void update(const Chains& chains, std::size_t sample, const FaceRange& faces,
              InNewDisk in_new_disk, InOldDisks in_old_disks, EndsInCoveredFace ends_in_covered_face)
  {
    // crossings of the new arcs with the stored arcs, face by face (§4.2.3: arcs only meet inside
    // a common triangle); (stored arc, parameter) pairs, and per new arc its crossings
    // (the buffers are members, kept to reuse their storage)
    std::vector<std::pair<std::size_t, double>>& stored_cuts = stored_cuts_;
    stored_cuts.clear();
    std::size_t new_arcs = 0;
    for(const auto& chain : chains) new_arcs += chain.arcs.size();
    if(new_cuts_.size() < new_arcs) new_cuts_.resize(new_arcs);
    std::size_t slot = 0;
    for(const auto& chain : chains)
      for(const Arc& arc : chain.arcs) {
        auto& mine = new_cuts_[slot++];
        mine.clear();
        for(std::size_t i : arcs_in_face_[get(fim_, arc.face)]) {
          stored_crossings_.clear();
          internal::arc_crossings(arc, stored(i).arc, &mine, &stored_crossings_);
          for(const internal::Arc_crossing& x : stored_crossings_) stored_cuts.emplace_back(i, x.t);
        }
      }
    std::stable_sort(stored_cuts.begin(), stored_cuts.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    // 1. stored arcs in the faces the new disk meets: drop what it covers
    std::vector<std::size_t>& candidates = candidates_;
    candidates.clear();
    for(face_descriptor f : faces) {
      const auto& list = arcs_in_face_[get(fim_, f)];
      candidates.insert(candidates.end(), list.begin(), list.end());
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    std::size_t k = 0;
    std::vector<double>& cuts = cuts_;
    for(std::size_t i : candidates) {
      cuts.clear();
      while(k < stored_cuts.size() && stored_cuts[k].first < i) ++k;
      for(std::size_t l = k; l < stored_cuts.size() && stored_cuts[l].first == i; ++l) cuts.push_back(stored_cuts[l].second);
      if(alive_[i]) replace_by_kept_pieces(i, cuts, [&](const Face_location& loc) { return !in_new_disk(loc); });
    }
    // 2. new chains: keep what no earlier disk covers, run by run
    slot = 0;
    for(const auto& chain : chains) {
      const bool open = !chain.closed && !chain.arcs.empty();
      add_uncovered_runs(chain, &new_cuts_[slot], sample, in_old_disks, open && ends_in_covered_face(chain.arcs.front(), false),
                         open && ends_in_covered_face(chain.arcs.back(), true));
      slot += chain.arcs.size();
    }
  }

  /// the surface point at parameter `t` in [0, 1] along the arc `a`
  Face_location location(const Arc& a, double t) const
  {
    std::array<double, 3> b = a.barycentric(t);
    double s = 0;
    for(double& x : b) { x = std::max(0.0, x); s += x; }
    if(s > 0) for(double& x : b) x /= s;
    return {a.face, b};
  }


  /// Drops a live arc (the sampler's safety net: an arc found inside the region of an earlier
  /// sample, which rounding in the conic case can leave behind).
  void remove_arc(std::size_t i) { if(i < alive_.size() && alive_[i]) kill(i); }

  /// decisions taken by crossing directions / by in_old_disks (for statistics)
  /// @{
  std::size_t runs_decided_by_crossings() const { return by_crossings_; }
  std::size_t runs_decided_by_distance() const { return by_distance_; }
  /// runs left out because they enter a face inside the earlier disks (see update())
  std::size_t runs_decided_by_covered_faces() const { return by_covered_faces_; }
  /// @}

  /// true when a live arc lies in face f
  bool has_arcs_in(face_descriptor f) const { return !arcs_in_face_[get(fim_, f)].empty(); }

private:
  struct Piece
  {
    Arc arc;
    int start = -1, end = -1;   // index of the crossing at its start / end, -1: none (arc junction)
  };

  // (`start_covered`, `end_covered`: the open chain breaks at a face inside the earlier disks)
  template <class Chain, class InOldDisks>
  void add_uncovered_runs(const Chain& chain, std::vector<internal::Arc_crossing>* cuts,
                          std::size_t sample, InOldDisks in_old_disks, bool start_covered, bool end_covered)
  {
    // pieces in chain order, with the crossings that bound them
    std::vector<Piece>& pieces = run_pieces_;
    std::vector<internal::Arc_crossing>& crossings = crossings_;
    pieces.clear();
    crossings.clear();
    for(std::size_t j = 0; j < chain.arcs.size(); ++j) {
      auto& cj = cuts[j];
      std::sort(cj.begin(), cj.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
      double t0 = 0;
      int pending = -1;   // crossing at t0
      for(const auto& x : cj) {
        if(x.t <= t0) { crossings.push_back(x); pending = int(crossings.size()) - 1; continue; }
        if(x.t >= 1) { crossings.push_back(x); pieces.push_back({internal::sub_arc(chain.arcs[j], t0, 1.0), pending, int(crossings.size()) - 1}); t0 = 1; pending = -1; break; }
        crossings.push_back(x);
        pieces.push_back({internal::sub_arc(chain.arcs[j], t0, x.t), pending, int(crossings.size()) - 1});
        t0 = x.t;
        pending = int(crossings.size()) - 1;
      }
      if(t0 < 1) pieces.push_back({internal::sub_arc(chain.arcs[j], t0, 1.0), pending, -1});
    }
    if(pieces.empty()) return;
    // runs: maximal sequences of pieces joined without crossing (closed chains wrap around)
    const std::size_t n = pieces.size();
    std::size_t first = 0;
    if(chain.closed) {
      while(first < n && pieces[first].start < 0) ++first;
      if(first == n) {   // no crossing at all: one decision for the whole curve
        ++by_distance_;
        const Piece& mid = pieces[n / 2];
        if(!in_old_disks(location(mid.arc, 0.5)))
          for(const Piece& p : pieces) if(p.arc.length() >= min_length_) add(p.arc, sample);
        return;
      }
    }
    std::size_t i = first;
    std::size_t done = 0;
    std::vector<std::size_t>& run = run_;
    while(done < n) {
      run.assign(1, i);
      std::size_t l = i;
      while(true) {
        const std::size_t next = chain.closed ? (l + 1) % n : l + 1;
        if(pieces[l].end >= 0 || next >= n || next == first || pieces[next].start >= 0) break;
        l = next;
        run.push_back(l);
      }
      const int sc = pieces[run.front()].start, ec = pieces[run.back()].end;
      double length = 0;
      for(std::size_t p : run) length += pieces[p].arc.length();
      if(length >= min_length_) {
        int inside = -1;   // -1: undecided
        const bool s_ok = sc >= 0 && crossings[sc].reliable, e_ok = ec >= 0 && crossings[ec].reliable;
        if(s_ok && e_ok && crossings[sc].entering != crossings[ec].entering) inside = crossings[sc].entering;
        const bool from_covered = run.front() == 0 && start_covered, to_covered = run.back() + 1 == n && end_covered;
        if(from_covered || to_covered) {
          // (a reliable cut at the run's other end that says it lies outside -- entering the
          // earlier disks at its end, or leaving them at its start -- disagrees: the distance decides)
          const bool disagree = inside == 0 || (from_covered && e_ok && crossings[ec].entering) || (to_covered && s_ok && !crossings[sc].entering);
          if(disagree) inside = -1;
          else if(inside < 0) { inside = 1; ++by_covered_faces_; }
        }
        if(inside < 0) {
          ++by_distance_;
          // the midpoint of the run, by length
          double half = 0.5 * length;
          std::size_t p = 0;
          while(p + 1 < run.size() && half > pieces[run[p]].arc.length()) half -= pieces[run[p++]].arc.length();
          const Arc& a = pieces[run[p]].arc;
          inside = in_old_disks(location(a, a.length() > 0 ? std::min(1.0, half / a.length()) : 0.5)) ? 1 : 0;
        } else {
          ++by_crossings_;
        }
        if(!inside)
          for(std::size_t p : run) if(pieces[p].arc.length() >= min_length_) add(pieces[p].arc, sample);
      }
      done += run.size();
      i = chain.closed ? (l + 1) % n : l + 1;
      if(!chain.closed && i >= n) break;
    }
  }

  // Arcs are numbered in the order they are made (the draws walk the Fenwick tree in that order,
  // which fixes the samples for a seed), but a dead arc's record slot is reused: the records (about
  // 200 bytes each) take as much room as the largest live boundary, not as every arc ever made
  // (several per sample); only 17 bytes per arc ever made remain (the Fenwick tree, the slot, the
  // live flag).
  void add(const Arc& a, std::size_t sample)
  {
    const std::size_t id = alive_.size();
    std::size_t slot;
    if(!free_.empty()) {
      slot = free_.back();
      free_.pop_back();
      arcs_[slot] = {a, sample};
    } else {
      slot = arcs_.size();
      arcs_.push_back({a, sample});
    }
    slot_of_.push_back(slot);
    alive_.push_back(1);
    const bool p = is_pickable(a.face);
    fenwick_.set(id, p ? a.length() : 0.0);
    arcs_in_face_[get(fim_, a.face)].push_back(id);
    ++alive_count_;
    if(p) ++pickable_count_;
  }

  void kill(std::size_t i)
  {
    alive_[i] = 0;
    fenwick_.set(i, 0.0);
    --alive_count_;
    if(is_pickable(stored(i).arc.face)) --pickable_count_;
    auto& list = arcs_in_face_[get(fim_, stored(i).arc.face)];
    list.erase(std::remove(list.begin(), list.end(), i), list.end());
    free_.push_back(slot_of_[i]);
  }

  const Stored_arc& stored(std::size_t i) const { return arcs_[slot_of_[i]]; }
  bool is_pickable(face_descriptor f) const { return pickable_.empty() || pickable_[std::size_t(get(fim_, f))]; }

  static void split(const Arc& a, std::vector<double>& cuts, std::vector<Arc>& pieces)
  {
    std::sort(cuts.begin(), cuts.end());
    double t0 = 0;
    for(double t : cuts) {
      if(t <= t0 || t >= 1) continue;
      pieces.push_back(internal::sub_arc(a, t0, t));
      t0 = t;
    }
    pieces.push_back(internal::sub_arc(a, t0, 1.0));
  }

  template <class Keep>
  void replace_by_kept_pieces(std::size_t i, std::vector<double>& cuts, Keep keep)
  {
    std::vector<Arc>& pieces = split_pieces_;
    pieces.clear();
    const Arc a = stored(i).arc;
    split(a, cuts, pieces);
    std::vector<char>& kept = kept_;
    kept.assign(pieces.size(), 0);
    bool all = true;
    for(std::size_t k = 0; k < pieces.size(); ++k) {
      kept[k] = pieces[k].length() >= min_length_ && keep(location(pieces[k], 0.5));
      all = all && kept[k];
    }
    if(all && pieces.size() == 1) return;
    const std::size_t sample = stored(i).sample;
    kill(i);
    // merge consecutive kept pieces back together
    for(std::size_t k = 0; k < pieces.size();) {
      if(!kept[k]) { ++k; continue; }
      std::size_t l = k;
      while(l + 1 < pieces.size() && kept[l + 1]) ++l;
      Arc merged = pieces[k];
      merged.theta_end = pieces[l].theta_end;
      add(merged, sample);
      k = l + 1;
    }
  }

  const TriangleMesh& tm_;
  FIM fim_;
  std::vector<Stored_arc> arcs_;
  std::vector<char> alive_;
  std::vector<std::size_t> slot_of_;   // arc number -> its record in arcs_
  std::vector<std::size_t> free_;      // records of dead arcs, reused by add()
  std::vector<std::vector<std::size_t>> arcs_in_face_;
  internal::Fenwick_tree fenwick_;
  std::size_t alive_count_ = 0, pickable_count_ = 0;
  std::vector<char> pickable_;   // (empty: every face)
  double min_length_ = 0;
  // the update's buffers (members only to reuse their storage from one update to the next)
  std::vector<std::pair<std::size_t, double>> stored_cuts_;
  std::vector<std::vector<internal::Arc_crossing>> new_cuts_;
  std::vector<internal::Arc_crossing> crossings_, stored_crossings_;
  std::vector<std::size_t> candidates_, run_;
  std::vector<double> cuts_;
  std::vector<Piece> run_pieces_;
  std::vector<Arc> split_pieces_;
  std::vector<char> kept_;
  std::size_t by_crossings_ = 0, by_distance_ = 0, by_covered_faces_ = 0;
};

} // namespace Poisson_remesh

#endif // POISSON_REMESH_BOUNDARY_CIRCULAR_AVAILABLE_BOUNDARY_H
