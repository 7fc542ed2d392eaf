// remesh_benchmark -- runs every contender on the same meshes at the same target vertex count,
// in the same run, and writes a Markdown and a JSON table of quality, time and peak memory.
//
// Each (contender, mesh) pair runs in a child process (fork), so that its peak memory (VmHWM)
// is its own and a crash of one contender does not end the run (VmHWM is reset just before the
// remesh, so the input mesh, already read, is counted, the quality report afterwards is not).
// Time is the wall clock of the remesh call alone (reading and reporting excluded; the peer: of its
// kept calibration run), single-threaded.
//
// usage: remesh_benchmark [--meshes fandisk,triceratops,...] [--factor F] [--contenders a,b]
//                         [--markdown FILE] [--json FILE]   (tables on stdout; files only when named)
#include "benchmark_support.h"
#include "isotropic_remeshing_peer.h"
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>

#include <sys/utsname.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;
using benchmark_support::fmt;
using benchmark_support::machine_description;
using benchmark_support::peak_memory_mib;
using benchmark_support::split;

struct Row
{
  std::string contender, mesh;
  bool ok = false;
  std::string error;
  double input_vertices = 0, input_faces = 0, target = 0, vertices = 0, faces = 0;
  double min_angle = 0, min_angle_away = 0, mean_min_angle = 0, below_30 = 0, irregular = 0, rms = 0, hausdorff = 0;
  double self_intersections = 0, self_intersections_away = 0, genus_kept = 0, seconds = 0, peak_mib = 0;
};

// A contender remeshes `input` into `output` at `target` vertices and returns the seconds spent.
typedef std::function<double(const Mesh& input, double target, Mesh& output)> Contender;

static unsigned int seed = 1;   // --seed: the random seed of our contenders

// the wall-clock seconds of f()
template <class F>
static double wall_seconds(F f)
{
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

static std::map<std::string, Contender> contenders()
{
  // ours: the wall clock of the library call (not the sum of its stage timers); the peer: that of
  // its kept calibration run (Peers::isotropic_remeshing_at_vertex_count times each run alone)
  return {
    {"poisson_remesh", [](const Mesh& input, double target, Mesh& output) {
       return wall_seconds([&] { PR::poisson_remesh(input, output, PR::parameters::target_vertex_count(std::size_t(target)).random_seed(seed)); });
     }},
    {"poisson_adaptive", [](const Mesh& input, double target, Mesh& output) {
       return wall_seconds([&] {
         PR::poisson_remesh(input, output, PR::parameters::target_vertex_count(std::size_t(target)).random_seed(seed).density(PR::Curvature_density()));
       });
     }},
    {"cgal_isotropic", [](const Mesh& input, double target, Mesh& output) {
       PR::Peers::Isotropic_remeshing_settings s;
       s.target_vertex_count = target;
       s.sharp_angle = 60;
       s.iterations = 5;
       return PR::Peers::isotropic_remeshing_at_vertex_count(input, output, s).seconds;
     }},
  };
}

// Runs in the child: everything for one row, written as "key value" lines to fd.
static void run_row(const std::string& contender, const Contender& run, const std::string& mesh_file, double factor, int fd)
{
  std::ostringstream os;
  os.precision(17);
  try {
    Mesh input, output;
    PR::read_surface_mesh(mesh_file, input);
    const double target = std::round(factor * double(num_vertices(input)));
    std::ofstream("/proc/self/clear_refs") << "5"; // reset VmHWM: the peak is the remesh's own
    const double seconds = run(input, target, output);
    const double peak = peak_memory_mib();
    const PR::Quality_report in = PR::quality_report(input, PR::parameters::check_self_intersections(false));
    const PR::Quality_report r = PR::quality_report(output, input);
    os << "ok 1\ninput_vertices " << num_vertices(input) << "\ninput_faces " << num_faces(input) << "\ntarget " << target << "\nvertices " << r.number_of_vertices
       << "\nfaces " << r.number_of_faces << "\nmin_angle " << r.min_angle
       << "\nmin_angle_away " << r.min_angle_away_from_sharp_corners.value_or(-1) << "\nmean_min_angle " << r.mean_min_angle
       << "\nbelow_30 " << r.share_min_angle_below_30 << "\nirregular " << r.irregular_share
       << "\nrms " << benchmark_support::two_sided_rms_distance(output, input) / in.bbox_diagonal
       << "\nhausdorff " << (r.hausdorff ? *r.hausdorff : -1) << "\nself_intersections " << r.number_of_self_intersecting_face_pairs
       << "\nself_intersections_away " << double(r.number_of_self_intersecting_face_pairs_away_from_reference_ones.value_or(r.number_of_self_intersecting_face_pairs))
       << "\ngenus_kept " << (r.genus == in.genus && r.number_of_components == in.number_of_components ? 1 : 0)
       << "\nseconds " << seconds << "\npeak_mib " << peak << "\n";
  } catch(const std::exception& e) {
    os << "ok 0\nerror " << e.what() << "\n";
  }
  const std::string s = os.str();
  ssize_t written = write(fd, s.data(), s.size());
  (void)written;
}

static Row run_in_child(const std::string& contender, const Contender& run, const std::string& mesh_name,
                        const std::string& mesh_file, double factor)
{
  Row row;
  row.contender = contender;
  row.mesh = mesh_name;
  int fds[2];
  if(pipe(fds) != 0) { row.error = "pipe failed"; return row; }
  std::cout.flush();
  const pid_t pid = fork();
  if(pid == 0) {
    close(fds[0]);
    run_row(contender, run, mesh_file, factor, fds[1]);
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buf[4096];
  ssize_t n;
  while((n = read(fds[0], buf, sizeof(buf))) > 0) text.append(buf, std::size_t(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  std::map<std::string, double> v = benchmark_support::parse_report(text, row.error);
  if(v["ok"] != 1) {
    if(row.error.empty()) row.error = WIFSIGNALED(status) ? std::string("killed by signal ") + strsignal(WTERMSIG(status)) : "failed";
    return row;
  }
  row.ok = true;
  row.input_vertices = v["input_vertices"]; row.input_faces = v["input_faces"]; row.target = v["target"]; row.vertices = v["vertices"]; row.faces = v["faces"];
  row.min_angle = v["min_angle"]; row.min_angle_away = v["min_angle_away"]; row.mean_min_angle = v["mean_min_angle"]; row.below_30 = v["below_30"];
  row.irregular = v["irregular"]; row.rms = v["rms"]; row.hausdorff = v["hausdorff"]; row.self_intersections = v["self_intersections"];
  row.self_intersections_away = v["self_intersections_away"];
  row.genus_kept = v["genus_kept"]; row.seconds = v["seconds"]; row.peak_mib = v["peak_mib"];
  return row;
}

int main(int argc, char** argv)
{
  std::vector<std::string> meshes = {"fandisk", "triceratops", "dino", "elephant", "cow", "knot1", "femur", "bull"};
  // (poisson_adaptive, the curvature-adaptive remesh, runs when asked for with --contenders)
  std::vector<std::string> names = {"cgal_isotropic", "poisson_remesh"};
  double factor = 1.0;
  // no file unless asked for (a default name once overwrote the hand-written RESULTS.md)
  std::string markdown, json, data = POISSON_REMESH_DATA_DIR;
  bool scale_table = false;
  for(int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if(i + 1 >= argc) { std::cerr << "remesh_benchmark: " << a << " needs a value\n"; std::exit(2); }
      return argv[++i];
    };
    if(a == "--meshes") meshes = split(value());
    else if(a == "--contenders") names = split(value());
    else if(a == "--factor") factor = std::stod(value());
    else if(a == "--markdown") markdown = value();
    else if(a == "--json") json = value();
    else if(a == "--data") data = value();
    else if(a == "--scale") scale_table = true;
    else if(a == "--seed") seed = unsigned(std::stoul(value()));
    else if(a == "--help") {
      std::cout << "usage: remesh_benchmark [--meshes a,b] [--contenders c,d] [--factor F] [--markdown FILE] [--json FILE] [--data DIR] [--scale] [--seed S]\n"
                   "  runs each contender on CGAL data meshes at F times the input's vertex count\n"
                   "  (a mesh given with a '/' is a file); --scale adds a table of time and peak memory per input\n"
                   "  face and their growth exponents from one mesh size to the next (meshes of one surface at\n"
                   "  increasing sizes, as make_scale_series writes them); --seed sets our contenders' random\n"
                   "  seed (default 1)\n";
      return 0;
    }
    else { std::cerr << "remesh_benchmark: unknown option " << a << "\n"; return 2; }
  }
  const auto all = contenders();
  std::vector<Row> rows;
  for(const std::string& mesh : meshes) {
    const bool is_path = mesh.find('/') != std::string::npos;
    const std::string file = is_path ? mesh : data + "/meshes/" + mesh + ".off";
    const std::string shown = is_path ? std::filesystem::path(mesh).stem().string() : mesh;
    for(const std::string& c : names) {
      if(!all.count(c)) { std::cerr << "remesh_benchmark: unknown contender " << c << "\n"; return 2; }
      std::cerr << "running " << c << " on " << shown << " ..." << std::flush;
      rows.push_back(run_in_child(c, all.at(c), shown, file, factor));
      std::cerr << (rows.back().ok ? " " + fmt(rows.back().seconds, 3) + " s\n" : " FAILED: " + rows.back().error + "\n");
    }
  }

  std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  std::ostringstream md;
  md << "| contender | mesh | input V | target V | V | θmin (°) | θmin away from sharp corners (°) | θ̄min (°) | <30° (%) | irregular (%) | RMS (% diag) | Hausdorff (% diag) | self-int. pairs | away from the input's own | topology kept | seconds | peak MiB |\n"
     << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|---:|---:|\n";
  for(const Row& r : rows) {
    if(!r.ok) { md << "| " << r.contender << " | " << r.mesh << " | failed: " << r.error << " |||||||||||||||\n"; continue; }
    md << "| " << r.contender << " | " << r.mesh << " | " << fmt(r.input_vertices, 0) << " | " << fmt(r.target, 0) << " | "
       << fmt(r.vertices, 0) << " | " << fmt(r.min_angle, 2) << " | " << fmt(r.min_angle_away, 2) << " | " << fmt(r.mean_min_angle, 2) << " | "
       << fmt(100 * r.below_30, 2) << " | " << fmt(100 * r.irregular, 1) << " | " << fmt(100 * r.rms, 4) << " | " << fmt(100 * r.hausdorff, 3) << " | "
       << fmt(r.self_intersections, 0) << " | " << fmt(r.self_intersections_away, 0) << " | " << (r.genus_kept ? "yes" : "no") << " | " << fmt(r.seconds, 3) << " | "
       << fmt(r.peak_mib, 0) << " |\n";
  }
  {
    // with both of our densities: how much closer to the input the adaptive remesh is, per mesh
    // and at the median (issue 22 asks for 25% less RMS and 20% less Hausdorff distance)
    std::vector<double> rms_ratio, hausdorff_ratio;
    std::ostringstream per_mesh;
    for(const Row& a : rows) {
      if(!a.ok || a.contender != "poisson_adaptive") continue;
      for(const Row& u : rows)
        if(u.ok && u.contender == "poisson_remesh" && u.mesh == a.mesh && u.rms > 0 && u.hausdorff > 0) {
          rms_ratio.push_back(a.rms / u.rms);
          hausdorff_ratio.push_back(a.hausdorff / u.hausdorff);
          per_mesh << "| " << a.mesh << " | " << fmt(100 * (a.rms / u.rms - 1), 1) << " | " << fmt(100 * (a.hausdorff / u.hausdorff - 1), 1) << " |\n";
        }
    }
    if(!rms_ratio.empty()) {
      auto median = [](std::vector<double> x) {
        std::sort(x.begin(), x.end());
        const std::size_t n = x.size();
        return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
      };
      md << "\n| mesh | adaptive against uniform: RMS (%) | Hausdorff (%) |\n|---|---:|---:|\n" << per_mesh.str()
         << "| **median** | " << fmt(100 * (median(rms_ratio) - 1), 1) << " | " << fmt(100 * (median(hausdorff_ratio) - 1), 1) << " |\n";
    }
  }
  if(scale_table) {
    // per contender, by increasing input size: cost per input face, and the exponent k of
    // cost ~ faces^k between consecutive sizes (k = 1: linear)
    md << "\n| contender | input faces | V out | seconds | µs / input face | time exponent | peak MiB | KiB / input face | memory exponent | time ours/peer | memory ours/peer |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for(const std::string& c : names) {
      std::vector<const Row*> series;
      for(const Row& r : rows) if(r.ok && r.contender == c) series.push_back(&r);
      std::sort(series.begin(), series.end(), [](const Row* a, const Row* b) { return a->input_faces < b->input_faces; });
      for(std::size_t i = 0; i < series.size(); ++i) {
        const Row& r = *series[i];
        auto exponent = [&](double now, double before) {
          if(i == 0 || before <= 0 || now <= 0) return std::string("");
          return fmt(std::log(now / before) / std::log(r.input_faces / series[i - 1]->input_faces), 2);
        };
        // the other contender on the same mesh, for the ratios
        const Row* peer = nullptr;
        for(const Row& o : rows) if(o.ok && o.mesh == r.mesh && o.contender == "cgal_isotropic" && c != o.contender) peer = &o;
        md << "| " << c << " | " << fmt(r.input_faces, 0) << " | " << fmt(r.vertices, 0) << " | " << fmt(r.seconds, 2) << " | "
           << fmt(1e6 * r.seconds / r.input_faces, 1) << " | " << exponent(r.seconds, i ? series[i - 1]->seconds : 0) << " | "
           << fmt(r.peak_mib, 0) << " | " << fmt(1024 * r.peak_mib / r.input_faces, 2) << " | "
           << exponent(r.peak_mib, i ? series[i - 1]->peak_mib : 0) << " | "
           << (peer ? fmt(r.seconds / peer->seconds, 2) : std::string("")) << " | "
           << (peer ? fmt(r.peak_mib / peer->peak_mib, 2) : std::string("")) << " |\n";
      }
    }
  }
  std::cout << md.str();
  if(!markdown.empty())
    std::ofstream(markdown) << "<!-- written by remesh_benchmark on " << date << " -->\n"
                          << "Machine: " << machine_description() << "\n\n"
                          << "Target: " << factor << " × the input's vertex count; time: the wall clock of one remesh call (the peer: of its kept calibration run), single-threaded.\n\n"
                          << md.str();
  if(json.empty()) return 0;
  std::ofstream js(json);
  js.precision(10);
  js << "{\n  \"date\": \"" << date << "\",\n  \"machine\": \"" << machine_description() << "\",\n  \"factor\": " << factor << ",\n  \"rows\": [\n";
  for(std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    js << "    {\"contender\": \"" << r.contender << "\", \"mesh\": \"" << r.mesh << "\", \"ok\": " << (r.ok ? "true" : "false");
    if(r.ok)
      js << ", \"input_vertices\": " << r.input_vertices << ", \"input_faces\": " << r.input_faces << ", \"target_vertices\": " << r.target << ", \"vertices\": " << r.vertices
         << ", \"faces\": " << r.faces << ", \"min_angle_deg\": " << r.min_angle << ", \"min_angle_away_from_sharp_corners_deg\": " << r.min_angle_away << ", \"mean_min_angle_deg\": " << r.mean_min_angle
         << ", \"share_min_angle_below_30\": " << r.below_30 << ", \"irregular_share\": " << r.irregular
         << ", \"rms_over_diagonal\": " << r.rms << ", \"hausdorff_over_diagonal\": " << r.hausdorff << ", \"self_intersecting_pairs\": " << r.self_intersections
         << ", \"self_intersecting_pairs_away_from_input_ones\": " << r.self_intersections_away
         << ", \"topology_kept\": " << (r.genus_kept ? "true" : "false") << ", \"seconds\": " << r.seconds
         << ", \"peak_mib\": " << r.peak_mib;
    else js << ", \"error\": \"" << r.error << "\"";
    js << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
  }
  js << "  ]\n}\n";
  return 0;
}
