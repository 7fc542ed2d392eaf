// Poisson_remesh/Geodesic/internal/conic_geometry.h
//
// Where the curves of adaptive sampling's available boundary meet (Section 5.1, Eq. 4-5). Inside a
// face laid out flat in 2D, a distance generator (an unfolded source c at distance sigma) meets
// the level r0 + r(x), with r linear in the face (gradient a, |a| < 1), on the conic
// |x - c| = p + a . (x - c), p = level(c) - sigma: an ellipse with a focus at c, met by each ray
// from c once, at rho(u) = p / (1 - a . u). The iso-curve extraction cuts such a conic where it
// crosses a line (a face edge, a wedge side) and where it crosses another generator's conic (the
// same gradient: the same face); both are found in closed form, each as the (at most two) polar
// angles around c of the meeting points.

#ifndef POISSON_REMESH_GEODESIC_INTERNAL_CONIC_GEOMETRY_H
#define POISSON_REMESH_GEODESIC_INTERNAL_CONIC_GEOMETRY_H

#include <Poisson_remesh/Geodesic/internal/Indexed_triangle_mesh.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// The polar angles u around c where the conic's points meet the line w . u = k: at most two,
/// base +- acos(k / |w|) (none when |k| > |w|, or w = 0).
inline void polar_angles_of(Vec2 w, double k, std::vector<double>& out)
{
  const double W = norm(w);
  if(!(W > 0.) || std::abs(k) > W) return;
  const double base = std::atan2(w.y, w.x), delta = std::acos((std::max)(-1., (std::min)(1., k / W)));
  out.push_back(base + delta);
  out.push_back(base - delta);
}

/// conic |x - c| = p + a . (x - c) (|a| < 1, p > 0) and the line through the two points given:
/// the polar angles around c of the (at most two) meeting points
inline void conic_line_angles(Vec2 c, double p, Vec2 a, Vec2 P, Vec2 Q, std::vector<double>& out)
{
  const Vec2 d = Q - P;
  const double L = norm(d);
  if(!(L > 0.)) return;
  const Vec2 n{-d.y / L, d.x / L};
  // rho n.u = k on the line, rho (1 - a.u) = p on the conic: (p n + k a) . u = k
  const double k = dot(n, P - c);
  polar_angles_of(p * n + k * a, k, out);
}

/// conic (c1, p1) and conic (c2, p2), the same gradient a (|a| < 1, p1 > 0): the polar angles
/// around c1 of their (at most two) meeting points.
/// On the first conic, x = c1 + rho u with rho = p1 + a . (x - c1); the second's equation
/// becomes |x - c2| = rho - K, K = p1 - p2 + a . (c2 - c1) (for |K| < |d| a hyperbola's branch,
/// foci c1, c2). Squared, with d = c2 - c1: 2 rho (K - u . d) = K^2 - |d|^2, and with
/// rho = p1 / (1 - a . u) linear in u: ((K^2 - |d|^2) a - 2 p1 d) . u = K^2 - |d|^2 - 2 p1 K.
/// A solution with rho < K solves rho + |x - c2| = K instead (only when p2 <= 0): dropped. A close
/// pair is found too, down to p2 ~ 1e-6 p1 (below, acos near 1 loses the angle: a miss possible).
inline void conic_conic_angles(Vec2 c1, double p1, Vec2 c2, double p2, Vec2 a, std::vector<double>& out)
{
  const Vec2 d = c2 - c1;
  const double K = p1 - p2 + dot(a, d), E = K * K - dot(d, d);
  const std::size_t first = out.size();
  polar_angles_of(E * a - (2. * p1) * d, E - 2. * p1 * K, out);
  // (a relative slack: a meeting point where rho = K (p2 = 0) is kept; an extra angle only
  // splits a piece of curve in two)
  std::size_t kept = first;
  for(std::size_t i = first; i < out.size(); ++i) {
    const Vec2 u{std::cos(out[i]), std::sin(out[i])};
    const double rho = p1 / (1. - dot(a, u));
    if(rho - K >= -1e-12 * (rho + std::abs(K))) out[kept++] = out[i];
  }
  out.resize(kept);
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_GEODESIC_INTERNAL_CONIC_GEOMETRY_H
