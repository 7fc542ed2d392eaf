// remesh_with_given_vertices [MESH] -- the tessellation and relaxation around the user's own
// vertices, through a user model of the Sampler concept (doc/Poisson_remesh/Concepts/Sampler.h).
//
// The user's vertices here: every fourth vertex of the input, plus the input's corners (so that
// the features are kept). The sampler locates them on the input; poisson_remesh() tessellates and
// relaxes around them.
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

struct Every_fourth_vertex
{
  template <class TriangleMesh, class VPM, class OutputIterator>
  PR::Poisson_disk_sampling_result operator()(const TriangleMesh& tm, VPM vpm, const PR::Feature_set<TriangleMesh>& features,
                                              double radius, const std::vector<double>&, unsigned int, OutputIterator out) const
  {
    typedef typename boost::property_traits<VPM>::value_type Point;
    PR::Poisson_disk_sampling_result result;
    result.radius = result.min_radius = result.max_radius = radius;
    std::size_t i = 0;
    for(auto v : vertices(tm)) {
      const bool corner = features.is_corner(v);
      if(!corner && i++ % 4 != 0) continue;
      // a vertex as a location: the target of one of its halfedges inside a face
      auto h = halfedge(v, tm);
      if(is_border(h, tm)) h = prev(opposite(h, tm), tm);
      PR::Poisson_sample<TriangleMesh, Point> s;
      s.location = PR::location_on_halfedge(h, 1.0, tm);
      s.point = get(vpm, v);
      s.kind = corner ? PR::Sample_kind::corner : PR::Sample_kind::surface;
      *out++ = s;
      ++result.number_of_samples;
      if(corner) ++result.number_of_corners;
    }
    return result;
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
  const PR::Poisson_remesh_result run = PR::poisson_remesh(input, output, PR::parameters::sampler(Every_fourth_vertex()));
  const PR::Quality_report q = PR::quality_report(output, input);
  std::cout << input.number_of_vertices() << " input vertices, " << run.sampling.number_of_samples << " given ("
            << run.sampling.number_of_corners << " corners); output: " << q.number_of_vertices << " vertices, min angle "
            << q.min_angle << ", mean min angle " << q.mean_min_angle << ", Hausdorff " << *q.hausdorff << "\n";
  return CGAL::is_valid_polygon_mesh(output) && q.euler_characteristic == PR::quality_report(input).euler_characteristic ? 0 : 1;
}
