// poisson_remesh [IN [OUT]] [options] -- the command-line remesher.
//
// Reads IN (OFF, OBJ, PLY, STL; default: CGAL's meshes/fandisk.off), remeshes it, prints the
// before/after quality table and writes OUT atomically (a failure never leaves a partial or
// clobbered OUT), plus optional JSON report and angle-histogram SVG.
//
// `--method poisson` (the default) runs Poisson_remesh::poisson_remesh (paper §3-§6);
// `--method isotropic` runs the peer, CGAL's isotropic_remeshing, at the same target, and
// `--compare-peer` adds the peer's column to the table.
#include "command_line.h"

#include <Poisson_remesh/IO/write_density_map_svg.h>
#include <Poisson_remesh/IO/write_quality_report.h>
#include <Poisson_remesh/Peers/isotropic_remeshing_peer.h>
#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/read_surface_mesh.h>
#include <Poisson_remesh/sizing.h>
#include <Poisson_remesh/write_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
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
  "  --iterations K      relaxation rounds (poisson: default 10, isotropic: default 5)\n"
  "  --sharp-angle A     dihedral angle in degrees over which edges are kept as features (default 60)\n"
  "  --fidelity-tolerance T  input points (vertices, edge midpoints, triangle centroids) farther than T\n"
  "                      (times the input's bounding-box diagonal) from the relaxed mesh are inserted, and\n"
  "                      mesh edges that far from the input are split (at most 1% of the vertex count\n"
  "                      per pass; default 0.008, 0: off)\n"
  "  --features none     keep no sharp features (borders are always kept)\n"
  "  --no-grading        sample pointed tips (horns, claws thinner than the spacing) at the spacing\n"
  "                      too (default: finer around them, graded back to the spacing)\n"
  "  --regrading K       remesh again, at most K times, sampling finer where the result still cuts\n"
  "                      itself or keeps triangles under 30 degrees away from the input's sharp corners\n"
  "                      (an input crumpled finer than the spacing); the best result is kept (default 6\n"
  "                      with a uniform density, 0 with --adaptive or --density; 0: off)\n"
  "  --compare-peer      also run the peer and add its column to the table\n"
  "  --report FILE.json  write the before/after quality report as JSON\n"
  "  --svg FILE          write the before/after angle histograms as an SVG picture\n"
  "  --density-svg FILE  write the sampling density on the input (samples per unit area) as an SVG picture\n"
  "  --repair            remove degenerate (zero-area) input faces instead of refusing them\n"
  "  --no-self-intersections  skip the self-intersection check of the report\n"
  "  --help              this text\n"
  "%s"
  "exit codes: 0 done, 1 bad input, 2 bad usage, 3 output not written\n";


int main(int argc, char** argv)
{
  std::vector<std::string> files;
  std::string method = "poisson", report_file, svg_file, density_svg_file;
  cli::Density_options density;
  double vertices = 0, edge_length = 0, sharp_angle = 60, fidelity = 0.008;
  unsigned long seed = 0, iterations = 0;
  long regrading = -1;   // (-1: the library's default, 6 for a uniform density, else 0)
  bool repair = false, self_intersections = true, compare_peer = false, features = true, grading = true;
  try {
    cli::Arguments args(argc, argv);
    while(!args.done()) {
      const std::string a = args.next();
      if(a == "--help" || a == "-h") { cli::print_usage(std::cout, usage); return cli::ok; }
      else if(density.parse(a, args)) {}
      else if(a == "--density-svg") density_svg_file = args.value(a);
      else if(a == "--vertices") vertices = double(args.whole_number(a));
      else if(a == "--edge-length") edge_length = args.number(a, 0);
      else if(a == "--method") method = args.value(a);
      else if(a == "--seed") seed = args.whole_number(a);
      else if(a == "--iterations") iterations = args.whole_number(a);
      else if(a == "--sharp-angle") sharp_angle = args.number(a);
      else if(a == "--fidelity-tolerance") fidelity = args.number(a);
      else if(a == "--report") report_file = args.value(a);
      else if(a == "--svg") svg_file = args.value(a);
      else if(a == "--repair") repair = true;
      else if(a == "--compare-peer") compare_peer = true;
      else if(a == "--no-grading") grading = false;
      else if(a == "--regrading") regrading = long(args.whole_number(a));
      else if(a == "--features") {
        const std::string v = args.value(a);
        if(v != "none") throw cli::Usage_error("--features takes 'none' (use --sharp-angle A for an angle)");
        features = false;
      }
      else if(a == "--no-self-intersections") self_intersections = false;
      else if(!a.empty() && a[0] == '-') throw cli::Usage_error("unknown option " + a);
      else files.push_back(a);
    }
    if(files.size() > 2) throw cli::Usage_error("too many file names (give IN and OUT)");
    if(vertices > 0 && edge_length > 0) throw cli::Usage_error("give --vertices or --edge-length, not both");
    if(method != "poisson" && method != "isotropic") throw cli::Usage_error("--method is poisson or isotropic, not " + method);
    density.validate();
    if(fidelity < 0) throw cli::Usage_error("--fidelity-tolerance must be >= 0");
    if(method == "isotropic" && (density.adaptive || !density.density_file.empty()))
      throw cli::Usage_error("adaptive density is for --method poisson");
  } catch(const cli::Usage_error& e) {
    std::cerr << "poisson_remesh: " << e.what() << "\n";
    cli::print_usage(std::cerr, usage);
    return cli::usage_error;
  }

  const std::string in = files.size() > 0 ? files[0] : cli::data_mesh("meshes/fandisk.off");
  const std::string out = files.size() > 1 ? files[1]
                        : std::filesystem::path(in).stem().string() + "_remeshed.off";
  const std::string out_ext = PR::internal::lower_extension(out);
  if(out_ext != "off" && out_ext != "obj" && out_ext != "ply" && out_ext != "stl") {
    std::cerr << "poisson_remesh: cannot write '" << out << "': unsupported extension (use .off .obj .ply .stl)\n";
    return cli::usage_error;
  }
  Mesh input, output;
  std::vector<double> user_density;
  try {
    PR::Read_report rr = PR::read_surface_mesh(in, input, PR::parameters::repair_degenerate_faces(repair));
    for(const std::string& w : rr.warnings) std::cerr << "poisson_remesh: note: " << in << ": " << w << "\n";
    user_density = cli::user_densities(density, rr, in, input);
  } catch(const std::exception& e) {
    std::cerr << "poisson_remesh: " << e.what() << "\n";
    return cli::input_error;
  }
  // calls f with the density field the options ask for
  auto with_density = [&](auto f) { return cli::with_density(density, input, user_density, f); };

  const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(input));
  const double target = edge_length > 0 ? PR::vertex_count_from_edge_length(area, edge_length)
                      : vertices > 0    ? vertices
                                        : double(num_vertices(input));
  auto run_peer = [&](Mesh& peer_output) {
    PR::Peers::Isotropic_remeshing_settings settings;
    settings.target_vertex_count = target;
    settings.sharp_angle = features ? sharp_angle : 0;
    settings.iterations = unsigned(iterations ? iterations : 5);
    std::cout << "CGAL isotropic_remeshing (the peer) to about " << std::llround(target) << " vertices ... " << std::flush;
    const PR::Peers::Isotropic_remeshing_result run = PR::Peers::isotropic_remeshing_at_vertex_count(input, peer_output, settings);
    std::cout << run.seconds << " s (edge length " << run.edge_length << ", " << run.runs << " calibration run(s))\n";
  };

  auto np = PR::parameters::check_self_intersections(self_intersections);
  PR::Labelled_quality_reports reports = {{"input", PR::quality_report(input, np)}};
  if(method == "poisson") {
    std::cout << "Poisson-disk remeshing of " << in << " (" << num_vertices(input) << " vertices) to about "
              << std::llround(target) << " vertices ... " << std::flush;
    const PR::Poisson_remesh_result run = with_density([&](const auto& field) {
      return PR::poisson_remesh(input, output,
        PR::parameters::target_vertex_count(std::size_t(std::llround(target)))
          .random_seed(unsigned(seed))
          .feature_policy(features ? PR::Feature_policy::detect : PR::Feature_policy::none)
          .sharp_angle(sharp_angle)
          .number_of_iterations(unsigned(iterations ? iterations : 10))
          .fidelity_tolerance(fidelity)
          .feature_grading(grading)
          .regrading_attempts(unsigned(regrading >= 0 ? regrading : density.adaptive || !density.density_file.empty() ? 0 : 6))
          .density(field));
    });
    std::cout << run.seconds() << " s (features " << run.seconds_features << ", sampling " << run.seconds_sampling
              << ", tessellation " << run.seconds_tessellation << ", relaxation " << run.seconds_relaxation << ")\n"
              << "  " << run.sampling.number_of_samples << " samples (" << run.sampling.number_of_corners << " corners, "
              << run.sampling.number_of_feature_samples << " on features), spacing 2r = " << 2 * run.sampling.radius;
    if(run.sampling.max_radius > run.sampling.min_radius)
      // (graded tips and remakes lower the uniform spacing near them; an adaptive density varies around its median)
      std::cout << (run.number_of_regrading_attempts ? " (finer near tips and where remade: from "
                    : run.number_of_graded_tips ? " (finer near tips: from " : " (median; from ") << 2 * run.sampling.min_radius << " to " << 2 * run.sampling.max_radius << ")";
    std::cout << "\n";
    if(run.sampling.statistics.open_iso_curves || run.sampling.statistics.dropped_arcs)
      std::cout << "  note: " << run.sampling.statistics.open_iso_curves << " iso-curves did not close, "
                << run.sampling.statistics.dropped_arcs << " boundary arcs left inside a disk were dropped ("
                << run.sampling.statistics.propagations << " propagations)\n";
    if(run.number_of_graded_tips)
      std::cout << "  note: sampled finer around " << run.number_of_graded_tips << " pointed tip(s) thinner than the spacing\n";
    if(run.number_of_dropped_feature_curves)
      std::cout << "  note: " << run.number_of_dropped_feature_curves << " feature curve(s) closer than the spacing beside another were not kept as features\n";
    if(run.number_of_leftover_input_vertices)
      std::cout << "  note: " << run.number_of_leftover_input_vertices
                << " input vertices could not be removed without changing the topology; they stay in the output\n";
    if(run.relaxation.fidelity_insertions)
      std::cout << "  note: " << run.relaxation.fidelity_insertions
                << " input vertices farther than the fidelity tolerance from the mesh were inserted\n";
    if(run.relaxation.refinement_insertions || run.relaxation.refinement_removals)
      std::cout << "  note: beside triangles still under 30 degrees, " << run.relaxation.refinement_insertions
                << " vertices were inserted and " << run.relaxation.refinement_removals << " removed ("
                << run.relaxation.refinement_flips << " flips)\n";
    if(run.number_of_regrading_attempts)
      std::cout << "  note: remeshed " << run.number_of_regrading_attempts << " more time(s), sampling finer where the result"
                << " cut itself or kept triangles under 30 degrees; kept the best\n";
    if(run.number_of_merged_samples)
      std::cout << "  note: " << run.number_of_merged_samples
                << " samples fell on the vertex of another inside nearly zero-area input faces and were merged\n";
    reports.push_back({"output (Poisson)", PR::quality_report(output, input, np)});
    if(compare_peer) {
      Mesh peer;
      run_peer(peer);
      reports.push_back({"peer (CGAL isotropic)", PR::quality_report(peer, input, np)});
    }
  } else {
    run_peer(output);
    reports.push_back({"output (CGAL isotropic)", PR::quality_report(output, input, np)});
  }
  std::cout << "\n";
  PR::write_quality_table(std::cout, reports);

  try {
    PR::write_surface_mesh(out, output);
    std::cout << "\nwrote " << out << "\n";
    if(!report_file.empty()) {
      PR::write_file_atomically(report_file, [&](std::ostream& os) { PR::write_quality_json(os, reports); });
      std::cout << "wrote " << report_file << "\n";
    }
    if(!density_svg_file.empty()) {
      // samples per unit area (Eq. 1) at each input vertex
      const std::vector<double> radii = with_density([&](const auto& field) {
        return PR::vertex_disk_radii(input, input.points(), PR::vertex_densities(field, input, input.points()), target,
                                     density.min_edge, density.max_edge);
      });
      const double c = PR::paper_rho * PR::paper_rho / (2 * std::sqrt(3.0));
      PR::Density_map_view view;
      view.title = std::filesystem::path(in).filename().string() + ": " +
                   (density.adaptive ? "curvature-adaptive" : user_density.empty() ? "uniform" : "user") + " sampling density";
      view.value_name = "samples / area";
      PR::write_file_atomically(density_svg_file, [&](std::ostream& os) {
        PR::write_density_map_svg(os, input, [&](Mesh::Vertex_index v) { return c / (radii[std::size_t(v)] * radii[std::size_t(v)]); }, view);
      });
      std::cout << "wrote " << density_svg_file << "\n";
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
