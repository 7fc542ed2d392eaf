// Small analytic test meshes generated in code (plane patch, cylinder, cone, sphere, torus, cube),
// for any MutableFaceGraph. Their exact areas, topologies and geodesics are known in closed form.
#ifndef POISSON_REMESH_TEST_ANALYTIC_MESHES_H
#define POISSON_REMESH_TEST_ANALYTIC_MESHES_H

#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <cmath>
#include <cstddef>
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

} // namespace analytic

#endif
