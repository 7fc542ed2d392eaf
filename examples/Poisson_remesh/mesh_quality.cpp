// mesh_quality MESH [REFERENCE] [--json] [--svg FILE] [--no-self-intersections] [--repair]
//
// Prints the quality report of MESH (Poisson_remesh::quality_report): topology, angles, shape
// quality, valences, self-intersections and, with a REFERENCE, the two-sided Hausdorff distance
// to it over the reference's bounding-box diagonal.
#include "command_line.h"

#include <Poisson_remesh/IO/write_quality_report.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>
#include <Poisson_remesh/write_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

static const char* usage =
  "usage: mesh_quality MESH [REFERENCE] [options]\n"
  "  Prints the quality of a triangle mesh (OFF, OBJ, PLY, STL): size, topology, angles,\n"
  "  Frey-Borouchaki shape quality, irregular vertices, self-intersections and, with a\n"
  "  REFERENCE mesh, the two-sided Hausdorff distance over the reference's bbox diagonal.\n"
  "options:\n"
  "  --json                    print JSON instead of the table\n"
  "  --svg FILE                write the angle histogram as an SVG picture\n"
  "  --no-self-intersections   skip the self-intersection check\n"
  "  --repair                  remove degenerate (zero-area) faces instead of refusing them\n"
  "  --help                    this text\n";

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  bool json = false, self_intersections = true, repair = false;
  std::string svg;
  try {
    cli::Arguments args(argc, argv);
    while(!args.done()) {
      const std::string a = args.next();
      if(a == "--help" || a == "-h") { std::cout << usage; return cli::ok; }
      else if(a == "--json") json = true;
      else if(a == "--svg") svg = args.value(a);
      else if(a == "--no-self-intersections") self_intersections = false;
      else if(a == "--repair") repair = true;
      else if(!a.empty() && a[0] == '-') throw cli::Usage_error("unknown option " + a);
      else files.push_back(a);
    }
    if(files.empty() || files.size() > 2) throw cli::Usage_error("give one MESH and at most one REFERENCE");
  } catch(const cli::Usage_error& e) {
    std::cerr << "mesh_quality: " << e.what() << "\n" << usage;
    return cli::usage_error;
  }

  Mesh mesh, reference;
  try {
    PR::read_surface_mesh(files[0], mesh, PR::parameters::repair_degenerate_faces(repair));
    if(files.size() == 2) PR::read_surface_mesh(files[1], reference, PR::parameters::repair_degenerate_faces(repair));
  } catch(const PR::Input_error& e) {
    std::cerr << "mesh_quality: " << e.what() << "\n";
    return cli::input_error;
  }

  auto np = PR::parameters::check_self_intersections(self_intersections);
  PR::Quality_report r = files.size() == 2 ? PR::quality_report(mesh, reference, np) : PR::quality_report(mesh, np);
  PR::Labelled_quality_reports reports = {{files[0], r}};
  if(json) PR::write_quality_json(std::cout, reports);
  else PR::write_quality_table(std::cout, reports);
  if(!svg.empty()) {
    try {
      PR::write_file_atomically(svg, [&](std::ostream& os) { PR::write_angle_histogram_svg(os, reports); });
    } catch(const PR::Output_error& e) {
      std::cerr << "mesh_quality: " << e.what() << "\n";
      return cli::output_error;
    }
  }
  return cli::ok;
}
