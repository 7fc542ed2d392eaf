// Poisson_remesh/internal/closest_point.h
//
// The point of a CGAL AABB tree's primitives closest to a query point, found with the nearer
// child box visited first and the box distances compared in double precision; and the primitives
// whose boxes meet a box.
//
// Why not AABB_tree::closest_point: it visits a node's children left one first, whatever their
// distance, and decides each box with the kernel's filtered predicate of a ball against a box. The relaxation
// asks for millions of projections (each Lloyd target, each angle-search trial, each fidelity
// query); with the nearer child first, the first leaf reached is usually the closest, every other
// box is pruned against a tight bound, and a box test is six comparisons. Which candidate is the
// closer is still decided by the tree's own traits (CGAL's Closest_point functor, exact
// predicates), so the closest point is CGAL's; only the boxes' pruning is in double precision,
// with a relative slack of 1e-12 so that rounding never prunes a box the exact test would visit;
// a leaf's triangle or segment whose distance in double is surely beyond the best so far is passed
// over before that functor (it would keep the best point).
// Without a hint the search needs no k-d tree: it starts from a point farther than the whole tree.
// (With a kernel whose coordinates are not doubles, the boxes are pruned with the coordinates
// rounded to double: a box may then be passed over for a point closer by that rounding alone.)

#ifndef POISSON_REMESH_INTERNAL_CLOSEST_POINT_H
#define POISSON_REMESH_INTERNAL_CLOSEST_POINT_H

#include <CGAL/AABB_tree/internal/Primitive_helper.h>
#include <CGAL/Bbox_3.h>
#include <CGAL/assertions.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
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
    if(farther_than_bound(primitive)) return;
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
  // True when the primitive, a triangle or a segment, is surely farther than bound(): CGAL's
  // functor, which would then keep the best point, is not called (the leaves of the tree come in
  // pairs, both primitives tested; where the input's triangles are long and thin, a query reaches
  // many leaves, most of them farther; the functor's projection and exact comparison cost several
  // times this test). The squared distance in double has an error of a few ulps of the squared
  // lengths it is made of (each difference below is one rounding; a triangle's face is measured
  // only where that holds, see below): a slack of 1e-10 of their sum covers it. The best point so
  // far is CGAL's construction, rounded to the coordinates' ulps: its distance may be short of the
  // exact one by about twice the distance times those ulps, which a second slack covers (a tie
  // with it still goes to CGAL's exact comparison). A degenerate triangle or segment may give no
  // finite answer: it is not filtered, nor other primitives.
  bool farther_than_bound(const Primitive& primitive) const
  {
    typedef typename Traits::Geom_traits::Triangle_3 Triangle_3;
    typedef typename Traits::Geom_traits::Segment_3 Segment_3;
    typedef std::decay_t<decltype(CGAL::internal::Primitive_helper<Traits>::get_datum(primitive, traits_))> Datum;
    constexpr bool triangle = std::is_same<Datum, Triangle_3>::value, segment = std::is_same<Datum, Segment_3>::value;
    if constexpr(!triangle && !segment) return false;
    else {
      const auto& t = CGAL::internal::Primitive_helper<Traits>::get_datum(primitive, traits_);
      constexpr int n = triangle ? 3 : 2;
      double v[n][3];
      double magnitude = (std::max)({std::abs(q_[0]), std::abs(q_[1]), std::abs(q_[2])});
      for(int i = 0; i < n; ++i)
        for(int k = 0; k < 3; ++k) {
          v[i][k] = CGAL::to_double(t.vertex(i)[k]);
          magnitude = (std::max)(magnitude, std::abs(v[i][k]));
        }
      double scale = 0;
      double d2;
      if constexpr(triangle) d2 = triangle_squared_distance(v[0], v[1], v[2], scale);
      else d2 = segment_squared_distance(v[0], v[1], scale);
      if(!std::isfinite(d2)) return false;
      const double ulps = 64 * std::numeric_limits<double>::epsilon() * magnitude;
      return d2 - 1e-10 * scale - 2 * ulps * std::sqrt(d2) - ulps * ulps > bound();
    }
  }
  static double dot(const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }
  // the squared length of x - s y - t z
  static double residual(const double* x, double s, const double* y, double t, const double* z)
  {
    double r2 = 0;
    for(int k = 0; k < 3; ++k) { const double r = x[k] - s * y[k] - t * z[k]; r2 += r * r; }
    return r2;
  }
  // The squared distance from the query to the segment ab; `scale` as below.
  double segment_squared_distance(const double* a, const double* b, double& scale) const
  {
    double ab[3], ap[3], bp[3];
    for(int k = 0; k < 3; ++k) { ab[k] = b[k] - a[k]; ap[k] = q_[k] - a[k]; bp[k] = q_[k] - b[k]; }
    const double l2 = dot(ab, ab), d = dot(ab, ap);
    scale = l2 + dot(ap, ap) + dot(bp, bp);
    const double t = d <= 0 ? 0 : d >= l2 ? 1 : d / l2;
    return residual(ap, t, ab, 0, ab);
  }
  // The squared distance from the query to the triangle abc (the region of its closest point found
  // from the signs of dot products, as in Ericson's "Real-Time Collision Detection", 5.1.5);
  // `scale`, the sum of the squared lengths the result is computed from.
  double triangle_squared_distance(const double* a, const double* b, const double* c, double& scale) const
  {
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for(int k = 0; k < 3; ++k) {
      ab[k] = b[k] - a[k]; ac[k] = c[k] - a[k];
      ap[k] = q_[k] - a[k]; bp[k] = q_[k] - b[k]; cp[k] = q_[k] - c[k];
    }
    const double sides = dot(ab, ab) + dot(ac, ac), ap2 = dot(ap, ap), bp2 = dot(bp, bp), cp2 = dot(cp, cp);
    scale = sides + ap2 + bp2 + cp2;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if(d1 <= 0 && d2 <= 0) return ap2;   // vertex a
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if(d3 >= 0 && d4 <= d3) return bp2;   // vertex b
    const double vc = d1 * d4 - d3 * d2;
    if(vc <= 0 && d1 >= 0 && d3 <= 0) return residual(ap, d1 / (d1 - d3), ab, 0, ac);   // edge ab
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if(d6 >= 0 && d5 <= d6) return cp2;   // vertex c
    const double vb = d5 * d2 - d1 * d6;
    if(vb <= 0 && d2 >= 0 && d6 <= 0) return residual(ap, 0, ab, d2 / (d2 - d6), ac);   // edge ac
    const double va = d3 * d6 - d5 * d4;
    if(va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {   // edge bc
      const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      double bc[3];
      for(int k = 0; k < 3; ++k) bc[k] = c[k] - b[k];
      return residual(bp, w, bc, 0, ac);
    }
    // the face. va + vb + vc is the squared norm of ab x ac; each of them is a difference of
    // products of dot products, rounded to ulps of (|ab|^2 + |ac|^2)(|ap|^2 + |bp|^2 + |cp|^2):
    // where the sum is not well above that (a needle of a triangle, or a query far from a small
    // one), v and w are not known well enough, and the distance to the triangle's box, a lower
    // bound, is taken instead
    const double sum = va + vb + vc;
    if(!(sum > 1e-4 * sides * (ap2 + bp2 + cp2)))
      return box_distance(CGAL::Bbox_3((std::min)({a[0], b[0], c[0]}), (std::min)({a[1], b[1], c[1]}), (std::min)({a[2], b[2], c[2]}),
                                       (std::max)({a[0], b[0], c[0]}), (std::max)({a[1], b[1], c[1]}), (std::max)({a[2], b[2], c[2]})));
    return residual(ap, vb / sum, ab, vc / sum, ac);
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

// the traversal traits of AABB_tree::traversal that collect the primitives whose boxes (of their
// points as they are now) meet a box: the tree's nodes are pruned by their boxes of its build
template <class Tree, class OutputIterator>
class Meeting_box
{
public:
  Meeting_box(const typename Tree::AABB_traits& traits, const CGAL::Bbox_3& box, OutputIterator out) : traits_(traits), box_(box), out_(out) {}
  bool go_further() const { return true; }
  template <class Query>
  void intersection(const Query&, const typename Tree::Primitive& primitive)
  {
    if(CGAL::do_overlap(CGAL::internal::Primitive_helper<typename Tree::AABB_traits>::get_datum(primitive, traits_).bbox(), box_))
      *out_++ = primitive.id();
  }
  template <class Query, class Node>
  bool do_intersect(const Query&, const Node& node) const { return CGAL::do_overlap(node.bbox(), box_); }

private:
  const typename Tree::AABB_traits& traits_;
  CGAL::Bbox_3 box_;
  OutputIterator out_;
};

} // namespace closest_point_detail

/// The ids of `tree`'s primitives whose boxes meet `box` (the primitives as they are now; a
/// primitive moved out of its box of the tree's build may be missed)
template <class Tree, class OutputIterator>
void primitives_meeting_box(const Tree& tree, const CGAL::Bbox_3& box, OutputIterator out)
{
  if(tree.empty()) return;
  closest_point_detail::Meeting_box<Tree, OutputIterator> search(tree.traits(), box, out);
  tree.traversal(box, search);
}

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
