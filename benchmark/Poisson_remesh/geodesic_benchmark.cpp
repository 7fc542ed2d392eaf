// Benchmark of Poisson_remesh::Exact_geodesic_oracle (truncated exact window
// propagation, paper Section 4.2.2) against CGAL::Surface_mesh_shortest_path
// (exact, untruncated: it builds its sequence tree over the whole mesh).
//
// Usage: geodesic_benchmark [MESH] [--target-faces N] [--sources K] [--cgal-sources C]
//   MESH defaults to CGAL's meshes/fandisk.off (POISSON_REMESH_DATA_DIR), which
//   is Loop-subdivided until it has about N faces (default 50000).
// For disks covering 0.1%, 0.3%, 1%, 3%, 10% of the surface area (pi R^2),
// prints a Markdown table: R, % area, faces in disk, ms per truncated
// propagation (average over K random vertex / face-interior sources), ms of
// CGAL for the same source (sequence tree + distance queries of the vertices
// in the disk, average over the first C sources, default 2), speed-up CGAL / ours and the
// largest difference between the two on these vertices, and the time of
// extracting the iso-curve at R after the propagation.  A last row gives
// the untruncated propagation over the whole mesh (average over 10 sources).

#include <Poisson_remesh/Geodesic/Exact_geodesic_oracle.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Poisson_remesh::Exact_geodesic_oracle<Mesh> Oracle;
typedef CGAL::Surface_mesh_shortest_path_traits<K, Mesh> SMSP_traits;
typedef CGAL::Surface_mesh_shortest_path<SMSP_traits> SMSP;
typedef std::chrono::steady_clock Clock;

static double ms_since(Clock::time_point t)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

int main(int argc, char** argv)
{
  std::string path;
#ifdef POISSON_REMESH_DATA_DIR
  path = std::string(POISSON_REMESH_DATA_DIR) + "/meshes/fandisk.off";
#endif
  std::size_t target_faces = 50000;
  int n_sources = 200, n_cgal = 2;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--target-faces" && i + 1 < argc) target_faces = std::size_t(std::atol(argv[++i]));
    else if(a == "--sources" && i + 1 < argc) n_sources = std::atoi(argv[++i]);
    else if(a == "--cgal-sources" && i + 1 < argc) n_cgal = std::atoi(argv[++i]);
    else if(!a.empty() && a[0] != '-') path = a;
    else
    {
      std::cerr << "usage: geodesic_benchmark [MESH] [--target-faces N] [--sources K] [--cgal-sources C]\n";
      return 1;
    }
  }
  if(path.empty())
  {
    std::cerr << "error: no mesh given (and POISSON_REMESH_DATA_DIR not defined)\n";
    return 1;
  }
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(path, mesh) || !CGAL::is_triangle_mesh(mesh) || num_faces(mesh) == 0)
  {
    std::cerr << "error: cannot read a triangle mesh from '" << path << "'\n";
    return 2;
  }
  while(target_faces > 0 && 4 * num_faces(mesh) <= (3 * target_faces) / 2)
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(1));
  n_cgal = (std::min)(n_cgal, n_sources);

  const double area = CGAL::Polygon_mesh_processing::area(mesh);
  std::cout << "mesh: " << path << " (" << num_vertices(mesh) << " vertices, " << num_faces(mesh)
            << " faces), area " << area << "\n";

  const auto t_build = Clock::now();
  Oracle oracle(mesh);
  std::cout << "oracle construction: " << ms_since(t_build) << " ms\n\n";

  // deterministic sources: alternately vertices and face-interior points
  std::mt19937 rng(42);
  std::vector<Oracle::Face_location> sources;
  for(int i = 0; i < n_sources; ++i)
  {
    if(i % 2 == 0)
      sources.push_back(CGAL::Polygon_mesh_processing::locate_vertex<double>(
          Mesh::Vertex_index(Mesh::size_type(rng() % num_vertices(mesh))), mesh));
    else
    {
      std::uniform_real_distribution<double> u(0.05, 1.);
      const double a = u(rng), b = u(rng), c = u(rng), s = a + b + c;
      sources.push_back(Oracle::Face_location(Mesh::Face_index(Mesh::size_type(rng() % num_faces(mesh))),
                                              {{a / s, b / s, c / s}}));
    }
  }

  // the last row is an untruncated propagation over the whole mesh (R = infinity)
  const int NR = 6;
  const double fractions[NR] = {0.001, 0.003, 0.01, 0.03, 0.1, std::numeric_limits<double>::infinity()};
  double radii[NR], ours_ms[NR], faces_in_disk[NR], cgal_ms[NR], max_diff[NR], iso_ms[NR];
  std::vector<char> inside(num_vertices(mesh), 0);
  for(int r = 0; r < NR; ++r)
  {
    const double R = radii[r] = std::sqrt(fractions[r] * area / CGAL_PI);
    // our truncated propagation (only a few sources for the whole-mesh row)
    const std::size_t ns = std::isfinite(R) ? sources.size() : (std::min)(sources.size(), std::size_t(10));
    const auto t0 = Clock::now();
    for(std::size_t i = 0; i < ns; ++i) oracle.propagate(sources[i], R);
    ours_ms[r] = ms_since(t0) / double(ns);
    // statistics (outside the timing): faces whose three vertices are within R
    faces_in_disk[r] = 0.;
    iso_ms[r] = 0.;
    for(std::size_t i = 0; i < ns; ++i)
    {
      oracle.propagate(sources[i], R);
      if(std::isfinite(R))
      {
        const auto ti = Clock::now();
        const std::vector<Oracle::Iso_curve> curves = oracle.iso_curve(R);
        iso_ms[r] += ms_since(ti);
      }
      std::vector<std::pair<Mesh::Vertex_index, double> > reached;
      oracle.reached_vertices(std::back_inserter(reached));
      for(const auto& vd : reached) inside[std::size_t(vd.first)] = 1;
      for(Mesh::Face_index f : faces(mesh))
      {
        bool all = true;
        for(Mesh::Vertex_index v : vertices_around_face(halfedge(f, mesh), mesh)) all = all && inside[std::size_t(v)];
        if(all) faces_in_disk[r] += 1.;
      }
      for(const auto& vd : reached) inside[std::size_t(vd.first)] = 0;
    }
    faces_in_disk[r] /= double(ns);
    iso_ms[r] /= double(ns);
    cgal_ms[r] = 0.;
    max_diff[r] = 0.;
  }
  // CGAL on the first sources.  Its sequence tree covers the whole mesh and
  // does not depend on R: it is built (and timed) once per source; the time of
  // querying the vertices inside each disk is added per radius.
  for(int i = 0; i < n_cgal; ++i)
  {
    const Oracle::Face_location& src = sources[std::size_t(i)];
    const auto t1 = Clock::now();
    SMSP smsp(mesh);
    smsp.add_source_point(src.first, SMSP::Barycentric_coordinates{{src.second[0], src.second[1], src.second[2]}});
    smsp.build_sequence_tree();
    const double build_ms = ms_since(t1);
    for(int r = 0; r < NR; ++r)
    {
      oracle.propagate(src, radii[r]);
      std::vector<std::pair<Mesh::Vertex_index, double> > reached;
      oracle.reached_vertices(std::back_inserter(reached));
      std::vector<double> ref;
      ref.reserve(reached.size());
      const auto t2 = Clock::now();
      for(const auto& vd : reached) ref.push_back(smsp.shortest_distance_to_source_points(vd.first).first);
      cgal_ms[r] += build_ms + ms_since(t2);
      for(std::size_t j = 0; j < reached.size(); ++j)
        max_diff[r] = (std::max)(max_diff[r], std::abs(ref[j] - reached[j].second));
    }
  }
  std::printf("| R | %% area | faces in disk | ours (ms/propagation) | CGAL SMSP (ms) | CGAL / ours | max abs(ours - CGAL) | iso_curve(R) (ms) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for(int r = 0; r < NR; ++r)
  {
    const double c = cgal_ms[r] / double((std::max)(n_cgal, 1));
    if(std::isfinite(radii[r]))
      std::printf("| %.6g | %.1f | %.0f | %.3f | %.1f | %.0f | %.2g | %.3f |\n", radii[r], 100. * fractions[r],
                  faces_in_disk[r], ours_ms[r], c, c / ours_ms[r], max_diff[r], iso_ms[r]);
    else
      std::printf("| inf (whole mesh) | 100 | %.0f | %.3f | %.1f | %.1f | %.2g | - |\n", faces_in_disk[r], ours_ms[r], c,
                  c / ours_ms[r], max_diff[r]);
  }
  return 0;
}
