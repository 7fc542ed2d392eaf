// sampling_benchmark -- the geodesic Poisson-disk sampler (paper §4, §7):
//   1. the calibration of rho in Eq. 1 (paper Fig. 10): N = 500..5000 per unit square, step 100,
//      sampled with rho = 1; the mean of N'/N gives rho = sqrt(mean) (the paper found 0.844);
//   2. count accuracy and speed on CGAL data meshes at their own vertex count and at 4x, rho = 0.844;
//   3. the radially averaged power spectrum of a flat square's samples, drawn as SVG.
// usage: sampling_benchmark [--markdown FILE] [--svg FILE] [--quick]
#include <Poisson_remesh/poisson_disk_sample.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include "../../test/Poisson_remesh/analytic_meshes.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cmath>
#include <complex>
#include <fstream>
#include <iostream>
#include <sstream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Poisson_remesh::Poisson_sample<Mesh, K::Point_3> Sample;
namespace PR = Poisson_remesh;

static double seconds_since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

int main(int argc, char** argv)
{
  std::string markdown = "sampling_results.md", svg = "sampling_spectrum.svg";
  bool quick = false;
  for(int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if(a == "--markdown" && i + 1 < argc) markdown = argv[++i];
    else if(a == "--svg" && i + 1 < argc) svg = argv[++i];
    else if(a == "--quick") quick = true;
    else { std::cerr << "usage: sampling_benchmark [--markdown FILE] [--svg FILE] [--quick]\n"; return 2; }
  }
  std::ostringstream md;

  // 1. rho calibration on the unit square
  const Mesh square = analytic::plane(40, 40).to_mesh<Mesh>();
  double sum = 0, sum2 = 0;
  int runs = 0;
  md << "### Calibration of rho (Eq. 1, paper Fig. 10)\n\nUnit square, rho = 1, N = 500..5000 step " << (quick ? 500 : 100)
     << ", seed = N, borders sampled as features.\n\n| N | N' (rho = 1) | N'/N |\n|---:|---:|---:|\n";
  for(int n = 500; n <= 5000; n += quick ? 500 : 100) {
    const double area = 1.0;
    const double r = PR::disk_radius_from_vertex_count(area, n, 1.0);
    std::vector<Sample> s;
    PR::poisson_disk_sample(square, std::back_inserter(s), PR::parameters::sampling_radius(r).random_seed(unsigned(n)));
    const double ratio = double(s.size()) / n;
    sum += ratio; sum2 += ratio * ratio; ++runs;
    if(n % 500 == 0) md << "| " << n << " | " << s.size() << " | " << ratio << " |\n";
  }
  const double mean = sum / runs, var = sum2 / runs - mean * mean, rho = std::sqrt(mean);
  md << "\nMean N'/N = " << mean << " (variance " << var << ") over " << runs << " runs: fitted rho = sqrt(mean) = **" << rho
     << "** (paper: 0.7124 and 0.844).\n\n";
  std::cerr << "rho fitted: " << rho << "\n";

  // 2. counts and speed on data meshes
  md << "### Count accuracy and speed (rho = 0.844), single-threaded\n\n"
     << "| mesh | faces | target N | samples | error (%) | corners + feature samples | seconds | samples / s |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
  const std::vector<std::string> meshes = quick ? std::vector<std::string>{"fandisk", "triceratops"}
    : std::vector<std::string>{"fandisk", "triceratops", "dino", "elephant", "cow", "knot1", "femur", "bull"};
  for(const std::string& name : meshes) {
    Mesh m;
    PR::read_surface_mesh(std::string(POISSON_REMESH_DATA_DIR) + "/meshes/" + name + ".off", m);
    for(int factor : {1, 4}) {
      const std::size_t n = factor * num_vertices(m);
      std::vector<Sample> s;
      const auto t = std::chrono::steady_clock::now();
      const auto res = PR::poisson_disk_sample(m, std::back_inserter(s), PR::parameters::target_vertex_count(n).random_seed(1u));
      const double sec = seconds_since(t);
      md << "| " << name << " | " << num_faces(m) << " | " << n << " | " << s.size() << " | "
         << 100.0 * (double(s.size()) - double(n)) / double(n) << " | " << res.number_of_corners + res.number_of_feature_samples
         << " | " << sec << " | " << std::llround(double(s.size()) / sec) << " |\n";
      std::cerr << name << " x" << factor << ": " << s.size() << " samples in " << sec << " s\n";
    }
  }

  // 3. spectrum on a flat square
  const double n_spec = quick ? 1500 : 4000;
  std::vector<Sample> s;
  const auto res = PR::poisson_disk_sample(square, std::back_inserter(s), PR::parameters::target_vertex_count(std::size_t(n_spec)).random_seed(5u));
  const double f0 = 1 / (2 * res.radius), fmax = 2.5 * f0;
  const int rings = 60, grid = quick ? 60 : 100;
  std::vector<double> power(rings, 0), count(rings, 0);
  double norm = 0;
  for(const Sample& x : s) norm += std::pow(std::sin(M_PI * x.point.x()) * std::sin(M_PI * x.point.y()), 4);
  for(int i = -grid; i <= grid; ++i)
    for(int j = 0; j <= grid; ++j) {
      const double fx = fmax * i / grid, fy = fmax * j / grid;
      const int ring = int(std::hypot(fx, fy) / fmax * rings);
      if(ring <= 0 || ring >= rings) continue;
      std::complex<double> acc = 0;
      for(const Sample& x : s) {
        const double w = std::pow(std::sin(M_PI * x.point.x()) * std::sin(M_PI * x.point.y()), 2);
        const double ph = -2 * M_PI * (fx * x.point.x() + fy * x.point.y());
        acc += w * std::complex<double>(std::cos(ph), std::sin(ph));
      }
      power[ring] += std::norm(acc) / norm;
      count[ring] += 1;
    }
  double pmax = 0;
  for(int k = 1; k < rings; ++k) { power[k] /= std::max(1.0, count[k]); pmax = std::max(pmax, power[k]); }
  std::ofstream out(svg);
  const double W = 640, H = 320, L = 60, B = 40;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"" << L << "\" y=\"20\" font-weight=\"bold\">Radially averaged power spectrum, "
      << s.size() << " geodesic Poisson-disk samples on a unit square</text>\n";
  auto X = [&](double f) { return L + (W - L - 20) * f / fmax; };
  auto Y = [&](double p) { return H - B - (H - B - 40) * p / std::max(pmax, 1.0) ; };
  out << "<polyline fill=\"none\" stroke=\"#4a6fa5\" stroke-width=\"2\" points=\"";
  for(int k = 1; k < rings; ++k) out << X((k + 0.5) * fmax / rings) << "," << Y(power[k]) << " ";
  out << "\"/>\n<line x1=\"" << X(0) << "\" y1=\"" << Y(1) << "\" x2=\"" << X(fmax) << "\" y2=\"" << Y(1) << "\" stroke=\"gray\" stroke-dasharray=\"4\"/>\n"
      << "<text x=\"" << X(fmax) - 5 << "\" y=\"" << Y(1) - 4 << "\" text-anchor=\"end\" fill=\"gray\">white noise</text>\n"
      << "<line x1=\"" << X(f0) << "\" y1=\"" << Y(0) << "\" x2=\"" << X(f0) << "\" y2=\"40\" stroke=\"red\"/>\n"
      << "<text x=\"" << X(f0) + 4 << "\" y=\"52\" fill=\"red\">1/(2r)</text>\n"
      << "<line x1=\"" << L << "\" y1=\"" << Y(0) << "\" x2=\"" << W - 20 << "\" y2=\"" << Y(0) << "\" stroke=\"black\"/>\n"
      << "<text x=\"" << (W + L) / 2 << "\" y=\"" << H - 10 << "\" text-anchor=\"middle\">frequency (0 to 2.5 / (2r))</text>\n</svg>\n";
  md << "\n### Spectrum\n\n`" << svg << "`: " << s.size() << " samples on the unit square (Hann-windowed periodogram, "
     << "radially averaged): low energy below 1/(2r), a peak just above it, flat (white) beyond.\n";

  std::cout << md.str();
  std::ofstream(markdown) << md.str();
  return 0;
}
