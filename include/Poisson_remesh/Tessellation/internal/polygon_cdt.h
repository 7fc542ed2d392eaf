// Poisson_remesh/Tessellation/internal/polygon_cdt.h
//
// The constrained Delaunay triangulation of a small polygon laid out around the origin, found
// directly (internal): the removal of an original vertex (paper §6.1) triangulates its laid-out
// one-ring, a polygon of a few vertices around the removed vertex, tens of thousands of times per
// remesh. CGAL's Constrained_Delaunay_triangulation_2 builds a whole triangulation data structure
// for each (most of the removal's time, much of it allocation); here the triangles come from the
// edges they stand on, with CGAL's exact predicates and no allocation of its own after the first
// calls.
//
// The layout must turn once around the origin, counterclockwise, starting on the positive x axis
// (a whole ring), or from angle 0 to a half turn (a half ring, closed by the side from its last
// vertex to its first): the origin then sees all of it, and whether a chord lies inside
// is told by the vertices on one side of it (is_diagonal below). Each sub-polygon i, i+1, ..., j
// (closed by the chord from j to i) takes the triangle (i, k, j) whose apex k sees both ends
// (both new sides are diagonals) and whose circumcircle holds no other such apex: the triangle of
// the constrained Delaunay triangulation on that chord (test_tessellation.cpp checks the result
// against CGAL's on random layouts). Where another apex lies on that circle the triangulation is
// not unique, and a layout that is not as above is not taken: the caller then uses CGAL's
// triangulation, so that the triangles are always those CGAL's gives (as a set; their order is
// the recursion's).

#ifndef POISSON_REMESH_TESSELLATION_INTERNAL_POLYGON_CDT_H
#define POISSON_REMESH_TESSELLATION_INTERNAL_POLYGON_CDT_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// The outcome of polygon_cdt: the triangles are the constrained Delaunay triangulation's, or
/// the polygon has cocircular apexes (not unique), or it is not a layout as the file's comment
/// says (or no triangulation was found).
enum class Polygon_cdt_outcome { found, cocircular, not_found };

/// The constrained Delaunay triangulation of the layout pts[0..n-1] (counterclockwise; `full`: a
/// whole ring, else a half one), as triangles of indices, each counterclockwise, in `out` (cleared
/// first); see the file's comment for when it is not `found` (then `out` is to be ignored).
inline Polygon_cdt_outcome polygon_cdt(const std::vector<std::array<double, 2>>& pts, bool full, std::vector<std::array<std::size_t, 3>>& out)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef K::Point_2 Point;
  out.clear();
  const std::size_t n = pts.size();
  if(n < 3) return n == 2 ? Polygon_cdt_outcome::found : Polygon_cdt_outcome::not_found;
  thread_local std::vector<Point> p;
  p.clear();
  for(const auto& x : pts) p.emplace_back(x[0], x[1]);
  const K::Orientation_2 orientation;
  const K::Side_of_oriented_circle_2 side_of_circle;
  // The origin O sees all of the layout: each vertex turns left from the one before,
  // seen from O, starting on the positive x axis, and a full layout turns once around O (above
  // the x axis, then below it) and left again from its last vertex to its first, while a half
  // layout stays above the x axis and ends left of O on it (at a half turn, to rounding).
  // Else the polygon goes to CGAL.
  const Point O(0, 0);
  for(std::size_t k = 0; k + 1 < n; ++k)
    if(orientation(O, p[k], p[k + 1]) != CGAL::LEFT_TURN) return Polygon_cdt_outcome::not_found;
  if(!(p[0].y() == 0 && p[0].x() > 0)) return Polygon_cdt_outcome::not_found;
  if(full) {
    if(orientation(O, p[n - 1], p[0]) != CGAL::LEFT_TURN) return Polygon_cdt_outcome::not_found;
    bool below = false;
    for(std::size_t k = 1; k < n; ++k) {
      if(p[k].y() < 0) below = true;
      else if(below || (p[k].y() == 0 && p[k].x() > 0)) return Polygon_cdt_outcome::not_found;
    }
  } else {
    for(std::size_t k = 1; k < n; ++k) if(p[k].y() < 0) return Polygon_cdt_outcome::not_found;
    if(!(p[n - 1].x() < 0 && p[n - 1].y() <= 1e-12 * -p[n - 1].x())) return Polygon_cdt_outcome::not_found;
    // (the closing side passes by the origin, not through it: every other vertex strictly left
    // of it, or the polygon is not simple)
    for(std::size_t k = 1; k + 1 < n; ++k)
      if(orientation(p[n - 1], p[0], p[k]) != CGAL::LEFT_TURN) return Polygon_cdt_outcome::not_found;
  }
  // Whether the chord from a to b (a < b) is a diagonal (inside the polygon, meeting its boundary
  // at a and b only). Seen from O the chord spans the angles from a to b; where that is under a
  // half turn, the polygon's boundary within that angle is the chain a, a + 1, ..., b, and the
  // chord is inside when every vertex between lies strictly beyond it (right of a -> b); over a
  // half turn, the same of the other chain (strictly left); at a half turn, both.
  auto is_diagonal = [&](std::size_t a, std::size_t b) {
    const CGAL::Orientation o = orientation(O, p[a], p[b]);
    if(o != CGAL::RIGHT_TURN)
      for(std::size_t k = a + 1; k < b; ++k) if(orientation(p[a], p[b], p[k]) != CGAL::RIGHT_TURN) return false;
    if(o != CGAL::LEFT_TURN)
      for(std::size_t k = 0; k < n; ++k) if((k < a || k > b) && orientation(p[a], p[b], p[k]) != CGAL::LEFT_TURN) return false;
    return true;
  };
  // the chords already known (1 inside, 2 not), by pair
  thread_local std::vector<signed char> inside;
  inside.assign(n * n, 0);
  auto diagonal = [&](std::size_t a, std::size_t b) {
    if(a > b) std::swap(a, b);
    if(b == a + 1 || (a == 0 && b == n - 1)) return true;
    signed char& known = inside[a * n + b];
    if(known == 0) known = is_diagonal(a, b) ? 1 : 2;
    return known == 1;
  };
  thread_local std::vector<std::pair<std::size_t, std::size_t>> todo;
  todo.assign(1, {0, n - 1});
  while(!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if(j < i + 2) continue;
    std::size_t apex = n;
    for(std::size_t k = i + 1; k < j; ++k) {
      if(orientation(p[i], p[k], p[j]) != CGAL::LEFT_TURN || !diagonal(i, k) || !diagonal(k, j)) continue;
      if(apex == n) { apex = k; continue; }
      // (the apex whose circle holds the other: the later one, unless on the circle)
      const CGAL::Oriented_side s = side_of_circle(p[i], p[apex], p[j], p[k]);
      if(s == CGAL::ON_ORIENTED_BOUNDARY) return Polygon_cdt_outcome::cocircular;
      if(s == CGAL::ON_POSITIVE_SIDE) apex = k;
    }
    if(apex == n) return Polygon_cdt_outcome::not_found;
    // (a candidate before the apex that lies on its circle was passed over above: look again)
    for(std::size_t k = i + 1; k < j; ++k) {
      if(k == apex || orientation(p[i], p[k], p[j]) != CGAL::LEFT_TURN || !diagonal(i, k) || !diagonal(k, j)) continue;
      const CGAL::Oriented_side s = side_of_circle(p[i], p[apex], p[j], p[k]);
      if(s == CGAL::ON_ORIENTED_BOUNDARY) return Polygon_cdt_outcome::cocircular;
      if(s == CGAL::ON_POSITIVE_SIDE) return Polygon_cdt_outcome::not_found;   // (cannot happen: the apex is the innermost)
    }
    out.push_back({i, apex, j});
    todo.push_back({i, apex});
    todo.push_back({apex, j});
  }
  return Polygon_cdt_outcome::found;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_TESSELLATION_INTERNAL_POLYGON_CDT_H
