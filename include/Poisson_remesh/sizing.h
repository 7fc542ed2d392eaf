// Poisson_remesh/sizing.h
//
// Relations between a target vertex count, an edge length and the Poisson-disk radius.
// An ideal isotropic mesh of a closed surface of area A with V vertices has about 2V
// equilateral triangles of side L, so A = 2V * (sqrt(3)/4) L^2, i.e. L = sqrt(2A / (sqrt(3) V)).
// The Poisson-disk radius (paper §4.2.1, Eq. 1) is r = rho * sqrt(1 / (2 sqrt(3) N)) for N points
// per unit area, with rho calibrated in §7 (0.844).

#ifndef POISSON_REMESH_SIZING_H
#define POISSON_REMESH_SIZING_H

#include <cmath>
#include <stdexcept>

namespace Poisson_remesh {

/// The paper's calibrated ratio between the Poisson-disk radius and the densest packing radius (§7).
constexpr double paper_rho = 0.844;

/// Edge length of an ideal isotropic mesh with `vertex_count` vertices on a surface of area `area`.
inline double edge_length_from_vertex_count(double area, double vertex_count)
{
  if(!(area > 0) || !(vertex_count > 0))
    throw std::invalid_argument("edge_length_from_vertex_count: area and vertex count must be positive");
  return std::sqrt(2.0 * area / (std::sqrt(3.0) * vertex_count));
}

/// Inverse of edge_length_from_vertex_count().
inline double vertex_count_from_edge_length(double area, double edge_length)
{
  if(!(area > 0) || !(edge_length > 0))
    throw std::invalid_argument("vertex_count_from_edge_length: area and edge length must be positive");
  return 2.0 * area / (std::sqrt(3.0) * edge_length * edge_length);
}

/// Eq. 1: the expellant-disk radius r for `vertex_count` points on a surface of area `area`.
inline double disk_radius_from_vertex_count(double area, double vertex_count, double rho = paper_rho)
{
  if(!(area > 0) || !(vertex_count > 0))
    throw std::invalid_argument("disk_radius_from_vertex_count: area and vertex count must be positive");
  return rho * std::sqrt(1.0 / (2.0 * std::sqrt(3.0) * (vertex_count / area)));
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_SIZING_H
