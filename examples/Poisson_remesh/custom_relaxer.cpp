// custom_relaxer [MESH] -- a user model of the Relaxer concept (doc/Poisson_remesh/Concepts/Relaxer.h).
//
// The remesher hands the relaxer the input, the mesh to improve and what it knows of it as
// property maps (feature edges, fixed vertices, the sampling density). This one is plain
// tangential smoothing: each free vertex that is on no feature edge moves to the density-weighted
// mean of its neighbours, then back onto the input (CGAL's AABB tree), a few rounds.
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

struct Smoothing_relaxer
{
  template <class InputMesh, class InputVPM, class M, class IsFeature, class IsFixed, class Density, class NewVertex>
  PR::Relaxation_statistics relax(const InputMesh& input, InputVPM input_vpm, M& mesh, IsFeature is_feature, IsFixed is_fixed,
                                  Density density, unsigned int iterations, NewVertex) const
  {
    typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<InputMesh, InputVPM>>> Tree;
    Tree tree(faces(input).first, faces(input).second, input, input_vpm);
    tree.accelerate_distance_queries();
    PR::Relaxation_statistics stats;
    auto vpm = get(CGAL::vertex_point, mesh);
    for(unsigned int round = 0; round < iterations; ++round)
      for(auto v : vertices(mesh)) {
        if(get(is_fixed, v) || CGAL::is_border(v, mesh)) continue;
        bool on_feature = false;
        for(auto h : CGAL::halfedges_around_target(v, mesh)) on_feature = on_feature || get(is_feature, edge(h, mesh));
        if(on_feature) continue;
        K::Vector_3 sum = CGAL::NULL_VECTOR;
        double weight = 0;
        for(auto w : CGAL::vertices_around_target(halfedge(v, mesh), mesh)) {
          sum = sum + get(density, w) * (get(vpm, w) - CGAL::ORIGIN);
          weight += get(density, w);
        }
        put(vpm, v, tree.closest_point(CGAL::ORIGIN + sum / weight));
        ++stats.moves;
      }
    return stats;
  }
};

int main(int argc, char** argv)
{
  const std::string file = argc > 1 ? argv[1] : std::string(POISSON_REMESH_DATA_DIR) + "/meshes/elephant.off";
  Mesh input, output;
  try {
    PR::read_surface_mesh(file, input);
  } catch(const PR::Input_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  const PR::Poisson_remesh_result run =
    PR::poisson_remesh(input, output, PR::parameters::target_vertex_count(1500).relaxer(Smoothing_relaxer()).number_of_iterations(3u));
  const PR::Quality_report q = PR::quality_report(output, input);
  std::cout << run.relaxation.moves << " moves of the user's relaxer; " << q.number_of_vertices << " vertices, min angle "
            << q.min_angle << ", mean min angle " << q.mean_min_angle << ", Hausdorff " << *q.hausdorff << "\n";
  return run.relaxation.moves > 0 && CGAL::is_valid_polygon_mesh(output) ? 0 : 1;
}
