// Poisson_remesh/Geodesic/internal/conic_geometry.h
//
// Where the curves of adaptive sampling's available boundary meet (Section 5.1, Eq. 4-5). Inside a
// face laid out flat in 2D, a distance generator (an unfolded source c at distance sigma) meets
// the level r0 + r(x), with r linear in the face (gradient a, |a| < 1), on the conic
// |x - c| = gap + a . (x - c), gap = level(c) - sigma: an ellipse with a focus at c, met by each
// ray from c (unit direction e) once, at rho(e) = gap / (1 - a . e). The iso-curve extraction cuts
// such a conic where it crosses a line (a face edge, a wedge side) and where it crosses another
// generator's conic (the same gradient: the same face); both are found in closed form, each as
// the (at most two) polar angles around c of the meeting points.

#ifndef POISSON_REMESH_GEODESIC_INTERNAL_CONIC_GEOMETRY_H
#define POISSON_REMESH_GEODESIC_INTERNAL_CONIC_GEOMETRY_H

#include <Poisson_remesh/Geodesic/internal/Indexed_triangle_mesh.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// The polar angles around c of the directions e of the conic meeting the line w . e = k: two at most,
/// base +- acos(k / |w|) (none when |k| > |w|, or w = 0).
inline void polar_angles_of(Vec2 w, double k, std::vector<double>& out)
{
  const double W = norm(w);
  if(!(W > 0.) || std::abs(k) > W) return;
  const double base = std::atan2(w.y, w.x), delta = std::acos((std::max)(-1., (std::min)(1., k / W)));
  out.push_back(base + delta);
  out.push_back(base - delta);
}

/// conic |x - c| = gap + a . (x - c) (|a| < 1, gap > 0) and the line through `from` and `to`:
/// the polar angles around c of the (at most two) meeting points
inline void conic_line_angles(Vec2 c, double gap, Vec2 a, Vec2 from, Vec2 to, std::vector<double>& out)
{
  const Vec2 d = to - from;
  const double L = norm(d);
  if(!(L > 0.)) return;
  const Vec2 n{-d.y / L, d.x / L};
  // rho n.e = k on the line, rho (1 - a.e) = gap on the conic: (gap n + k a) . e = k
  const double k = dot(n, from - c);
  polar_angles_of(gap * n + k * a, k, out);
}

/// conic (c1, p1) and conic (c2, p2), the same gradient a (|a| < 1, p1 > 0): the polar angles
/// around c1 of their (at most two) meeting points.
/// On the first conic, x = c1 + rho e with rho = p1 + a . (x - c1); the second's equation
/// becomes |x - c2| = rho - K, K = p1 - p2 + a . (c2 - c1) (for |K| < |d| a hyperbola's branch,
/// foci c1, c2). Squared, with d = c2 - c1: 2 rho (K - e . d) = K^2 - |d|^2, and with
/// rho = p1 / (1 - a . e) linear in e: w . e = k, w = E a - 2 p1 d, k = E - 2 p1 K,
/// E = K^2 - |d|^2. The angles are base +- delta, base the direction of w and delta the angle
/// whose cosine is k / |w|, its sine from |w|^2 - k^2 = -E (E (1 - |a|^2) + 4 p1 p2) in that
/// closed form: for a small conic on a large one (p2 << p1) the difference of the two squares
/// cancels, and an acos of k / |w| near 1 would lose the angle between the two crossings.
/// Where p2 <= 0 the second conic has no point but c2 (|x - c2| + a . (x - c2) >= 0): no angle
/// (the squared equation's solutions there have rho < K and solve rho + |x - c2| = K instead).
inline void conic_conic_angles(Vec2 c1, double p1, Vec2 c2, double p2, Vec2 a, std::vector<double>& out)
{
  if(!(p2 > 0.)) return;
  const Vec2 d = c2 - c1;
  const double K = p1 - p2 + dot(a, d), E = K * K - dot(d, d);
  const Vec2 w = E * a - (2. * p1) * d;
  const double k = E - 2. * p1 * K, sine2 = -E * (E * (1. - dot(a, a)) + 4. * p1 * p2);
  if(!(sine2 >= 0.) || !(norm(w) > 0.)) return;
  const double base = std::atan2(w.y, w.x), delta = std::atan2(std::sqrt(sine2), k);
  out.push_back(base + delta);
  out.push_back(base - delta);
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_GEODESIC_INTERNAL_CONIC_GEOMETRY_H
