// libFuzzer target: the mesh reader and its validation (issue 7).
// The first byte chooses the format; the rest is the file's content. A bad file must end in a
// Poisson_remesh::Input_error (a clear message), never in a crash, a hang or another exception;
// a file that is accepted must give a valid, closed-or-bordered triangle mesh with finite points.
// Build and run: scripts/fuzz.sh (see doc/Poisson_remesh/Poisson_remesh.md, "Fuzzing").
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(size == 0) return 0;
  static const char* extensions[] = {"off", "obj", "ply", "stl"};
  const std::string path = "/tmp/poisson_remesh_fuzz_" + std::to_string(getpid()) + "." + extensions[data[0] % 4];
  {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
  }
  Mesh m;
  try {
    Poisson_remesh::read_surface_mesh(path, m);
  } catch(const Poisson_remesh::Input_error&) {
    std::remove(path.c_str());
    return 0;   // refused with a clear message: fine
  }
  std::remove(path.c_str());
  // accepted: a valid triangle mesh with finite coordinates
  if(!CGAL::is_valid_polygon_mesh(m) || !CGAL::is_triangle_mesh(m) || faces(m).empty()) std::abort();
  for(auto v : vertices(m)) {
    const K::Point_3& p = m.point(v);
    if(!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) std::abort();
  }
  return 0;
}
