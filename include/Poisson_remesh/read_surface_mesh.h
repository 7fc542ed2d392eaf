// Poisson_remesh/read_surface_mesh.h
//
// Entry point: read_surface_mesh(filename, mesh, np) -- reads OFF, OBJ, PLY, STL (and GOCAD .ts)
// through CGAL's readers, merges duplicated points, triangulates polygons, makes the orientation consistent where that is
// possible, removes zero-area faces and splits non-manifold vertices (unless `strict_input`), and checks that the result is input the remesher can work on (paper §3: an orientable
// two-manifold; borders and several components are allowed). Every problem is reported by a
// Poisson_remesh::Input_error with a specific code and a message that names the problem, how many
// elements it touches and the first of them. Nothing is written: a failed read leaves `mesh` empty.

#ifndef POISSON_REMESH_READ_SURFACE_MESH_H
#define POISSON_REMESH_READ_SURFACE_MESH_H

#include <Poisson_remesh/internal/plain_off.h>
#include <Poisson_remesh/internal/repair_degenerate_faces.h>
#include <Poisson_remesh/parameters.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Kernel_traits.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace Poisson_remesh {

/// What went wrong with an input file.
enum class Input_error_code {
  cannot_open,            ///< missing, unreadable, or a directory
  empty_file,             ///< zero bytes
  unsupported_format,     ///< extension not among off, obj, ply, stl, ts
  parse_error,            ///< the reader could not parse the file (truncated, garbage, wrong header)
  empty_mesh,             ///< parsed, but no vertices or no faces
  invalid_coordinates,    ///< NaN or infinite coordinates
  invalid_face,           ///< fewer than 3 vertices, an index out of range, or a vertex repeated in a face
  non_manifold_edges,     ///< an edge shared by more than two faces
  non_manifold_vertices,  ///< a vertex whose faces form more than one fan
  non_orientable,         ///< no consistent orientation exists (Moebius-like)
  degenerate_faces,       ///< zero-area faces (three collinear points)
  cannot_triangulate      ///< a polygon that CGAL could not triangulate
};

/// The name of an error code, as written in the enumeration ("non_manifold_edges", ...).
inline const char* to_string(Input_error_code c)
{
  switch(c) {
    case Input_error_code::cannot_open: return "cannot_open";
    case Input_error_code::empty_file: return "empty_file";
    case Input_error_code::unsupported_format: return "unsupported_format";
    case Input_error_code::parse_error: return "parse_error";
    case Input_error_code::empty_mesh: return "empty_mesh";
    case Input_error_code::invalid_coordinates: return "invalid_coordinates";
    case Input_error_code::invalid_face: return "invalid_face";
    case Input_error_code::non_manifold_edges: return "non_manifold_edges";
    case Input_error_code::non_manifold_vertices: return "non_manifold_vertices";
    case Input_error_code::non_orientable: return "non_orientable";
    case Input_error_code::degenerate_faces: return "degenerate_faces";
    case Input_error_code::cannot_triangulate: return "cannot_triangulate";
  }
  return "unknown";
}

/// The exception thrown by read_surface_mesh(): `what()` is a complete sentence for the user.
class Input_error : public std::runtime_error
{
public:
  /// `message`: the sentence `what()` returns
  Input_error(Input_error_code code, const std::string& message)
    : std::runtime_error(message), code_(code) {}
  /// what went wrong
  Input_error_code code() const { return code_; }
private:
  Input_error_code code_;
};

/// What read_surface_mesh() did to the file's content on the way to a valid mesh.
struct Read_report
{
  std::size_t input_points = 0;           ///< points in the file
  std::size_t input_polygons = 0;         ///< faces in the file
  std::size_t triangulated_polygons = 0;  ///< faces with more than 3 vertices that were triangulated
  bool reoriented = false;                ///< faces were flipped to make the orientation consistent
  std::size_t removed_degenerate_faces = 0; ///< zero-area faces removed (repair_degenerate_faces, the default)
  std::size_t removed_isolated_points = 0;  ///< points used by no face (dropped)
  std::size_t merged_duplicate_points = 0;  ///< points at the same position as another one, merged into it
  std::size_t unmerged_duplicate_points = 0; ///< duplicates left apart: merging them would break manifoldness
  std::size_t split_pinched_vertices = 0;    ///< with repair_degenerate_faces(true): vertices split after the removal
  std::size_t split_non_manifold_vertices = 0; ///< with repair_non_manifold_vertices(true): vertices of the file where several fans met, split (one vertex per fan)
  std::vector<std::string> warnings;      ///< one sentence each
};

namespace internal {

inline std::string lower_extension(const std::string& fname)
{
  std::string ext = std::filesystem::path(fname).extension().string();
  if(!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// After a failed parse of a text file: is there a NaN/inf token, and on which line?
inline bool find_non_finite_token(const std::string& fname, std::size_t& line_number)
{
  std::ifstream in(fname);
  std::string line;
  line_number = 0;
  while(std::getline(in, line)) {
    ++line_number;
    std::istringstream ls(line);
    std::string tok;
    while(ls >> tok) {
      std::string t;
      for(char c : tok) if(c != '+' && c != '-') t += char(std::tolower((unsigned char)c));
      if(t == "nan" || t == "inf" || t == "infinity" || t.rfind("nan(", 0) == 0 || t == "1.#inf" || t == "1.#qnan")
        return true;
    }
  }
  return false;
}

typedef std::pair<std::size_t, std::size_t> Soup_edge;

inline Soup_edge make_soup_edge(std::size_t a, std::size_t b) { return a < b ? Soup_edge(a, b) : Soup_edge(b, a); }

// Vertices whose incident polygons form more than one fan (connected through edges incident
// to the vertex). Returns the count and the first such vertex. With `split` (and `points`), each
// fan after the first gets a copy of the vertex's point, so that the soup has no such vertex left.
template <class PolygonRange, class PointRange = std::vector<int>>
std::size_t count_non_manifold_soup_vertices(PolygonRange& polygons, std::size_t nb_points,
                                             std::size_t& first, PointRange* points = nullptr)
{
  // the polygons around each vertex, in one array (offset[v] to offset[v + 1])
  std::vector<std::size_t> offset(nb_points + 1, 0), incident;
  for(const auto& poly : polygons)
    for(std::size_t v : poly) ++offset[v + 1];
  for(std::size_t v = 0; v < nb_points; ++v) offset[v + 1] += offset[v];
  incident.resize(offset[nb_points]);
  {
    std::vector<std::size_t> fill(offset.begin(), offset.end() - 1);
    for(std::size_t f = 0; f < polygons.size(); ++f)
      for(std::size_t v : polygons[f]) incident[fill[v]++] = f;
  }

  std::size_t count = 0;
  first = std::size_t(-1);
  std::vector<std::size_t> parent;
  std::vector<std::pair<std::size_t, std::size_t>> neighbors;   // (w, local index of a polygon with edge (v, w))
  for(std::size_t v = 0; v < nb_points; ++v) {
    const std::size_t* const inc = incident.data() + offset[v];
    const std::size_t m = offset[v + 1] - offset[v];
    if(m < 2) continue;
    parent.resize(m);
    for(std::size_t i = 0; i < m; ++i) parent[i] = i;
    auto find = [&](std::size_t i) { while(parent[i] != i) i = parent[i] = parent[parent[i]]; return i; };
    // link the polygons around v that share an edge (v, w): sorted by w, those of one w are adjacent
    neighbors.clear();
    for(std::size_t i = 0; i < m; ++i) {
      const auto& poly = polygons[inc[i]];
      const std::size_t n = poly.size();
      for(std::size_t k = 0; k < n; ++k) {
        if(poly[k] != v) continue;
        neighbors.emplace_back(poly[(k + 1) % n], i);
        neighbors.emplace_back(poly[(k + n - 1) % n], i);
      }
    }
    std::sort(neighbors.begin(), neighbors.end());
    for(std::size_t j = 1; j < neighbors.size(); ++j)
      if(neighbors[j].first == neighbors[j - 1].first) parent[find(neighbors[j].second)] = find(neighbors[j - 1].second);
    std::size_t fans = 0;
    for(std::size_t i = 0; i < m; ++i) if(find(i) == i) ++fans;
    if(fans < 2) continue;
    if(count == 0) first = v;
    ++count;
    if(points == nullptr) continue;
    // the fan of the first polygon keeps v; every other fan gets a new point
    std::map<std::size_t, std::size_t> fan_vertex;   // root -> vertex index
    fan_vertex[find(0)] = v;
    for(std::size_t i = 0; i < m; ++i) {
      auto it = fan_vertex.find(find(i));
      if(it == fan_vertex.end()) {
        it = fan_vertex.emplace(find(i), points->size()).first;
        const auto p = (*points)[v];
        points->push_back(p);
      }
      for(auto& w : polygons[inc[i]]) if(w == v) w = it->second;
    }
  }
  return count;
}

// The polygons' edges, sorted: as (smaller, larger) vertex pairs, or (with `directed`) in the
// direction each polygon runs through them. (A sorted vector, not a map: the checks below run on
// every input.)
template <class PolygonRange>
std::vector<Soup_edge> sorted_soup_edges(const PolygonRange& polygons, bool directed)
{
  std::vector<Soup_edge> edges;
  for(const auto& poly : polygons)
    for(std::size_t k = 0; k < poly.size(); ++k) {
      const std::size_t a = poly[k], b = poly[(k + 1) % poly.size()];
      edges.push_back(directed ? Soup_edge(a, b) : make_soup_edge(a, b));
    }
  std::sort(edges.begin(), edges.end());
  return edges;
}

// Edges shared by more than two polygons: the count and the first such edge.
template <class PolygonRange>
std::size_t count_non_manifold_soup_edges(const PolygonRange& polygons, Soup_edge& first)
{
  const std::vector<Soup_edge> edges = sorted_soup_edges(polygons, false);
  std::size_t bad = 0;
  for(std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while(j < edges.size() && edges[j] == edges[i]) ++j;
    if(j - i > 2 && bad++ == 0) first = edges[i];
    i = j;
  }
  return bad;
}

// Does every directed edge (u, v) occur in one polygon at most? On a soup whose edges and vertices
// are manifold and whose polygons repeat no vertex, that is all CGAL's test of a soup being a
// polygon mesh still asks: the two polygons of an edge run through it in opposite directions (a
// consistent orientation). (CGAL's test checks the rest again, and was most of the reading time
// of large meshes.)
template <class PolygonRange>
bool soup_is_consistently_oriented(const PolygonRange& polygons)
{
  const std::vector<Soup_edge> directed = sorted_soup_edges(polygons, true);
  return std::adjacent_find(directed.begin(), directed.end()) == directed.end();
}

template <class PolygonRange>
bool soup_has_repeated_vertex(const PolygonRange& polygons)
{
  std::vector<std::size_t> sorted;
  for(const auto& poly : polygons) {
    sorted.assign(poly.begin(), poly.end());
    std::sort(sorted.begin(), sorted.end());
    if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return true;
  }
  return false;
}

} // namespace internal

/*!
  reads `fname` into `tm`, a model of `MutableFaceGraph`, and checks it (see the file comment).
  Throws Input_error on failure, with `tm` left empty.

  Named parameters:
  - `vertex_point_map`: the mesh's point map (default: `boost::get(CGAL::vertex_point, tm)`).
  - `repair_degenerate_faces` (bool, default true): remove zero-area faces with
    `CGAL::Polygon_mesh_processing::remove_degenerate_faces()` instead of refusing them
    (`Read_report::removed_degenerate_faces` counts them).
  - `repair_non_manifold_vertices` (bool, default true): split each vertex whose faces form
    several fans into one vertex per fan, as `CGAL::Polygon_mesh_processing::duplicate_non_manifold_vertices()`
    does on a mesh, instead of refusing it (`Read_report::split_non_manifold_vertices`).
  - `strict_input` (bool, default false): true makes both repairs default to false (the input is
    refused with Input_error instead); an explicit repair parameter still wins.
  What cannot be repaired is always refused: unreadable or empty files, NaN or infinite
  coordinates, bad face indices, non-manifold edges, non-orientable surfaces.
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Read_report read_surface_mesh(const std::string& fname, TriangleMesh& tm,
                              const NamedParameters& np = parameters::default_values())
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename CGAL::GetVertexPointMap<TriangleMesh, NamedParameters>::type VPM;
  typedef typename boost::property_traits<VPM>::value_type Point;

  const bool strict = choose_parameter(get_parameter(np, internal_np::strict_input), false);
  const bool repair = choose_parameter(get_parameter(np, internal_np::repair_degenerate_faces), !strict);
  const bool repair_vertices = choose_parameter(get_parameter(np, internal_np::repair_non_manifold_vertices), !strict);
  Read_report report;
  const std::string quoted = "'" + fname + "'";

  // 1. the file itself
  std::error_code ec;
  if(!std::filesystem::exists(fname, ec))
    throw Input_error(Input_error_code::cannot_open, "cannot open " + quoted + ": no such file");
  if(std::filesystem::is_directory(fname, ec))
    throw Input_error(Input_error_code::cannot_open, "cannot open " + quoted + ": it is a directory");
  {
    std::ifstream probe(fname, std::ios::binary);
    if(!probe)
      throw Input_error(Input_error_code::cannot_open,
                        "cannot open " + quoted + ": " + std::strerror(errno));
  }
  if(std::filesystem::file_size(fname, ec) == 0)
    throw Input_error(Input_error_code::empty_file, quoted + " is empty (0 bytes)");
  const std::string ext = internal::lower_extension(fname);
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl" && ext != "ts")
    throw Input_error(Input_error_code::unsupported_format,
                      "cannot read " + quoted + ": unsupported extension '" + ext +
                      "' (supported: .off .obj .ply .stl .ts)");

  // 2. the polygon soup
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool parsed = false;
  try {
    // (plain ASCII OFF without iostreams, anything else by CGAL's readers: internal/plain_off.h)
    parsed = (ext == "off" && internal::read_plain_off(fname, points, polygons)) ||
             CGAL::IO::read_polygon_soup(fname, points, polygons, CGAL::parameters::verbose(false));
  } catch(const std::exception&) {
    parsed = false;
  }
  if(!parsed) {
    std::size_t line = 0;
    if(internal::find_non_finite_token(fname, line))
      throw Input_error(Input_error_code::invalid_coordinates,
                        "cannot read " + quoted + ": NaN or infinite coordinate at line " + std::to_string(line));
    throw Input_error(Input_error_code::parse_error,
                      "cannot read " + quoted + ": not a valid " + ext +
                      " file (truncated, malformed header or counts, or not a mesh)");
  }
  report.input_points = points.size();
  report.input_polygons = polygons.size();
  if(points.empty() || polygons.empty())
    throw Input_error(Input_error_code::empty_mesh,
                      quoted + " has " + std::to_string(points.size()) + " vertices and " +
                      std::to_string(polygons.size()) + " faces: nothing to remesh");

  // 3. coordinates and faces
  {
    std::size_t bad = 0, first = 0;
    for(std::size_t i = 0; i < points.size(); ++i) {
      const Point& p = points[i];
      if(!(std::isfinite(CGAL::to_double(p.x())) && std::isfinite(CGAL::to_double(p.y())) &&
           std::isfinite(CGAL::to_double(p.z())))) {
        if(bad++ == 0) first = i;
      }
    }
    if(bad)
      throw Input_error(Input_error_code::invalid_coordinates,
                        quoted + ": " + std::to_string(bad) + " vertices have NaN or infinite coordinates (first: vertex " +
                        std::to_string(first) + ")");
  }
  std::vector<std::size_t> sorted;   // (a face's vertices, sorted: its storage reused)
  for(std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    auto where = [&] { return quoted + ": face " + std::to_string(f); };
    if(poly.size() < 3)
      throw Input_error(Input_error_code::invalid_face, where() + " has " + std::to_string(poly.size()) + " vertices (at least 3 needed)");
    for(std::size_t v : poly)
      if(v >= points.size())
        throw Input_error(Input_error_code::invalid_face, where() + " refers to vertex " + std::to_string(v) +
                          " but there are only " + std::to_string(points.size()));
    sorted.assign(poly.begin(), poly.end());
    std::sort(sorted.begin(), sorted.end());
    auto dup = std::adjacent_find(sorted.begin(), sorted.end());
    if(dup != sorted.end())
      throw Input_error(Input_error_code::invalid_face, where() + " repeats vertex " + std::to_string(*dup));
  }

  // points no face uses (common in STL and in scans) would be isolated vertices: dropped, and said
  {
    std::vector<bool> used(points.size(), false);
    for(const auto& poly : polygons) for(std::size_t v : poly) used[v] = true;
    const std::size_t unused = std::size_t(std::count(used.begin(), used.end(), false));
    if(unused > 0) {
      std::vector<std::size_t> new_index(points.size(), 0);
      std::vector<Point> kept;
      for(std::size_t i = 0; i < points.size(); ++i)
        if(used[i]) { new_index[i] = kept.size(); kept.push_back(points[i]); }
      for(auto& poly : polygons) for(std::size_t& v : poly) v = new_index[v];
      points.swap(kept);
      report.removed_isolated_points = unused;
      report.warnings.push_back(std::to_string(unused) + " points used by no face were dropped");
    }
  }

  // points at the same position (each triangle with its own corners, as STL-like exports and
  // some isosurface extractors write them) are merged with CGAL's soup repair, unless the merge
  // would make a face repeat a vertex or the surface non-manifold: then they are kept apart
  {
    std::vector<Point> merged_points(points);
    std::vector<std::vector<std::size_t>> merged_polygons(polygons);
    const std::size_t merged = PMP::merge_duplicate_points_in_polygon_soup(merged_points, merged_polygons);
    if(merged > 0) {
      internal::Soup_edge e;
      std::size_t v = 0;
      if(!internal::soup_has_repeated_vertex(merged_polygons) &&
         internal::count_non_manifold_soup_edges(merged_polygons, e) == 0 &&
         internal::count_non_manifold_soup_vertices(merged_polygons, merged_points.size(), v) == 0) {
        points.swap(merged_points);
        polygons.swap(merged_polygons);
        report.merged_duplicate_points = merged;
        report.warnings.push_back(std::to_string(merged) + " points at the same position as another were merged");
      } else {
        report.unmerged_duplicate_points = merged;
        report.warnings.push_back(std::to_string(merged) + " points at the same position as another were kept apart "
                                  "(merging them would make the surface non-manifold)");
      }
    }
  }

  // 4. manifoldness and orientation
  {
    internal::Soup_edge first;
    const std::size_t bad = internal::count_non_manifold_soup_edges(polygons, first);
    if(bad)
      throw Input_error(Input_error_code::non_manifold_edges,
                        quoted + ": " + std::to_string(bad) + " non-manifold edges (shared by more than two faces), first between vertices " +
                        std::to_string(first.first) + " and " + std::to_string(first.second));
  }
  {
    std::size_t first = 0;
    const std::size_t bad = internal::count_non_manifold_soup_vertices(polygons, points.size(), first,
                                                                        repair_vertices ? &points : nullptr);
    if(bad && repair_vertices) {
      report.split_non_manifold_vertices = bad;
      report.warnings.push_back(std::to_string(bad) + " non-manifold vertices (faces around them formed several fans) were split, one vertex per fan");
    } else if(bad)
      throw Input_error(Input_error_code::non_manifold_vertices,
                        quoted + ": " + std::to_string(bad) + " non-manifold vertices (faces around them form several fans), first: vertex " +
                        std::to_string(first));
  }
  // (the soup's edges and vertices are manifold here: only the orientation is left to check)
  if(!internal::soup_is_consistently_oriented(polygons)) {
    const std::size_t before = points.size();
    PMP::orient_polygon_soup(points, polygons);
    if(points.size() != before)
      throw Input_error(Input_error_code::non_orientable,
                        quoted + ": the surface is not orientable (no consistent orientation of its faces exists)");
    report.reoriented = true;
    report.warnings.push_back("face orientation was inconsistent and has been made consistent");
  }

  // 5. the mesh, triangulated
  clear(tm);
  VPM vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_property_map(CGAL::vertex_point, tm));
  PMP::polygon_soup_to_polygon_mesh(points, polygons, tm, CGAL::parameters::default_values(),
                                    CGAL::parameters::vertex_point_map(vpm));
  for(const auto& poly : polygons) if(poly.size() > 3) ++report.triangulated_polygons;
  if(report.triangulated_polygons) {
    if(!PMP::triangulate_faces(tm, CGAL::parameters::vertex_point_map(vpm))) {
      clear(tm);
      throw Input_error(Input_error_code::cannot_triangulate, quoted + ": some polygons could not be triangulated");
    }
    report.warnings.push_back(std::to_string(report.triangulated_polygons) + " polygons with more than 3 vertices were triangulated");
  }

  // 6. degenerate faces
  std::size_t first_degenerate = 0;
  const std::size_t degenerate = internal::count_degenerate_faces(tm, vpm, &first_degenerate);
  if(degenerate) {
    if(!repair) {
      clear(tm);
      throw Input_error(Input_error_code::degenerate_faces,
                        quoted + ": " + std::to_string(degenerate) + " degenerate (zero-area) faces, first: face " +
                        std::to_string(first_degenerate) + (report.triangulated_polygons ? " after triangulation" : "") +
                        "; they are removed unless strict input is asked for");
    }
    const internal::Degenerate_face_repair repaired = internal::remove_degenerate_faces(tm, vpm);
    if(!repaired.complete) {
      clear(tm);
      throw Input_error(Input_error_code::degenerate_faces,
                        quoted + ": " + std::to_string(degenerate) + " degenerate faces could not all be removed");
    }
    report.removed_degenerate_faces = degenerate;
    report.warnings.push_back(std::to_string(degenerate) + " degenerate faces were removed");
    if(repaired.split_vertices) {
      report.split_pinched_vertices = repaired.split_vertices;
      report.warnings.push_back(std::to_string(repaired.split_vertices) + " vertices where the removed faces left two fans touching were split");
    }
  }
  return report;
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_READ_SURFACE_MESH_H
