// remesh_polyhedron [MESH] -- the remesher on CGAL::Polyhedron_3, as any FaceGraph.
//
// A plain Polyhedron_3 (its items have no ids: the package makes its own index maps), remeshed
// into another Polyhedron_3; then a Surface_mesh remeshed into a Polyhedron_3 (input and output
// may be of different types), read through a user vertex_point_map that scales it.
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Polyhedron_3<K> Polyhedron;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

int main(int argc, char** argv)
{
  const std::string file = argc > 1 ? argv[1] : std::string(POISSON_REMESH_DATA_DIR) + "/meshes/elephant.off";
  Polyhedron input, output;
  Mesh sm;
  try {
    PR::read_surface_mesh(file, input);
    PR::read_surface_mesh(file, sm);
  } catch(const PR::Input_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  PR::poisson_remesh(input, output, PR::parameters::target_vertex_count(1500).random_seed(1u));
  const PR::Quality_report q = PR::quality_report(output, input);
  std::cout << "Polyhedron_3 -> Polyhedron_3: " << q.number_of_vertices << " vertices, min angle " << q.min_angle
            << ", mean min angle " << q.mean_min_angle << ", Hausdorff " << *q.hausdorff << " of the diagonal\n";

  // Surface_mesh in, Polyhedron_3 out, the input read through a point map that doubles it
  auto doubled = sm.add_property_map<Mesh::Vertex_index, K::Point_3>("v:doubled").first;
  for(auto v : vertices(sm)) put(doubled, v, CGAL::ORIGIN + 2 * (sm.point(v) - CGAL::ORIGIN));
  Polyhedron big;
  PR::poisson_remesh(sm, big, PR::parameters::target_vertex_count(1500).random_seed(1u).vertex_point_map(doubled));
  const PR::Quality_report b = PR::quality_report(big);
  std::cout << "Surface_mesh (doubled by its point map) -> Polyhedron_3: " << b.number_of_vertices
            << " vertices, bounding-box diagonal " << b.bbox_diagonal << " (the input's: "
            << PR::quality_report(sm, PR::parameters::vertex_point_map(doubled)).bbox_diagonal << ")\n";
  return q.min_angle > 20 && CGAL::is_closed(big) ? 0 : 1;
}
