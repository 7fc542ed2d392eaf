// Poisson_remesh/Postprocessing/internal/near_surface.h
//
// Whether a point lies within a distance of a triangle mesh, told by the triangles around the
// mesh's vertex nearest to it (internal). A "yes" is certain (those triangles belong to the
// mesh); a "no" only says that they are farther, and the caller then asks its tree, whose answer
// is exact. The fidelity insertions ask this of every point they measure, in every pass: on a
// mesh that follows its input, a point's nearest point on the mesh is nearly always on a triangle
// around its nearest vertex, and a grid lookup and a few point-triangle distances cost less than
// a tree search (and, when every point is answered so, than making the tree at all).

#ifndef POISSON_REMESH_POSTPROCESSING_INTERNAL_NEAR_SURFACE_H
#define POISSON_REMESH_POSTPROCESSING_INTERNAL_NEAR_SURFACE_H

#include <Poisson_remesh/internal/near_points.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/number_utils.h>
#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace Postprocessing {
namespace internal {

template <class Point_3>
class Near_surface
{
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel::Triangle_3 Triangle_3;

public:
  /// `points`: the mesh's vertices; `triangles`: its triangles, as places among `points`; `cell`:
  /// the grid's cell (the fidelity insertions take twice the mean edge length): the vertices within
  /// a cell's size of a point are always among those searched, farther ones may not be
  template <class ConcurrencyTag>
  Near_surface(std::vector<Point_3> points, std::vector<std::array<std::size_t, 3>> triangles, double cell, ConcurrencyTag tag)
    : points_(std::move(points)), triangles_(std::move(triangles)), first_(points_.size() + 1, 0)
  {
    // each vertex's triangles, one array for all (first_[v] to first_[v + 1])
    for(const auto& t : triangles_)
      for(std::size_t v : t) ++first_[v + 1];
    for(std::size_t v = 0; v < points_.size(); ++v) first_[v + 1] += first_[v];
    around_.resize(first_.back());
    std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
    for(std::size_t t = 0; t < triangles_.size(); ++t)
      for(std::size_t v : triangles_[t]) around_[next[v]++] = t;
    // the grid of the vertices of a triangle (a vertex on none is no point of the surface)
    std::vector<Point_3> corners;
    for(std::size_t v = 0; v < points_.size(); ++v)
      if(first_[v + 1] > first_[v]) {
        vertex_of_.push_back(v);
        corners.push_back(points_[v]);
      }
    vertices_.emplace(corners, cell, tag);
  }

  /// the squared distance from `p` to the triangles around the vertex nearest to it, at least the
  /// squared distance to the mesh (infinity when the cells searched hold no vertex); a search that
  /// meets a vertex or a triangle at a squared distance of `enough` or less stops there and returns
  /// it (that vertex need not be the nearest)
  double squared_distance_bound(const Point_3& p, double enough = -1) const
  {
    const auto [place, d2] = vertices_->nearest(p, enough);
    if(place == std::size_t(-1) || d2 <= enough) return d2;
    const std::size_t v = vertex_of_[place];
    double best = d2;
    for(std::size_t k = first_[v]; k < first_[v + 1] && best > enough; ++k) {
      const std::array<std::size_t, 3>& t = triangles_[around_[k]];
      best = (std::min)(best, CGAL::to_double(CGAL::squared_distance(p, Triangle_3(points_[t[0]], points_[t[1]], points_[t[2]]))));
    }
    return best;
  }

private:
  std::vector<Point_3> points_;
  std::vector<std::array<std::size_t, 3>> triangles_;
  std::vector<std::size_t> first_, around_;
  std::vector<std::size_t> vertex_of_;   // (the vertex of each place of the grid)
  std::optional<Poisson_remesh::internal::Near_points<Point_3>> vertices_;
};

} // namespace internal
} // namespace Postprocessing
} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_INTERNAL_NEAR_SURFACE_H
