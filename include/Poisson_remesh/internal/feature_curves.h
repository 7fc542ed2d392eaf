// Poisson_remesh/internal/feature_curves.h
//
// The input's feature curves as segments in an AABB tree: the closest point on them. The
// relaxation slides feature vertices along them, and the remesher tells an output edge that
// follows a curve from one that cuts across with them.

#ifndef POISSON_REMESH_INTERNAL_FEATURE_CURVES_H
#define POISSON_REMESH_INTERNAL_FEATURE_CURVES_H

#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/internal/closest_point.h>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>

#include <vector>

namespace Poisson_remesh {
namespace internal {

template <class K>
class Feature_curves
{
  typedef typename K::Point_3 Point_3;
  typedef typename K::Segment_3 Segment_3;
  typedef typename std::vector<Segment_3>::const_iterator Iterator;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_segment_primitive<K, Iterator>>> Tree;

public:
  // the feature edges of `features` on `tm`, read through its own point map
  template <class TriangleMesh>
  Feature_curves(const TriangleMesh& tm, const Feature_set<TriangleMesh>& features)
  {
    const auto vpm = get(CGAL::vertex_point, tm);
    for(auto e : edges(tm))
      if(features.is_feature(e)) segments_.emplace_back(get(vpm, source(halfedge(e, tm), tm)), get(vpm, target(halfedge(e, tm), tm)));
    if(segments_.empty()) return;
    tree_.insert(segments_.begin(), segments_.end());
    tree_.do_not_accelerate_distance_queries();   // (internal/closest_point.h needs no k-d tree)
    tree_.build();
  }
  Feature_curves(const Feature_curves&) = delete;   // (the tree points into segments_)
  Feature_curves& operator=(const Feature_curves&) = delete;

  bool empty() const { return segments_.empty(); }
  // (not empty)
  Point_3 closest_point(const Point_3& p) const { return internal::closest_point(tree_, p); }
  Point_3 closest_point(const Point_3& p, const Point_3& hint) const { return internal::closest_point(tree_, p, hint); }

private:
  std::vector<Segment_3> segments_;
  Tree tree_;
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_FEATURE_CURVES_H
