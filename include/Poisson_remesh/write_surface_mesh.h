// Poisson_remesh/write_surface_mesh.h
//
// Entry points: write_surface_mesh(filename, mesh, np) and write_file_atomically(filename, writer).
// Outputs are written atomically: into a temporary file next to the destination, which is renamed
// over the destination only once everything was written and flushed. A failure (full disk,
// unwritable directory, exception in the writer) leaves the destination as it was -- never a
// partial or clobbered file -- and throws Poisson_remesh::Output_error.

#ifndef POISSON_REMESH_WRITE_SURFACE_MESH_H
#define POISSON_REMESH_WRITE_SURFACE_MESH_H

#include <Poisson_remesh/internal/plain_off.h>
#include <Poisson_remesh/parameters.h>

#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <iterator>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {

/// Thrown when an output file cannot be written; the destination is left untouched.
class Output_error : public std::runtime_error
{
public:
  /// `message`: a complete sentence for the user, naming the file
  explicit Output_error(const std::string& message) : std::runtime_error(message) {}
};

namespace internal {

// A temporary name in the destination's folder that keeps its extension (CGAL's writers choose
// the format by extension).
inline std::filesystem::path temporary_sibling(const std::filesystem::path& destination)
{
  std::random_device rd;
  const std::filesystem::path dir = destination.has_parent_path() ? destination.parent_path() : std::filesystem::path(".");
  if(!std::filesystem::is_directory(dir))
    throw Output_error("cannot write '" + destination.string() + "': folder '" + dir.string() + "' does not exist");
  for(int attempt = 0; attempt < 100; ++attempt) {
    std::filesystem::path candidate = dir / ("." + destination.stem().string() + ".partial-" +
                                             std::to_string(rd() % 1000000) + destination.extension().string());
    if(!std::filesystem::exists(candidate)) return candidate;
  }
  throw Output_error("cannot write '" + destination.string() + "': no free temporary name in its folder");
}

inline void commit_temporary(const std::filesystem::path& tmp, const std::filesystem::path& destination)
{
  std::error_code ec;
  std::filesystem::rename(tmp, destination, ec);
  if(ec) {
    std::filesystem::remove(tmp, ec);
    throw Output_error("cannot write '" + destination.string() + "': " + ec.message());
  }
}

} // namespace internal

/// Calls `writer(stream)` on a temporary file and, if it succeeded, renames it to `filename`.
inline void write_file_atomically(const std::string& filename, const std::function<void(std::ostream&)>& writer)
{
  const std::filesystem::path destination(filename);
  if(std::filesystem::is_directory(destination))
    throw Output_error("cannot write '" + filename + "': it is a directory");
  const std::filesystem::path tmp = internal::temporary_sibling(destination);
  {
    std::ofstream out(tmp, std::ios::binary);
    if(!out)
      throw Output_error("cannot write '" + filename + "': " + std::strerror(errno));
    try {
      writer(out);
      out.flush();
    } catch(...) {
      out.close();
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw;
    }
    if(!out) {
      out.close();
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw Output_error("cannot write '" + filename + "': write failed (disk full?)");
    }
  }
  internal::commit_temporary(tmp, destination);
}

/*!
  writes `tm` to `filename` in the format its extension names (.off, .obj, .ply, .stl, .ts, .vtp),
  with full double precision, atomically (see the file comment). `np` is passed to CGAL's writer
  (`vertex_point_map`, `use_binary_mode`, ...).
*/
template <class PolygonMesh, class NamedParameters = parameters::Default_named_parameters>
void write_surface_mesh(const std::string& filename, const PolygonMesh& tm,
                        const NamedParameters& np = parameters::default_values())
{
  const std::filesystem::path destination(filename);
  if(std::filesystem::is_directory(destination))
    throw Output_error("cannot write '" + filename + "': it is a directory");
  const std::string ext = destination.extension().string();
  static const char* const supported[] = {".off", ".obj", ".ply", ".stl", ".ts", ".vtp", ".OFF", ".OBJ", ".PLY", ".STL"};
  if(std::find(std::begin(supported), std::end(supported), ext) == std::end(supported))
    throw Output_error("cannot write '" + filename + "': unsupported extension '" + ext + "' (use .off .obj .ply .stl .ts)");
  const std::filesystem::path tmp = internal::temporary_sibling(destination);
  bool ok = false;
  try {
    if((ext == ".off" || ext == ".OFF") && std::is_same<NamedParameters, parameters::Default_named_parameters>::value) {
      // (with no option to pass on, plain ASCII OFF without iostreams' number formatting:
      // internal/plain_off.h; the same points and faces when read back)
      std::vector<typename boost::property_traits<typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::const_type>::value_type> points;
      std::vector<std::vector<std::size_t>> polygons;
      CGAL::Polygon_mesh_processing::polygon_mesh_to_polygon_soup(tm, points, polygons);
      std::vector<std::array<double, 3>> coordinates;
      coordinates.reserve(points.size());
      for(const auto& q : points) coordinates.push_back({CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())});
      std::ofstream out(tmp, std::ios::binary);
      if(out) {
        internal::write_plain_off(out, coordinates, polygons);
        out.flush();
        ok = bool(out);
      }
    } else
      ok = CGAL::IO::write_polygon_mesh(tmp.string(), tm, np.stream_precision(17));
  } catch(const std::exception&) {
    ok = false;
  }
  if(!ok) {
    std::error_code ec;
    const bool existed = std::filesystem::exists(tmp, ec);
    std::filesystem::remove(tmp, ec);
    throw Output_error("cannot write '" + filename + "': " +
                       (existed ? std::string("write failed (disk full?)")
                                : std::string("unwritable folder or unsupported extension (use .off .obj .ply .stl .ts)")));
  }
  internal::commit_temporary(tmp, destination);
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_WRITE_SURFACE_MESH_H
