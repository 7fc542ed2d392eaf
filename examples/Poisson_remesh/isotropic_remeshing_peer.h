// isotropic_remeshing_peer.h -- the benchmark contender: CGAL's isotropic_remeshing at a target vertex count (not part of the library: used by the programs and the benchmark)
//
// The peer every benchmark row is set beside: CGAL's
// Polygon_mesh_processing::isotropic_remeshing(), driven to a target vertex count the way a
// user would drive it -- target edge length from the count (sizing.h), sharp edges over an angle
// as constraints (detect_sharp_edges), a fixed number of iterations -- and calibrated: the edge
// length is rescaled by sqrt(V / target) and the remesh redone (up to `calibration_runs` runs),
// because CGAL's edge-length target does not fix the vertex count. The run whose vertex count is
// closest to the target is kept, and its own time is reported.

#ifndef POISSON_REMESH_PEERS_ISOTROPIC_REMESHING_PEER_H
#define POISSON_REMESH_PEERS_ISOTROPIC_REMESHING_PEER_H

#include <Poisson_remesh/sizing.h>

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iterator>

namespace Poisson_remesh {
namespace Peers {

/// How isotropic_remeshing_at_vertex_count() drives CGAL's `isotropic_remeshing()`.
struct Isotropic_remeshing_settings
{
  double target_vertex_count = 0;   ///< 0: the input's vertex count
  double sharp_angle = 60;          ///< dihedral angle (degrees) over which edges are constrained; <= 0: none
  unsigned int iterations = 5;      ///< `number_of_iterations` of each `isotropic_remeshing()` call
  unsigned int calibration_runs = 3; ///< runs at most, the edge length rescaled by sqrt(V / target) after each
};

/// What isotropic_remeshing_at_vertex_count() did.
struct Isotropic_remeshing_result
{
  double edge_length = 0;   ///< the target edge length of the kept run
  double seconds = 0;       ///< time of the kept run (one isotropic_remeshing call, feature detection included)
  unsigned int runs = 0;    ///< `isotropic_remeshing()` calls made (calibration included)
};

/// Remeshes a copy of `input` into `output` (both triangle meshes of type Mesh).
template <class Mesh>
Isotropic_remeshing_result isotropic_remeshing_at_vertex_count(const Mesh& input, Mesh& output,
                                                               const Isotropic_remeshing_settings& s = {})
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef typename boost::graph_traits<Mesh>::edge_descriptor edge_descriptor;
  const double target = s.target_vertex_count > 0 ? s.target_vertex_count : double(num_vertices(input));
  const double area = CGAL::to_double(PMP::area(input));
  double L = edge_length_from_vertex_count(area, target);

  Isotropic_remeshing_result best;
  double best_error = -1;
  const unsigned int runs = s.calibration_runs ? s.calibration_runs : 1;
  for(unsigned int run = 0; run < runs; ++run) {
    Mesh m;
    CGAL::copy_face_graph(input, m);
    auto start = std::chrono::steady_clock::now();
    auto ecm = get(CGAL::dynamic_edge_property_t<bool>(), m);
    for(edge_descriptor e : edges(m)) put(ecm, e, false);
    if(s.sharp_angle > 0) PMP::detect_sharp_edges(m, s.sharp_angle, ecm);
    PMP::isotropic_remeshing(faces(m), L, m,
                             CGAL::parameters::number_of_iterations(s.iterations).edge_is_constrained_map(ecm));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // vertices(m), not num_vertices(m): a Surface_mesh counts its removed vertices in the latter
    const double V = double(std::distance(vertices(m).begin(), vertices(m).end()));
    const double error = std::abs(V - target);
    if(best_error < 0 || error < best_error) {
      best_error = error;
      best.edge_length = L;
      best.seconds = seconds;
      clear(output);
      CGAL::copy_face_graph(m, output);
    }
    ++best.runs;
    if(error <= 0.01 * target) break;
    L *= std::sqrt(V / target);
  }
  return best;
}

} // namespace Peers
} // namespace Poisson_remesh

#endif // POISSON_REMESH_PEERS_ISOTROPIC_REMESHING_PEER_H
