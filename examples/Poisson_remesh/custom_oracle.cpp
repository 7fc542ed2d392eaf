// custom_oracle [MESH] -- plugs a user's geodesic oracle into the sampler.
//
// A model of the GeodesicOracle concept (doc/Poisson_remesh/Concepts/GeodesicOracle.h) is given
// to poisson_disk_sample() (or poisson_remesh()) with the named parameter `geodesic_oracle`. Here
// the user's oracle is the exact one, counting its propagations: a place to log, cache or replace
// what the sampler asks of the geodesics.
#include <Poisson_remesh/Geodesic/Exact_geodesic_oracle.h>
#include <Poisson_remesh/poisson_disk_sample.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>
#include <memory>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Surface;
namespace PR = Poisson_remesh;
typedef PR::Exact_geodesic_oracle<Surface> Exact_oracle;

// The sampler keeps copies of its oracle: the count is shared by them.
struct Counting_oracle : Exact_oracle
{
  using Exact_oracle::Exact_oracle;
  std::shared_ptr<std::size_t> propagations = std::make_shared<std::size_t>(0);

  template <class... Args>
  void propagate(Args&&... args)
  {
    ++*propagations;
    Exact_oracle::propagate(std::forward<Args>(args)...);
  }
};

int main(int argc, char** argv)
{
  const std::string file = argc > 1 ? argv[1] : std::string(POISSON_REMESH_DATA_DIR) + "/meshes/fandisk.off";
  Surface mesh;
  try {
    PR::read_surface_mesh(file, mesh);
  } catch(const PR::Input_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  Counting_oracle oracle(mesh);
  std::vector<PR::Poisson_sample<Surface, K::Point_3>> samples;
  const PR::Poisson_disk_sampling_result run = PR::poisson_disk_sample(mesh, std::back_inserter(samples),
    PR::parameters::target_vertex_count(2000).random_seed(1u).geodesic_oracle(oracle));
  std::cout << run.number_of_samples << " samples at spacing " << 2 * run.radius << ", "
            << *oracle.propagations << " propagations of the user's oracle\n";
  return run.number_of_samples > 0 && *oracle.propagations >= run.number_of_samples ? 0 : 1;
}
