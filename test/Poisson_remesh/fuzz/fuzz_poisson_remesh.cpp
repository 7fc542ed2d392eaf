// libFuzzer target: the whole pipeline on small random meshes (issue 7).
// The bytes drive a small random surface: a grid of (nx+1) x (ny+1) points bent into a plane
// patch, a cylinder or a sphere-like cap, with heights and jitter read from the input, random
// diagonal flips and possibly collapsed (degenerate) cells; then the reader's validation
// (as a file, so that degenerate input goes the user's way) and poisson_remesh() at a small
// vertex count, with uniform or (one in three) curvature-adaptive density. Refused input is fine; an accepted one must give a valid mesh with the input's
// Euler characteristic and every vertex on the input, and nothing may crash or hang.
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <string>
#include <unistd.h>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

namespace {
struct Bytes
{
  const std::uint8_t* d;
  std::size_t n, i = 0;
  unsigned next() { return i < n ? d[i++] : 0u; }
  double unit() { return next() / 255.0; }
};
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(size < 4) return 0;
  Bytes b{data, size};
  const unsigned nx = 2 + b.next() % 9, ny = 2 + b.next() % 9, shape = b.next() % 3;
  const double jitter = 0.3 * b.unit();
  std::vector<std::array<double, 3>> pts;
  for(unsigned j = 0; j <= ny; ++j)
    for(unsigned i = 0; i <= nx; ++i) {
      const double u = (i + jitter * (b.unit() - 0.5)) / nx, v = (j + jitter * (b.unit() - 0.5)) / ny;
      const double h = 0.2 * (b.unit() - 0.5);
      if(shape == 0) pts.push_back({u, v, h});
      else if(shape == 1) pts.push_back({std::cos(2 * M_PI * u) * (1 + h), std::sin(2 * M_PI * u) * (1 + h), v});
      else pts.push_back({u - 0.5, v - 0.5, 0.5 - (u - 0.5) * (u - 0.5) - (v - 0.5) * (v - 0.5) + h});
    }
  std::vector<std::array<unsigned, 3>> tris;
  auto id = [&](unsigned i, unsigned j) { return j * (nx + 1) + (shape == 1 && i == nx ? 0 : i); };
  for(unsigned j = 0; j < ny; ++j)
    for(unsigned i = 0; i < nx; ++i) {
      const unsigned a = id(i, j), c = id(i + 1, j), d = id(i + 1, j + 1), e = id(i, j + 1);
      const unsigned r = b.next();
      if(r % 17 == 0) continue;                  // a hole
      if(r % 2) { tris.push_back({a, c, d}); tris.push_back({a, d, e}); }
      else { tris.push_back({a, c, e}); tris.push_back({c, d, e}); }
    }
  if(b.next() % 5 == 0 && !pts.empty()) pts[b.next() % pts.size()] = pts[b.next() % pts.size()];   // a degenerate face or two
  const std::string path = "/tmp/poisson_remesh_fuzz_pipeline_" + std::to_string(getpid()) + ".off";
  {
    std::ofstream f(path);
    f.precision(17);
    f << "OFF\n" << pts.size() << " " << tris.size() << " 0\n";
    for(const auto& p : pts) f << p[0] << " " << p[1] << " " << p[2] << "\n";
    for(const auto& t : tris) f << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  }
  Mesh in, out;
  try {
    PR::read_surface_mesh(path, in, PR::parameters::repair_degenerate_faces(true));
  } catch(const PR::Input_error&) {
    std::remove(path.c_str());
    return 0;
  }
  if(std::getenv("POISSON_REMESH_FUZZ_VERBOSE")) std::ofstream("/tmp/poisson_remesh_fuzz_input.off") << std::setprecision(17) << in;
  std::remove(path.c_str());
  const std::size_t target = 20 + b.next() % 80;
  // one input in three with adaptive density (the conic available boundary of §5.1)
  const unsigned seed = b.next();
  const bool adaptive = b.next() % 3 == 0;
  if(std::getenv("POISSON_REMESH_FUZZ_VERBOSE")) std::fprintf(stderr, "%s density, target %zu, seed %u\n", adaptive ? "adaptive" : "uniform", target, seed);
  if(adaptive) {
    PR::Curvature_density density;
    density.smoothing = b.next() % 4;
    if(std::getenv("POISSON_REMESH_FUZZ_VERBOSE")) std::fprintf(stderr, "smoothing %u\n", density.smoothing);
    PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(target).random_seed(seed).number_of_iterations(3u).density(density));
  } else {
    PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(target).random_seed(seed).number_of_iterations(3u));
  }
  if(!CGAL::is_valid_polygon_mesh(out) || !CGAL::is_triangle_mesh(out)) std::abort();
  long used = 0;   // vertices of the surface (a grid point under a hole is left isolated)
  for(auto v : vertices(in)) if(halfedge(v, in) != Mesh::null_halfedge()) ++used;
  const long chi_in = used - long(edges(in).size()) + long(faces(in).size());
  const long chi_out = long(vertices(out).size()) - long(edges(out).size()) + long(faces(out).size());
  if(std::getenv("POISSON_REMESH_FUZZ_VERBOSE"))
    std::fprintf(stderr, "input V %zu F %zu chi %ld, output V %zu F %zu chi %ld\n", std::size_t(used), std::size_t(faces(in).size()),
                 chi_in, std::size_t(vertices(out).size()), std::size_t(faces(out).size()), chi_out);
  if(chi_in != chi_out) std::abort();
  // every output vertex on the input surface (the remesher projects onto it): within 1e-7 of the
  // input's bounding-box diagonal, measured with CGAL's AABB tree
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> tree(faces(in).first, faces(in).second, in);
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(in);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  for(auto v : vertices(out)) {
    const double d = std::sqrt(tree.squared_distance(out.point(v)));
    if(std::getenv("POISSON_REMESH_FUZZ_VERBOSE") && d > 1e-7 * diagonal)
      std::fprintf(stderr, "vertex %zu is %g (relative %g) off the input\n", std::size_t(v), d, d / diagonal);
    if(d > 1e-7 * diagonal) std::abort();
  }
  return 0;
}
