// Small command-line helpers shared by the example programs (not part of the library).
#ifndef POISSON_REMESH_EXAMPLES_COMMAND_LINE_H
#define POISSON_REMESH_EXAMPLES_COMMAND_LINE_H

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {

/// Exit codes of every program of the package.
enum Exit_code { ok = 0, input_error = 1, usage_error = 2, output_error = 3, not_available = 4, internal_error = 5 };

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
