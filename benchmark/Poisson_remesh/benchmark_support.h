// benchmark_support.h -- what the benchmark programs share: the process's peak memory, the
// machine's description, a comma-separated list, a number printed with fixed digits, a child
// process's "key value" report, and the RMS distance between two surfaces.
#ifndef POISSON_REMESH_BENCHMARK_SUPPORT_H
#define POISSON_REMESH_BENCHMARK_SUPPORT_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>   // (before distance.h: its calls need the kernel's functions)
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Random.h>
#include <CGAL/version.h>

#include <sys/utsname.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace benchmark_support {

// the resident-set peak of this process (VmHWM), in MiB; writing "5" to /proc/self/clear_refs
// resets it
inline double peak_memory_mib()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while(std::getline(status, line))
    if(line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0;
}

// CPU, cores, system, CGAL and compiler
inline std::string machine_description()
{
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  std::string line;
  while(std::getline(info, line))
    if(line.rfind("model name", 0) == 0) { cpu = line.substr(line.find(':') + 2); break; }
  struct utsname u;
  uname(&u);
  std::ostringstream os;
  os << cpu << ", " << sysconf(_SC_NPROCESSORS_ONLN) << " cores, " << u.sysname << " " << u.release << " " << u.machine
     << ", CGAL " << CGAL_VERSION_STR << ", g++ " << __VERSION__;
  return os.str();
}

// "a,b,c" -> {a, b, c} (empty items dropped)
inline std::vector<std::string> split(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while(std::getline(ss, item, ',')) if(!item.empty()) out.push_back(item);
  return out;
}

// x with `digits` digits after the point
inline std::string fmt(double x, int digits)
{
  char b[64];
  std::snprintf(b, sizeof(b), "%.*f", digits, x);
  return b;
}

// "key value" lines -> map; the value of the key "error" (the rest of its line) goes to `error`
inline std::map<std::string, double> parse_report(const std::string& text, std::string& error)
{
  std::istringstream is(text);
  std::string key;
  std::map<std::string, double> v;
  while(is >> key) {
    if(key == "error") { std::getline(is, error); continue; }
    is >> v[key];
  }
  return v;
}

// the RMS distance between surfaces `a` and `b`, both ways: over 30,000 uniform random points on
// each (fixed seeds: the same points for the same meshes in every run), the squared distance to
// the other surface (CGAL's AABB tree), averaged over both sets
template <class Mesh>
double two_sided_rms_distance(const Mesh& a, const Mesh& b)
{
  typedef typename boost::property_traits<typename boost::property_map<Mesh, CGAL::vertex_point_t>::const_type>::value_type Point_3;
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel K;
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  double sq = 0;
  std::size_t count = 0;
  for(int side = 0; side < 2; ++side) {
    const Mesh& from = side ? b : a;
    const Mesh& to = side ? a : b;
    CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> tree(faces(to).first, faces(to).second, to);
    tree.accelerate_distance_queries();
    std::vector<Point_3> points;
    // (CGAL 5.5's sampler draws the triangles with random_seed's generator but the point inside
    // each triangle with CGAL's default one, seeded by the clock: that one is seeded too, or the
    // figure moves by about 1% from run to run)
    CGAL::get_default_random() = CGAL::Random(7 + side);
    CGAL::Polygon_mesh_processing::sample_triangle_mesh(
      from, std::back_inserter(points),
      CGAL::parameters::use_random_uniform_sampling(true).number_of_points_on_faces(30000).do_sample_vertices(false).do_sample_edges(false).random_seed(7));
    for(const auto& p : points) { sq += CGAL::to_double(tree.squared_distance(p)); ++count; }
  }
  return count ? std::sqrt(sq / double(count)) : 0;
}

} // namespace benchmark_support

#endif // POISSON_REMESH_BENCHMARK_SUPPORT_H
