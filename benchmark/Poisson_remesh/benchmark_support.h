// benchmark_support.h -- what the benchmark programs share: the process's peak memory, the
// machine's description, a comma-separated list, a number printed with fixed digits, and a child
// process's "key value" report.
#ifndef POISSON_REMESH_BENCHMARK_SUPPORT_H
#define POISSON_REMESH_BENCHMARK_SUPPORT_H

#include <CGAL/version.h>

#include <sys/utsname.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace benchmark_support {

// the resident-set peak of this process (VmHWM), in MiB; writing "5" to /proc/self/clear_refs
// resets it
inline double peak_memory_mib()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while(std::getline(status, line))
    if(line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0;
}

// CPU, cores, system, CGAL and compiler
inline std::string machine_description()
{
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  std::string line;
  while(std::getline(info, line))
    if(line.rfind("model name", 0) == 0) { cpu = line.substr(line.find(':') + 2); break; }
  struct utsname u;
  uname(&u);
  std::ostringstream os;
  os << cpu << ", " << sysconf(_SC_NPROCESSORS_ONLN) << " cores, " << u.sysname << " " << u.release << " " << u.machine
     << ", CGAL " << CGAL_VERSION_STR << ", g++ " << __VERSION__;
  return os.str();
}

// "a,b,c" -> {a, b, c} (empty items dropped)
inline std::vector<std::string> split(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while(std::getline(ss, item, ',')) if(!item.empty()) out.push_back(item);
  return out;
}

// x with `digits` digits after the point
inline std::string fmt(double x, int digits)
{
  char b[64];
  std::snprintf(b, sizeof(b), "%.*f", digits, x);
  return b;
}

// "key value" lines -> map; the value of the key "error" (the rest of its line) goes to `error`
inline std::map<std::string, double> parse_report(const std::string& text, std::string& error)
{
  std::istringstream is(text);
  std::string key;
  std::map<std::string, double> v;
  while(is >> key) {
    if(key == "error") { std::getline(is, error); continue; }
    is >> v[key];
  }
  return v;
}

} // namespace benchmark_support

#endif // POISSON_REMESH_BENCHMARK_SUPPORT_H
