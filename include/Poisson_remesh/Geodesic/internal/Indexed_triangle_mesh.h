// Poisson_remesh/Geodesic/internal/Indexed_triangle_mesh.h
//
// The index-based copy of a triangle mesh that the geodesic oracles work on (faces, adjacency,
// edge lengths, each face laid out in its 2D frame, see Geodesic/Iso_arc.h), with the 2D vector
// helpers and constants they share.

#ifndef POISSON_REMESH_GEODESIC_INTERNAL_INDEXED_TRIANGLE_MESH_H
#define POISSON_REMESH_GEODESIC_INTERNAL_INDEXED_TRIANGLE_MESH_H

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
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {


constexpr double kPi = 3.14159265358979323846;
// 1 / sqrt(3), rounded up: the farthest a point of a triangle can be from its nearest corner, per
// unit of the longest edge
constexpr double kInvSqrt3 = 0.5774;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Vec2
{
  double x, y;
};
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }   // (lengths of mesh size: no overflow to guard)

/// Area of a triangle from its edge lengths (Kahan's stable Heron formula).
inline double stable_area(double a, double b, double c)
{
  if(a < b) std::swap(a, b);
  if(a < c) std::swap(a, c);
  if(b < c) std::swap(b, c);
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return p <= 0. ? 0. : 0.25 * std::sqrt(p);
}

/// Position of the apex of a triangle with base [0,L] on the x axis, given
/// the lengths `la` (apex to origin) and `lb` (apex to (L,0)); apex has y >= 0.
inline Vec2 layout_apex(double L, double la, double lb)
{
  const double x = (L * L + (la - lb) * (la + lb)) / (2. * L);
  const double y = 2. * stable_area(L, la, lb) / L;
  return {x, y};
}

/// Index-based copy of a triangle mesh (faces, adjacency, edge lengths and
/// the 2D layouts of every face), built once and shared by the oracles.
template <class TriangleMesh, class VertexPointMap>
class Indexed_triangle_mesh
{
public:
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename CGAL::GetInitializedVertexIndexMap<TriangleMesh>::const_type VIM;
  typedef typename CGAL::GetInitializedFaceIndexMap<TriangleMesh>::const_type FIM;
  typedef typename CGAL::GetInitializedHalfedgeIndexMap<TriangleMesh>::const_type HIM;

  Indexed_triangle_mesh(const TriangleMesh& tm, VertexPointMap vpm)
    : vim(CGAL::get_initialized_vertex_index_map(tm)),
      fim(CGAL::get_initialized_face_index_map(tm)),
      him(CGAL::get_initialized_halfedge_index_map(tm))
  {
    std::size_t nv = 0, nf = 0, nh = 0;
    for(vertex_descriptor v : vertices(tm)) nv = (std::max)(nv, std::size_t(get(vim, v)) + 1);
    for(face_descriptor f : faces(tm)) nf = (std::max)(nf, std::size_t(get(fim, f)) + 1);
    for(halfedge_descriptor h : halfedges(tm)) nh = (std::max)(nh, std::size_t(get(him, h)) + 1);
    vertex_of.resize(nv);
    face_of.resize(nf);
    valid_face.assign(nf, 0);
    pos.assign(nv, std::array<double, 3>{{0., 0., 0.}});
    double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
    for(vertex_descriptor v : vertices(tm))
    {
      const int i = int(get(vim, v));
      vertex_of[i] = v;
      const auto& p = get(vpm, v);
      pos[i] = {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
      for(int c = 0; c < 3; ++c)
      {
        lo[c] = (std::min)(lo[c], pos[i][c]);
        hi[c] = (std::max)(hi[c], pos[i][c]);
      }
    }
    diag = (nv == 0) ? 1. : std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if(!(diag > 0.)) diag = 1.;

    fv.assign(3 * nf, -1);
    fadj.assign(3 * nf, -1);
    fedge.assign(3 * nf, -1);
    slot_halfedge.resize(3 * nf);
    std::vector<int> hslot(nh, -1);
    for(face_descriptor f : faces(tm))
    {
      const int fi = int(get(fim, f));
      face_of[fi] = f;
      valid_face[fi] = 1;
      halfedge_descriptor h = halfedge(f, tm);
      int k = 0;
      for(halfedge_descriptor hh : CGAL::halfedges_around_face(h, tm))
      {
        if(k >= 3) throw std::invalid_argument("Poisson_remesh geodesic oracle: the mesh is not a triangle mesh");
        fv[3 * fi + k] = int(get(vim, source(hh, tm)));
        slot_halfedge[3 * fi + k] = hh;
        hslot[get(him, hh)] = 3 * fi + k;
        ++k;
      }
      if(k != 3) throw std::invalid_argument("Poisson_remesh geodesic oracle: the mesh is not a triangle mesh");
    }
    // adjacency and undirected edge indices
    int ne = 0;
    for(std::size_t s = 0; s < 3 * nf; ++s)
    {
      if(!valid_face[s / 3]) continue;
      halfedge_descriptor hh = slot_halfedge[s];
      halfedge_descriptor ho = opposite(hh, tm);
      if(!is_border(ho, tm)) fadj[s] = hslot[get(him, ho)];
      if(fadj[s] >= 0 && fedge[fadj[s]] >= 0)
        fedge[s] = fedge[fadj[s]];
      else
        fedge[s] = ne++;
    }
    num_edges = ne;
    elen.assign(ne, 0.);
    for(std::size_t s = 0; s < 3 * nf; ++s)
    {
      if(!valid_face[s / 3]) continue;
      const int a = fv[s], b = fv[3 * (s / 3) + (s % 3 + 1) % 3];
      elen[fedge[s]] = dist3(a, b);
    }
    // per-slot apex layouts and per-face frames
    apex.assign(3 * nf, Vec2{0., 0.});
    flayout.assign(3 * nf, 0.);
    for(std::size_t f = 0; f < nf; ++f)
    {
      if(!valid_face[f]) continue;
      for(int k = 0; k < 3; ++k)
      {
        const double L = elen[fedge[3 * f + k]];
        const double la = elen[fedge[3 * f + (k + 2) % 3]];
        const double lb = elen[fedge[3 * f + (k + 1) % 3]];
        apex[3 * f + k] = (L > 0.) ? layout_apex(L, la, lb) : Vec2{0., 0.};
      }
      flayout[3 * f + 0] = elen[fedge[3 * f]];
      flayout[3 * f + 1] = apex[3 * f].x;
      flayout[3 * f + 2] = apex[3 * f].y;
    }
    // the unit direction of each edge in its face's frame, computed once: the edge frames are
    // asked for by every distance evaluation and every inside-face test
    edge_dir.assign(3 * nf, Vec2{1., 0.});
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k)
      {
        const Vec2 d = corner_2(int(f), (k + 1) % 3) - corner_2(int(f), k);
        const double l = norm(d);
        if(l > 0.) edge_dir[3 * f + k] = Vec2{d.x / l, d.y / l};
      }
    // vertex -> incident (face, corner) lists, angle sums, border flags
    vf_start.assign(nv + 1, 0);
    for(std::size_t s = 0; s < 3 * nf; ++s)
      if(valid_face[s / 3]) ++vf_start[fv[s] + 1];
    for(std::size_t i = 0; i < nv; ++i) vf_start[i + 1] += vf_start[i];
    vf_list.assign(vf_start[nv], 0);
    {
      std::vector<int> fill(vf_start.begin(), vf_start.end() - 1);
      for(std::size_t s = 0; s < 3 * nf; ++s)
        if(valid_face[s / 3]) vf_list[fill[fv[s]]++] = int(s);
    }
    pseudo.assign(nv, 0);
    std::vector<double> angle_sum(nv, 0.);
    for(std::size_t s = 0; s < 3 * nf; ++s)
    {
      if(!valid_face[s / 3]) continue;
      // angle at corner k: between edges k and k+2
      const std::size_t f = s / 3;
      const int k = int(s % 3);
      const double a = elen[fedge[3 * f + k]], b = elen[fedge[3 * f + (k + 2) % 3]];
      const double c = elen[fedge[3 * f + (k + 1) % 3]];
      double ang = kPi;
      if(a > 0. && b > 0.) ang = std::atan2(4. * stable_area(a, b, c), (a * a + b * b - c * c));
      angle_sum[fv[s]] += ang;
      if(fadj[s] < 0)
      {
        pseudo[fv[s]] = 1;
        pseudo[fv[3 * f + (k + 1) % 3]] = 1;
      }
    }
    for(std::size_t i = 0; i < nv; ++i)
      if(angle_sum[i] > 2. * kPi + 1e-13) pseudo[i] = 1;  // saddle (see the note on tolerances above)
  }

  double dist3(int a, int b) const
  {
    const double dx = pos[a][0] - pos[b][0], dy = pos[a][1] - pos[b][1], dz = pos[a][2] - pos[b][2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  std::size_t number_of_vertices() const { return vertex_of.size(); }
  std::size_t number_of_faces() const { return face_of.size(); }
  double edge_length(int slot) const { return elen[fedge[slot]]; }
  static int next_slot(int s) { return 3 * (s / 3) + (s % 3 + 1) % 3; }
  static int prev_slot(int s) { return 3 * (s / 3) + (s % 3 + 2) % 3; }

  /// corner `i` of face `f` in the face frame
  Vec2 corner_2(int f, int i) const
  {
    if(i == 0) return {0., 0.};
    if(i == 1) return {flayout[3 * f], 0.};
    return {flayout[3 * f + 1], flayout[3 * f + 2]};
  }
  /// face frame -> frame of edge k (origin at corner k, x towards corner k+1, y >= 0 inside the face)
  Vec2 to_edge_frame(int f, int k, Vec2 p) const
  {
    const Vec2 a = corner_2(f, k), u = edge_dir[3 * f + k];
    const Vec2 q = p - a;
    return {dot(q, u), cross(u, q)};
  }
  Vec2 from_edge_frame(int f, int k, Vec2 p) const
  {
    const Vec2 a = corner_2(f, k), u = edge_dir[3 * f + k];
    return {a.x + p.x * u.x - p.y * u.y, a.y + p.x * u.y + p.y * u.x};
  }
  Vec2 bary_to_2(int f, const std::array<double, 3>& b) const
  {
    const Vec2 p1 = corner_2(f, 1), p2 = corner_2(f, 2);
    return {b[1] * p1.x + b[2] * p2.x, b[2] * p2.y};
  }
  std::array<double, 3> point_3(int f, const std::array<double, 3>& b) const
  {
    std::array<double, 3> r{{0., 0., 0.}};
    for(int i = 0; i < 3; ++i)
      for(int c = 0; c < 3; ++c) r[c] += b[i] * pos[fv[3 * f + i]][c];
    return r;
  }

  VIM vim;
  FIM fim;
  HIM him;
  std::vector<vertex_descriptor> vertex_of;
  std::vector<face_descriptor> face_of;
  std::vector<char> valid_face;
  std::vector<std::array<double, 3> > pos;
  std::vector<int> fv;     // 3f+k -> vertex of corner k
  std::vector<int> fadj;   // 3f+k -> slot of the twin edge in the neighbor face (-1 on border)
  std::vector<int> fedge;  // 3f+k -> undirected edge index
  std::vector<halfedge_descriptor> slot_halfedge;
  std::vector<double> elen;   // per undirected edge
  std::vector<Vec2> apex;     // 3f+k -> corner k+2 in the frame of edge k
  std::vector<double> flayout;  // 3f + {0,1,2} -> |v0v1|, x2, y2
  std::vector<Vec2> edge_dir;   // 3f+k -> unit direction of edge k in the face frame
  std::vector<int> vf_start, vf_list;  // vertex -> slots 3f+corner
  std::vector<char> pseudo;  // saddle or border vertex
  int num_edges = 0;
  double diag = 1.;
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_GEODESIC_INTERNAL_INDEXED_TRIANGLE_MESH_H
