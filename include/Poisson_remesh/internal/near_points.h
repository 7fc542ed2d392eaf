// Poisson_remesh/internal/near_points.h
//
// Points in a hash grid of cubic cells (internal): which of them lie within a cell's size of a
// point or a triangle. Used by the remakes (internal/regrading.h, internal/local_remake.h) and the
// fidelity insertions (Postprocessing/fidelity_insertion.h).

#ifndef POISSON_REMESH_INTERNAL_NEAR_POINTS_H
#define POISSON_REMESH_INTERNAL_NEAR_POINTS_H

#include <CGAL/number_utils.h>
#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// `points` in cells of size `cell`
template <class Point_3>
class Near_points
{
  typedef std::array<long long, 3> Cell;
  struct Hash { std::size_t operator()(const Cell& c) const { return std::size_t(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL); } };

public:
  Near_points(const std::vector<Point_3>& points, double cell) : cell_(cell)
  {
    for(const Point_3& p : points) cells_[cell_of(p)].push_back(p);
  }
  /// the squared distance to the nearest point when it is within one cell (else infinity)
  double squared_distance(const Point_3& p) const
  {
    double best = std::numeric_limits<double>::infinity();
    any_near(p, [&](double d2) { best = std::min(best, d2); return false; });
    return best;
  }
  /// whether a point lies within `d` (<= the cell) of `p`
  bool within(const Point_3& p, double d) const
  {
    return any_near(p, [&](double d2) { return d2 <= d * d; });
  }
  /// whether a point lies within `d` (<= the cell) of the triangle (a, b, c)
  template <class Triangle_3>
  bool near_triangle(const Triangle_3& t, double d) const
  {
    const auto box = t.bbox();
    const Cell lo = cell_of(box.xmin() - d, box.ymin() - d, box.zmin() - d), hi = cell_of(box.xmax() + d, box.ymax() + d, box.zmax() + d);
    const double span = double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
    auto near = [&](const Point_3& q) { return CGAL::to_double(CGAL::squared_distance(q, t)) < d * d; };
    if(span > double(cells_.size())) {   // (a triangle larger than the places' spread: every point)
      for(const auto& kv : cells_)
        for(const Point_3& q : kv.second) if(near(q)) return true;
      return false;
    }
    for(long long x = lo[0]; x <= hi[0]; ++x)
      for(long long y = lo[1]; y <= hi[1]; ++y)
        for(long long z = lo[2]; z <= hi[2]; ++z) {
          const auto it = cells_.find(Cell{{x, y, z}});
          if(it == cells_.end()) continue;
          for(const Point_3& q : it->second) if(near(q)) return true;
        }
    return false;
  }

private:
  // stop(d2) for the squared distance d2 from p to each point of p's cell and of the 26 around it
  // (its own cell first: the likeliest to hold what is looked for), until stop returns true;
  // returns whether it did
  template <class Stop>
  bool any_near(const Point_3& p, Stop stop) const
  {
    const Cell c = cell_of(p);
    auto in = [&](const Cell& k) {
      const auto it = cells_.find(k);
      if(it == cells_.end()) return false;
      for(const Point_3& q : it->second) if(stop(CGAL::to_double(CGAL::squared_distance(p, q)))) return true;
      return false;
    };
    if(in(c)) return true;
    for(long long dx = -1; dx <= 1; ++dx)
      for(long long dy = -1; dy <= 1; ++dy)
        for(long long dz = -1; dz <= 1; ++dz)
          if((dx != 0 || dy != 0 || dz != 0) && in(Cell{{c[0] + dx, c[1] + dy, c[2] + dz}})) return true;
    return false;
  }
  Cell cell_of(double x, double y, double z) const
  {
    return Cell{{(long long)std::floor(x / cell_), (long long)std::floor(y / cell_), (long long)std::floor(z / cell_)}};
  }
  Cell cell_of(const Point_3& p) const { return cell_of(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())); }

  double cell_;
  std::unordered_map<Cell, std::vector<Point_3>, Hash> cells_;
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_NEAR_POINTS_H
