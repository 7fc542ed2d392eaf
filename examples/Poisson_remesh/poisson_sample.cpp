// poisson_sample IN OUT.xyz (--vertices N | --spacing D) [--features none|ANGLE] [--seed S] [--adaptive | --density FILE]
//
// A maximal geodesic Poisson-disk sample set of a triangle surface (paper §4), written as one
// "x y z" line per sample: object distribution on surfaces (§8), or the vertices of a remesh.
// D is the minimum geodesic distance between samples (2r).
#include "command_line.h"

#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/poisson_disk_sample.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif
#include <Poisson_remesh/read_surface_mesh.h>
#include <Poisson_remesh/write_surface_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cstdio>
#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

static const char* usage =
  "usage: poisson_sample IN OUT.xyz (--vertices N | --spacing D) [options]\n"
  "  Writes a maximal geodesic Poisson-disk set of the surface IN (OFF, OBJ, PLY, STL) to OUT,\n"
  "  one 'x y z' line per sample: no two samples closer than D along the surface, every surface\n"
  "  point within D of a sample. Sharp features are sampled first.\n"
  "  --vertices N      about N samples (the radius follows from Eq. 1 of the paper)\n"
  "  --spacing D       minimum geodesic distance between samples (D = 2r)\n"
  "options:\n"
  "  --features F      none, or the dihedral angle in degrees over which edges are features (default 60)\n"
  "  --seed S          random seed (default 0); the same seed gives the same samples\n"
  "  --kinds           add a fourth column: 0 corner, 1 feature, 2 surface\n"
  "  --radii           add a column with each sample's disk radius r (samples p, q are at least\n"
  "                    r(p) + r(q) apart; with adaptive density r varies)\n"
  "  --threads N       the parallel mode on N threads (slabs of the surface filled at once): another\n"
  "                    maximal set than the default sequential one, the same for any N\n"
  "  --help            this text\n"
  "%s"
  "  (with a density, --spacing D sets the count that uniform spacing D would give)\n"
  "exit codes: 0 done, 1 bad input, 2 bad usage, 3 output not written\n";


int main(int argc, char** argv)
{
  std::vector<std::string> files;
  double vertices = 0, spacing = 0, angle = 60;
  bool features = true, kinds = false, radii = false;
  cli::Density_options density;
  unsigned long seed = 0, threads = 0;
  try {
    cli::Arguments args(argc, argv);
    while(!args.done()) {
      const std::string a = args.next();
      if(a == "--help" || a == "-h") { cli::print_usage(std::cout, usage); return cli::ok; }
      else if(density.parse(a, args)) {}
      else if(a == "--radii") radii = true;
      else if(a == "--vertices") vertices = double(args.whole_number(a));
      else if(a == "--spacing") spacing = args.number(a, 0);
      else if(a == "--seed") seed = args.whole_number(a);
      else if(a == "--kinds") kinds = true;
      else if(a == "--threads") {
        threads = args.whole_number(a);
        if(threads == 0) throw cli::Usage_error("--threads needs at least 1");
      }
      else if(a == "--features") {
        const std::string v = args.value(a);
        if(v == "none") features = false;
        else {
          char* end = nullptr;
          angle = std::strtod(v.c_str(), &end);
          if(end == v.c_str() || *end || !(angle > 0 && angle < 180))
            throw cli::Usage_error("--features is none or an angle in (0, 180) degrees, not " + v);
        }
      }
      else if(!a.empty() && a[0] == '-') throw cli::Usage_error("unknown option " + a);
      else files.push_back(a);
    }
    if(files.size() != 2) throw cli::Usage_error("give IN and OUT");
    if((vertices > 0) == (spacing > 0)) throw cli::Usage_error("give one of --vertices N or --spacing D");
    density.validate();
  } catch(const cli::Usage_error& e) {
    std::cerr << "poisson_sample: " << e.what() << "\n";
    cli::print_usage(std::cerr, usage);
    return cli::usage_error;
  }

  Mesh mesh;
  std::vector<double> user_density;
  try {
    const PR::Read_report rr = PR::read_surface_mesh(files[0], mesh);
    user_density = cli::user_densities(density, rr, files[0], mesh);
  } catch(const std::exception& e) {
    std::cerr << "poisson_sample: " << e.what() << "\n";
    return cli::input_error;
  }

  std::vector<PR::Poisson_sample<Mesh, K::Point_3>> samples;
  const auto start = std::chrono::steady_clock::now();
  auto np = PR::parameters::random_seed(unsigned(seed))
              .feature_policy(features ? PR::Feature_policy::detect : PR::Feature_policy::none)
              .sharp_angle(angle);
  // (--threads: the parallel mode, on that many of TBB's threads)
#ifdef CGAL_LINKED_WITH_TBB
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, std::max<std::size_t>(1, threads));
#endif
  auto run = [&](const auto& field) {
    auto sample = [&](const auto& named) {
      if(threads > 0) return PR::poisson_disk_sample<CGAL::Parallel_if_available_tag>(mesh, std::back_inserter(samples), named);
      return PR::poisson_disk_sample(mesh, std::back_inserter(samples), named);
    };
    return spacing > 0 ? sample(np.sampling_radius(0.5 * spacing).density(field))
                       : sample(np.target_vertex_count(std::size_t(vertices)).density(field));
  };
  const PR::Poisson_disk_sampling_result result = cli::with_density(density, mesh, user_density, run);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  try {
    PR::write_file_atomically(files[1], [&](std::ostream& os) {
      char line[192];
      for(const auto& s : samples) {
        int n = std::snprintf(line, sizeof(line), "%.17g %.17g %.17g", s.point.x(), s.point.y(), s.point.z());
        if(kinds) n += std::snprintf(line + n, sizeof(line) - std::size_t(n), " %d", int(s.kind));
        if(radii) n += std::snprintf(line + n, sizeof(line) - std::size_t(n), " %.17g", s.radius);
        line[n++] = '\n';
        os.write(line, n);
      }
    });
  } catch(const PR::Output_error& e) {
    std::cerr << "poisson_sample: " << e.what() << "\n";
    return cli::output_error;
  }
  std::cerr << "poisson_sample: " << samples.size() << " samples (" << result.number_of_corners << " corners, "
            << result.number_of_feature_samples << " on feature curves), spacing 2r = " << 2 * result.radius
            << (result.max_radius > result.min_radius ? " (median; adaptive from " + std::to_string(2 * result.min_radius) + " to " +
                                                          std::to_string(2 * result.max_radius) + ")" : std::string())
            << (result.statistics.slabs > 0 ? ", " + std::to_string(result.statistics.slabs) + " slabs" : std::string()) << ", " << seconds << " s\n";
  return cli::ok;
}
