// Example of Poisson_remesh::Exact_geodesic_oracle (exact truncated window
// propagation, paper Section 4.2.2 / Surazhsky et al. 2005).
//
// Usage:
//   geodesic_distances MESH (--source-vertex I | --source-face F --bary A B C) --radius R
//
// Prints one line "vertex_index distance" (distance with 17 significant
// digits) for every vertex at geodesic distance <= R from the source, sorted by
// vertex index, and nothing else on stdout.  Errors go to stderr, with a
// non-zero exit status.

#include <Poisson_remesh/Geodesic/Exact_geodesic_oracle.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Poisson_remesh::Exact_geodesic_oracle<Mesh> Oracle;

static int usage(const std::string& msg)
{
  std::cerr << "error: " << msg << "\n"
            << "usage: geodesic_distances MESH (--source-vertex I | --source-face F --bary A B C) --radius R\n";
  return 2;
}

static bool parse_double(const char* s, double& x)
{
  char* end = nullptr;
  x = std::strtod(s, &end);
  return end != s && *end == '\0' && std::isfinite(x);
}

static bool parse_index(const char* s, long& x)
{
  char* end = nullptr;
  x = std::strtol(s, &end, 10);
  return end != s && *end == '\0' && x >= 0;
}

int main(int argc, char** argv)
{
  if(argc < 2) return usage("missing arguments");
  std::string mesh_path;
  long source_vertex = -1, source_face = -1;
  double bary[3] = {0., 0., 0.};
  bool has_bary = false, has_radius = false;
  double radius = 0.;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--source-vertex")
    {
      if(i + 1 >= argc || !parse_index(argv[++i], source_vertex)) return usage("--source-vertex expects a non-negative integer");
    }
    else if(a == "--source-face")
    {
      if(i + 1 >= argc || !parse_index(argv[++i], source_face)) return usage("--source-face expects a non-negative integer");
    }
    else if(a == "--bary")
    {
      if(i + 3 >= argc) return usage("--bary expects three numbers");
      for(int k = 0; k < 3; ++k)
        if(!parse_double(argv[++i], bary[k])) return usage("--bary expects three numbers");
      has_bary = true;
    }
    else if(a == "--radius")
    {
      if(i + 1 >= argc || !parse_double(argv[++i], radius) || radius < 0.)
        return usage("--radius expects a non-negative number");
      has_radius = true;
    }
    else if(!a.empty() && a[0] == '-')
      return usage("unknown option '" + a + "'");
    else if(mesh_path.empty())
      mesh_path = a;
    else
      return usage("more than one mesh given");
  }
  if(mesh_path.empty()) return usage("no mesh given");
  if(!has_radius) return usage("--radius is required");
  if((source_vertex >= 0) == (source_face >= 0)) return usage("give exactly one of --source-vertex and --source-face");
  if(source_face >= 0 && !has_bary) return usage("--source-face requires --bary A B C");
  if(source_vertex >= 0 && has_bary) return usage("--bary is only valid with --source-face");

  Mesh mesh;
  try
  {
    // the package's reader: validation with clear messages; vertex indices are the file's
    Poisson_remesh::read_surface_mesh(mesh_path, mesh);
  }
  catch(const Poisson_remesh::Input_error& e)
  {
    std::cerr << "geodesic_distances: " << e.what() << "\n";
    return 1;
  }

  Oracle::Face_location source;
  if(source_vertex >= 0)
  {
    if(std::size_t(source_vertex) >= num_vertices(mesh))
    {
      std::cerr << "error: vertex index " << source_vertex << " out of range [0, " << num_vertices(mesh) << ")\n";
      return 2;
    }
    const Mesh::Vertex_index v(static_cast<Mesh::size_type>(source_vertex));
    if(halfedge(v, mesh) == Mesh::null_halfedge())
    {
      std::cerr << "error: vertex " << source_vertex << " is isolated\n";
      return 2;
    }
    source = CGAL::Polygon_mesh_processing::locate_vertex<double>(v, mesh);
  }
  else
  {
    if(std::size_t(source_face) >= num_faces(mesh))
    {
      std::cerr << "error: face index " << source_face << " out of range [0, " << num_faces(mesh) << ")\n";
      return 2;
    }
    const double s = bary[0] + bary[1] + bary[2];
    if(bary[0] < 0. || bary[1] < 0. || bary[2] < 0. || !(s > 0.))
    {
      std::cerr << "error: barycentric coordinates must be non-negative with a positive sum\n";
      return 2;
    }
    source = Oracle::Face_location(Mesh::Face_index(static_cast<Mesh::size_type>(source_face)),
                                   {{bary[0] / s, bary[1] / s, bary[2] / s}});
  }

  Oracle oracle(mesh);
  oracle.propagate(source, radius);
  std::vector<std::pair<Mesh::Vertex_index, double> > reached;
  oracle.reached_vertices(std::back_inserter(reached));
  std::sort(reached.begin(), reached.end());
  for(const auto& vd : reached) std::printf("%u %.17g\n", static_cast<unsigned>(vd.first), vd.second);
  return 0;
}
