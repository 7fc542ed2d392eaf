// Poisson_remesh/Postprocessing/internal/face_box_grid.h
//
// The bounding boxes of a mesh's faces in a uniform grid, kept up to date as faces move (internal):
// the faces whose boxes meet a given box are found among the few cells it covers instead of by a
// scan of every face. The untangling asks it once per trial position of a vertex or flip; the
// local repair's crossing checks, through Region_near_faces, once per trial step.

#ifndef POISSON_REMESH_POSTPROCESSING_INTERNAL_FACE_BOX_GRID_H
#define POISSON_REMESH_POSTPROCESSING_INTERNAL_FACE_BOX_GRID_H

#include <Poisson_remesh/Relaxation/internal/Relaxation_context.h>
#include <CGAL/Bbox_3.h>
#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace Postprocessing {
namespace internal {

/// The faces of a mesh by the grid cells their boxes cover. A face whose box covers more than
/// `max_cells` cells (much larger than the others) is kept in a list of its own that every query
/// scans. Cells are hashed: two cells that share a key only add candidates, which the exact box
/// test drops.
template <class Mesh>
class Face_box_grid
{
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  struct Entry { CGAL::Bbox_3 box; std::vector<std::uint64_t> keys; bool big = false; };
  // (the cells and the list of big faces hold each face's box beside it: a query then reads no
  // entry, whose lookup from the map cost more than the box test itself)
  typedef std::pair<face_descriptor, CGAL::Bbox_3> Filed;

public:
  /// `boxes(f)`: the box of face f; the cell side is the mean of the boxes' largest extents
  template <class FaceRange, class BoxOf>
  Face_box_grid(const FaceRange& fs, BoxOf boxes)
  {
    double sum = 0;
    std::size_t n = 0;
    for(face_descriptor f : fs) {
      const CGAL::Bbox_3 b = boxes(f);
      sum += (std::max)({b.xmax() - b.xmin(), b.ymax() - b.ymin(), b.zmax() - b.zmin()});
      ++n;
    }
    cell_ = n > 0 && sum > 0 && std::isfinite(sum) ? sum / double(n) : 1.0;
    for(face_descriptor f : fs) insert(f, boxes(f));
  }

  /// the box of f is now `b` (f new, or moved)
  void update(face_descriptor f, const CGAL::Bbox_3& b)
  {
    remove(f);
    insert(f, b);
  }

  /// the box of f, as last given
  const CGAL::Bbox_3& box(face_descriptor f) const { return entries_.at(f).box; }

  /// appends to `out` each face g whose box meets `b` (closed boxes, as CGAL::do_overlap), in no
  /// particular order and possibly more than once
  void overlapping(const CGAL::Bbox_3& b, std::vector<face_descriptor>& out) const
  {
    for(const Filed& g : big_)
      if(CGAL::do_overlap(g.second, b)) out.push_back(g.first);
    // (a query box may cover as many cells as there are faces: walking them costs about what a
    // scan of every face does)
    std::int64_t lo[3], hi[3];
    if(!range(b, lo, hi, (std::max)(double(max_cells), double(entries_.size())))) {   // (a huge query: every face is looked at)
      for(const auto& e : entries_)
        if(!e.second.big && CGAL::do_overlap(e.second.box, b)) out.push_back(e.first);
      return;
    }
    for(std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for(std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for(std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          const auto it = cells_.find(key(x, y, z));
          if(it == cells_.end()) continue;
          for(const Filed& g : it->second)
            if(CGAL::do_overlap(g.second, b)) out.push_back(g.first);
        }
  }

private:
  static constexpr std::int64_t max_cells = 64;
  // the cells of b's box, false when it covers more than `limit` (or is not finite)
  bool range(const CGAL::Bbox_3& b, std::int64_t lo[3], std::int64_t hi[3], double limit = double(max_cells)) const
  {
    double count = 1;
    for(int i = 0; i < 3; ++i) {
      const double a = std::floor(b.min(i) / cell_), c = std::floor(b.max(i) / cell_);
      if(!(std::abs(a) < 1e15 && std::abs(c) < 1e15)) return false;
      lo[i] = std::int64_t(a);
      hi[i] = std::int64_t(c);
      count *= double(hi[i] - lo[i] + 1);
    }
    return count <= limit;
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z)
  {
    return (std::uint64_t(x) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(y) * 0xC2B2AE3D27D4EB4Full) ^ (std::uint64_t(z) * 0x165667B19E3779F9ull);
  }
  void insert(face_descriptor f, const CGAL::Bbox_3& b)
  {
    Entry& e = entries_[f];
    e.box = b;
    e.keys.clear();
    std::int64_t lo[3], hi[3];
    e.big = !range(b, lo, hi);
    if(e.big) { big_.push_back({f, b}); return; }
    for(std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for(std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for(std::int64_t z = lo[2]; z <= hi[2]; ++z) e.keys.push_back(key(x, y, z));
    std::sort(e.keys.begin(), e.keys.end());
    e.keys.erase(std::unique(e.keys.begin(), e.keys.end()), e.keys.end());
    for(std::uint64_t k : e.keys) cells_[k].push_back({f, b});
  }
public:
  /// f is no longer a face (or no longer to be found)
  void remove(face_descriptor f)
  {
    const auto it = entries_.find(f);
    if(it == entries_.end()) return;
    Entry& e = it->second;
    auto is_f = [&](const Filed& g) { return g.first == f; };
    if(e.big) big_.erase(std::find_if(big_.begin(), big_.end(), is_f));
    for(std::uint64_t k : e.keys) {
      std::vector<Filed>& c = cells_[k];
      c.erase(std::find_if(c.begin(), c.end(), is_f));
    }
    e.keys.clear();
    entries_.erase(it);
  }

private:
  double cell_ = 1;
  std::map<face_descriptor, Entry> entries_;
  std::unordered_map<std::uint64_t, std::vector<Filed>> cells_;
  std::vector<Filed> big_;
};

/// The faces near a region of a mesh that changes only there, for intersecting_pairs_near's
/// `near_faces` (Relaxation_context.h): the local repair's trials move the region's vertices, flip
/// and split its edges and take all that back, and check for new crossings after each step. The
/// boxes of the faces away from the region are kept in a Face_box_grid, current because they do
/// not change; the faces around the region's vertices, whose boxes and even descriptors a trial
/// changes, are read from the mesh at each call. begin(region) before the region changes (the
/// faces around its vertices then are the ones the grid no longer answers for), end() after its
/// last change (their places in the grid updated: faces gone removed, new ones filed). Between the
/// two, no vertex outside the region may move, and every face that a change makes or changes must
/// have a corner in the region (a split's new vertex has: it lies on an edge of the region).
template <class Mesh, class BoxOf>
class Region_near_faces
{
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;

public:
  /// every face of m filed with its box, `box_of(f)`
  Region_near_faces(const Mesh& m, BoxOf box_of) : m_(m), box_of_(box_of), grid_(faces(m), box_of) {}

  /// the vertices of `region` are about to move, or their faces to change
  void begin(const std::vector<vertex_descriptor>& region)
  {
    region_ = region;
    filed_ = Poisson_remesh::internal::faces_around(m_, region_);
  }

  /// the region's changes are over: its faces filed as they are now
  void end()
  {
    const std::vector<face_descriptor> now = Poisson_remesh::internal::faces_around(m_, region_);
    for(face_descriptor f : filed_)
      if(!std::binary_search(now.begin(), now.end(), f)) grid_.remove(f);
    for(face_descriptor f : now) grid_.update(f, box_of_(f));
    region_.clear();
    filed_.clear();
  }

  /// appends to `out` every face whose box meets `b`, and more: the faces around the region
  void operator()(const CGAL::Bbox_3& b, std::vector<face_descriptor>& out) const
  {
    const std::size_t first = out.size();
    grid_.overlapping(b, out);
    // (the grid's answers for the region's faces as they were filed: replaced by its faces now)
    out.erase(std::remove_if(out.begin() + std::ptrdiff_t(first), out.end(),
                             [&](face_descriptor f) { return std::binary_search(filed_.begin(), filed_.end(), f); }),
              out.end());
    const std::vector<face_descriptor> now = Poisson_remesh::internal::faces_around(m_, region_);
    out.insert(out.end(), now.begin(), now.end());
  }

private:
  const Mesh& m_;
  BoxOf box_of_;
  Face_box_grid<Mesh> grid_;
  std::vector<vertex_descriptor> region_;
  std::vector<face_descriptor> filed_;   // (sorted)
};

} // namespace internal
} // namespace Postprocessing
} // namespace Poisson_remesh

#endif // POISSON_REMESH_POSTPROCESSING_INTERNAL_FACE_BOX_GRID_H
