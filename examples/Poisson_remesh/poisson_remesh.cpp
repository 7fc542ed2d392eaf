// poisson_remesh [IN [OUT]] [options] -- the command-line remesher.
//
// Reads IN (OFF, OBJ, PLY, STL; default: CGAL's meshes/fandisk.off), remeshes it, prints the
// before/after quality table and writes OUT atomically (a failure never leaves a partial or
// clobbered OUT), plus optional JSON report and angle-histogram SVG.
//
// The Poisson-disk remesher itself (paper §4-§6) is being built stage by stage; until it is
// complete, `--method poisson` (the default) says so and exits with code 4, and
// `--method isotropic` runs the peer, CGAL's isotropic_remeshing, at the same target.
#include "command_line.h"

#include <Poisson_remesh/IO/write_quality_report.h>
#include <Poisson_remesh/Peers/isotropic_remeshing_peer.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>
#include <Poisson_remesh/sizing.h>
#include <Poisson_remesh/write_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <filesystem>
#include <iostream>
#include <map>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

static const char* usage =
  "usage: poisson_remesh [IN [OUT]] [options]\n"
  "  Remeshes the triangle mesh IN (OFF, OBJ, PLY, STL) into OUT (.off .obj .ply .stl) and prints\n"
  "  the quality before and after. IN defaults to CGAL's meshes/fandisk.off, OUT to\n"
  "  <IN's name>_remeshed.off in the current folder. OUT is replaced only when all went well.\n"
  "target size (one of them; default: the input's vertex count):\n"
  "  --vertices N        target number of output vertices\n"
  "  --edge-length L     target edge length\n"
  "options:\n"
  "  --method M          poisson (default; the Poisson-disk remesher) or isotropic (CGAL's\n"
  "                      isotropic_remeshing, the peer of our benchmarks)\n"
  "  --seed S            random seed (default 0); the same seed gives the same output\n"
  "  --iterations K      relaxation iterations (isotropic: default 5)\n"
  "  --sharp-angle A     dihedral angle in degrees over which edges are kept as features (default 60)\n"
  "  --report FILE.json  write the before/after quality report as JSON\n"
  "  --svg FILE          write the before/after angle histograms as an SVG picture\n"
  "  --repair            remove degenerate (zero-area) input faces instead of refusing them\n"
  "  --no-self-intersections  skip the self-intersection check of the report\n"
  "  --help              this text\n"
  "exit codes: 0 done, 1 bad input, 2 bad usage, 3 output not written, 4 stage not available yet\n";

// Options of pipeline stages that do not exist yet, with the stage that will bring them.
static const std::map<std::string, std::string> later_options = {
  {"--adaptive", "adaptive density"}, {"--gamma", "adaptive density"}, {"--min-edge", "adaptive density"},
  {"--max-edge", "adaptive density"}, {"--smoothing", "adaptive density"}, {"--density", "user density fields"},
  {"--features", "the feature-preservation policy of the Poisson-disk sampler"},
};

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  std::string method = "poisson", report_file, svg_file;
  double vertices = 0, edge_length = 0, sharp_angle = 60;
  unsigned long seed = 0, iterations = 5;
  bool repair = false, self_intersections = true;
  try {
    cli::Arguments args(argc, argv);
    while(!args.done()) {
      const std::string a = args.next();
      if(a == "--help" || a == "-h") { std::cout << usage; return cli::ok; }
      else if(a == "--vertices") vertices = double(args.whole_number(a));
      else if(a == "--edge-length") edge_length = args.number(a, 0);
      else if(a == "--method") method = args.value(a);
      else if(a == "--seed") seed = args.whole_number(a);
      else if(a == "--iterations") iterations = args.whole_number(a);
      else if(a == "--sharp-angle") sharp_angle = args.number(a);
      else if(a == "--report") report_file = args.value(a);
      else if(a == "--svg") svg_file = args.value(a);
      else if(a == "--repair") repair = true;
      else if(a == "--no-self-intersections") self_intersections = false;
      else if(later_options.count(a)) {
        std::cerr << "poisson_remesh: option " << a << " belongs to " << later_options.at(a)
                  << ", which is not implemented yet\n";
        return cli::not_available;
      }
      else if(!a.empty() && a[0] == '-') throw cli::Usage_error("unknown option " + a);
      else files.push_back(a);
    }
    if(files.size() > 2) throw cli::Usage_error("too many file names (give IN and OUT)");
    if(vertices > 0 && edge_length > 0) throw cli::Usage_error("give --vertices or --edge-length, not both");
    if(method != "poisson" && method != "isotropic") throw cli::Usage_error("--method is poisson or isotropic, not " + method);
  } catch(const cli::Usage_error& e) {
    std::cerr << "poisson_remesh: " << e.what() << "\n" << usage;
    return cli::usage_error;
  }
  (void)seed;

  const std::string in = files.size() > 0 ? files[0] : cli::data_mesh("meshes/fandisk.off");
  const std::string out = files.size() > 1 ? files[1]
                        : std::filesystem::path(in).stem().string() + "_remeshed.off";
  const std::string out_ext = PR::internal::lower_extension(out);
  if(out_ext != "off" && out_ext != "obj" && out_ext != "ply" && out_ext != "stl") {
    std::cerr << "poisson_remesh: cannot write '" << out << "': unsupported extension (use .off .obj .ply .stl)\n";
    return cli::usage_error;
  }
  if(method == "poisson") {
    std::cerr << "poisson_remesh: the Poisson-disk remesher is not implemented yet (its geodesic oracle,\n"
                 "sampler and mutual tessellation are being built); nothing was written.\n"
                 "Use --method isotropic to run CGAL's isotropic_remeshing, the peer, at the same target.\n";
    return cli::not_available;
  }

  Mesh input, output;
  try {
    PR::Read_report rr = PR::read_surface_mesh(in, input, PR::parameters::repair_degenerate_faces(repair));
    for(const std::string& w : rr.warnings) std::cerr << "poisson_remesh: note: " << in << ": " << w << "\n";
  } catch(const PR::Input_error& e) {
    std::cerr << "poisson_remesh: " << e.what() << "\n";
    return cli::input_error;
  }

  PR::Peers::Isotropic_remeshing_settings settings;
  const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(input));
  settings.target_vertex_count = edge_length > 0 ? PR::vertex_count_from_edge_length(area, edge_length)
                               : vertices > 0    ? vertices
                                                 : double(num_vertices(input));
  settings.sharp_angle = sharp_angle;
  settings.iterations = unsigned(iterations);
  std::cout << "remeshing " << in << " (" << num_vertices(input) << " vertices) with CGAL isotropic_remeshing"
            << " (the peer) to about " << std::llround(settings.target_vertex_count) << " vertices\n";
  PR::Peers::Isotropic_remeshing_result run = PR::Peers::isotropic_remeshing_at_vertex_count(input, output, settings);
  std::cout << "done in " << run.seconds << " s (edge length " << run.edge_length << ", " << run.runs
            << " calibration run(s))\n\n";

  auto np = PR::parameters::check_self_intersections(self_intersections);
  PR::Labelled_quality_reports reports = {
    {"input", PR::quality_report(input, np)},
    {"output (CGAL isotropic)", PR::quality_report(output, input, np)},
  };
  PR::write_quality_table(std::cout, reports);

  try {
    PR::write_surface_mesh(out, output);
    std::cout << "\nwrote " << out << "\n";
    if(!report_file.empty()) {
      PR::write_file_atomically(report_file, [&](std::ostream& os) { PR::write_quality_json(os, reports); });
      std::cout << "wrote " << report_file << "\n";
    }
    if(!svg_file.empty()) {
      PR::write_file_atomically(svg_file, [&](std::ostream& os) { PR::write_angle_histogram_svg(os, reports); });
      std::cout << "wrote " << svg_file << "\n";
    }
  } catch(const PR::Output_error& e) {
    std::cerr << "poisson_remesh: " << e.what() << "\n";
    return cli::output_error;
  }
  return cli::ok;
}
