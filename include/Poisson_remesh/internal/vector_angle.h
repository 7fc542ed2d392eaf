// Poisson_remesh/internal/vector_angle.h
//
// The angle between two vectors from y = |u x v| >= 0 and x = u . v: atan2(y, x), in [0, pi].
//
// Why not std::atan2: the relaxation's angle searches and Lloyd steps ask for millions of
// triangle angles, and glibc's atan2 handles the whole plane and saves and restores the rounding
// mode at every call (RESULTS.md gives its share of a remesh). With y >= 0 only a half-plane
// is left: the quotient of the smaller by the larger of y and |x| is in [0, 1], it is moved
// next to the nearest of nine table points k/8 (atan(u) = atan(c) + atan((u - c) / (1 + u c))),
// leaving an argument of at most 1/16, where seven terms of the arctangent's series are exact to
// the last bit. The result is within a few units in the last place of std::atan2 (the test asks
// for 1e-15 over arguments of every size and sign); infinite and NaN arguments go to std::atan2.

#ifndef POISSON_REMESH_INTERNAL_VECTOR_ANGLE_H
#define POISSON_REMESH_INTERNAL_VECTOR_ANGLE_H

#include <cmath>

namespace Poisson_remesh {
namespace internal {

namespace vector_angle_detail {

// atan(t) for t in [0, 1]
inline double atan_unit(double t)
{
  // atan(k / 8), k = 0..8 (the doubles nearest them)
  static constexpr double table[9] = {0.0, 0.12435499454676144, 0.24497866312686414, 0.35877067027057225, 0.4636476090008061,
                                      0.5585993153435624, 0.6435011087932844, 0.7188299996216245, 0.7853981633974483};
  const int k = int(t * 8 + 0.5);
  const double c = k / 8.0;
  const double u = (t - c) / (1 + t * c);   // tan(atan(t) - atan(c)), |u| <= 1/16
  const double s = u * u;
  // u - u^3/3 + u^5/5 - ... - u^15/15 (the next term is below 1e-19 u)
  const double series =
    u * (1 + s * (-1.0 / 3 + s * (1.0 / 5 + s * (-1.0 / 7 + s * (1.0 / 9 + s * (-1.0 / 11 + s * (1.0 / 13 + s * (-1.0 / 15))))))));
  return table[k] + series;
}

} // namespace vector_angle_detail

/// atan2(y, x) for y >= 0 (or NaN): the angle between two vectors whose cross product has length
/// y and whose dot product is x.
inline double vector_angle(double y, double x)
{
  const double pi = 3.141592653589793238462643383279502884, half_pi = 1.570796326794896619231321691639751442;
  if(!(std::isfinite(y) && std::isfinite(x)) || y < 0) return std::atan2(y, x);
  if(y == 0) return std::signbit(x) ? pi : 0.0;   // (as std::atan2(+0, x))
  const double ax = std::abs(x);
  if(y <= ax) {
    const double a = vector_angle_detail::atan_unit(y / ax);
    return x > 0 ? a : pi - a;
  }
  const double a = vector_angle_detail::atan_unit(ax / y);
  return x >= 0 ? half_pi - a : half_pi + a;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_VECTOR_ANGLE_H
