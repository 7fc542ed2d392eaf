// Small analytic test meshes generated in code (plane patch, cylinder, cone, sphere, torus, cube,
// and the zero set of an implicit function extracted on a grid), for any MutableFaceGraph. Their exact areas, topologies and geodesics are known in closed form.
#ifndef POISSON_REMESH_TEST_ANALYTIC_MESHES_H
#define POISSON_REMESH_TEST_ANALYTIC_MESHES_H

#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace analytic {

struct Soup
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> triangles;

  // Adds the two triangles of quad (a, b, c, d), counter-clockwise, split along the shorter diagonal.
  void quad(std::size_t a, std::size_t b, std::size_t c, std::size_t d)
  {
    auto d2 = [&](std::size_t i, std::size_t j) {
      double s = 0;
      for(int k = 0; k < 3; ++k) s += (points[i][k] - points[j][k]) * (points[i][k] - points[j][k]);
      return s;
    };
    if(d2(a, c) <= d2(b, d)) { triangles.push_back({a, b, c}); triangles.push_back({a, c, d}); }
    else { triangles.push_back({a, b, d}); triangles.push_back({b, c, d}); }
  }

  template <class Mesh>
  Mesh to_mesh() const
  {
    typedef typename boost::property_traits<typename boost::property_map<Mesh, CGAL::vertex_point_t>::type>::value_type Point;
    std::vector<Point> pts;
    for(const auto& p : points) pts.push_back(Point(p[0], p[1], p[2]));
    Mesh m;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, triangles, m);
    return m;
  }
};

/// Grid of nx by ny quads on [0, sx] x [0, sy] in the plane z = 0 (open, one border).
inline Soup plane(std::size_t nx, std::size_t ny, double sx = 1, double sy = 1)
{
  Soup s;
  for(std::size_t j = 0; j <= ny; ++j)
    for(std::size_t i = 0; i <= nx; ++i) s.points.push_back({sx * double(i) / double(nx), sy * double(j) / double(ny), 0});
  auto id = [&](std::size_t i, std::size_t j) { return j * (nx + 1) + i; };
  for(std::size_t j = 0; j < ny; ++j)
    for(std::size_t i = 0; i < nx; ++i) s.quad(id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  return s;
}

/// Open cylinder of radius r around the z axis, z in [0, h], n segments around, m rings (two borders).
inline Soup cylinder(std::size_t n, std::size_t m, double r = 1, double h = 2)
{
  Soup s;
  for(std::size_t j = 0; j <= m; ++j)
    for(std::size_t i = 0; i < n; ++i) {
      const double t = 2 * M_PI * double(i) / double(n);
      s.points.push_back({r * std::cos(t), r * std::sin(t), h * double(j) / double(m)});
    }
  auto id = [&](std::size_t i, std::size_t j) { return j * n + (i % n); };
  for(std::size_t j = 0; j < m; ++j)
    for(std::size_t i = 0; i < n; ++i) s.quad(id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  return s;
}

/// Open cone with apex (0,0,h) over the circle of radius r at z = 0: n segments, m rings; apex is a vertex.
inline Soup cone(std::size_t n, std::size_t m, double r = 1, double h = 1)
{
  Soup s;
  s.points.push_back({0, 0, h});
  for(std::size_t j = 1; j <= m; ++j)
    for(std::size_t i = 0; i < n; ++i) {
      const double t = 2 * M_PI * double(i) / double(n), f = double(j) / double(m);
      s.points.push_back({f * r * std::cos(t), f * r * std::sin(t), h * (1 - f)});
    }
  auto id = [&](std::size_t i, std::size_t j) { return 1 + (j - 1) * n + (i % n); };
  for(std::size_t i = 0; i < n; ++i) s.triangles.push_back({0, id(i, 1), id(i + 1, 1)});
  for(std::size_t j = 1; j < m; ++j)
    for(std::size_t i = 0; i < n; ++i) s.quad(id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
  return s;
}

/// UV sphere of radius r (closed, genus 0): n segments around, m stacks.
inline Soup sphere(std::size_t n, std::size_t m, double r = 1)
{
  Soup s;
  s.points.push_back({0, 0, r});
  for(std::size_t j = 1; j < m; ++j)
    for(std::size_t i = 0; i < n; ++i) {
      const double phi = M_PI * double(j) / double(m), t = 2 * M_PI * double(i) / double(n);
      s.points.push_back({r * std::sin(phi) * std::cos(t), r * std::sin(phi) * std::sin(t), r * std::cos(phi)});
    }
  s.points.push_back({0, 0, -r});
  const std::size_t south = s.points.size() - 1;
  auto id = [&](std::size_t i, std::size_t j) { return 1 + (j - 1) * n + (i % n); };
  for(std::size_t i = 0; i < n; ++i) s.triangles.push_back({0, id(i, 1), id(i + 1, 1)});
  for(std::size_t j = 1; j + 1 < m; ++j)
    for(std::size_t i = 0; i < n; ++i) s.quad(id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
  for(std::size_t i = 0; i < n; ++i) s.triangles.push_back({south, id(i + 1, m - 1), id(i, m - 1)});
  return s;
}

/// Torus (closed, genus 1) with radii R > r, n segments around the axis, m around the tube.
inline Soup torus(std::size_t n, std::size_t m, double R = 2, double r = 0.7)
{
  Soup s;
  for(std::size_t j = 0; j < m; ++j)
    for(std::size_t i = 0; i < n; ++i) {
      const double u = 2 * M_PI * double(i) / double(n), v = 2 * M_PI * double(j) / double(m);
      s.points.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](std::size_t i, std::size_t j) { return (j % m) * n + (i % n); };
  for(std::size_t j = 0; j < m; ++j)
    for(std::size_t i = 0; i < n; ++i) s.quad(id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  return s;
}

/// Cube [0, a]^3 with each face an n by n grid (closed, genus 0, 12 sharp edges, 8 corners).
inline Soup cube(std::size_t n, double a = 1)
{
  Soup s;
  // six faces, each given by an origin and two axis vectors with outward normal u x v
  const double F[6][9] = {
    {0, 0, 0, 0, 1, 0, 1, 0, 0}, {0, 0, a, 1, 0, 0, 0, 1, 0},   // z = 0 (normal -z), z = a (+z)
    {0, 0, 0, 1, 0, 0, 0, 0, 1}, {0, a, 0, 0, 0, 1, 1, 0, 0},   // y = 0 (-y), y = a (+y)
    {0, 0, 0, 0, 0, 1, 0, 1, 0}, {a, 0, 0, 0, 1, 0, 0, 0, 1}};  // x = 0 (-x), x = a (+x)
  // Shared points along edges are merged by coordinates.
  auto add = [&](double x, double y, double z) {
    for(std::size_t k = 0; k < s.points.size(); ++k)
      if(std::abs(s.points[k][0] - x) + std::abs(s.points[k][1] - y) + std::abs(s.points[k][2] - z) < 1e-12 * a) return k;
    s.points.push_back({x, y, z});
    return s.points.size() - 1;
  };
  for(const auto& f : F) {
    std::vector<std::size_t> ids;
    for(std::size_t j = 0; j <= n; ++j)
      for(std::size_t i = 0; i <= n; ++i) {
        const double u = a * double(i) / double(n), v = a * double(j) / double(n);
        ids.push_back(add(f[0] + u * f[3] + v * f[6], f[1] + u * f[4] + v * f[7], f[2] + u * f[5] + v * f[8]));
      }
    auto id = [&](std::size_t i, std::size_t j) { return ids[j * (n + 1) + i]; };
    for(std::size_t j = 0; j < n; ++j)
      for(std::size_t i = 0; i < n; ++i) s.quad(id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  }
  return s;
}

/// The surface f = 0 of an implicit function, extracted on an n x n x n grid over the box [lo, hi]^3
/// the way marching cubes does it, with each grid cell split into six tetrahedra (Kuhn's split, which
/// conforms across cells) so that no case table is needed: one vertex per grid edge the surface
/// crosses (linear interpolation), shared by the cells around that edge. The output has the defects
/// of marching-cubes meshes: needle and cap triangles, vertices almost on top of each other where
/// the surface passes near a grid point, valences from 3 to 12. Closed if f > 0 on the box's
/// boundary; oriented with normals towards f > 0.
template <class F>
Soup iso_surface(const F& f, double lo, double hi, std::size_t n)
{
  Soup s;
  const double h = (hi - lo) / double(n);
  const std::size_t m = n + 1;
  std::vector<double> value(m * m * m);
  auto gid = [&](std::size_t i, std::size_t j, std::size_t k) { return (k * m + j) * m + i; };
  auto pos = [&](std::size_t g, int c) {
    const std::size_t idx[3] = {g % m, (g / m) % m, g / (m * m)};
    return lo + h * double(idx[c]);
  };
  for(std::size_t k = 0; k < m; ++k)
    for(std::size_t j = 0; j < m; ++j)
      for(std::size_t i = 0; i < m; ++i) {
        double v = f(lo + h * double(i), lo + h * double(j), lo + h * double(k));
        if(std::abs(v) < 1e-12) v = 1e-12; // no grid point exactly on the surface: no zero-area faces
        value[gid(i, j, k)] = v;
      }
  std::unordered_map<std::uint64_t, std::size_t> on_edge;
  auto crossing = [&](std::size_t a, std::size_t b) {
    if(a > b) std::swap(a, b);
    const std::uint64_t key = std::uint64_t(a) * std::uint64_t(m * m * m) + b;
    auto it = on_edge.find(key);
    if(it != on_edge.end()) return it->second;
    const double t = value[a] / (value[a] - value[b]);
    s.points.push_back({pos(a, 0) + t * (pos(b, 0) - pos(a, 0)), pos(a, 1) + t * (pos(b, 1) - pos(a, 1)),
                        pos(a, 2) + t * (pos(b, 2) - pos(a, 2))});
    on_edge.emplace(key, s.points.size() - 1);
    return s.points.size() - 1;
  };
  // a triangle of crossings, turned so that its normal points from `in` towards `out`
  auto triangle = [&](std::size_t p, std::size_t q, std::size_t r, const double dir[3]) {
    const auto &P = s.points[p], &Q = s.points[q], &R = s.points[r];
    const double u[3] = {Q[0] - P[0], Q[1] - P[1], Q[2] - P[2]}, w[3] = {R[0] - P[0], R[1] - P[1], R[2] - P[2]};
    const double nrm[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    if(nrm[0] * dir[0] + nrm[1] * dir[1] + nrm[2] * dir[2] >= 0) s.triangles.push_back({p, q, r});
    else s.triangles.push_back({p, r, q});
  };
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for(std::size_t k = 0; k < n; ++k)
    for(std::size_t j = 0; j < n; ++j)
      for(std::size_t i = 0; i < n; ++i)
        for(const auto& p : perms) {
          // the tetrahedron corner, corner + e_a, corner + e_a + e_b, corner + (1,1,1)
          std::size_t c[3] = {i, j, k};
          std::size_t tet[4];
          tet[0] = gid(c[0], c[1], c[2]);
          for(int s2 = 0; s2 < 3; ++s2) { ++c[p[s2]]; tet[s2 + 1] = gid(c[0], c[1], c[2]); }
          std::vector<std::size_t> in, out;
          for(std::size_t g : tet) (value[g] < 0 ? in : out).push_back(g);
          if(in.empty() || out.empty()) continue;
          double dir[3] = {0, 0, 0};
          for(int a = 0; a < 3; ++a) {
            for(std::size_t g : out) dir[a] += pos(g, a) / double(out.size());
            for(std::size_t g : in) dir[a] -= pos(g, a) / double(in.size());
          }
          if(in.size() == 1 || out.size() == 1) {
            const std::vector<std::size_t>& one = in.size() == 1 ? in : out;
            const std::vector<std::size_t>& three = in.size() == 1 ? out : in;
            triangle(crossing(one[0], three[0]), crossing(one[0], three[1]), crossing(one[0], three[2]), dir);
          } else {
            // the quad in[0]-out[0], in[0]-out[1], in[1]-out[1], in[1]-out[0], split in two
            const std::size_t q0 = crossing(in[0], out[0]), q1 = crossing(in[0], out[1]),
                              q2 = crossing(in[1], out[1]), q3 = crossing(in[1], out[0]);
            triangle(q0, q1, q2, dir);
            triangle(q0, q2, q3, dir);
          }
        }
  return s;
}

} // namespace analytic

#endif
