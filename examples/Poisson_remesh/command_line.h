// Small command-line helpers shared by the example programs (not part of the library).
#ifndef POISSON_REMESH_EXAMPLES_COMMAND_LINE_H
#define POISSON_REMESH_EXAMPLES_COMMAND_LINE_H

#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {

/// Exit codes of every program of the package.
enum Exit_code { ok = 0, input_error = 1, usage_error = 2, output_error = 3, internal_error = 5 };

struct Usage_error : std::runtime_error { using std::runtime_error::runtime_error; };

/// Walks argv; options take their value from the next argument.
class Arguments
{
public:
  Arguments(int argc, char** argv) : args_(argv + 1, argv + argc) {}
  bool done() const { return i_ >= args_.size(); }
  const std::string& peek() const { return args_[i_]; }
  std::string next() { return args_[i_++]; }
  std::string value(const std::string& option)
  {
    if(done()) throw Usage_error("option " + option + " needs a value");
    return next();
  }
  double number(const std::string& option, double min_exclusive = -HUGE_VAL)
  {
    const std::string v = value(option);
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(v.c_str(), &end);
    if(end == v.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(x))
      throw Usage_error("option " + option + " needs a number, not '" + v + "'");
    if(!(x > min_exclusive))
      throw Usage_error("option " + option + " needs a number greater than " + std::to_string(min_exclusive) + ", not '" + v + "'");
    return x;
  }
  unsigned long whole_number(const std::string& option)
  {
    const std::string v = value(option);
    char* end = nullptr;
    errno = 0;
    const unsigned long long x = std::strtoull(v.c_str(), &end, 10);
    if(v.empty() || v[0] == '-' || end == v.c_str() || *end != '\0' || errno == ERANGE)
      throw Usage_error("option " + option + " needs a whole number, not '" + v + "'");
    return static_cast<unsigned long>(x);
  }
private:
  std::vector<std::string> args_;
  std::size_t i_ = 0;
};

/// The adaptive-density options shared by poisson_remesh and poisson_sample (issue 6).
struct Density_options
{
  bool adaptive = false;
  double gamma = -1, min_edge = 0, max_edge = 0;
  long smoothing = -1;
  std::string density_file;

  static constexpr const char* help =
    "adaptive density (default: uniform):\n"
    "  --adaptive          denser where the surface bends (principal curvatures, paper §5)\n"
    "  --gamma G           density ~ curvature^G (default 1; 0 is uniform)\n"
    "  --min-edge A --max-edge B   clamp the target edge length to [A, B] (default: B = 5 A, set\n"
    "                      by the vertex count)\n"
    "  --smoothing K       Laplacian smoothing passes of the density (default 8)\n"
    "  --density FILE      the density at each input vertex, one number per vertex in the order\n"
    "                      of the input file (relative: scaled to the target vertex count)\n";

  /// Consumes option `a` if it is one of the above.
  bool parse(const std::string& a, Arguments& args)
  {
    if(a == "--adaptive") adaptive = true;
    else if(a == "--gamma") gamma = args.number(a, -1e-300);
    else if(a == "--min-edge") min_edge = args.number(a, 0);
    else if(a == "--max-edge") max_edge = args.number(a, 0);
    else if(a == "--smoothing") smoothing = long(args.whole_number(a));
    else if(a == "--density") density_file = args.value(a);
    else return false;
    return true;
  }

  void validate() const
  {
    const bool tuning = gamma >= 0 || min_edge > 0 || max_edge > 0 || smoothing >= 0;
    if(tuning && !adaptive) throw Usage_error("--gamma, --min-edge, --max-edge and --smoothing go with --adaptive");
    if(adaptive && !density_file.empty()) throw Usage_error("give --adaptive or --density, not both");
    if((min_edge > 0) != (max_edge > 0)) throw Usage_error("give both --min-edge and --max-edge");
    if(min_edge > 0 && !(min_edge < max_edge)) throw Usage_error("--min-edge must be smaller than --max-edge");
  }
};

/// Prints a program's usage text, whose "%s" stands for the density options' help.
inline void print_usage(std::ostream& os, const std::string& usage)
{
  std::string text = usage;
  const std::size_t at = text.find("%s");
  if(at != std::string::npos) text.replace(at, 2, Density_options::help);
  os << text;
}

/// Reads one density per vertex: whitespace-separated numbers, '#' starts a comment. Throws
/// std::runtime_error naming the problem (and the line) when the file is unreadable, holds
/// something else than positive finite numbers, or has not exactly `count` of them.
inline std::vector<double> read_density_file(const std::string& file, std::size_t count)
{
  std::ifstream in(file);
  if(!in) throw std::runtime_error("cannot open density file '" + file + "'");
  std::vector<double> values;
  std::string line;
  std::size_t line_number = 0;
  while(std::getline(in, line)) {
    ++line_number;
    const std::size_t hash = line.find('#');
    if(hash != std::string::npos) line.erase(hash);
    std::istringstream ls(line);
    std::string tok;
    while(ls >> tok) {
      char* end = nullptr;
      const double x = std::strtod(tok.c_str(), &end);
      if(end == tok.c_str() || *end != '\0' || !std::isfinite(x) || !(x > 0))
        throw std::runtime_error("density file '" + file + "', line " + std::to_string(line_number) +
                                 ": '" + tok + "' is not a positive number");
      values.push_back(x);
    }
  }
  if(values.size() != count)
    throw std::runtime_error("density file '" + file + "' has " + std::to_string(values.size()) +
                             " values for " + std::to_string(count) + " vertices");
  return values;
}

/// The density file of the options for `mesh` as read (empty without --density); throws
/// std::runtime_error when the reader merged or dropped points (the file's order is lost) or the
/// file is bad.
template <class Mesh>
std::vector<double> user_densities(const Density_options& o, const Poisson_remesh::Read_report& rr,
                                   const std::string& mesh_file, const Mesh& mesh)
{
  if(o.density_file.empty()) return {};
  if(rr.merged_duplicate_points || rr.removed_isolated_points)
    throw std::runtime_error("the vertices of '" + mesh_file + "' were merged or dropped on reading: "
                             "a density file given per vertex of the file cannot be matched to them");
  return read_density_file(o.density_file, num_vertices(mesh));
}

/// Calls f with the density field the options ask for: Curvature_density (--adaptive), the
/// user's values (a vertex property map added to the Surface_mesh `mesh`), or Uniform_density.
template <class Mesh, class F>
auto with_density(const Density_options& o, Mesh& mesh, const std::vector<double>& user, F f)
{
  namespace PR = Poisson_remesh;
  if(o.adaptive) {
    PR::Curvature_density c;
    if(o.gamma >= 0) c.gamma = o.gamma;
    if(o.smoothing >= 0) c.smoothing = unsigned(o.smoothing);
    c.min_edge = o.min_edge;
    c.max_edge = o.max_edge;
    return f(c);
  }
  if(!user.empty()) {
    typedef typename Mesh::Vertex_index V;
    auto map = mesh.template add_property_map<V, double>("v:user_density", 1.0).first;
    for(std::size_t i = 0; i < user.size(); ++i) map[V(typename Mesh::size_type(i))] = user[i];
    return f(PR::vertex_density(map));
  }
  return f(PR::Uniform_density());
}

/// CGAL's data set as extracted by the build (meshes/fandisk.off, ...).
inline std::string data_mesh(const std::string& name)
{
#ifdef POISSON_REMESH_DATA_DIR
  return std::string(POISSON_REMESH_DATA_DIR) + "/" + name;
#else
  return name;
#endif
}

} // namespace cli

#endif
