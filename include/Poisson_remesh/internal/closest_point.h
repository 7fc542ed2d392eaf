// Poisson_remesh/internal/closest_point.h
//
// The point of a CGAL AABB tree's primitives closest to a query point, found with the nearer
// child box visited first and the box distances compared in double precision.
//
// Why not AABB_tree::closest_point: it visits a node's children left one first, whatever their
// distance, and decides each box with the kernel's filtered sphere-box predicate. The relaxation
// asks for millions of projections (each Lloyd target, each angle-search trial, each fidelity
// query); with the nearer child first, the first leaf reached is usually the closest, every other
// box is pruned against a tight bound, and a box test is six comparisons. Which candidate is the
// closer is still decided by the tree's own traits (CGAL's Closest_point functor, exact
// predicates), so the closest point is CGAL's; only the boxes' pruning is in double precision,
// with a relative slack of 1e-12 so that rounding never prunes a box the exact test would visit.
// Without a hint the search needs no k-d tree: it starts from a point farther than the whole tree.
// (With a kernel whose coordinates are not doubles, the boxes are pruned with the coordinates
// rounded to double: a box may then be passed over for a point closer by that rounding alone.)

#ifndef POISSON_REMESH_INTERNAL_CLOSEST_POINT_H
#define POISSON_REMESH_INTERNAL_CLOSEST_POINT_H

#include <CGAL/Bbox_3.h>
#include <CGAL/assertions.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace Poisson_remesh {
namespace internal {

namespace closest_point_detail {

// the traversal traits of AABB_tree::traversal_with_priority: the best point so far, and each
// box's squared distance to the query as its priority (nearer first)
template <class Tree>
class Nearest_first
{
  typedef typename Tree::AABB_traits Traits;
  typedef typename Tree::Point Point;
  typedef typename Tree::Primitive Primitive;
  typedef typename Tree::Primitive_id Primitive_id;

public:
  typedef double Priority;   // (higher first: minus the squared distance)

  Nearest_first(const Traits& traits, const Point& query, const Point& start)
    : traits_(traits), q_{CGAL::to_double(query.x()), CGAL::to_double(query.y()), CGAL::to_double(query.z())}, best_(start)
  {
    best_d2_ = squared_distance_to(best_);
  }

  bool go_further() const { return true; }

  void intersection(const Point& query, const Primitive& primitive)
  {
    const Point c = traits_.closest_point_object()(query, primitive, best_);
    if(!traits_.equal_3_object()(c, best_)) {
      best_ = c;
      id_ = primitive.id();
      best_d2_ = squared_distance_to(best_);
    }
  }

  template <class Node>
  bool do_intersect(const Point&, const Node& node) const { return box_distance(node.bbox()) <= bound(); }

  template <class Node>
  std::pair<bool, Priority> do_intersect_with_priority(const Point&, const Node& node) const
  {
    const double d2 = box_distance(node.bbox());
    return {d2 <= bound(), -d2};
  }

  const Point& point() const { return best_; }
  // (the primitive of point(), when the start point was not the closest)
  const Primitive_id& id() const { return id_; }

private:
  // (the absolute term: a squared distance in the subnormal range, where the relative slack adds nothing)
  double bound() const { return best_d2_ * (1 + 1e-12) + (std::numeric_limits<double>::min)(); }
  double squared_distance_to(const Point& p) const
  {
    const double x = CGAL::to_double(p.x()) - q_[0], y = CGAL::to_double(p.y()) - q_[1], z = CGAL::to_double(p.z()) - q_[2];
    return x * x + y * y + z * z;
  }
  double box_distance(const CGAL::Bbox_3& b) const
  {
    double d2 = 0;
    for(int i = 0; i < 3; ++i) {
      if(q_[i] < b.min(i)) d2 += (b.min(i) - q_[i]) * (b.min(i) - q_[i]);
      else if(q_[i] > b.max(i)) d2 += (q_[i] - b.max(i)) * (q_[i] - b.max(i));
    }
    return d2;
  }

  const Traits& traits_;
  double q_[3];
  Point best_;
  double best_d2_;
  Primitive_id id_{};
};

// a point farther from `query` than every point of the tree's box (those are within
// sqrt(3) max(dx, dy, dz) of it; no square, which could overflow)
template <class Tree>
typename Tree::Point beyond_the_tree(const Tree& tree, const typename Tree::Point& query)
{
  const CGAL::Bbox_3 b = tree.bbox();
  const double x = CGAL::to_double(query.x()), y = CGAL::to_double(query.y()), z = CGAL::to_double(query.z());
  const double d = (std::max)({std::abs(x - b.xmin()), std::abs(x - b.xmax()), std::abs(y - b.ymin()), std::abs(y - b.ymax()),
                               std::abs(z - b.zmin()), std::abs(z - b.zmax())});
  return typename Tree::Point(x + 4 * d + 1, y, z);
}

} // namespace closest_point_detail

/// The point of `tree`'s primitives closest to `query`; `hint`, a point on them (the search's
/// first bound). `tree` is not empty.
template <class Tree>
typename Tree::Point closest_point(const Tree& tree, const typename Tree::Point& query, const typename Tree::Point& hint)
{
  closest_point_detail::Nearest_first<Tree> search(tree.traits(), query, hint);
  tree.traversal_with_priority(query, search);
  return search.point();
}

/// The closest point of `tree`'s primitives to `query`, and its primitive. `tree` is not empty;
/// `query`'s coordinates are finite.
template <class Tree>
typename Tree::Point_and_primitive_id closest_point_and_primitive(const Tree& tree, const typename Tree::Point& query)
{
  CGAL_precondition(std::isfinite(CGAL::to_double(query.x())) && std::isfinite(CGAL::to_double(query.y())) &&
                    std::isfinite(CGAL::to_double(query.z())));
  closest_point_detail::Nearest_first<Tree> search(tree.traits(), query, closest_point_detail::beyond_the_tree(tree, query));
  tree.traversal_with_priority(query, search);
  return {search.point(), search.id()};
}

/// The closest point of `tree`'s primitives to `query`. `tree` is not empty.
template <class Tree>
typename Tree::Point closest_point(const Tree& tree, const typename Tree::Point& query)
{
  return closest_point_and_primitive(tree, query).first;
}

/// The squared distance from `query` to `tree`'s primitives. `tree` is not empty.
template <class Tree>
double squared_distance_to(const Tree& tree, const typename Tree::Point& query)
{
  return CGAL::to_double(CGAL::squared_distance(query, closest_point(tree, query)));
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_CLOSEST_POINT_H
