// poisson_remesh [IN [OUT]] [options]
// poisson_remesh IN... -o OUTDIR [options]  -- the command-line remesher.
//
// Reads IN (OFF, OBJ, PLY, STL; default: CGAL's meshes/fandisk.off), remeshes it, prints the
// before/after quality table and writes OUT atomically (a failure never leaves a partial or
// clobbered OUT), plus optional JSON report and angle-histogram SVG.
//
// With -o OUTDIR it remeshes every input (files, or the meshes of a folder) into OUTDIR, each in a
// child process (-j N at once; a crash or a bad file stops only that file), prints one line per
// file and writes a summary of the quality figures (--summary FILE.csv, --summary-json FILE.json).
//
// `--method poisson` (the default) runs Poisson_remesh::poisson_remesh (paper §3-§6);
// `--method isotropic` runs the peer, CGAL's isotropic_remeshing, at the same target, and
// `--compare-peer` adds the peer's column to the table.
//
// Progress goes to stderr when stderr is a terminal (not with --quiet): the stage and how far it
// is, on one line rewritten in place.
#include "command_line.h"

#include <Poisson_remesh/IO/write_density_map_svg.h>
#include <Poisson_remesh/IO/write_mesh_svg.h>
#include <Poisson_remesh/IO/write_quality_report.h>
#include "isotropic_remeshing_peer.h"
#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/progress.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/read_surface_mesh.h>
#include <Poisson_remesh/sizing.h>
#include <Poisson_remesh/write_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif
#include <thread>

#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#endif

#include <algorithm>
#include <chrono>
#include <optional>
#include <functional>
#include <future>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;
namespace fs = std::filesystem;

static const char* usage =
  "usage: poisson_remesh [IN [OUT]] [options]\n"
  "       poisson_remesh IN... -o OUTDIR [options]\n"
  "  Remeshes the triangle mesh IN (OFF, OBJ, PLY, STL) into OUT (.off .obj .ply .stl) and prints\n"
  "  the quality before and after. IN defaults to CGAL's meshes/fandisk.off, OUT to\n"
  "  <IN's name>_remeshed.off in the current folder. OUT is replaced only when all went well.\n"
  "  With -o OUTDIR, every IN (a mesh file, or a folder: its .off .obj .ply .stl files) is remeshed\n"
  "  into OUTDIR/<name>_remeshed.<ext>, one line per file is printed, and a bad file is reported and\n"
  "  skipped.\n"
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
  "  --local-remakes     remake only the regions at fault (resampled finer, tessellated and relaxed\n"
  "                      inside, the rest of the mesh untouched) when the result does not cut itself:\n"
  "                      faster, but on the CGAL corpus it meets the angle floor less often\n"
  "  --compare-peer      also run the peer and add its column to the table\n"
  "  --report FILE.json  write the before/after quality report as JSON\n"
  "  --svg FILE          write the before/after angle histograms as an SVG picture\n"
  "  --density-svg FILE  write the sampling density on the input (samples per unit area) as an SVG picture\n"
  "  --picture FILE.svg  write the input and the output side by side (and the peer's with --compare-peer),\n"
  "                      flat-shaded with their edges, triangles under 30 degrees in red\n"
  "  --full-report       the Hausdorff distance to within 1e-4 of the diagonal (CGAL's bounded-error\n"
  "                      algorithm; default: sampled at the vertices, edge midpoints and triangle\n"
  "                      centroids of both meshes, a lower bound shown with the most it can miss)\n"
  "  --no-self-intersections  skip the self-intersection count of the report\n"
  "  --strict            refuse zero-area faces and non-manifold vertices instead of repairing them\n"
  "                      (by default they are removed and split, and the program says how many)\n"
  "  --quiet             no progress on stderr (it is shown only when stderr is a terminal)\n"
  "  --timings           the relaxation's time by step (the paper's and each operator beyond it)\n"
  "  --threads N         threads of the parallel mode (default: all cores, divided among the --jobs;\n"
  "                      the output is the same for any N)\n"
  "  --help              this text\n"
  "several inputs (batch):\n"
  "  -o, --output-dir D  remesh every input into folder D (created if missing)\n"
  "  --format EXT        the outputs' format in a batch: off (default), obj, ply or stl\n"
  "  -j, --jobs N        remesh N files at once (default 1), each in its own process\n"
  "  --summary FILE.csv  write one line of quality figures per file (also for a single input)\n"
  "  --summary-json FILE.json  the same as JSON\n"
  "%s"
  "exit codes: 0 done, 1 bad input (in a batch: at least one file could not be read or remeshed),\n"
  "2 bad usage, 3 output not written, 5 a remesh crashed (batch)\n";


namespace {

struct Options
{
  std::string method = "poisson", report_file, svg_file, density_svg_file, picture_file, output_dir, format = "off";
  std::string summary_csv, summary_json;
  cli::Density_options density;
  double vertices = 0, edge_length = 0, sharp_angle = 60, fidelity = 0.008;
  unsigned long seed = 0, iterations = 0, jobs = 1, threads = 0;
  long regrading = -1;   // (-1: the library's default, 6 for a uniform density, else 0)
  bool strict = false, self_intersections = true, compare_peer = false, features = true, grading = true;
  bool full_report = false, quiet = false, timings = false, local_remakes = false;
};

// One remesh: where it came from and went, and its figures (the summary's line).
struct Row
{
  std::string input, output;
  int status = cli::ok;
  std::string error;
  double input_vertices = 0, vertices = 0, min_angle = 0, min_angle_away = -1, mean_min_angle = 0, irregular = 0;
  double hausdorff = -1, self_intersections = -1, seconds_remesh = 0, seconds_total = 0;
  double repaired_faces = 0, split_vertices = 0;
};

// Progress on stderr, one line rewritten in place, at most ten times a second.
class Terminal_progress
{
public:
  explicit Terminal_progress(bool on, std::string prefix = "") : on_(on), prefix_(std::move(prefix)) {}
  bool on() const { return on_; }
  bool operator()(const PR::Progress& p)
  {
    const auto now = std::chrono::steady_clock::now();
    const bool new_stage = p.stage != stage_;
    if(!new_stage && now - last_ < std::chrono::milliseconds(100)) return true;
    last_ = now;
    stage_ = p.stage;
    const std::string stage(p.stage);
    std::ostringstream line;
    line << prefix_ << stage;
    if(stage == "sampling") line << ": " << p.done << " samples of about " << p.total;
    else if(stage == "relaxation") line << ": round " << p.done + 1 << " of " << p.total;
    else if(p.total > 0) line << ": step " << std::min(p.done + 1, p.total) << " of " << p.total;
    std::string text = line.str();
    if(text.size() < width_) text += std::string(width_ - text.size(), ' ');
    width_ = line.str().size();
    std::fprintf(stderr, "\r%s", text.c_str());
    std::fflush(stderr);
    shown_ = true;
    return true;
  }
  void clear()
  {
    if(!shown_) return;
    std::fprintf(stderr, "\r%s\r", std::string(width_, ' ').c_str());
    std::fflush(stderr);
    shown_ = false;
    stage_ = nullptr;
  }
private:
  bool on_;
  std::string prefix_;
  const char* stage_ = nullptr;
  std::chrono::steady_clock::time_point last_;
  std::size_t width_ = 0;
  bool shown_ = false;
};

std::string format_figure(double x, int precision)
{
  if(x < 0) return "";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(precision);
  s << x;
  return s.str();
}

// Remeshes one file. Prints the before/after table when `table`, else nothing (the caller prints
// the row). Returns the exit code; fills `row`.
int remesh_one(const Options& o, const std::string& in, const std::string& out, bool table, Terminal_progress& progress, Row& row)
{
  // the parallel mode's threads (each process of a batch sets its own: a share of the cores)
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t thread_count = o.threads ? o.threads : std::max<std::size_t>(1, cores / std::max<std::size_t>(1, o.jobs));
#ifdef CGAL_LINKED_WITH_TBB
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, thread_count);
#endif
  const auto start = std::chrono::steady_clock::now();
  auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); };
  std::ostream& os = std::cout;
  std::ostringstream quiet_sink;
  std::ostream& say = table ? os : quiet_sink;
  row.input = in;
  row.output = out;
  auto fail = [&](int code, const std::string& message) {
    progress.clear();
    row.status = code;
    row.error = message;
    if(table) std::cerr << "poisson_remesh: " << message << "\n";
    return code;
  };

  Mesh input, output;
  std::vector<double> user_density;
  try {
    PR::Read_report rr = PR::read_surface_mesh(in, input, PR::parameters::strict_input(o.strict));
    if(table)
      for(const std::string& w : rr.warnings) std::cerr << "poisson_remesh: note: " << in << ": " << w << "\n";
    row.repaired_faces = double(rr.removed_degenerate_faces);
    row.split_vertices = double(rr.split_non_manifold_vertices + rr.split_pinched_vertices);
    user_density = cli::user_densities(o.density, rr, in, input);
  } catch(const std::exception& e) {
    return fail(cli::input_error, e.what());
  }
  row.input_vertices = double(num_vertices(input));
  // calls f with the density field the options ask for
  auto with_density = [&](auto f) { return cli::with_density(o.density, input, user_density, f); };

  const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(input));
  const double target = o.edge_length > 0 ? PR::vertex_count_from_edge_length(area, o.edge_length)
                      : o.vertices > 0    ? o.vertices
                                          : double(num_vertices(input));
  auto run_peer = [&](Mesh& peer_output) {
    PR::Peers::Isotropic_remeshing_settings settings;
    settings.target_vertex_count = target;
    settings.sharp_angle = o.features ? o.sharp_angle : 0;
    settings.iterations = unsigned(o.iterations ? o.iterations : 5);
    say << "CGAL isotropic_remeshing (the peer) to about " << std::llround(target) << " vertices ... " << std::flush;
    const PR::Peers::Isotropic_remeshing_result run = PR::Peers::isotropic_remeshing_at_vertex_count(input, peer_output, settings);
    say << run.seconds << " s (edge length " << run.edge_length << ", " << run.runs << " calibration run(s))\n";
    return run.seconds;
  };

  // (the Hausdorff distance: sampled by default, to within 1e-4 of the diagonal with --full-report,
  // which costs more than the remesh on large flat parts)
  auto np = PR::parameters::check_self_intersections(o.self_intersections)
                           .sampled_hausdorff(!o.full_report)
                           .hausdorff_relative_error_bound(1e-4);
  // the input's report is made beside the remesh, on its own thread (with one thread, or without
  // TBB, when it is taken), from a copy of the input (no mesh is read by two threads that may add
  // property maps to it; cheap insurance across CGAL versions); taken when the output's is due
  const Mesh input_for_report = input;
#ifdef CGAL_LINKED_WITH_TBB
  const bool beside = thread_count > 1;
#else
  const bool beside = false;
  (void)thread_count;
#endif
  // Beside the remesh, the report's thread runs at the lowest priority (Linux): it takes the
  // cores the remesh leaves idle (its sequential steps), not a share of those its parallel loops
  // use. It runs sequentially, so that it sends no work to TBB's threads (when it is not beside,
  // there is one thread anyway)
  auto input_report = std::async(beside ? std::launch::async : std::launch::deferred, [&] {
#ifdef __linux__
    if(beside) setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), 19);   // (per thread on Linux; on failure, as before)
#endif
    return PR::quality_report<CGAL::Sequential_tag>(input_for_report, np);
  });
  PR::Labelled_quality_reports reports;
  // (the reports against the input reuse its count of crossing pairs, when that count has no
  // degenerate face's pair with itself in it, instead of searching the input again)
  auto against_input = [&] {
    if(reports.empty()) {
      try {
        reports.push_back({"input", input_report.get()});
      } catch(const std::exception& e) {
        throw std::runtime_error(std::string("the input's quality report: ") + e.what());
      }
    }
    const std::size_t input_crossings = reports[0].second.self_intersections_checked && reports[0].second.number_of_degenerate_faces == 0
                                      ? reports[0].second.number_of_self_intersecting_face_pairs : std::size_t(-1);
    return np.reference_self_intersections(input_crossings);
  };
  std::optional<Mesh> peer;   // the peer's remesh, with --compare-peer (for --picture)
  try {
    if(o.method == "poisson") {
      say << "Poisson-disk remeshing of " << in << " (" << num_vertices(input) << " vertices) to about "
          << std::llround(target) << " vertices ... " << std::flush;
      // (always the same parameter type, empty without progress: each density type instantiates
      // the whole remesher once, which is most of this program's compile time)
      std::function<bool(const PR::Progress&)> on_progress;
      if(progress.on()) on_progress = [&](const PR::Progress& p) { return progress(p); };
      const auto remesh_start = std::chrono::steady_clock::now();
      const PR::Poisson_remesh_result run = with_density([&](const auto& field) {
        auto params = PR::parameters::target_vertex_count(std::size_t(std::llround(target)))
            .random_seed(unsigned(o.seed))
            .feature_policy(o.features ? PR::Feature_policy::detect : PR::Feature_policy::none)
            .sharp_angle(o.sharp_angle)
            .number_of_iterations(unsigned(o.iterations ? o.iterations : 10))
            .fidelity_tolerance(o.fidelity)
            .feature_grading(o.grading)
            .regrading_attempts(unsigned(o.regrading >= 0 ? o.regrading : o.density.adaptive || !o.density.density_file.empty() ? 0 : 6))
            .local_remakes(o.local_remakes)
            .strict_input(o.strict)
            .density(field)
            .progress(on_progress);
        return PR::poisson_remesh<CGAL::Parallel_if_available_tag>(input, output, params);
      });
      row.seconds_remesh = seconds_since(remesh_start);
      progress.clear();
      say << run.seconds() << " s (features " << run.seconds_features << ", sampling " << run.seconds_sampling
          << ", tessellation " << run.seconds_tessellation << ", relaxation " << run.seconds_relaxation << ")\n"
          << "  " << run.sampling.number_of_samples << " samples (" << run.sampling.number_of_corners << " corners, "
          << run.sampling.number_of_feature_samples << " on features), spacing 2r = " << 2 * run.sampling.radius;
      if(run.sampling.max_radius > run.sampling.min_radius)
        // (graded tips and remakes lower the uniform spacing near them; an adaptive density varies around its median)
        say << (run.number_of_regrading_attempts ? " (finer near tips and where remade: from "
                : run.number_of_graded_tips ? " (finer near tips: from " : " (median; from ") << 2 * run.sampling.min_radius << " to " << 2 * run.sampling.max_radius << ")";
      say << "\n";
      if(run.sampling.statistics.open_iso_curves || run.sampling.statistics.dropped_arcs)
        say << "  note: " << run.sampling.statistics.open_iso_curves << " iso-curves did not close, "
            << run.sampling.statistics.dropped_arcs << " boundary arcs left inside a disk were dropped ("
            << run.sampling.statistics.propagations << " propagations)\n";
      if(run.number_of_graded_tips)
        say << "  note: sampled finer around " << run.number_of_graded_tips << " pointed tip(s) thinner than the spacing\n";
      if(run.number_of_dropped_feature_curves)
        say << "  note: " << run.number_of_dropped_feature_curves << " feature curve(s) closer than the spacing beside another were not kept as features\n";
      if(run.number_of_leftover_input_vertices)
        say << "  note: " << run.number_of_leftover_input_vertices
            << " input vertices could not be removed without changing the topology; they stay in the output\n";
      if(run.relaxation.fidelity_insertions)
        say << "  note: " << run.relaxation.fidelity_insertions
            << " input vertices farther than the fidelity tolerance from the mesh were inserted\n";
      if(run.relaxation.refinement_insertions || run.relaxation.refinement_removals)
        say << "  note: beside triangles still under 30 degrees, " << run.relaxation.refinement_insertions
            << " vertices were inserted and " << run.relaxation.refinement_removals << " removed ("
            << run.relaxation.refinement_flips << " flips)\n";
      if(run.number_of_regrading_attempts)
        say << "  note: remeshed " << (o.local_remakes ? "the regions at fault " : "") << run.number_of_regrading_attempts
            << " more time(s), sampling finer where the result cut itself or kept triangles under 30 degrees; kept the best\n";
      if(o.timings) {
        say << "  relaxation by step (s):";
        run.seconds_by_step.for_each([&](const char* step, double seconds) { if(seconds > 0) say << ' ' << step << ' ' << seconds; });
        say << "; remakes' checks and copies " << run.seconds_relaxation - run.seconds_by_step.total() << "\n";
      }
      if(run.number_of_merged_samples)
        say << "  note: " << run.number_of_merged_samples
            << " samples fell on the vertex of another inside nearly zero-area input faces and were merged\n";
      const auto np_against_input = against_input();
      reports.push_back({"output (Poisson)", PR::quality_report<CGAL::Parallel_if_available_tag>(output, input, np_against_input)});
      if(o.compare_peer) {
        peer.emplace();
        run_peer(*peer);
        reports.push_back({"peer (CGAL isotropic)", PR::quality_report<CGAL::Parallel_if_available_tag>(*peer, input, np_against_input)});
      }
    } else {
      row.seconds_remesh = run_peer(output);
      reports.push_back({"output (CGAL isotropic)", PR::quality_report<CGAL::Parallel_if_available_tag>(output, input, against_input())});
    }
  } catch(const PR::Cancelled& e) {
    return fail(cli::internal_error, e.what());
  } catch(const std::exception& e) {
    return fail(cli::input_error, std::string("cannot remesh: ") + e.what());
  }
  const PR::Quality_report& r = reports[1].second;
  row.vertices = double(r.number_of_vertices);
  row.min_angle = r.min_angle;
  row.min_angle_away = r.min_angle_away_from_sharp_corners ? *r.min_angle_away_from_sharp_corners : -1;
  row.mean_min_angle = r.mean_min_angle;
  row.irregular = 100 * r.irregular_share;
  row.hausdorff = r.hausdorff ? *r.hausdorff : -1;
  row.self_intersections = r.self_intersections_checked ? double(r.number_of_self_intersecting_face_pairs) : -1;
  if(table) {
    os << "\n";
    PR::write_quality_table(os, reports);
  }

  try {
    PR::write_surface_mesh(out, output);
    say << "\nwrote " << out << "\n";
    if(!o.report_file.empty()) {
      PR::write_file_atomically(o.report_file, [&](std::ostream& s) { PR::write_quality_json(s, reports); });
      say << "wrote " << o.report_file << "\n";
    }
    if(!o.density_svg_file.empty()) {
      // samples per unit area (Eq. 1) at each input vertex
      // (the radii the remesh samples with: the density field at the target count, a curvature
      // density measured beside the feature edges)
      const std::vector<double> radii = with_density([&](const auto& field) {
        return PR::disk_radii(input, PR::parameters::target_vertex_count(std::size_t(std::llround(target)))
                                       .feature_policy(o.features ? PR::Feature_policy::detect : PR::Feature_policy::none)
                                       .sharp_angle(o.sharp_angle)
                                       .density(field));
      });
      const double c = PR::paper_rho * PR::paper_rho / (2 * std::sqrt(3.0));
      PR::Density_map_view view;
      view.title = fs::path(in).filename().string() + ": " +
                   (o.density.adaptive ? "curvature-adaptive" : user_density.empty() ? "uniform" : "user") + " sampling density";
      view.value_name = "samples / area";
      PR::write_file_atomically(o.density_svg_file, [&](std::ostream& s) {
        PR::write_density_map_svg(s, input, [&](Mesh::Vertex_index v) { return c / (radii[std::size_t(v)] * radii[std::size_t(v)]); }, view);
      });
      say << "wrote " << o.density_svg_file << "\n";
    }
    if(!o.svg_file.empty()) {
      PR::write_file_atomically(o.svg_file, [&](std::ostream& s) { PR::write_angle_histogram_svg(s, reports); });
      say << "wrote " << o.svg_file << "\n";
    }
    if(!o.picture_file.empty()) {
      std::vector<std::pair<const Mesh*, std::string>> panels = {{&input, "input"}, {&output, reports[1].first}};
      if(peer) panels.push_back({&*peer, reports.back().first});
      PR::Mesh_svg_view view;
      view.title = fs::path(in).filename().string();
      PR::write_file_atomically(o.picture_file, [&](std::ostream& s) { PR::write_mesh_comparison_svg(s, panels, view); });
      say << "wrote " << o.picture_file << "\n";
    }
  } catch(const PR::Output_error& e) {
    return fail(cli::output_error, e.what());
  }
  row.seconds_total = seconds_since(start);
  return cli::ok;
}

// ------------------------------------------------------------------ rows across processes
// A row travels from a child process to the batch's parent as one line of tab-separated fields.
std::string escape(const std::string& s)
{
  std::string t;
  for(char c : s) t += (c == '\t' || c == '\n' || c == '\r') ? ' ' : c;
  return t;
}

std::string serialize(const Row& r)
{
  std::ostringstream s;
  s.precision(17);
  s << escape(r.input) << '\t' << escape(r.output) << '\t' << r.status << '\t' << escape(r.error) << '\t'
    << r.input_vertices << '\t' << r.vertices << '\t' << r.min_angle << '\t' << r.min_angle_away << '\t'
    << r.mean_min_angle << '\t' << r.irregular << '\t' << r.hausdorff << '\t' << r.self_intersections << '\t'
    << r.seconds_remesh << '\t' << r.seconds_total << '\t' << r.repaired_faces << '\t' << r.split_vertices << '\n';
  return s.str();
}

bool deserialize(const std::string& line, Row& r)
{
  std::vector<std::string> f;
  std::string field;
  std::istringstream s(line);
  while(std::getline(s, field, '\t')) f.push_back(field);
  if(f.size() != 16) return false;
  try {
    r.input = f[0]; r.output = f[1]; r.status = std::stoi(f[2]); r.error = f[3];
    double* numbers[] = {&r.input_vertices, &r.vertices, &r.min_angle, &r.min_angle_away, &r.mean_min_angle, &r.irregular,
                         &r.hausdorff, &r.self_intersections, &r.seconds_remesh, &r.seconds_total, &r.repaired_faces, &r.split_vertices};
    for(std::size_t i = 0; i < 12; ++i) *numbers[i] = std::stod(f[4 + i]);
  } catch(const std::exception&) {
    return false;
  }
  return true;
}

std::string status_name(int status)
{
  switch(status) {
    case cli::ok: return "ok";
    case cli::input_error: return "bad input";
    case cli::output_error: return "output not written";
    default: return "crashed";
  }
}

std::string csv_field(const std::string& s)
{
  if(s.find_first_of(",\"") == std::string::npos) return s;
  std::string t = "\"";
  for(char c : s) { if(c == '"') t += '"'; t += c; }
  return t + "\"";
}

std::string json_string(const std::string& s)
{
  std::string t = "\"";
  for(char c : s) {
    if(c == '"' || c == '\\') { t += '\\'; t += c; }
    else if(static_cast<unsigned char>(c) < 0x20) t += ' ';
    else t += c;
  }
  return t + "\"";
}

void write_summaries(const Options& o, const std::vector<Row>& rows)
{
  const char* names[] = {"input_vertices", "vertices", "min_angle_deg", "min_angle_away_from_sharp_corners_deg",
                         "mean_min_angle_deg", "irregular_percent", "hausdorff_over_diagonal", "self_intersecting_face_pairs",
                         "seconds_remesh", "seconds_total", "repaired_faces", "split_vertices"};
  auto numbers = [](const Row& r) {
    return std::vector<std::pair<double, int>>{{r.input_vertices, 0}, {r.vertices, 0}, {r.min_angle, 3}, {r.min_angle_away, 3},
      {r.mean_min_angle, 3}, {r.irregular, 2}, {r.hausdorff, 6}, {r.self_intersections, 0}, {r.seconds_remesh, 3},
      {r.seconds_total, 3}, {r.repaired_faces, 0}, {r.split_vertices, 0}}; };
  if(!o.summary_csv.empty())
    PR::write_file_atomically(o.summary_csv, [&](std::ostream& s) {
      s << "input,output,status,error";
      for(const char* n : names) s << "," << n;
      s << "\n";
      for(const Row& r : rows) {
        s << csv_field(r.input) << "," << csv_field(r.status == cli::ok ? r.output : "") << "," << status_name(r.status) << "," << csv_field(r.error);
        for(const auto& x : numbers(r)) s << "," << (r.status == cli::ok ? format_figure(x.first, x.second) : "");
        s << "\n";
      }
    });
  if(!o.summary_json.empty())
    PR::write_file_atomically(o.summary_json, [&](std::ostream& s) {
      s << "[\n";
      for(std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        s << "  {\"input\": " << json_string(r.input) << ", \"output\": " << (r.status == cli::ok ? json_string(r.output) : "null")
          << ", \"status\": " << json_string(status_name(r.status)) << ", \"error\": " << (r.error.empty() ? "null" : json_string(r.error));
        const auto x = numbers(r);
        for(std::size_t k = 0; k < x.size(); ++k) {
          const std::string v = r.status == cli::ok ? format_figure(x[k].first, x[k].second) : "";
          s << ", \"" << names[k] << "\": " << (v.empty() ? "null" : v);
        }
        s << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
      }
      s << "]\n";
    });
}

// The mesh files of a folder (sorted), or the file itself.
std::vector<std::string> expand_input(const std::string& path)
{
  std::error_code ec;
  if(!fs::is_directory(path, ec)) return {path};
  std::vector<std::string> files;
  for(const auto& entry : fs::directory_iterator(path, ec)) {
    if(!entry.is_regular_file(ec)) continue;
    const std::string ext = PR::internal::lower_extension(entry.path().string());
    if(ext == "off" || ext == "obj" || ext == "ply" || ext == "stl") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Remeshes the jobs in child processes, at most o.jobs at once; one line per file on stdout.
int run_batch(const Options& o, const std::vector<std::pair<std::string, std::string>>& jobs)
{
  std::vector<Row> rows(jobs.size());
  struct Child { std::size_t job; int fd; };
  std::map<pid_t, Child> running;
  std::size_t next = 0, done = 0;
  const bool show_progress = !o.quiet && o.jobs == 1 && isatty(STDERR_FILENO);
  auto finish = [&](pid_t pid, int wstatus) {
    const Child c = running.at(pid);
    running.erase(pid);
    std::string text;
    char buffer[4096];
    ssize_t n;
    while((n = read(c.fd, buffer, sizeof buffer)) > 0) text.append(buffer, std::size_t(n));
    close(c.fd);
    Row& row = rows[c.job];
    if(!(WIFEXITED(wstatus) && deserialize(text.substr(0, text.find('\n')), row))) {
      row.input = jobs[c.job].first;
      row.output = jobs[c.job].second;
      row.status = cli::internal_error;
      row.error = WIFSIGNALED(wstatus) ? "crashed (signal " + std::to_string(WTERMSIG(wstatus)) + ")" : "ended without a result";
    }
    ++done;
    std::cout << "[" << done << "/" << jobs.size() << "] " << row.input;
    if(row.status == cli::ok)
      std::cout << " -> " << row.output << ": " << std::llround(row.vertices) << " vertices, min angle "
                << format_figure(row.min_angle, 2) << " (" << format_figure(row.min_angle_away, 2) << " away from sharp corners), mean min angle "
                << format_figure(row.mean_min_angle, 2) << ", irregular " << format_figure(row.irregular, 1) << "%, Hausdorff "
                << format_figure(row.hausdorff, 4) << ", " << format_figure(row.seconds_total, 2) << " s\n";
    else
      std::cout << ": FAILED (" << status_name(row.status) << "): " << row.error << "\n";
    std::cout << std::flush;
  };
  while(done < jobs.size()) {
    while(running.size() < o.jobs && next < jobs.size()) {
      int fds[2];
      if(pipe(fds) != 0) { std::perror("poisson_remesh: pipe"); return cli::internal_error; }
      std::cout << std::flush;
      const pid_t pid = fork();
      if(pid < 0) { std::perror("poisson_remesh: fork"); return cli::internal_error; }
      if(pid == 0) {   // the child: remesh, send the row, exit
        close(fds[0]);
        Terminal_progress progress(show_progress, fs::path(jobs[next].first).filename().string() + ": ");
        Row row;
        const int code = remesh_one(o, jobs[next].first, jobs[next].second, false, progress, row);
        const std::string line = serialize(row);
        std::size_t at = 0;
        while(at < line.size()) {
          const ssize_t w = write(fds[1], line.data() + at, line.size() - at);
          if(w <= 0) break;
          at += std::size_t(w);
        }
        close(fds[1]);
        std::cout << std::flush;
        _exit(code);
      }
      close(fds[1]);
      running[pid] = Child{next, fds[0]};
      ++next;
    }
    int wstatus = 0;
    const pid_t pid = waitpid(-1, &wstatus, 0);
    if(pid < 0) { std::perror("poisson_remesh: waitpid"); return cli::internal_error; }
    if(running.count(pid)) finish(pid, wstatus);
  }
  // the exit code: a bad input first, then a crash, then an unwritten output
  std::size_t failed = 0;
  std::set<int> codes;
  for(const Row& r : rows)
    if(r.status != cli::ok) { ++failed; codes.insert(r.status); }
  int code = cli::ok;
  for(int c : {int(cli::input_error), int(cli::internal_error), int(cli::output_error)})
    if(code == cli::ok && codes.count(c)) code = c;
  std::cout << jobs.size() - failed << " of " << jobs.size() << " remeshed";
  if(failed) {
    std::cout << "; failed:";
    for(const Row& r : rows) if(r.status != cli::ok) std::cout << " " << r.input;
  }
  std::cout << "\n";
  try {
    write_summaries(o, rows);
    if(!o.summary_csv.empty()) std::cout << "wrote " << o.summary_csv << "\n";
    if(!o.summary_json.empty()) std::cout << "wrote " << o.summary_json << "\n";
  } catch(const PR::Output_error& e) {
    std::cerr << "poisson_remesh: " << e.what() << "\n";
    return code == cli::ok ? cli::output_error : code;
  }
  return code;
}

} // namespace

int main(int argc, char** argv)
{
  Options o;
  std::vector<std::string> files;
  try {
    cli::Arguments args(argc, argv);
    while(!args.done()) {
      const std::string a = args.next();
      if(a == "--help" || a == "-h") { cli::print_usage(std::cout, usage); return cli::ok; }
      else if(o.density.parse(a, args)) {}
      else if(a == "--density-svg") o.density_svg_file = args.value(a);
      else if(a == "--vertices") o.vertices = double(args.whole_number(a));
      else if(a == "--edge-length") o.edge_length = args.number(a, 0);
      else if(a == "--method") o.method = args.value(a);
      else if(a == "--seed") o.seed = args.whole_number(a);
      else if(a == "--iterations") o.iterations = args.whole_number(a);
      else if(a == "--sharp-angle") o.sharp_angle = args.number(a);
      else if(a == "--fidelity-tolerance") o.fidelity = args.number(a);
      else if(a == "--report") o.report_file = args.value(a);
      else if(a == "--svg") o.svg_file = args.value(a);
      else if(a == "--picture") o.picture_file = args.value(a);
      else if(a == "--repair") {}   // (the default now: kept so that older command lines still run)
      else if(a == "--strict") o.strict = true;
      else if(a == "--compare-peer") o.compare_peer = true;
      else if(a == "--no-grading") o.grading = false;
      else if(a == "--regrading") o.regrading = long(args.whole_number(a));
      else if(a == "--local-remakes") o.local_remakes = true;
      else if(a == "--features") {
        const std::string v = args.value(a);
        if(v != "none") throw cli::Usage_error("--features takes 'none' (use --sharp-angle A for an angle)");
        o.features = false;
      }
      else if(a == "--no-self-intersections") o.self_intersections = false;
      else if(a == "--full-report") o.full_report = true;
      else if(a == "--quiet" || a == "-q") o.quiet = true;
      else if(a == "--timings") o.timings = true;
      else if(a == "--threads") {
        o.threads = args.whole_number(a);
        if(o.threads == 0) throw cli::Usage_error("--threads needs at least 1");
      }
      else if(a == "-o" || a == "--output-dir") o.output_dir = args.value(a);
      else if(a == "--format") o.format = args.value(a);
      else if(a == "-j" || a == "--jobs") o.jobs = args.whole_number(a);
      else if(a == "--summary") o.summary_csv = args.value(a);
      else if(a == "--summary-json") o.summary_json = args.value(a);
      else if(!a.empty() && a[0] == '-') throw cli::Usage_error("unknown option " + a);
      else files.push_back(a);
    }
    if(o.output_dir.empty() && files.size() > 2) throw cli::Usage_error("too many file names (give IN and OUT, or several inputs with -o OUTDIR)");
    if(!o.output_dir.empty() && files.empty()) throw cli::Usage_error("-o OUTDIR needs at least one input (a mesh file or a folder)");
    if(o.vertices > 0 && o.edge_length > 0) throw cli::Usage_error("give --vertices or --edge-length, not both");
    if(o.method != "poisson" && o.method != "isotropic") throw cli::Usage_error("--method is poisson or isotropic, not " + o.method);
    if(o.format != "off" && o.format != "obj" && o.format != "ply" && o.format != "stl") throw cli::Usage_error("--format is off, obj, ply or stl, not " + o.format);
    if(o.jobs == 0) throw cli::Usage_error("--jobs needs at least 1");
    o.density.validate();
    if(o.fidelity < 0) throw cli::Usage_error("--fidelity-tolerance must be >= 0");
    if(o.method == "isotropic" && (o.density.adaptive || !o.density.density_file.empty()))
      throw cli::Usage_error("adaptive density is for --method poisson");
    if(!o.output_dir.empty() && !o.density.density_file.empty())
      throw cli::Usage_error("--density FILE gives one value per vertex of one mesh: not for a batch");
    if(!o.output_dir.empty() && (!o.report_file.empty() || !o.svg_file.empty() || !o.density_svg_file.empty() || !o.picture_file.empty()))
      throw cli::Usage_error("--report, --svg, --density-svg and --picture name one file: not for a batch (use --summary)");
  } catch(const cli::Usage_error& e) {
    std::cerr << "poisson_remesh: " << e.what() << "\n";
    cli::print_usage(std::cerr, usage);
    return cli::usage_error;
  }

  if(!o.output_dir.empty()) {
    std::vector<std::pair<std::string, std::string>> jobs;
    std::set<std::string> outputs;
    for(const std::string& f : files) {
      const std::vector<std::string> inputs = expand_input(f);
      if(inputs.empty()) std::cerr << "poisson_remesh: note: no mesh file in folder '" << f << "'\n";
      for(const std::string& in : inputs) {
        const std::string out = (fs::path(o.output_dir) / (fs::path(in).stem().string() + "_remeshed." + o.format)).string();
        if(!outputs.insert(out).second) {
          std::cerr << "poisson_remesh: two inputs would both be written to '" << out << "'\n";
          return cli::usage_error;
        }
        jobs.push_back({in, out});
      }
    }
    if(jobs.empty()) { std::cerr << "poisson_remesh: no input mesh found\n"; return cli::input_error; }
    std::error_code ec;
    fs::create_directories(o.output_dir, ec);
    if(!fs::is_directory(o.output_dir, ec)) {
      std::cerr << "poisson_remesh: cannot create the output folder '" << o.output_dir << "'\n";
      return cli::output_error;
    }
    return run_batch(o, jobs);
  }

  const std::string in = files.size() > 0 ? files[0] : cli::data_mesh("meshes/fandisk.off");
  const std::string out = files.size() > 1 ? files[1] : fs::path(in).stem().string() + "_remeshed.off";
  const std::string out_ext = PR::internal::lower_extension(out);
  if(out_ext != "off" && out_ext != "obj" && out_ext != "ply" && out_ext != "stl") {
    std::cerr << "poisson_remesh: cannot write '" << out << "': unsupported extension (use .off .obj .ply .stl)\n";
    return cli::usage_error;
  }
  Terminal_progress progress(!o.quiet && isatty(STDERR_FILENO));
  Row row;
  const int code = remesh_one(o, in, out, true, progress, row);
  if(code == cli::ok && (!o.summary_csv.empty() || !o.summary_json.empty())) {
    try {
      write_summaries(o, {row});
    } catch(const PR::Output_error& e) {
      std::cerr << "poisson_remesh: " << e.what() << "\n";
      return cli::output_error;
    }
  }
  return code;
}
