// Poisson_remesh/internal/memory_free_order.h
//
// A strict order of a mesh's vertices, edges and faces that does not depend on where they lie in
// memory, for the steps that visit elements in a sorted order (each change there depends on those
// before it). A Surface_mesh's descriptors are indices: they are compared as they are, and its
// results do not change. Other meshes' descriptors (a Polyhedron_3's) are addresses, which
// address-space randomization moves from run to run: sorted by them, the output would change
// between runs of the same input and settings. Their vertices are compared by their points, lexicographically (by
// address only where two points coincide), their edges and faces by their vertices in that order.

#ifndef POISSON_REMESH_INTERNAL_MEMORY_FREE_ORDER_H
#define POISSON_REMESH_INTERNAL_MEMORY_FREE_ORDER_H

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

#include <algorithm>
#include <array>
#include <type_traits>
#include <utility>

namespace Poisson_remesh {
namespace internal {

template <class Mesh> struct Has_index_descriptors : std::false_type {};
template <class P> struct Has_index_descriptors<CGAL::Surface_mesh<P>> : std::true_type {};

template <class Mesh, class VPM = typename boost::property_map<Mesh, CGAL::vertex_point_t>::const_type>
class Memory_free_order
{
  typedef boost::graph_traits<Mesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::edge_descriptor edge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  static constexpr bool indices = Has_index_descriptors<Mesh>::value;

public:
  explicit Memory_free_order(const Mesh& m) : m_(m), vpm_(get(CGAL::vertex_point, m)) {}
  Memory_free_order(const Mesh& m, VPM vpm) : m_(m), vpm_(vpm) {}

  bool operator()(vertex_descriptor a, vertex_descriptor b) const
  {
    if constexpr(indices) {
      return a < b;
    } else {
      const auto &p = get(vpm_, a), &q = get(vpm_, b);
      if(p < q) return true;
      if(q < p) return false;
      return a < b;
    }
  }
  bool operator()(edge_descriptor a, edge_descriptor b) const { return by_vertices(a, b); }
  bool operator()(face_descriptor a, face_descriptor b) const { return by_vertices(a, b); }
  template <class T>
  bool operator()(const std::pair<T, T>& a, const std::pair<T, T>& b) const
  {
    if((*this)(a.first, b.first)) return true;
    if((*this)(b.first, a.first)) return false;
    return (*this)(a.second, b.second);
  }

private:
  // an edge or a face, by its vertices in the order above
  template <class D>
  bool by_vertices(D a, D b) const
  {
    if constexpr(indices) {
      return a < b;
    } else {
      const auto ka = vertices_of(a), kb = vertices_of(b);
      return std::lexicographical_compare(ka.begin(), ka.end(), kb.begin(), kb.end(), *this);
    }
  }
  std::array<vertex_descriptor, 2> vertices_of(edge_descriptor e) const
  {
    std::array<vertex_descriptor, 2> k = {{source(halfedge(e, m_), m_), target(halfedge(e, m_), m_)}};
    if((*this)(k[1], k[0])) std::swap(k[0], k[1]);
    return k;
  }
  std::array<vertex_descriptor, 3> vertices_of(face_descriptor f) const
  {
    std::array<vertex_descriptor, 3> k;
    int i = 0;
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, m_), m_)) {
      if(i == 3) break;   // (the order is for triangles; a larger face is keyed by three of its corners)
      k[i++] = v;
    }
    std::sort(k.begin(), k.begin() + i, *this);
    for(; i < 3; ++i) k[i] = k[0];
    return k;
  }
  const Mesh& m_;
  VPM vpm_;
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_MEMORY_FREE_ORDER_H
