// Copyright (c) 2026 Poisson_remesh contributors.
//
// Approximate_geodesic_oracle
// ===========================
//
// A cheap geodesic distance oracle with the queries of the concept `GeodesicOracle`
// (see doc/Poisson_remesh/Concepts/GeodesicOracle.h): distances and iso-lines
// in place of the exact window propagation of Section 4.2.2 (the paper's
// conclusion suggests approximating the geodesic isolines to save time). Its
// iso-curves are straight segments, which the sampler's circular available
// boundary does not take: it does not drive the sampler.
//
// Method: truncated Dijkstra on the vertices, where the relaxation of a face
// (A, B, C) uses the one-face unfolding update of fast marching methods
// (Kimmel & Sethian 1998; also the "vertex update" of Surazhsky et al. 2005
// Section 4): a virtual source S is placed in the plane of the face at
// distances d(A), d(B) from A and B; if the segment S-C crosses the edge AB,
// d(C) <= |S C|, otherwise d(C) <= min(d(A) + |AC|, d(B) + |BC|).  Every
// value is finally clamped from below by the 3D Euclidean distance to the
// source, which is a lower bound of the geodesic distance.
//
// Accuracy: exact on planar regions (up to the propagation order of the
// Dijkstra front) and first-order in the edge length elsewhere (the error
// against the exact distance stays within 5% of the distance plus one mean
// edge length, which test_geodesic.cpp checks); values are never below the
// Euclidean distance.  Iso-curves are the level sets of the linear
// interpolation of the vertex distances: straight segments (`is_segment`).
//
// Face-local 2D frame and Face_location barycentric conventions are the ones
// of Exact_geodesic_oracle.h.
//
// Complexity: O(V_R log V_R) per propagation, V_R being the number of
// vertices at distance <= R (plus their neighbors); storage is allocated once.

#ifndef POISSON_REMESH_GEODESIC_APPROXIMATE_GEODESIC_ORACLE_H
#define POISSON_REMESH_GEODESIC_APPROXIMATE_GEODESIC_ORACLE_H

#include <Poisson_remesh/Geodesic/Exact_geodesic_oracle.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace Poisson_remesh {

/// Approximate geodesic distances, truncated at a radius: a Dijkstra propagation on the vertices
/// with the one-face unfolding update of fast marching, never below the Euclidean distance (first
/// order in the edge length: within 5% of the distance plus one edge length). A model of the concept
/// `GeodesicOracle`, with the interface of `Exact_geodesic_oracle` at a lower cost; its
/// iso-curves are straight segments (`Iso_arc::is_segment`).
template <class TriangleMesh,
          class VertexPointMap = typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type,
          class GeomTraits = typename CGAL::Kernel_traits<
              typename boost::property_traits<VertexPointMap>::value_type>::Kernel>
class Approximate_geodesic_oracle
{
public:
  /// `boost::graph_traits<TriangleMesh>`
  typedef boost::graph_traits<TriangleMesh> GT;
  /// the mesh's vertex descriptor
  typedef typename GT::vertex_descriptor vertex_descriptor;
  /// the mesh's face descriptor
  typedef typename GT::face_descriptor face_descriptor;
  /// the kernel
  typedef GeomTraits Geom_traits;
  /// the point type
  typedef typename GeomTraits::Point_3 Point_3;
  /// a surface point: a face and barycentric coordinates
  typedef CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> Face_location;
  /// a straight piece of an iso-distance curve inside one face
  typedef Poisson_remesh::Iso_arc<face_descriptor, Point_3> Iso_arc;
  /// an ordered chain of `Iso_arc`s
  typedef Poisson_remesh::Iso_curve<face_descriptor, Point_3> Iso_curve;

private:
  typedef internal::Indexed_triangle_mesh<TriangleMesh, VertexPointMap> Mesh;
  typedef internal::Vec2 Vec2;
  struct Entry
  {
    double key;
    int v;
    bool operator<(const Entry& o) const { return key > o.key; }
  };

public:
  /// Precomputes the per-mesh data of `tm` (which must outlive the oracle and stay unchanged).
  explicit Approximate_geodesic_oracle(const TriangleMesh& tm)
    : Approximate_geodesic_oracle(tm, get(CGAL::vertex_point, tm))
  {}
  /// The same with the points of `vpm`.
  Approximate_geodesic_oracle(const TriangleMesh& tm, VertexPointMap vpm) : m_tm(tm), m(tm, vpm)
  {
    m_dist.assign(m.number_of_vertices(), internal::kInf);
    m_final.assign(m.number_of_vertices(), 0);
  }

  /// the mesh
  const TriangleMesh& mesh() const { return m_tm; }
  /// diagonal of the bounding box of the mesh
  double bbox_diagonal() const { return m.diag; }
  /// radius of the last propagation
  double radius() const { return m_radius; }

  /// Truncated approximate propagation: vertices up to distance `radius`
  /// (and their neighbors, as upper bounds) get a distance.
  void propagate(const Face_location& source, double radius)
  {
    reset();
    m_radius = radius;
    m_source_face = int(get(m.fim, source.first));
    std::array<double, 3> b = source.second;
    internal::snap_barycentric(b);
    m_source_bary = b;
    m_source_3 = m.point_3(m_source_face, b);
    const Vec2 q = m.bary_to_2(m_source_face, b);
    for(int i = 0; i < 3; ++i)
      relax(m.fv[3 * m_source_face + i], internal::norm(q - m.corner_2(m_source_face, i)));
    // a source on an edge or a vertex also sees the other incident faces directly
    for(int i = 0; i < 3; ++i)
      if(b[i] == 1.) m_dist[m.fv[3 * m_source_face + i]] = 0.;
    run_dijkstra();
  }

  /// Approximate geodesic distance of vertex `v`, or nullopt if not reached within the radius.
  std::optional<double> distance(vertex_descriptor v) const
  {
    const double d = m_dist[get(m.vim, v)];
    if(d <= m_radius) return d;
    return std::nullopt;
  }

  /// Approximate geodesic distance of a surface point (from its face's vertices, by the same
  /// unfolding), or nullopt if farther than the radius.
  std::optional<double> distance(const Face_location& p) const
  {
    const int f = int(get(m.fim, p.first));
    std::array<double, 3> b = p.second;
    internal::snap_barycentric(b);
    const double d = point_distance(f, b);
    if(d <= m_radius) return d;
    return std::nullopt;
  }

  /// Outputs `std::pair<vertex_descriptor, double>` for every vertex at distance <= radius.
  template <class OutputIterator>
  OutputIterator reached_vertices(OutputIterator out) const
  {
    for(int v : m_touched)
      if(m_dist[v] <= m_radius) *out++ = std::make_pair(m.vertex_of[v], m_dist[v]);
    return out;
  }

  /// Level set R of the piecewise-linear interpolation of vertex distances.
  std::vector<Iso_curve> iso_curve(double R) const
  {
    std::vector<Iso_arc> arcs;
    std::vector<int> faces_to_visit;
    for(int v : m_touched)
      for(int i = m.vf_start[v]; i < m.vf_start[v + 1]; ++i) faces_to_visit.push_back(m.vf_list[i] / 3);
    std::sort(faces_to_visit.begin(), faces_to_visit.end());
    faces_to_visit.erase(std::unique(faces_to_visit.begin(), faces_to_visit.end()), faces_to_visit.end());
    for(int f : faces_to_visit) add_face_segment(f, R, arcs);
    return Exact_geodesic_oracle<TriangleMesh, VertexPointMap, GeomTraits>::chain_arcs_by_endpoints(
        arcs, [this](face_descriptor fd) { return int(get(m.fim, fd)); }, m);
  }

private:
  void reset()
  {
    for(int v : m_touched)
    {
      m_dist[v] = internal::kInf;
      m_final[v] = 0;
    }
    m_touched.clear();
    m_heap.clear();
  }

  double euclid(int v) const
  {
    const auto& p = m.pos[v];
    return std::sqrt((p[0] - m_source_3[0]) * (p[0] - m_source_3[0]) + (p[1] - m_source_3[1]) * (p[1] - m_source_3[1]) +
                     (p[2] - m_source_3[2]) * (p[2] - m_source_3[2]));
  }

  void relax(int v, double d)
  {
    if(m_final[v]) return;
    d = (std::max)(d, euclid(v));
    if(!(d < m_dist[v])) return;
    if(m_dist[v] == internal::kInf) m_touched.push_back(v);
    m_dist[v] = d;
    m_heap.push_back({d, v});
    std::push_heap(m_heap.begin(), m_heap.end());
  }

  /// One-face unfolding update: distance at the apex of slot s (edge k of face f)
  /// from the distances at the endpoints of edge k.
  double unfold_update(int s, double dA, double dB) const
  {
    const double L = m.edge_length(s);
    const Vec2 C = m.apex[s];
    const double best_edge = (std::min)(dA + internal::norm(C), dB + internal::norm(C - Vec2{L, 0.}));
    if(!(L > 0.)) return best_edge;
    // virtual source below the edge: |S| = dA, |S - (L,0)| = dB
    const double sx = (L * L + dA * dA - dB * dB) / (2. * L);
    const double h2 = dA * dA - sx * sx;
    if(h2 < 0.) return best_edge;
    const Vec2 S{sx, -std::sqrt(h2)};
    const double den = C.y - S.y;
    if(!(den > 0.)) return best_edge;
    const double x = S.x + (C.x - S.x) * (-S.y) / den;
    if(x < 0. || x > L) return best_edge;
    return (std::min)(best_edge, internal::norm(C - S));
  }

  void run_dijkstra()
  {
    while(!m_heap.empty())
    {
      std::pop_heap(m_heap.begin(), m_heap.end());
      const Entry e = m_heap.back();
      m_heap.pop_back();
      if(m_final[e.v] || e.key > m_dist[e.v]) continue;
      if(e.key > m_radius) break;
      m_final[e.v] = 1;
      const int v = e.v;
      for(int i = m.vf_start[v]; i < m.vf_start[v + 1]; ++i)
      {
        const int c = m.vf_list[i];
        const int f = c / 3, j = c % 3;
        const int a = m.fv[3 * f + (j + 1) % 3], b = m.fv[3 * f + (j + 2) % 3];
        relax(a, m_dist[v] + m.edge_length(c));
        relax(b, m_dist[v] + m.edge_length(3 * f + (j + 2) % 3));
        // edge (v,a) is slot c, apex b ; edge (b,v) is slot 3f+(j+2)%3, apex a
        if(m_dist[a] < internal::kInf) relax(b, unfold_update(c, m_dist[v], m_dist[a]));
        if(m_dist[b] < internal::kInf) relax(a, unfold_update(3 * f + (j + 2) % 3, m_dist[b], m_dist[v]));
      }
    }
  }

  double point_distance(int f, const std::array<double, 3>& b) const
  {
    const Vec2 q = m.bary_to_2(f, b);
    double best = internal::kInf;
    for(int i = 0; i < 3; ++i)
    {
      const double dv = m_dist[m.fv[3 * f + i]];
      if(dv < internal::kInf) best = (std::min)(best, dv + internal::norm(q - m.corner_2(f, i)));
    }
    // unfolded virtual source from the two endpoints of each edge
    for(int k = 0; k < 3; ++k)
    {
      const double dA = m_dist[m.fv[3 * f + k]], dB = m_dist[m.fv[3 * f + (k + 1) % 3]];
      const double L = m.edge_length(3 * f + k);
      if(!(dA < internal::kInf && dB < internal::kInf && L > 0.)) continue;
      const double sx = (L * L + dA * dA - dB * dB) / (2. * L);
      const double h2 = dA * dA - sx * sx;
      if(h2 < 0.) continue;
      const Vec2 S{sx, -std::sqrt(h2)};
      const Vec2 qk = m.to_edge_frame(f, k, q);
      const double den = qk.y - S.y;
      const double x = (den > 0.) ? S.x + (qk.x - S.x) * (-S.y) / den : qk.x;
      if(x >= 0. && x <= L) best = (std::min)(best, internal::norm(qk - S));
    }
    if(f == m_source_face) best = (std::min)(best, internal::norm(q - m.bary_to_2(f, m_source_bary)));
    const std::array<double, 3> p = m.point_3(f, b);
    const double e = std::sqrt((p[0] - m_source_3[0]) * (p[0] - m_source_3[0]) +
                               (p[1] - m_source_3[1]) * (p[1] - m_source_3[1]) +
                               (p[2] - m_source_3[2]) * (p[2] - m_source_3[2]));
    return (std::max)(best, e);
  }

  void add_face_segment(int f, double R, std::vector<Iso_arc>& arcs) const
  {
    double d[3];
    Vec2 P[3];
    for(int i = 0; i < 3; ++i)
    {
      d[i] = m_dist[m.fv[3 * f + i]];
      P[i] = m.corner_2(f, i);
      if(!(d[i] < internal::kInf)) return;
    }
    Vec2 pts[2];
    int n = 0;
    for(int k = 0; k < 3 && n < 2; ++k)
    {
      const double a = d[k], b = d[(k + 1) % 3];
      if((a < R) == (b < R)) continue;
      const double t = (R - a) / (b - a);
      pts[n++] = P[k] + t * (P[(k + 1) % 3] - P[k]);
    }
    if(n != 2) return;
    // gradient of the linear interpolation in the face frame
    const Vec2 e1 = P[1] - P[0], e2 = P[2] - P[0];
    const double det = internal::cross(e1, e2);
    if(det == 0.) return;
    const double g1 = d[1] - d[0], g2 = d[2] - d[0];
    const Vec2 grad{(g1 * e2.y - g2 * e1.y) / det, (g2 * e1.x - g1 * e2.x) / det};
    Vec2 dir = pts[1] - pts[0];
    // the region closer than R must be on the left: grad points to the right
    if(internal::cross(dir, grad) > 0.) std::swap(pts[0], pts[1]);
    Iso_arc arc;
    arc.face = m.face_of[f];
    arc.is_segment = true;
    arc.segment_start = {{pts[0].x, pts[0].y}};
    arc.segment_end = {{pts[1].x, pts[1].y}};
    arc.radius = 0.;
    for(int i = 0; i < 3; ++i)
    {
      const auto& q = m.pos[m.fv[3 * f + i]];
      arc.corners[i] = Point_3(q[0], q[1], q[2]);
    }
    arc.layout = {{m.flayout[3 * f], m.flayout[3 * f + 1], m.flayout[3 * f + 2]}};
    arcs.push_back(arc);
  }

  const TriangleMesh& m_tm;
  Mesh m;
  double m_radius = 0.;
  int m_source_face = 0;
  std::array<double, 3> m_source_bary{{1., 0., 0.}};
  std::array<double, 3> m_source_3{{0., 0., 0.}};
  std::vector<double> m_dist;
  std::vector<char> m_final;
  std::vector<int> m_touched;
  std::vector<Entry> m_heap;
};

}  // namespace Poisson_remesh

#endif  // POISSON_REMESH_GEODESIC_APPROXIMATE_GEODESIC_ORACLE_H
