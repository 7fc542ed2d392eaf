// Copyright (c) 2026 Poisson_remesh contributors.
//
// Exact_geodesic_oracle
// =====================
//
// Implements the geodesic machinery of "Direct Sampling on Surfaces for High
// Quality Remeshing", Section 4.2.2 (computing the geodesic equidistant curve
// of a sample, truncated window propagation) and Section 5.2 (window
// propagation stopped by a user predicate, used for the adaptive available
// boundary).  The geodesic computation itself is the exact "window
// propagation" algorithm of Mitchell, Mount and Papadimitriou as described and
// simplified by Surazhsky, Surazhsky, Kirsanov, Gortler and Hoppe, "Fast
// exact and approximate geodesics on meshes", SIGGRAPH 2005 (Section 3 of that
// paper: windows, pseudo-sources at saddle and boundary vertices, window
// trimming on edges, priority queue ordered by the window minimal distance).
//
// This class is a model of the concept `GeodesicOracle`
// (see doc/Poisson_remesh/Concepts/GeodesicOracle.h).
//
// Units: all distances are in the length unit of the input mesh coordinates.
//
// Face-local 2D frame convention (used by `Iso_arc`, Geodesic/Iso_arc.h):
//   Let h0 = halfedge(f), v0 = source(h0), v1 = target(h0),
//   v2 = target(next(h0)).  The face is laid out isometrically in the plane
//   with v0 = (0,0), v1 = (|v0v1|, 0) and v2 = (x2, y2) with y2 > 0, so the
//   face is counter-clockwise in its frame (consistent with the mesh
//   orientation).  The barycentric coordinates of a `Face_location` use the
//   same vertex order (this is also CGAL's PMP/locate convention).
//
// Complexity: let F be the number of faces inside the propagation disk.  For
// well-shaped meshes a propagation touches O(F) windows in practice (the
// theoretical worst case of the method is O(F^2 log F)).  All per-element
// storage is allocated once in the constructor (O(|V| + |F|)); a propagation
// only resets the elements it touched, so small truncated propagations cost
// time proportional to the disk size, not to the mesh size.
//
// Numerical tolerances: two window distance functions closer than
// 1e-13 x (bounding box diagonal) are considered equal when windows are
// trimmed (the existing window wins ties).  No window of positive width is
// ever dropped: even a very narrow window can fan out into a wide wedge when
// its (pseudo-)source is close to its edge, and dropping it would leave a
// crack in the distance field.  Vertices whose angle sum exceeds 2 pi + 1e-13
// are saddles (pseudo-sources): the shadow left behind a vertex with a smaller
// excess is narrower than the visibility tolerance (1e-10 x edge length) used
// when a face point is tested against a window.  Measured agreement with CGAL::Surface_mesh_shortest_path
// is ~1e-15 x diagonal on well-shaped meshes and ~3e-14 x diagonal on meshes
// with needle triangles.
//
// Thread safety: `propagate()` modifies the oracle; the const queries do not
// modify it and may run concurrently.  Use one oracle per thread to propagate
// in parallel (the mesh is only read).

#ifndef POISSON_REMESH_GEODESIC_EXACT_GEODESIC_ORACLE_H
#define POISSON_REMESH_GEODESIC_EXACT_GEODESIC_ORACLE_H

#include <Poisson_remesh/Geodesic/Iso_arc.h>
#include <Poisson_remesh/Geodesic/internal/Indexed_triangle_mesh.h>
#include <Poisson_remesh/Geodesic/internal/conic_geometry.h>
#include <Poisson_remesh/Geodesic/internal/window_geometry.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/locate.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace Poisson_remesh {

// ---------------------------------------------------------------------------
// The exact oracle
// ---------------------------------------------------------------------------

/// Exact polyhedral geodesic distances from a surface point, truncated at a radius (paper
/// §4.2.2), by window propagation (Mitchell, Mount and Papadimitriou, as simplified by Surazhsky et
/// al. 2005), and the iso-distance curves of the adaptive rule (§5.1-5.2). A model of the concepts
/// `GeodesicOracle` and `WindowPropagationGeodesicOracle`. The cost of a propagation follows the
/// size of the geodesic disk, not of the mesh; storage is allocated once.
///
/// `TriangleMesh`: a `FaceGraph` whose faces are triangles; `VertexPointMap`: its points (default:
/// the internal map); `GeomTraits`: the kernel of the points (default: from `CGAL::Kernel_traits`).
template <class TriangleMesh,
          class VertexPointMap = typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type,
          class GeomTraits = typename CGAL::Kernel_traits<
              typename boost::property_traits<VertexPointMap>::value_type>::Kernel>
class Exact_geodesic_oracle
{
public:
  /// `boost::graph_traits<TriangleMesh>`
  typedef boost::graph_traits<TriangleMesh> GT;
  /// the mesh's vertex descriptor
  typedef typename GT::vertex_descriptor vertex_descriptor;
  /// the mesh's face descriptor
  typedef typename GT::face_descriptor face_descriptor;
  /// the mesh's halfedge descriptor
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  /// the kernel
  typedef GeomTraits Geom_traits;
  /// the point type
  typedef typename GeomTraits::Point_3 Point_3;
  /// a surface point: a face and barycentric coordinates
  typedef CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> Face_location;
  /// a piece of an iso-distance curve inside one face
  typedef Poisson_remesh::Iso_arc<face_descriptor, Point_3> Iso_arc;
  /// an ordered chain of `Iso_arc`s
  typedef Poisson_remesh::Iso_curve<face_descriptor, Point_3> Iso_curve;

  /// Geometry of a window handed to stop predicates (Section 5.2 of the paper).
  /// Everything is expressed in the frame of `halfedge`: origin at
  /// `source(halfedge)`, x axis along the halfedge, y axis pointing into
  /// `face(halfedge)`, which is the face the window is about to enter.
  struct Window_geometry
  {
    halfedge_descriptor halfedge;  ///< the window lies on its edge and is about to enter its face
    std::array<double, 2> source;  ///< unfolded (pseudo-)source, y <= 0
    double sigma;                  ///< distance from the source to the pseudo-source
    /// window extent along the halfedge, 0 <= b0 <= b1 <= length
    /// @{
    double b0, b1;
    /// @}
    /// 3D endpoints of the window
    /// @{
    Point_3 p0, p1;
    /// @}
    /// the smallest and the largest distance on the window
    /// @{
    double min_distance, max_distance;
    /// @}
  };

private:
  typedef internal::Indexed_triangle_mesh<TriangleMesh, VertexPointMap> Mesh;
  typedef internal::Vec2 Vec2;

  struct Window
  {
    double b0, b1;  // extent on the edge, in the frame of `slot`
    double sx, sy;  // unfolded source in the frame of `slot`, sy <= 0
    double sigma;
    double key;     // key used in the queue
    int slot;       // 3*face + k: the window lies on edge k of `face` and propagates into `face`
    bool alive, propagated;
  };
  struct Queue_entry
  {
    double key;
    int id;  // >= 0: window, < 0: pseudo-source event of vertex -(id+1)
    bool operator<(const Queue_entry& o) const { return key > o.key; }  // min-heap
  };

public:
  /// Precomputes edge lengths, face layouts and saddle / border vertices.  O(|V| + |F|).
  explicit Exact_geodesic_oracle(const TriangleMesh& tm) : Exact_geodesic_oracle(tm, get(CGAL::vertex_point, tm)) {}

  /// The same with the points of `vpm`.
  Exact_geodesic_oracle(const TriangleMesh& tm, VertexPointMap vpm) : m_tm(tm), m_vpm(vpm), m(std::make_shared<const Mesh>(tm, vpm))
  {
    m_dist.assign(m->number_of_vertices(), internal::kInf);
    m_pseudo_done.assign(m->number_of_vertices(), internal::kInf);
    m_edge_windows.resize(m->num_edges);
    m_edge_touched.assign(m->num_edges, 0);
    m_tol = 1e-13 * m->diag;
  }

  /// the mesh (it must outlive the oracle and stay unchanged)
  const TriangleMesh& mesh() const { return m_tm; }
  /// diagonal of the bounding box of the mesh
  double bbox_diagonal() const { return m->diag; }
  /// radius of the last propagation (the `report_radius` of predicate-driven propagations)
  double radius() const { return m_radius; }

  // -------------------------------------------------------------------------
  // Propagation
  // -------------------------------------------------------------------------

  /// Exact propagation from `source`, truncated at `radius` (Section 4.2.2):
  /// windows whose minimal distance exceeds `radius` are not propagated.
  /// Afterwards every vertex / surface point at distance <= radius is reached.
  void propagate(const Face_location& source, double radius)
  {
    // a window farther than the radius (beyond the reporting tolerance) is not even stored: no
    // point it reaches is reported, and it could only trim other windows where they are farther too
    propagate_impl(source, [radius](const Window_geometry& w) { return w.min_distance > radius; }, radius,
                   radius * (1. + 1e-9) + m_tol);
  }

  /// Exact propagation stopped by a predicate (Section 5.2): `stop(w)` is called
  /// for every new window `w` (a `Window_geometry`) and returns true when the
  /// window must not be propagated further.  Distances returned afterwards are
  /// exact for points whose shortest path only crosses propagated windows;
  /// distances larger than `report_radius` are reported as unreached.
  template <class StopPredicate>
  void propagate(const Face_location& source, StopPredicate stop,
                 double report_radius = std::numeric_limits<double>::infinity())
  {
    propagate_impl(source, stop, report_radius);
  }

  // -------------------------------------------------------------------------
  // Queries
  // -------------------------------------------------------------------------

  /// Exact geodesic distance of vertex `v`, or nullopt if not reached within the radius.  O(1).
  std::optional<double> distance(vertex_descriptor v) const
  {
    const double d = m_dist[get(m->vim, v)];
    if(d <= m_radius) return d;
    return std::nullopt;
  }

  /// Exact geodesic distance of a surface point, or nullopt if farther than the radius.
  /// O(number of windows on the edges of the face).
  std::optional<double> distance(const Face_location& p) const
  {
    const int f = int(get(m->fim, p.first));
    std::array<double, 3> b = p.second;
    internal::snap_barycentric(b);
    const double d = point_distance(f, m->bary_to_2(f, b));
    // points of the iso-curve at the radius itself must be reported despite rounding
    if(d <= m_radius * (1. + 1e-9) + m_tol) return d;
    return std::nullopt;
  }

  /// Outputs `std::pair<vertex_descriptor, double>` for every vertex at distance
  /// <= radius (in no particular order).  O(number of reached vertices).
  template <class OutputIterator>
  OutputIterator reached_vertices(OutputIterator out) const
  {
    for(int v : m_touched_vertices)
      if(m_dist[v] <= m_radius) *out++ = std::make_pair(m->vertex_of[v], m_dist[v]);
    return out;
  }

  /// The iso-distance curve at distance `R` (`R` <= the propagation radius),
  /// as ordered chains of trimmed circular arcs (Section 4.2.2, Fig. 3a).
  /// O(A log A) where A is the number of arcs.
  std::vector<Iso_curve> iso_curve(double R) const { return iso_curve_outside(R, No_skip()); }

  /// iso_curve(R) without the arcs in the faces f for which `skip(f)` holds (the sampler passes
  /// the faces that lie inside earlier samples' disks, whose arcs it would drop): the chains
  /// break where they enter such a face.
  template <class SkipFace>
  std::vector<Iso_curve> iso_curve_outside(double R, SkipFace skip) const
  {
    thread_local std::vector<Iso_arc> arcs;   // (per thread, its storage reused from one call to the next)
    arcs.clear();
    extract_iso_arcs([R](int) { return Face_level{Vec2{0., 0.}, R}; }, arcs, R, skip);
    return chain_iso_arcs(arcs);
  }

  /// The available boundary of adaptive sampling (Section 5.1, Eq. 4-5): the points x with
  /// d(x) = r0 + r(x), where r(x) is the disk radius interpolated linearly inside each face from
  /// `vertex_radius(v)` at its vertices (Eq. 3), as ordered chains of conic arcs (ellipses with a
  /// focus at the unfolded source).  The propagation radius must be at least r0 + max r(x) over
  /// the region where d(x) <= r0 + r(x).  Faces where |grad r| >= 0.95 (a radius changing almost
  /// as fast as the distance, possible only on needle faces) use a gradient shortened to 0.95.
  template <class VertexRadius>
  std::vector<Iso_curve> iso_curve(double r0, VertexRadius vertex_radius) const { return iso_curve_outside(r0, vertex_radius, No_skip()); }

  /// iso_curve(r0, vertex_radius) without the arcs in the faces f for which `skip(f)` holds (as
  /// iso_curve_outside(R, skip)).
  template <class VertexRadius, class SkipFace>
  std::vector<Iso_curve> iso_curve_outside(double r0, VertexRadius vertex_radius, SkipFace skip) const
  {
    thread_local std::vector<Iso_arc> arcs;   // (as in iso_curve(R))
    arcs.clear();
    extract_iso_arcs([&](int f) {
      const double rv[3] = {vertex_radius(m->vertex_of[m->fv[3 * f]]), vertex_radius(m->vertex_of[m->fv[3 * f + 1]]),
                            vertex_radius(m->vertex_of[m->fv[3 * f + 2]])};
      const double l0 = m->flayout[3 * f], x2 = m->flayout[3 * f + 1], y2 = m->flayout[3 * f + 2];
      Vec2 a{0., 0.};
      if(l0 > 0. && y2 > 0.) {
        a.x = (rv[1] - rv[0]) / l0;
        a.y = (rv[2] - rv[0] - a.x * x2) / y2;
      }
      const double na = internal::norm(a);
      if(na > 0.95) a = (0.95 / na) * a;
      return Face_level{a, r0 + (l0 > 0. && y2 > 0. ? rv[0] : (rv[0] + rv[1] + rv[2]) / 3.)};
    }, arcs, internal::kInf, skip);
    return chain_iso_arcs(arcs);
  }

  /// number of windows created by the last propagation (statistics)
  std::size_t number_of_windows() const { return m_windows.size(); }

private:
  // -------------------------------------------------------------------------
  // Propagation steps
  // -------------------------------------------------------------------------

  template <class Stop>
  void propagate_impl(const Face_location& source, Stop stop, double report_radius, double discard_beyond = internal::kInf)
  {
    reset();
    m_radius = report_radius;
    m_discard_beyond = discard_beyond;
    initialize_windows_from_source(source, stop);
    while(!m_queue.empty())
    {
      std::pop_heap(m_queue.begin(), m_queue.end());
      const Queue_entry e = m_queue.back();
      m_queue.pop_back();
      if(e.id < 0)
      {
        const int v = -(e.id + 1);
        if(e.key > m_dist[v] + m_tol) continue;  // stale event
        if(m_pseudo_done[v] <= m_dist[v] + m_tol) continue;
        if(m_dist[v] > m_radius) continue;
        create_pseudo_source(v, m_dist[v], stop);
        continue;
      }
      Window& w = m_windows[e.id];
      if(!w.alive || w.propagated) continue;
      const double k = window_min_distance(w);
      if(k > e.key + m_tol)
      {  // the window was trimmed since it was queued: requeue with its new key
        w.key = k;
        push(k, e.id);
        continue;
      }
      w.propagated = true;
      propagate_window_across_face(e.id, stop);
    }
  }

  void reset()
  {
    for(int v : m_touched_vertices)
    {
      m_dist[v] = internal::kInf;
      m_pseudo_done[v] = internal::kInf;
    }
    m_touched_vertices.clear();
    for(int e : m_touched_edges)
    {
      m_edge_windows[e].clear();
      m_edge_touched[e] = 0;
    }
    m_touched_edges.clear();
    m_windows.clear();
    m_queue.clear();
    m_source_faces.clear();
  }

  void push(double key, int id)
  {
    m_queue.push_back({key, id});
    std::push_heap(m_queue.begin(), m_queue.end());
  }

  void update_vertex(int v, double d)
  {
    if(!(d < m_dist[v])) return;
    if(m_dist[v] == internal::kInf) m_touched_vertices.push_back(v);
    m_dist[v] = d;
    if(m->pseudo[v] && d <= m_radius) push(d, -(v + 1));
  }

  static double window_min_distance(const Window& w)
  {
    const double x = (std::min)((std::max)(w.sx, w.b0), w.b1);
    return w.sigma + std::sqrt((x - w.sx) * (x - w.sx) + w.sy * w.sy);
  }
  static double window_max_distance(const Window& w)
  {
    return w.sigma + std::sqrt((std::max)((w.b0 - w.sx) * (w.b0 - w.sx), (w.b1 - w.sx) * (w.b1 - w.sx)) + w.sy * w.sy);
  }

  /// Windows created by the source: vertex source = pseudo-source of distance 0;
  /// edge / face source = windows on the edges of the face(s) containing it.
  template <class Stop>
  void initialize_windows_from_source(const Face_location& source, Stop& stop)
  {
    const int f = int(get(m->fim, source.first));
    std::array<double, 3> b = source.second;
    const int nz = internal::snap_barycentric(b);
    if(nz == 1)
    {
      const int i = (b[0] > 0.) ? 0 : (b[1] > 0.) ? 1 : 2;
      const int v = m->fv[3 * f + i];
      update_vertex(v, 0.);
      m_pseudo_done[v] = 0.;
      create_pseudo_source(v, 0., stop);
      return;
    }
    const Vec2 q = m->bary_to_2(f, b);
    m_source_faces.push_back({f, q});
    if(nz == 2)
    {
      // on edge k where b[k+2] == 0: also the face across that edge
      const int k = (b[2] == 0.) ? 0 : (b[0] == 0.) ? 1 : 2;
      const int so = m->fadj[3 * f + k];
      if(so >= 0)
      {
        const int g = so / 3, ko = so % 3;
        const double L = m->edge_length(3 * f + k);
        const Vec2 qe = m->to_edge_frame(f, k, q);
        const Vec2 qg = m->from_edge_frame(g, ko, Vec2{L - qe.x, 0.});
        m_source_faces.push_back({g, qg});
      }
    }
    for(const auto& sf : m_source_faces)
    {
      const int g = sf.first;
      for(int i = 0; i < 3; ++i) update_vertex(m->fv[3 * g + i], internal::norm(sf.second - m->corner_2(g, i)));
    }
    const std::size_t nsf = m_source_faces.size();
    for(std::size_t i = 0; i < nsf; ++i)
    {
      const int g = m_source_faces[i].first;
      const Vec2 q2 = m_source_faces[i].second;
      for(int k = 0; k < 3; ++k)
      {
        const Vec2 qe = m->to_edge_frame(g, k, q2);
        if(nz == 2 && !(qe.y > 1e-14 * m->edge_length(3 * g + k))) continue;  // the source edge itself
        emit_window_through_edge(3 * g + k, qe, 0., stop);
      }
    }
  }

  /// A point `s` (frame of slot `s_slot`, y >= 0: inside the face) emits a
  /// full-edge window into the face across that edge.
  template <class Stop>
  void emit_window_through_edge(int s_slot, Vec2 s, double sigma, Stop& stop)
  {
    const int t = m->fadj[s_slot];
    if(t < 0) return;  // border edge: nothing beyond
    const double L = m->edge_length(s_slot);
    Window w;
    w.b0 = 0.;
    w.b1 = L;
    w.sx = L - s.x;
    w.sy = (std::min)(0., -s.y);
    w.sigma = sigma;
    w.slot = t;
    trim_and_insert_window(w, stop);
  }

  /// Saddle / border vertex `v` reached at distance `d` becomes a pseudo-source:
  /// full windows on the edges opposite to `v` in all incident faces.
  template <class Stop>
  void create_pseudo_source(int v, double d, Stop& stop)
  {
    m_pseudo_done[v] = d;
    for(int i = m->vf_start[v]; i < m->vf_start[v + 1]; ++i)
    {
      const int c = m->vf_list[i];  // slot 3f + corner of v
      const int f = c / 3, j = c % 3;
      update_vertex(m->fv[3 * f + (j + 1) % 3], d + m->edge_length(c));
      update_vertex(m->fv[3 * f + (j + 2) % 3], d + m->edge_length(3 * f + (j + 2) % 3));
      const int k = (j + 1) % 3;  // opposite edge; its apex is v
      emit_window_through_edge(3 * f + k, m->apex[3 * f + k], d, stop);
    }
  }

  /// Window propagation (Surazhsky et al. Section 3.2): the window on edge AB of
  /// face f = (A,B,C) is propagated through f onto AC and CB.
  template <class Stop>
  void propagate_window_across_face(int id, Stop& stop)
  {
    const Window w = m_windows[id];
    const int s = w.slot, f = s / 3, k = s % 3;
    const double L = m->edge_length(s);
    const Vec2 C = m->apex[s];
    const Vec2 S{w.sx, w.sy};
    const int vC = m->fv[3 * f + (k + 2) % 3];
    // abscissa where the ray from S to C crosses AB
    const double den = C.y - S.y;
    const double xC = (den > 0.) ? S.x + (C.x - S.x) * (-S.y) / den : S.x;
    const double tolx = 1e-12 * L;
    if(xC >= w.b0 - tolx && xC <= w.b1 + tolx) update_vertex(vC, w.sigma + internal::norm(C - S));

    const double lAC = m->edge_length(3 * f + (k + 2) % 3);
    const double lBC = m->edge_length(3 * f + (k + 1) % 3);
    // left part: rays through [b0, min(b1,xC)] hit AC; new window on the twin of C->A (frame origin A, x along A->C)
    if(w.b0 < xC && lAC > 0.)
    {
      const double x1 = (std::min)(w.b1, xC);
      const Vec2 A{0., 0.};
      double u0 = ray_hit(S, w.b0, A, C), u1 = ray_hit(S, x1, A, C);
      if(u0 > u1) std::swap(u0, u1);
      const Vec2 dir{C.x / lAC, C.y / lAC};
      const Vec2 sn{internal::dot(S, dir), internal::cross(dir, S)};
      make_child(3 * f + (k + 2) % 3, u0 * lAC, u1 * lAC, sn, w.sigma, stop);
    }
    // right part: rays through [max(b0,xC), b1] hit BC; new window on the twin of B->C (origin C, x along C->B)
    if(w.b1 > xC && lBC > 0.)
    {
      const double x0 = (std::max)(w.b0, xC);
      const Vec2 B{L, 0.};
      double v0 = ray_hit(S, x0, C, B), v1 = ray_hit(S, w.b1, C, B);
      if(v0 > v1) std::swap(v0, v1);
      const Vec2 dir{(B.x - C.x) / lBC, (B.y - C.y) / lBC};
      const Vec2 sc = S - C;
      const Vec2 sn{internal::dot(sc, dir), internal::cross(dir, sc)};
      make_child(3 * f + (k + 1) % 3, v0 * lBC, v1 * lBC, sn, w.sigma, stop);
    }
  }

  /// Parameter in [0,1] along Q0->Q1 where the ray from S through (x,0) hits line Q0Q1.
  static double ray_hit(Vec2 S, double x, Vec2 Q0, Vec2 Q1)
  {
    const Vec2 r{x - S.x, -S.y};
    const Vec2 d = Q1 - Q0;
    const double den = internal::cross(d, r);
    if(den == 0.) return 0.;
    const double u = internal::cross(S - Q0, r) / den;
    return (std::min)(1., (std::max)(0., u));
  }

  /// Child window on edge slot `from_slot` of the current face, passed to the
  /// face across it.  `sn` is the source in the frame of the twin edge
  /// (already mirrored: y <= 0), [a,b] the extent in that frame.
  template <class Stop>
  void make_child(int from_slot, double a, double b, Vec2 sn, double sigma, Stop& stop)
  {
    const int t = m->fadj[from_slot];
    const double L = m->edge_length(from_slot);
    if(!(b - a > 0.)) return;  // zero-width windows carry nothing (vertices are updated directly)
    if(t < 0) return;  // border: endpoint distances were already recorded through the face
    Window w;
    w.b0 = (std::max)(0., a);
    w.b1 = (std::min)(L, b);
    w.sx = sn.x;
    w.sy = (std::min)(0., sn.y);
    w.sigma = sigma;
    w.slot = t;
    trim_and_insert_window(w, stop);
  }

  /// Surazhsky's window trimming: keep, on every point of the edge, only the
  /// window(s) realising the smallest distance.  The new window is also
  /// compared with the four vertices of the two faces sharing the edge (a
  /// vertex v gives the upper bound d(v) + |v x|).  Pieces of the new window
  /// that survive are stored and queued unless `stop` says otherwise.
  template <class Stop>
  void trim_and_insert_window(const Window& w, Stop& stop)
  {
    const int s = w.slot, f = s / 3, k = s % 3;
    const double L = m->edge_length(s);
    const double tol_x = 1e-12 * L;
    const internal::Edge_distance_function Dw{w.sx, w.sy * w.sy, w.sigma};
    // endpoint distances (a window covering a vertex gives it an upper bound)
    if(w.b0 <= tol_x) update_vertex(m->fv[s], Dw(0.));
    if(w.b1 >= L - tol_x) update_vertex(m->fv[3 * f + (k + 1) % 3], Dw(L));
    // (trimming only shrinks a window: farther than the bound before it, farther after it)
    if(window_min_distance(w) > m_discard_beyond) return;

    m_pieces.v.clear();
    m_pieces.v.push_back({w.b0, w.b1});
    trim_by_vertex_distances(w, Dw, m_pieces);
    if(m_pieces.v.empty()) return;
    trim_against_edge_windows(w, Dw, m_pieces);
    store_window_pieces(w, m_pieces, stop);
  }

  /// Removes the parts of the window where one of the vertices of the two
  /// faces adjacent to its edge already gives a shorter distance.
  void trim_by_vertex_distances(const Window& w, const internal::Edge_distance_function& Dw,
                                internal::Interval_set& pieces) const
  {
    const int s = w.slot, f = s / 3, k = s % 3;
    const double L = m->edge_length(s);
    const int vA = m->fv[s], vB = m->fv[3 * f + (k + 1) % 3], vC = m->fv[3 * f + (k + 2) % 3];
    const Vec2 C = m->apex[s];
    // a vertex can take a part of the window only where it is closer by more than the tolerance;
    // it cannot when even its nearest point of the edge line is not closer than the window's
    // farthest point (the window's distance is convex along the edge: largest at an end)
    const double farthest = (std::max)(Dw(w.b0), Dw(w.b1)) - m_tol;
    auto subtract = [&](const internal::Edge_distance_function& vertex) {
      if(vertex.sigma + std::sqrt(vertex.sy2) < farthest) subtract_dominated(Dw, vertex, w.b0, w.b1, pieces);
    };
    subtract(internal::Edge_distance_function{0., 0., m_dist[vA]});
    subtract(internal::Edge_distance_function{L, 0., m_dist[vB]});
    subtract(internal::Edge_distance_function{C.x, C.y * C.y, m_dist[vC]});
    const int t = m->fadj[s];
    if(t >= 0)
    {
      const int vD = m->fv[3 * (t / 3) + (t % 3 + 2) % 3];
      const Vec2 D = m->apex[t];
      subtract(internal::Edge_distance_function{L - D.x, D.y * D.y, m_dist[vD]});
    }
  }

  /// Compares the new window with every window already stored on its edge
  /// (from either side).  On each overlap, the points where both distance
  /// functions are equal split the overlap; each part goes to the window with
  /// the smaller distance (ties go to the existing window).  Existing windows
  /// are shrunk, split or deleted accordingly; `pieces` keeps what remains of
  /// the new window.
  void trim_against_edge_windows(const Window& w, const internal::Edge_distance_function& Dw,
                                 internal::Interval_set& pieces)
  {
    const int s = w.slot;
    const double L = m->edge_length(s);
    const int e = m->fedge[s];
    std::vector<int>& list = m_edge_windows[e];
    m_new_list.clear();
    for(std::size_t i = 0; i < list.size(); ++i)
    {
      const int eid = list[i];
      Window E = m_windows[eid];  // copy, expressed in the frame of `s`
      if(E.slot != s)
      {
        const double a = L - E.b1, b = L - E.b0;
        E.b0 = a;
        E.b1 = b;
        E.sx = L - E.sx;
      }
      const double o0 = (std::max)(E.b0, w.b0), o1 = (std::min)(E.b1, w.b1);
      if(!(o1 > o0) || pieces.v.empty())
      {
        m_new_list.push_back(eid);
        continue;
      }
      const internal::Edge_distance_function De{E.sx, E.sy * E.sy, E.sigma};
      double pts[4];
      pts[0] = o0;
      int np = 1 + internal::equal_distance_points(Dw, De, o0, o1, pts + 1);
      pts[np++] = o1;
      m_e_pieces.v.clear();
      m_e_pieces.v.push_back({E.b0, E.b1});
      for(int j = 0; j + 1 < np; ++j)
      {
        const double a = pts[j], b = pts[j + 1];
        if(!(b > a)) continue;
        const double x = 0.5 * (a + b);
        if(Dw(x) < De(x) - m_tol)
          m_e_pieces.subtract(a, b);
        else
          pieces.subtract(a, b);
      }
      // write back the surviving pieces of E (converted back to its own frame)
      bool first = true;
      for(const auto& I : m_e_pieces.v)
      {
        if(!(I.second - I.first > 0.)) continue;
        const double a = (E.slot != s) ? L - I.second : I.first;
        const double b = (E.slot != s) ? L - I.first : I.second;
        if(first)
        {
          m_windows[eid].b0 = a;
          m_windows[eid].b1 = b;
          m_new_list.push_back(eid);
          first = false;
          continue;
        }
        Window W2 = m_windows[eid];  // E was split: new window for this piece
        W2.b0 = a;
        W2.b1 = b;
        W2.key = window_min_distance(W2);
        const int nid = int(m_windows.size());
        m_windows.push_back(W2);
        m_new_list.push_back(nid);
        if(!W2.propagated) push(W2.key, nid);
      }
      if(first) m_windows[eid].alive = false;
    }
    list.swap(m_new_list);
  }

  /// Stores the surviving pieces of a new window on its edge and queues them
  /// unless the stop predicate rejects them.
  template <class Stop>
  void store_window_pieces(const Window& w, const internal::Interval_set& pieces, Stop& stop)
  {
    const int s = w.slot;
    const int e = m->fedge[s];
    if(!m_edge_touched[e])
    {
      m_edge_touched[e] = 1;
      m_touched_edges.push_back(e);
    }
    for(const auto& I : pieces.v)
    {
      if(!(I.second - I.first > 0.)) continue;
      Window W2 = w;
      W2.b0 = I.first;
      W2.b1 = I.second;
      W2.alive = true;
      W2.propagated = false;
      W2.key = window_min_distance(W2);
      const int nid = int(m_windows.size());
      m_windows.push_back(W2);
      m_edge_windows[e].push_back(nid);
      if(stop(window_geometry(W2)))
        m_windows[nid].propagated = true;  // stored (for queries and trimming) but not propagated
      else
        push(W2.key, nid);
    }
  }

  /// Removes from `pieces` the parts of [lo,hi] where `competitor` is strictly smaller than `Dw`.
  void subtract_dominated(const internal::Edge_distance_function& Dw, const internal::Edge_distance_function& competitor,
                          double lo, double hi, internal::Interval_set& pieces) const
  {
    if(competitor.sigma == internal::kInf || pieces.v.empty()) return;
    double pts[4];
    pts[0] = lo;
    int np = 1 + internal::equal_distance_points(Dw, competitor, lo, hi, pts + 1);
    pts[np++] = hi;
    for(int j = 0; j + 1 < np; ++j)
    {
      const double a = pts[j], b = pts[j + 1];
      if(!(b > a)) continue;
      const double x = 0.5 * (a + b);
      if(competitor(x) < Dw(x) - m_tol) pieces.subtract(a, b);
    }
  }

  Window_geometry window_geometry(const Window& w) const
  {
    Window_geometry g;
    g.halfedge = m->slot_halfedge[w.slot];
    g.source = {{w.sx, w.sy}};
    g.sigma = w.sigma;
    g.b0 = w.b0;
    g.b1 = w.b1;
    const double L = m->edge_length(w.slot);
    const int a = m->fv[w.slot], b = m->fv[Mesh::next_slot(w.slot)];
    const double t0 = (L > 0.) ? w.b0 / L : 0., t1 = (L > 0.) ? w.b1 / L : 0.;
    const auto& pa = m->pos[a];
    const auto& pb = m->pos[b];
    g.p0 = Point_3(pa[0] + t0 * (pb[0] - pa[0]), pa[1] + t0 * (pb[1] - pa[1]), pa[2] + t0 * (pb[2] - pa[2]));
    g.p1 = Point_3(pa[0] + t1 * (pb[0] - pa[0]), pa[1] + t1 * (pb[1] - pa[1]), pa[2] + t1 * (pb[2] - pa[2]));
    g.min_distance = window_min_distance(w);
    g.max_distance = window_max_distance(w);
    return g;
  }

  // -------------------------------------------------------------------------
  // Distance inside a face
  // -------------------------------------------------------------------------

  /// Distance through window `w` (into face f through its edge k) of the point
  /// `pk` given in the frame of edge k, or +infinity if `pk` is not visible
  /// from the unfolded source through the window.
  double window_value(const Window& w, Vec2 pk, double L) const
  {
    const double dy = pk.y - w.sy;
    const double x = (dy > 1e-300) ? w.sx + (pk.x - w.sx) * (-w.sy) / dy : pk.x;
    const double tol = 1e-10 * L;
    if(x < w.b0 - tol || x > w.b1 + tol) return internal::kInf;
    return w.sigma + std::sqrt((pk.x - w.sx) * (pk.x - w.sx) + (pk.y - w.sy) * (pk.y - w.sy));
  }

  /// Minimum over the windows entering face f, its vertices (as pseudo-sources)
  /// and the source itself when it lies in f.
  double point_distance(int f, Vec2 q) const
  {
    double best = internal::kInf;
    for(int k = 0; k < 3; ++k)
    {
      const int s = 3 * f + k;
      const std::vector<int>& list = m_edge_windows[m->fedge[s]];
      if(list.empty()) continue;
      const Vec2 qk = m->to_edge_frame(f, k, q);
      const double L = m->edge_length(s);
      for(int id : list)
      {
        const Window& w = m_windows[id];
        if(w.slot == s) best = (std::min)(best, window_value(w, qk, L));
      }
    }
    for(int i = 0; i < 3; ++i)
    {
      const double dv = m_dist[m->fv[3 * f + i]];
      if(dv < internal::kInf) best = (std::min)(best, dv + internal::norm(q - m->corner_2(f, i)));
    }
    for(const auto& sf : m_source_faces)
      if(sf.first == f) best = (std::min)(best, internal::norm(q - sf.second));
    return best;
  }

  // -------------------------------------------------------------------------
  // Iso-distance curve extraction (Section 4.2.2, Figure 3a)
  // -------------------------------------------------------------------------

  /// A distance field generator inside a face: D(p) = sigma + |p - c| for p
  /// in the visibility wedge of a window (or everywhere for a vertex / source).
  struct Generator
  {
    Vec2 c;        // center (unfolded source) in the face frame
    double sigma;  // distance of the center
    const Window* window;  // nullptr: no wedge restriction (vertex or source)
    Vec2 eo, eu;   // frame of the window's edge: origin and unit direction
    double L;      // length of that edge
  };

  double generator_value(const Generator& g, Vec2 p) const
  {
    if(g.window == nullptr) return g.sigma + internal::norm(p - g.c);
    const Vec2 q = p - g.eo;
    return window_value(*g.window, Vec2{internal::dot(q, g.eu), internal::cross(g.eu, q)}, g.L);
  }

  /// squared distance from `c` to the triangle P (0 inside)
  static double squared_distance_to_triangle(const Vec2 P[3], Vec2 c)
  {
    bool inside = true;
    double best = internal::kInf;
    for(int i = 0; i < 3; ++i)
    {
      const Vec2 a = P[i], d = P[(i + 1) % 3] - P[i];
      if(internal::cross(d, c - a) < 0.) inside = false;
      const double dd = internal::dot(d, d);
      double t = (dd > 0.) ? internal::dot(c - a, d) / dd : 0.;
      t = (std::min)(1., (std::max)(0., t));
      const Vec2 x = c - (a + t * d);
      best = (std::min)(best, internal::dot(x, x));
    }
    return inside ? 0. : best;
  }

  bool inside_face(int f, Vec2 p) const
  {
    for(int k = 0; k < 3; ++k)
      if(m->to_edge_frame(f, k, p).y < -1e-9 * m->edge_length(3 * f + k)) return false;
    return true;
  }

  /// A cut of a circle, as the unit direction from its center (no angle: the circle's pieces are
  /// sorted by a pseudo-angle, and an angle is computed only at the ends of the arcs kept).
  struct Circle_cut
  {
    double key;   // pseudo-angle in [0, 4), increasing with the polar angle in [0, 2 pi)
    Vec2 u;
  };
  static double pseudo_angle(Vec2 u)
  {
    if(u.y >= 0.) return u.x >= 0. ? u.y / (u.x + u.y) : 1. - u.x / (u.y - u.x);
    return u.x < 0. ? 2. - u.y / (-u.x - u.y) : 3. + u.x / (u.x - u.y);
  }
  static void push_cut(Vec2 x, double r, std::vector<Circle_cut>& out)
  {
    const Vec2 u{x.x / r, x.y / r};
    out.push_back({pseudo_angle(u), u});
  }
  /// circle (c, r) and the line p + t (q - p): the directions from c of the meeting points with
  /// tmin <= t <= tmax that `accept`
  template <class Accept>
  static void circle_line_cuts(Vec2 c, double r, Vec2 p, Vec2 q, std::vector<Circle_cut>& out, double tmin, double tmax,
                               Accept accept)
  {
    const Vec2 d = q - p;
    const double dd = internal::dot(d, d);
    if(!(dd > 0.)) return;
    const Vec2 pc = p - c;
    // |pc + t d|^2 = r^2
    const double b = internal::dot(pc, d) / dd;
    const double cc = (internal::dot(pc, pc) - r * r) / dd;
    const double disc = b * b - cc;
    if(disc < 0.) return;
    const double sq = std::sqrt(disc);
    for(double t : {-b - sq, -b + sq})
    {
      if(t < tmin || t > tmax) continue;
      const Vec2 x = pc + t * d;
      if(accept(c + x)) push_cut(x, r, out);
    }
  }
  /// circles (c1, r1) and (c2, r2): the directions from c1 of the meeting points that `accept`
  template <class Accept>
  static void circle_circle_cuts(Vec2 c1, double r1, Vec2 c2, double r2, std::vector<Circle_cut>& out, Accept accept)
  {
    const Vec2 d = c2 - c1;
    const double D = internal::norm(d);
    if(!(D > 0.) || D > r1 + r2 || D < std::abs(r1 - r2)) return;
    const double a = (r1 * r1 - r2 * r2 + D * D) / (2. * D);
    const double h = std::sqrt((std::max)(0., r1 * r1 - a * a));
    const Vec2 u{d.x / D, d.y / D};
    const Vec2 first{a * u.x - h * u.y, a * u.y + h * u.x}, second{a * u.x + h * u.y, a * u.y - h * u.x};
    if(accept(c1 + first)) push_cut(first, r1, out);
    if(accept(c1 + second)) push_cut(second, r1, out);
  }

  /// The level of an iso-curve inside a face: level(x) = a . x + b in the face frame (a = 0: a
  /// constant level, circular arcs).
  struct Face_level
  {
    Vec2 a;
    double b;
    double at(Vec2 x) const { return internal::dot(a, x) + b; }
  };

  /// Distance generators of face f whose disk of radius R - sigma meets the face.
  void collect_generators(int f, double R, std::vector<Generator>& gens) const
  {
    gens.clear();
    const Vec2 P[3] = {m->corner_2(f, 0), m->corner_2(f, 1), m->corner_2(f, 2)};
    auto add = [&](const Generator& g) {
      const double reach = R - g.sigma;
      if(reach > 0. && squared_distance_to_triangle(P, g.c) < reach * reach) gens.push_back(g);
    };
    for(int k = 0; k < 3; ++k)
    {
      const int s = 3 * f + k;
      const std::vector<int>& list = m_edge_windows[m->fedge[s]];
      if(list.empty()) continue;
      const Vec2 eo = P[k], d = P[(k + 1) % 3] - P[k];
      const double L = internal::norm(d);
      const Vec2 eu = (L > 0.) ? Vec2{d.x / L, d.y / L} : Vec2{1., 0.};
      for(int id : list)
      {
        const Window& w = m_windows[id];
        if(w.slot != s || !(w.sigma < R) || window_min_distance(w) > R) continue;
        const Vec2 c{eo.x + w.sx * eu.x - w.sy * eu.y, eo.y + w.sx * eu.y + w.sy * eu.x};
        add(Generator{c, w.sigma, &w, eo, eu, m->edge_length(s)});
      }
    }
    for(const auto& sf : m_source_faces)
      if(sf.first == f) add(Generator{sf.second, 0., nullptr, Vec2{0., 0.}, Vec2{1., 0.}, 0.});
    // vertices: pseudo-sources (saddle / border vertices) and a source vertex.
    // A convex vertex never realises the minimum on a set of positive measure,
    // so it would only add breakpoints.
    for(int i = 0; i < 3; ++i)
    {
      const int v = m->fv[3 * f + i];
      const double dv = m_dist[v];
      if(dv < R && (m->pseudo[v] || dv == 0.)) add(Generator{P[i], dv, nullptr, Vec2{0., 0.}, Vec2{1., 0.}, 0.});
    }
  }

  /// (no face skipped)
  struct No_skip
  {
    bool operator()(face_descriptor) const { return false; }
  };

  /// For every face near the propagated region, the curve of every generator
  /// at the face's level (the circle of radius R - sigma for a constant level
  /// R, a conic for a level linear in the face) is cut at its intersections
  /// with the face edges, the wedge boundaries and the other generators'
  /// curves; a piece is kept when its midpoint lies in the face, in the
  /// generator's wedge, and no other generator gives a distance below the
  /// level there (artificial arcs are trimmed).
  ///
  /// `level_bound`: the level's largest value in any face (infinite: not known). A pseudo-source
  /// at that distance or farther is no generator of its faces (collect_generators() takes those
  /// closer than the face's level), whose other generators bring them in: its faces are not
  /// visited for it.
  ///
  /// `skip(f)`: the faces left out (their arcs are not made).
  template <class LevelOfFace, class SkipFace = No_skip>
  void extract_iso_arcs(LevelOfFace level_of_face, std::vector<Iso_arc>& arcs, double level_bound = internal::kInf,
                        SkipFace skip = SkipFace()) const
  {
    // faces to examine: those with a distance generator (collect_generators): the faces that
    // windows enter, the faces around reached pseudo-sources closer than the level and a source
    // vertex, the source's faces (sorted list, no O(|F|) storage: iso_curve stays cheap and
    // thread-safe for disks of few faces; the buffers are per thread, to reuse their storage from one
    // call to the next)
    thread_local std::vector<int> faces_to_visit;
    faces_to_visit.clear();
    for(int v : m_touched_vertices)
      if((m->pseudo[v] && m_dist[v] < level_bound) || m_dist[v] == 0.)
        for(int i = m->vf_start[v]; i < m->vf_start[v + 1]; ++i) faces_to_visit.push_back(m->vf_list[i] / 3);
    for(int e : m_touched_edges)
      for(int id : m_edge_windows[e]) faces_to_visit.push_back(m_windows[id].slot / 3);
    for(const auto& sf : m_source_faces) faces_to_visit.push_back(sf.first);
    std::sort(faces_to_visit.begin(), faces_to_visit.end());
    faces_to_visit.erase(std::unique(faces_to_visit.begin(), faces_to_visit.end()), faces_to_visit.end());

    thread_local std::vector<Generator> gens;
    thread_local std::vector<double> angles;
    thread_local std::vector<std::pair<double, double> > kept;
    for(int f : faces_to_visit)
    {
      if constexpr(!std::is_same<SkipFace, No_skip>::value)
        if(skip(m->face_of[f])) continue;
      const Vec2 P[3] = {m->corner_2(f, 0), m->corner_2(f, 1), m->corner_2(f, 2)};
      const Face_level level = level_of_face(f);
      const bool conic = level.a.x != 0. || level.a.y != 0.;
      double Lmin = internal::kInf, Lmax = -internal::kInf;
      for(int i = 0; i < 3; ++i)
      {
        Lmin = (std::min)(Lmin, level.at(P[i]));
        Lmax = (std::max)(Lmax, level.at(P[i]));
      }
      const double tie = 1e-11 * (std::max)(Lmax, m->diag * 1e-6);
      // faces entirely closer than the level have no arc. d(p) <= d(v_i) + |p v_i| for every
      // corner, so d <= dmin + lmax on the face; and every point of a triangle is within
      // lmax / sqrt(3) of its nearest corner (the circumradius of an acute triangle, whose largest
      // angle is at least 60 degrees, is at most lmax / sqrt(3)), so d <= dmax + lmax / sqrt(3).
      double dmin = internal::kInf, dmax = 0., lmax = 0.;
      for(int i = 0; i < 3; ++i)
      {
        dmin = (std::min)(dmin, m_dist[m->fv[3 * f + i]]);
        dmax = (std::max)(dmax, m_dist[m->fv[3 * f + i]]);
        lmax = (std::max)(lmax, m->edge_length(3 * f + i));
      }
      if(dmin + lmax < Lmin || dmax + lmax * internal::kInvSqrt3 < Lmin) continue;
      collect_generators(f, Lmax, gens);
      if(gens.empty()) continue;
      // a point near enough to the face to bound a piece of curve in it (loose: a needless cut
      // only splits a piece in two)
      const double cut_margin = 1e-7;
      auto near_face = [&](Vec2 x) {
        for(int k = 0; k < 3; ++k)
          if(m->to_edge_frame(f, k, x).y < -cut_margin * lmax) return false;
        return true;
      };
      // the curve of generator g: |x - c| = r + a . (x - c), r = level(c) - sigma (a circle of
      // radius R - sigma when the level is constant)
      auto curve_radius = [&](const Generator& g) { return level.at(g.c) - g.sigma; };
      auto curve_point = [&](const Generator& g, double r, double th) {   // (on a conic)
        const Vec2 u{std::cos(th), std::sin(th)};
        return g.c + (r / (1. - internal::dot(level.a, u))) * u;
      };
      for(std::size_t gi = 0; gi < gens.size(); ++gi)
      {
        const Generator& g = gens[gi];
        const double r = curve_radius(g);
        if(!(r > 0.)) continue;
        // quick rejection: the curve contains the triangle
        bool contains = true;
        for(int i = 0; i < 3 && contains; ++i)
        {
          const Vec2 x = P[i] - g.c;
          contains = internal::norm(x) - r - internal::dot(level.a, x) < 0.;
        }
        if(contains) continue;
        // a piece of curve is kept when its midpoint lies in the face, in g's wedge, and no other
        // generator gives a distance below the level there
        auto keep_point = [&](Vec2 p) {
          if(!inside_face(f, p)) return false;
          if(!(generator_value(g, p) < internal::kInf)) return false;
          const double L = level.at(p);
          for(std::size_t hi = 0; hi < gens.size(); ++hi)
          {
            if(hi == gi) continue;
            const double dh = generator_value(gens[hi], p);
            if(dh < L - tie || (dh <= L + tie && hi < gi)) return false;
          }
          return true;
        };
        if(!conic)
        {   // a constant level: g's circle (the same cuts and classification without angles)
          extract_circle_arcs(f, g, gi, r, P, gens, cut_margin, near_face, keep_point, level.b, arcs);
          continue;
        }
        // the conic is cut where a piece's classification can change: where it crosses the
        // face's edges, a wedge boundary or another generator's curve inside the face (a cut
        // outside the face would only split a piece that is dropped anyway)
        angles.clear();
        for(int i = 0; i < 3; ++i) internal::conic_line_angles(g.c, r, level.a, P[i], P[(i + 1) % 3], angles);
        if(angles.empty() && !inside_face(f, curve_point(g, r, 0.))) continue;
        for(std::size_t hi = 0; hi < gens.size(); ++hi)
        {
          const Generator& h = gens[hi];
          if(h.window != nullptr)
          {
            const Vec2 a = h.eo + h.window->b0 * h.eu, b = h.eo + h.window->b1 * h.eu;
            internal::conic_line_angles(g.c, r, level.a, h.c, a, angles);
            internal::conic_line_angles(g.c, r, level.a, h.c, b, angles);
          }
          if(hi == gi) continue;
          internal::conic_conic_angles(g.c, r, h.c, curve_radius(h), level.a, angles);
        }
        for(double& a : angles)
        {
          a = std::fmod(a, 2. * internal::kPi);
          if(a < 0.) a += 2. * internal::kPi;
        }
        std::sort(angles.begin(), angles.end());
        if(angles.empty()) angles.push_back(0.);
        // classify the pieces between consecutive angles (cyclically)
        kept.clear();
        const std::size_t na = angles.size();
        for(std::size_t i = 0; i < na; ++i)
        {
          const double a0 = angles[i];
          const double a1 = (i + 1 < na) ? angles[i + 1] : angles[0] + 2. * internal::kPi;
          if(!(a1 - a0 > 1e-13)) continue;
          const double am = 0.5 * (a0 + a1);
          if(!keep_point(curve_point(g, r, am))) continue;
          if(!kept.empty() && std::abs(kept.back().second - a0) < 1e-15)
            kept.back().second = a1;
          else
            kept.push_back({a0, a1});
        }
        // merge the last piece with the first one across the 2 pi seam
        if(kept.size() >= 2 && std::abs(kept.back().second - (kept.front().first + 2. * internal::kPi)) < 1e-15)
        {
          kept.front().first = kept.back().first - 2. * internal::kPi;
          kept.pop_back();
        }
        for(const auto& I : kept)
        {
          const double rm = internal::norm(curve_point(g, r, 0.5 * (I.first + I.second)) - g.c);
          if(!(rm * (I.second - I.first) > 1e-12 * Lmax)) continue;
          push_arc(f, g, r, level.a, I.first, I.second, arcs);
        }
      }
    }
  }

  void push_arc(int f, const Generator& g, double r, Vec2 gradient, double theta_start, double theta_end,
                std::vector<Iso_arc>& arcs) const
  {
    Iso_arc arc;
    arc.face = m->face_of[f];
    arc.center = {{g.c.x, g.c.y}};
    arc.radius = r;
    arc.gradient = {{gradient.x, gradient.y}};
    arc.sigma = g.sigma;
    arc.theta_start = theta_start;
    arc.theta_end = theta_end;
    for(int i = 0; i < 3; ++i)
    {
      const auto& q = m->pos[m->fv[3 * f + i]];
      arc.corners[i] = Point_3(q[0], q[1], q[2]);
    }
    arc.layout = {{m->flayout[3 * f], m->flayout[3 * f + 1], m->flayout[3 * f + 2]}};
    arcs.push_back(arc);
  }

  /// extract_iso_arcs() for generator g (number gi of `gens`) when the level R is constant in face
  /// f: its circle of radius r, cut as the general path cuts a curve, but with the cuts as
  /// directions sorted by a pseudo-angle and each piece's midpoint found by halving the angle
  /// between its ends' directions; an angle (atan2) is computed only at the ends of a kept arc.
  template <class NearFace, class KeepPoint>
  void extract_circle_arcs(int f, const Generator& g, std::size_t gi, double r, const Vec2 P[3], const std::vector<Generator>& gens,
                           double cut_margin, NearFace near_face, KeepPoint keep_point, double R, std::vector<Iso_arc>& arcs) const
  {
    thread_local std::vector<Circle_cut> cuts;
    cuts.clear();
    for(int i = 0; i < 3; ++i)
      circle_line_cuts(g.c, r, P[i], P[(i + 1) % 3], cuts, -cut_margin, 1. + cut_margin, [](Vec2) { return true; });
    if(cuts.empty() && !inside_face(f, Vec2{g.c.x + r, g.c.y})) return;
    for(std::size_t hi = 0; hi < gens.size(); ++hi)
    {
      const Generator& h = gens[hi];
      if(h.window != nullptr)
      {   // (the wedge's sides begin on the window's edge: t >= 1)
        const Vec2 a = h.eo + h.window->b0 * h.eu, b = h.eo + h.window->b1 * h.eu;
        circle_line_cuts(g.c, r, h.c, a, cuts, 1. - cut_margin, internal::kInf, near_face);
        circle_line_cuts(g.c, r, h.c, b, cuts, 1. - cut_margin, internal::kInf, near_face);
      }
      if(hi == gi) continue;
      circle_circle_cuts(g.c, r, h.c, R - h.sigma, cuts, near_face);
    }
    std::sort(cuts.begin(), cuts.end(), [](const Circle_cut& a, const Circle_cut& b) { return a.key < b.key; });
    if(cuts.empty()) cuts.push_back({0., Vec2{1., 0.}});
    // the pieces between consecutive cuts (cyclically); ks: a piece's span in pseudo-angle (4: the
    // whole circle), which tells a span over pi (ks > 2) from one under it
    const std::size_t n = cuts.size();
    struct Run
    {
      std::size_t first, last;   // from cut `first` to cut `last` (modulo n)
      double ks;                 // its span in pseudo-angle
    };
    thread_local std::vector<Run> runs;   // the kept pieces, consecutive ones merged
    runs.clear();
    for(std::size_t i = 0; i < n; ++i)
    {
      const Circle_cut& A = cuts[i];
      const Circle_cut& B = cuts[(i + 1) % n];
      const double ks = (n == 1) ? 4. : (i + 1 < n ? B.key - A.key : 4. - (A.key - B.key));
      const double cr = internal::cross(A.u, B.u), dt = internal::dot(A.u, B.u);
      if(ks <= 2. && dt > 0. && cr <= 1e-13) continue;   // a piece shorter than 1e-13 radians
      // the direction halfway from A to B, counter-clockwise
      Vec2 mid;
      const Vec2 sum = A.u + B.u;
      if(internal::dot(sum, sum) > 0.5)
      {
        const double l = internal::norm(sum) * (ks < 2. ? 1. : -1.);
        mid = Vec2{sum.x / l, sum.y / l};
      }
      else
      {   // (the ends nearly opposite: cos and sin of half the span from its cosine)
        const double c = std::sqrt((std::max)(0., 0.5 * (1. + dt))) * (ks < 2. ? 1. : -1.), sn = std::sqrt((std::max)(0., 0.5 * (1. - dt)));
        mid = Vec2{c * A.u.x - sn * A.u.y, c * A.u.y + sn * A.u.x};
      }
      if(!keep_point(g.c + r * mid)) continue;
      if(!runs.empty() && (runs.back().last == i || (cuts[runs.back().last % n].u.x == A.u.x && cuts[runs.back().last % n].u.y == A.u.y)))
      {
        runs.back().last = i + 1;
        runs.back().ks += ks;
      }
      else
        runs.push_back({i, i + 1, ks});
    }
    // merge the last run with the first across the seam
    if(runs.size() >= 2 && runs.back().last == n && runs.front().first == 0)
    {
      runs.front().first = runs.back().first;
      runs.front().ks += runs.back().ks;
      runs.pop_back();
    }
    for(const Run& run : runs)
    {
      const Vec2 us = cuts[run.first % n].u, ue = cuts[run.last % n].u;
      const double t0 = std::atan2(us.y, us.x);
      double span;
      if(run.ks >= 4.) span = 2. * internal::kPi;   // the whole circle
      else
      {   // (a pseudo-angle span of 1 is a quarter turn give or take 0.08 radians: the margins)
        span = std::atan2(ue.y, ue.x) - t0;
        if(span < 0.) span += 2. * internal::kPi;
        if(run.ks > 3. && span < 0.5 * internal::kPi) span += 2. * internal::kPi;        // near 2 pi, rounded to near 0
        else if(run.ks < 1. && span > 1.5 * internal::kPi) span -= 2. * internal::kPi;   // near 0, rounded to near 2 pi
      }
      if(!(r * span > 1e-12 * R)) continue;
      push_arc(f, g, r, Vec2{0., 0.}, t0, t0 + span, arcs);
    }
  }

  /// Chains arcs end-to-start (arcs of the same or adjacent faces whose 3D
  /// endpoints coincide) into closed curves or open border-to-border curves.
  std::vector<Iso_curve> chain_iso_arcs(const std::vector<Iso_arc>& arcs) const
  {
    return chain_arcs_by_endpoints(arcs, [this](face_descriptor fd) { return int(get(m->fim, fd)); }, *m);
  }

public:
  /// (implementation detail shared with the approximate oracle)
  template <class FaceIndex>
  static std::vector<Iso_curve> chain_arcs_by_endpoints(const std::vector<Iso_arc>& arcs, FaceIndex face_index,
                                                        const Mesh& mesh)
  {
    const std::size_t n = arcs.size();
    // (the buffers are per thread, their storage reused from one call to the next)
    thread_local std::vector<std::array<double, 3> > st, en;
    thread_local std::vector<int> fidx;
    thread_local std::vector<std::pair<int, int> > by_face;  // (face index, arc), sorted
    st.resize(n);
    en.resize(n);
    fidx.resize(n);
    by_face.clear();
    for(std::size_t i = 0; i < n; ++i)
    {
      const Point_3 a = arcs[i].point(0.), b = arcs[i].point(1.);
      st[i] = {{CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())}};
      en[i] = {{CGAL::to_double(b.x()), CGAL::to_double(b.y()), CGAL::to_double(b.z())}};
      fidx[i] = face_index(arcs[i].face);
      by_face.push_back({fidx[i], int(i)});
    }
    std::sort(by_face.begin(), by_face.end());
    auto d2 = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
      return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
    };
    thread_local std::vector<int> next, prev, by_x;   // (by_x: the arcs by their start's x)
    next.assign(n, -1);
    prev.assign(n, -1);
    by_x.resize(n);
    for(std::size_t i = 0; i < n; ++i) by_x[i] = int(i);
    std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return st[a][0] < st[b][0] || (st[a][0] == st[b][0] && a < b); });
    // candidate successors: arcs of the same face and of the faces sharing a vertex with it
    thread_local std::vector<int> cand, close;
    auto share_a_vertex = [&](int f, int g) {
      for(int k = 0; k < 3; ++k)
        for(int l = 0; l < 3; ++l)
          if(mesh.fv[3 * f + k] == mesh.fv[3 * g + l]) return true;
      return false;
    };
    for(std::size_t i = 0; i < n; ++i)
    {
      const int f = fidx[i];
      double scale = 0.;
      for(int k = 0; k < 3; ++k) scale = (std::max)(scale, mesh.edge_length(3 * f + k));
      // Matching tolerance: 1e-4 x the longest edge of the face.  Where several
      // windows carry distance fields that differ by ~1e-11 (the same source
      // unfolded along slightly different face strips), the ownership of the
      // level set switches at ill-conditioned points and consecutive arcs may
      // be separated by gaps of ~1e-7 x edge length (all arc points are still
      // at distance R up to ~1e-11).
      const double tol2 = (1e-4 * scale) * (1e-4 * scale);
      // the arcs that start close enough: almost always one, taken at once when it is a candidate
      // (those whose start's x is within the tolerance, found in the starts sorted by x; the
      // window a hair wider than the tolerance: the squared distance decides)
      close.clear();
      const double reach = 1e-4 * scale * (1. + 1e-9);
      for(auto it = std::lower_bound(by_x.begin(), by_x.end(), en[i][0] - reach,
                                     [&](int j, double x) { return st[j][0] < x; });
          it != by_x.end() && st[*it][0] <= en[i][0] + reach; ++it)
        if(prev[*it] < 0 && d2(en[i], st[*it]) <= tol2) close.push_back(*it);
      if(close.empty()) continue;
      const auto full_circle = [&](int j) {
        return !(arcs[j].is_segment || arcs[j].theta_end - arcs[j].theta_start < 2. * internal::kPi - 1e-9);
      };
      if(close.size() == 1)
      {
        const int j = close[0];
        if((j != int(i) || full_circle(j)) && share_a_vertex(f, fidx[j]))
        {
          next[i] = j;
          prev[j] = int(i);
        }
        continue;
      }
      // several: the closest, ties to the last in the order of the faces around f's corners
      cand.clear();
      for(int k = 0; k < 3; ++k)
      {
        const int v = mesh.fv[3 * f + k];
        for(int j = mesh.vf_start[v]; j < mesh.vf_start[v + 1]; ++j)
        {
          const int g = mesh.vf_list[j] / 3;
          for(auto it = std::lower_bound(by_face.begin(), by_face.end(), std::make_pair(g, -1));
              it != by_face.end() && it->first == g; ++it)
            cand.push_back(it->second);
        }
      }
      int best = -1;
      double bd = tol2;
      for(int j : cand)
      {
        if(j == int(i) && (arcs[i].is_segment || arcs[i].theta_end - arcs[i].theta_start < 2. * internal::kPi - 1e-9))
          continue;  // only a full circle may close on itself
        const double dd = d2(en[i], st[j]);
        if(dd <= bd && prev[j] < 0)
        {
          bd = dd;
          best = j;
        }
      }
      if(best >= 0)
      {
        next[i] = best;
        prev[best] = int(i);
      }
    }
    // consecutive arcs of the same circle in the same face (pieces of one
    // source's circle seen through adjacent windows) are merged into one arc
    auto mergeable = [](const Iso_arc& a, const Iso_arc& b) {
      if(a.is_segment || b.is_segment || a.face != b.face) return false;
      const double eps = 1e-12 * (std::max)(a.radius, 1e-300);
      if(std::abs(a.radius - b.radius) > eps || std::abs(a.center[0] - b.center[0]) > eps ||
         std::abs(a.center[1] - b.center[1]) > eps)
        return false;
      double gap = std::remainder(b.theta_start - a.theta_end, 2. * internal::kPi);
      return std::abs(gap) < 1e-9 &&
             (a.theta_end - a.theta_start) + (b.theta_end - b.theta_start) < 2. * internal::kPi + 1e-9;
    };
    std::vector<Iso_curve> curves;
    thread_local std::vector<char> used;
    used.assign(n, 0);
    auto walk = [&](int start) {
      Iso_curve c;
      std::size_t length = 0;   // (the chain's arcs reserved at once: arc records are large)
      for(int i = start; i >= 0 && !used[i] && length < n; i = next[i]) {
        ++length;
        if(next[i] == start) break;
      }
      c.arcs.reserve(length);
      int i = start;
      while(i >= 0 && !used[i])
      {
        used[i] = 1;
        if(!c.arcs.empty() && mergeable(c.arcs.back(), arcs[i]))
          c.arcs.back().theta_end += arcs[i].theta_end - arcs[i].theta_start;
        else
          c.arcs.push_back(arcs[i]);
        i = next[i];
      }
      c.closed = (i == start);
      if(c.closed && c.arcs.size() > 1 && mergeable(c.arcs.back(), c.arcs.front()))
      {
        c.arcs.front().theta_start -= c.arcs.back().theta_end - c.arcs.back().theta_start;
        c.arcs.pop_back();
      }
      curves.push_back(std::move(c));
    };
    for(std::size_t i = 0; i < n; ++i)
      if(prev[i] < 0 && !used[i]) walk(int(i));
    for(std::size_t i = 0; i < n; ++i)
      if(!used[i]) walk(int(i));
    return curves;
  }

private:
  const TriangleMesh& m_tm;
  VertexPointMap m_vpm;
  // the index-based copy of the mesh, read-only once built: the copies of an oracle (the sampler's
  // own and its classifier) share it
  std::shared_ptr<const Mesh> m;
  double m_tol = 0.;
  double m_radius = 0.;
  double m_discard_beyond = internal::kInf;   // windows whose minimal distance exceeds this are dropped
  std::vector<double> m_dist, m_pseudo_done;
  std::vector<int> m_touched_vertices, m_touched_edges;
  std::vector<std::vector<int> > m_edge_windows;
  std::vector<char> m_edge_touched;
  std::vector<Window> m_windows;
  std::vector<Queue_entry> m_queue;
  std::vector<std::pair<int, Vec2> > m_source_faces;
  internal::Interval_set m_pieces, m_e_pieces;
  std::vector<int> m_new_list;
};

}  // namespace Poisson_remesh

#endif  // POISSON_REMESH_GEODESIC_EXACT_GEODESIC_ORACLE_H
