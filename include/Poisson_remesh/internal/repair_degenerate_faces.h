// Poisson_remesh/internal/repair_degenerate_faces.h
//
// Zero-area faces removed from a mesh, for the reader and the remesher alike: CGAL's
// remove_degenerate_faces(), then the vertices a removed face left where two fans touch split
// into one vertex per fan (duplicate_non_manifold_vertices: every face kept, the surface a
// manifold again).

#ifndef POISSON_REMESH_INTERNAL_REPAIR_DEGENERATE_FACES_H
#define POISSON_REMESH_INTERNAL_REPAIR_DEGENERATE_FACES_H

#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/boost/graph/helpers.h>

#include <cstddef>

namespace Poisson_remesh {
namespace internal {

// the zero-area faces of tm, and the index (in the order of faces(tm)) of the first
template <class TriangleMesh, class VPM>
std::size_t count_degenerate_faces(const TriangleMesh& tm, VPM vpm, std::size_t* first = nullptr)
{
  std::size_t count = 0, index = 0;
  for(auto f : faces(tm)) {
    if(CGAL::Polygon_mesh_processing::is_degenerate_triangle_face(f, tm, CGAL::parameters::vertex_point_map(vpm)))
      if(count++ == 0 && first != nullptr) *first = index;
    ++index;
  }
  return count;
}

struct Degenerate_face_repair
{
  bool complete = false;            // no zero-area face left, the mesh valid and not empty
  std::size_t split_vertices = 0;   // vertices split after the removal
};

// removes the zero-area faces of tm; when that leaves a valid mesh, splits the pinched vertices
template <class TriangleMesh, class VPM>
Degenerate_face_repair remove_degenerate_faces(TriangleMesh& tm, VPM vpm)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  Degenerate_face_repair r;
  PMP::remove_degenerate_faces(tm, CGAL::parameters::vertex_point_map(vpm));
  if(count_degenerate_faces(tm, vpm) > 0 || CGAL::is_empty(tm) || !CGAL::is_valid_polygon_mesh(tm)) return r;
  r.complete = true;
  r.split_vertices = PMP::duplicate_non_manifold_vertices(tm, CGAL::parameters::vertex_point_map(vpm));
  return r;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_REPAIR_DEGENERATE_FACES_H
