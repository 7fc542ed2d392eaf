// make_scale_series -- writes one surface at several sizes, for the scale benchmark (issue 7):
// the input simplified by edge collapse (Lindstrom-Turk) to smaller face counts, the input
// itself, and the input refined by Loop subdivision (4x the faces per step).
//
// usage: make_scale_series IN OUTDIR [--simplify F1,F2,...] [--subdivide K]
//   writes OUTDIR/NAME_fN.off for each size (N = number of faces) and prints the paths, one a line.
// Defaults: --simplify 10000,30000 --subdivide 2 (bunny00: 10k, 30k, 75k, 302k, 1.21M faces).
#include <Poisson_remesh/read_surface_mesh.h>
#include <Poisson_remesh/write_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;
namespace SMS = CGAL::Surface_mesh_simplification;

static std::vector<std::size_t> split_sizes(const std::string& s)
{
  std::vector<std::size_t> out;
  std::stringstream ss(s);
  std::string item;
  while(std::getline(ss, item, ',')) if(!item.empty()) out.push_back(std::stoul(item));
  return out;
}

int main(int argc, char** argv)
{
  if(argc < 3) {
    std::cerr << "usage: make_scale_series IN OUTDIR [--simplify F1,F2,...] [--subdivide K]\n";
    return 2;
  }
  const std::string in_file = argv[1], out_dir = argv[2];
  std::vector<std::size_t> simplify = {10000, 30000};
  int subdivide = 2;
  for(int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if(i + 1 >= argc) { std::cerr << "make_scale_series: " << a << " needs a value\n"; return 2; }
    if(a == "--simplify") simplify = split_sizes(argv[++i]);
    else if(a == "--subdivide") subdivide = std::stoi(argv[++i]);
    else { std::cerr << "make_scale_series: unknown option " << a << "\n"; return 2; }
  }
  try {
    Mesh input;
    PR::read_surface_mesh(in_file, input);
    std::filesystem::create_directories(out_dir);
    const std::string stem = std::filesystem::path(in_file).stem().string();
    auto save = [&](const Mesh& m) {
      const std::string path = out_dir + "/" + stem + "_f" + std::to_string(num_faces(m)) + ".off";
      PR::write_surface_mesh(path, m);
      std::cout << path << "\n";
    };
    for(std::size_t faces : simplify) {
      if(faces >= num_faces(input)) continue;
      Mesh m = input;
      SMS::Count_stop_predicate<Mesh> stop(faces * 3 / 2); // counts edges: 3F/2 on a closed mesh
      SMS::edge_collapse(m, stop);
      m.collect_garbage();
      save(m);
    }
    save(input);
    Mesh m = input;
    for(int k = 0; k < subdivide; ++k) {
      CGAL::Subdivision_method_3::Loop_subdivision(m, CGAL::parameters::number_of_iterations(1));
      save(m);
    }
  } catch(const std::exception& e) {
    std::cerr << "make_scale_series: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
