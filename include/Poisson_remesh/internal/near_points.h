// Poisson_remesh/internal/near_points.h
//
// Points in a grid of cubic cells (internal): which of them lie within a cell's size of a
// point or a triangle, and which is the nearest within a cell's size. Used by the remakes
// (internal/regrading.h, internal/local_remake.h) and the fidelity insertions
// (Postprocessing/fidelity_insertion.h, Postprocessing/internal/near_surface.h).

#ifndef POISSON_REMESH_INTERNAL_NEAR_POINTS_H
#define POISSON_REMESH_INTERNAL_NEAR_POINTS_H

#include <Poisson_remesh/internal/parallel.h>
#include <Poisson_remesh/internal/radix_sort.h>
#include <CGAL/number_utils.h>
#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// `points` in cells of size `cell`: the points sorted by cell in one array, and a table of the
/// non-empty cells (open addressing) giving each cell's range in it -- no allocation per cell, which
/// the fidelity passes build and drop several times per remesh
template <class Point_3>
class Near_points
{
  typedef std::array<long long, 3> Cell;
  static std::size_t hash(const Cell& c)
  {
    // (the three coordinates mixed, then the bits spread: neighbouring cells land apart in the table)
    std::uint64_t h = std::uint64_t(c[0]) * 73856093u ^ std::uint64_t(c[1]) * 19349663u ^ std::uint64_t(c[2]) * 83492791u;
    h ^= h >> 31;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 29;
    return std::size_t(h);
  }
  struct Slot { Cell cell; std::size_t begin = 0, end = 0; };   // (end == 0: an empty slot)

public:
  /// (`ConcurrencyTag`: the points' cells, keys and places computed on TBB's threads with
  /// CGAL::Parallel_tag; the same grid in both modes)
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  Near_points(const std::vector<Point_3>& points, double cell, ConcurrencyTag = ConcurrencyTag()) : cell_(cell)
  {
    // the points' order by cell (and by index within a cell): sorted on one 64-bit key when the
    // cells' span fits 21 bits per axis (always, in practice), else on the cells themselves
    const std::size_t n = points.size();
    std::vector<Cell> point_cell(n);
    for_each_index<ConcurrencyTag>(n, [&](std::size_t i) { point_cell[i] = cell_of(points[i]); }, 1024);
    Cell lo{{0, 0, 0}}, hi{{0, 0, 0}};
    for(std::size_t i = 0; i < n; ++i)
      for(int k = 0; k < 3; ++k) {
        lo[k] = i == 0 ? point_cell[i][k] : std::min(lo[k], point_cell[i][k]);
        hi[k] = i == 0 ? point_cell[i][k] : std::max(hi[k], point_cell[i][k]);
      }
    std::vector<std::size_t> order(n);
    // the cells in `order`'s order (read in sequence below, not through `order`)
    std::vector<Cell> sorted_cell(n);
    const long long fits = 1LL << 21;
    if(hi[0] - lo[0] < fits && hi[1] - lo[1] < fits && hi[2] - lo[2] < fits) {
      std::vector<std::pair<std::uint64_t, std::size_t>> keyed(n);
      for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
        keyed[i] = {std::uint64_t(point_cell[i][0] - lo[0]) << 42 | std::uint64_t(point_cell[i][1] - lo[1]) << 21 | std::uint64_t(point_cell[i][2] - lo[2]), i};
      }, 1024);
      stable_sort_by_key(keyed);   // (made in index order: std::sort's order of the pairs)
      const std::uint64_t mask = (std::uint64_t(1) << 21) - 1;
      for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
        order[i] = keyed[i].second;
        const std::uint64_t key = keyed[i].first;
        sorted_cell[i] = Cell{{lo[0] + (long long)(key >> 42), lo[1] + (long long)((key >> 21) & mask), lo[2] + (long long)(key & mask)}};
      }, 1024);
    } else {
      std::vector<std::pair<Cell, std::size_t>> keyed(n);
      for(std::size_t i = 0; i < n; ++i) keyed[i] = {point_cell[i], i};
      std::sort(keyed.begin(), keyed.end());
      for(std::size_t i = 0; i < n; ++i) { order[i] = keyed[i].second; sorted_cell[i] = keyed[i].first; }
    }
    points_.resize(n);
    for_each_index<ConcurrencyTag>(n, [&](std::size_t i) { points_[i] = points[order[i]]; }, 1024);
    place_ = std::move(order);
    std::size_t cells = 0;
    for(std::size_t i = 0; i < n; ++i) cells += (i == 0 || sorted_cell[i] != sorted_cell[i - 1]);
    std::size_t size = 1;
    while(size < 2 * cells) size *= 2;
    table_.resize(size);
    mask_ = size - 1;
    number_of_cells_ = cells;
    for(std::size_t i = 0, j = 0; i < n; i = j) {
      const Cell& c = sorted_cell[i];
      while(j < n && sorted_cell[j] == c) ++j;
      std::size_t h = hash(c) & mask_;
      while(table_[h].end != 0) h = (h + 1) & mask_;
      table_[h] = Slot{c, i, j};
    }
  }
  /// the squared distance to the nearest point when it is within one cell (else infinity)
  double squared_distance(const Point_3& p) const
  {
    double best = std::numeric_limits<double>::infinity();
    any_near(p, [&](double d2) { best = std::min(best, d2); return false; });
    return best;
  }
  /// the place (among the points given) of the point nearest `p` among those of p's cell and the 26
  /// around it -- every point within a cell's size of `p` is among them -- and its squared
  /// distance; (-1 as a size_t, infinity) when those cells are empty. The search stops at a point
  /// whose squared distance is `enough` or less (then it returns that one: the cells are searched
  /// in the same order for the same `p`, their points in the grid's order)
  std::pair<std::size_t, double> nearest(const Point_3& p, double enough = -1) const
  {
    std::size_t best = std::size_t(-1);
    double best_d2 = std::numeric_limits<double>::infinity();
    nearest_in_reach(p, [&](double d2, std::size_t i) {
      if(d2 < best_d2 || (d2 == best_d2 && place_[i] < best)) { best_d2 = d2; best = place_[i]; }
      return best_d2 <= enough ? -1. : best_d2;   // (no cell is nearer than -1: the search ends)
    });
    return {best, best_d2};
  }
  /// whether a point lies within `d` (<= the cell) of `p`
  bool within(const Point_3& p, double d) const
  {
    return any_near(p, [&](double d2) { return d2 <= d * d; }, d);
  }
  /// whether a point lies within `d` (<= the cell) of the triangle (a, b, c)
  template <class Triangle_3>
  bool near_triangle(const Triangle_3& t, double d) const
  {
    const auto box = t.bbox();
    const Cell lo = cell_of(box.xmin() - d, box.ymin() - d, box.zmin() - d), hi = cell_of(box.xmax() + d, box.ymax() + d, box.zmax() + d);
    const double span = double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
    auto near = [&](const Point_3& q) { return CGAL::to_double(CGAL::squared_distance(q, t)) < d * d; };
    if(span > double(number_of_cells_)) {   // (a triangle larger than the places' spread: every point)
      for(const Point_3& q : points_) if(near(q)) return true;
      return false;
    }
    for(long long x = lo[0]; x <= hi[0]; ++x)
      for(long long y = lo[1]; y <= hi[1]; ++y)
        for(long long z = lo[2]; z <= hi[2]; ++z)
          if(const Slot* s = find(Cell{{x, y, z}}))
            for(std::size_t i = s->begin; i < s->end; ++i) if(near(points_[i])) return true;
    return false;
  }

private:
  const Slot* find(const Cell& c) const
  {
    if(table_.empty()) return nullptr;
    // (the cells compared coordinate by coordinate: std::array's == calls memcmp)
    for(std::size_t h = hash(c) & mask_; table_[h].end != 0; h = (h + 1) & mask_) {
      const Cell& k = table_[h].cell;
      if(k[0] == c[0] && k[1] == c[1] && k[2] == c[2]) return &table_[h];
    }
    return nullptr;
  }
  // stop(d2) for the squared distance d2 from p to each point of p's cell and of the 26 around it
  // (its own cell first: the likeliest to hold what is looked for), until stop returns true;
  // returns whether it did. With `reach` (<= the cell), the cells farther than `reach` from the
  // point asked about are passed over: stop must then return true for no point farther than
  // `reach` (their points are all farther)
  template <class Stop>
  bool any_near(const Point_3& p, Stop stop, double reach = std::numeric_limits<double>::infinity()) const
  {
    const double x[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    const Cell c = cell_of(x[0], x[1], x[2]);
    auto in = [&](const Cell& k) {
      const Slot* s = find(k);
      if(s == nullptr) return false;
      for(std::size_t i = s->begin; i < s->end; ++i)
        if(stop(CGAL::to_double(CGAL::squared_distance(p, points_[i])))) return true;
      return false;
    };
    const double bound = reach * reach;
    return scan(x, c, in, [&] { return bound; });
  }
  // the squared distance from the point x (in cell c) to the neighbouring cells' slabs along each
  // axis, at least: below (0) and above (2) its own cell's, 0 within it (1). A cell's points have
  // floor(coordinate / cell) equal to its index, which rounding may give to a point a few ulps
  // across the bound index * cell: the distances are shortened by that much (`slack`)
  void gaps(const double x[3], const Cell& c, double gap[3][3]) const
  {
    for(int k = 0; k < 3; ++k) {
      const double bound_low = double(c[k]) * cell_, bound_high = double(c[k] + 1) * cell_;
      const double slack = 16 * std::numeric_limits<double>::epsilon() * (std::abs(x[k]) + std::abs(bound_low) + std::abs(bound_high));
      const double low = x[k] - bound_low - slack, high = bound_high - x[k] - slack;
      gap[k][0] = low > 0 ? low * low : 0;
      gap[k][1] = 0;
      gap[k][2] = high > 0 ? high * high : 0;
    }
  }
  // visit(d2, i) for the points i of p's cell, then of the cells around it that are not farther
  // than the squared distance visit returned last (the cells' gaps as in any_near)
  template <class Visit>
  void nearest_in_reach(const Point_3& p, Visit visit) const
  {
    const double x[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    const Cell c = cell_of(x[0], x[1], x[2]);
    double bound = std::numeric_limits<double>::infinity();
    auto in = [&](const Cell& k) {
      if(const Slot* s = find(k))   // (a bound under 0: visit asks for no more points)
        for(std::size_t i = s->begin; i < s->end && !(bound < 0); ++i) bound = visit(CGAL::to_double(CGAL::squared_distance(p, points_[i])), i);
    };
    scan(x, c, [&](const Cell& k) { in(k); return false; }, [&] { return bound; });
  }
  // in(k) for the cell c of the point x, then for each of the 26 cells k around it whose squared
  // distance to x is not above bound() (asked again before each), until in returns true; returns
  // whether it did
  template <class In, class Bound>
  bool scan(const double x[3], const Cell& c, In in, Bound bound) const
  {
    if(in(c)) return true;
    double gap[3][3];
    gaps(x, c, gap);
    for(long long dx = -1; dx <= 1; ++dx)
      for(long long dy = -1; dy <= 1; ++dy) {
        const double gxy = gap[0][dx + 1] + gap[1][dy + 1];
        if(gxy > bound()) continue;
        for(long long dz = -1; dz <= 1; ++dz)
          if((dx != 0 || dy != 0 || dz != 0) && !(gxy + gap[2][dz + 1] > bound()) && in(Cell{{c[0] + dx, c[1] + dy, c[2] + dz}})) return true;
      }
    return false;
  }
  Cell cell_of(double x, double y, double z) const
  {
    return Cell{{(long long)std::floor(x / cell_), (long long)std::floor(y / cell_), (long long)std::floor(z / cell_)}};
  }
  Cell cell_of(const Point_3& p) const { return cell_of(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())); }

  double cell_;
  std::vector<Point_3> points_;   // sorted by cell
  std::vector<std::size_t> place_;   // each one's place among the points given
  std::vector<Slot> table_;
  std::size_t mask_ = 0, number_of_cells_ = 0;
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_NEAR_POINTS_H
