// Poisson_remesh/internal/self_intersections.h
//
// The intersecting face pairs of a triangle mesh (internal): the pairs that CGAL's
// Polygon_mesh_processing::self_intersections() reports, by the same per-pair rule (faces that
// share an edge intersect when they are coplanar and overlap, faces that share a vertex when an
// edge of one meets the other, other faces when their triangles meet; a zero-area face is the
// pair (f, f)), found with far fewer tests on the meshes the relaxation makes.
//
// Why not CGAL's search itself: the relaxation checks a whole mesh for new crossings after every
// pass that moved most of its vertices, and that check was a quarter of a remesh. CGAL's box sweep
// finds every pair of faces whose boxes meet, about seven per face, nearly all of them neighbours
// sharing a vertex, and tests each exactly. Two facts make most of that work unneeded:
// - Two faces that share a vertex whose star (the faces around it) projects one-to-one onto one of
//   the coordinate planes cannot meet anywhere else: their projections meet only at what they
//   share, so the faces do too. Whether a star projects one-to-one is decided by exact 2D
//   orientation tests on the points' coordinates (the fan's triangles all turn the same way and go
//   round once), a few tests per vertex instead of two exact tests per neighbouring pair. In a
//   well-shaped mesh nearly every star does; pairs sharing a vertex of another star are tested.
// - The candidate pairs come from a uniform grid whose cells are as large as the largest face's box
//   (at most twice the box of the face larger than nine tenths of the faces; a larger face is
//   checked against every box): a face's box is filed under the cell of its centre, and faces whose
//   boxes meet (their centres are no farther apart than the larger box) lie in the same or adjacent
//   cells. (CGAL's sweep sorts and scans all the boxes along one axis; on a mesh of near-equal
//   faces the grid touches fewer boxes.) On faces of very unequal sizes the grid would crowd, and
//   CGAL's box sweep (box_self_intersection_d) gives the candidates instead.
// The faces' pairs are the same as CGAL's (the tests compare both on meshes that cut themselves);
// only the work differs. With CGAL::Parallel_tag the faces' boxes, the star tests, the grid's
// candidate pairs (by runs of cells, taken in in the cells' order) and the exact tests run in
// parallel; the pairs and their order do not depend on the number of threads.

#ifndef POISSON_REMESH_INTERNAL_SELF_INTERSECTIONS_H
#define POISSON_REMESH_INTERNAL_SELF_INTERSECTIONS_H

#include <Poisson_remesh/internal/parallel.h>
#include <Poisson_remesh/internal/radix_sort.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/enum.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

namespace self_intersection_detail {

// Whether the faces around v project one-to-one onto the coordinate plane most facing their summed
// normal: the fan of v (one umbrella holding every face around v) whose triangles all turn left
// in the projection and whose ring goes round v once (the directions to the ring's vertices
// increase in angle from the first, by half-planes and exact orientation tests; an open fan, at a
// border, must not reach its first direction again).
// `in_range(f)`: whether face f is one of the searched faces; `searched`: how many of those have v
// as a vertex. Only pairs of searched faces are asked about, so the fan must hold all of them (a
// second umbrella at v, not reached by the walk around v, makes the count differ: nothing is claimed).
template <class Mesh, class VPM, class InRange>
bool star_projects_one_to_one(typename boost::graph_traits<Mesh>::vertex_descriptor v, const Mesh& m, const VPM& vpm,
                              InRange in_range, std::size_t searched)
{
  typedef typename boost::property_traits<VPM>::value_type Point_3;
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel K;
  typedef typename K::Point_2 Point_2;
  typedef typename boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;

  halfedge_descriptor start = halfedge(v, m);
  if(start == boost::graph_traits<Mesh>::null_halfedge()) return false;
  for(halfedge_descriptor h : CGAL::halfedges_around_target(start, m))
    if(is_border(h, m)) { start = h; break; }
  const bool open = is_border(start, m);
  // the fan's triangles (v, a, b), counterclockwise about the face's normal, in the order of the
  // walk around v (halfedges_around_target turns clockwise: each triangle's `a` is the next one's `b`)
  std::array<std::pair<vertex_descriptor, vertex_descriptor>, 32> fan_store;
  std::size_t count = 0, counted = 0;
  double n[3] = {0, 0, 0};
  const Point_3& o3 = get(vpm, v);
  for(halfedge_descriptor h : CGAL::halfedges_around_target(start, m)) {
    if(is_border(h, m)) continue;
    if(count == fan_store.size()) return false;   // (a vertex of very high valence: tested pair by pair)
    const vertex_descriptor a = target(next(h, m), m), b = source(h, m);
    fan_store[count++] = {a, b};
    if(in_range(face(h, m))) ++counted;
    const Point_3 &pa = get(vpm, a), &pb = get(vpm, b);
    const double ux = pa.x() - o3.x(), uy = pa.y() - o3.y(), uz = pa.z() - o3.z();
    const double wx = pb.x() - o3.x(), wy = pb.y() - o3.y(), wz = pb.z() - o3.z();
    n[0] += uy * wz - uz * wy;
    n[1] += uz * wx - ux * wz;
    n[2] += ux * wy - uy * wx;
  }
  if(count == 0 || counted != searched) return false;
  std::reverse(fan_store.begin(), fan_store.begin() + count);   // counterclockwise
  int axis = 0;
  for(int i = 1; i < 3; ++i) if(std::abs(n[i]) > std::abs(n[axis])) axis = i;
  if(!(std::abs(n[axis]) > 0)) return false;
  const int i0 = (axis + 1) % 3, i1 = (axis + 2) % 3;
  const bool mirrored = n[axis] < 0;   // (seen from below: swap the two coordinates to keep the turns)
  auto project = [&](const Point_3& p) { return mirrored ? Point_2(p[i1], p[i0]) : Point_2(p[i0], p[i1]); };
  const Point_2 o = project(o3);
  const Point_2 first = project(get(vpm, fan_store[0].first));
  // 0: the half-plane from `first` counterclockwise (first's own direction included), 1: the other
  auto half = [&](const Point_2& d) {
    const CGAL::Orientation s = CGAL::orientation(o, first, d);
    if(s == CGAL::LEFT_TURN) return 0;
    if(s == CGAL::RIGHT_TURN) return 1;
    return CGAL::angle(first, o, d) == CGAL::ACUTE ? 0 : 1;
  };
  int last_half = 0;
  for(std::size_t i = 0; i < count; ++i) {
    if(i > 0 && fan_store[i].first != fan_store[i - 1].second) return false;
    const Point_2 a = project(get(vpm, fan_store[i].first)), b = project(get(vpm, fan_store[i].second));
    if(CGAL::orientation(o, a, b) != CGAL::LEFT_TURN) return false;
    if(i + 1 == count && !open) break;   // (the closing triangle comes back to `first`)
    const int h = half(b);
    if(h < last_half) return false;   // past a full turn
    if(h == 0 && CGAL::orientation(o, first, b) == CGAL::COLLINEAR) return false;   // back on `first`
    last_half = h;
  }
  if(!open && fan_store[count - 1].second != fan_store[0].first) return false;
  return true;
}

// CGAL's rule for one pair of distinct faces (see the file's comment), with the kernel's predicates
template <class Mesh, class VPM>
bool faces_intersect(typename boost::graph_traits<Mesh>::face_descriptor f, typename boost::graph_traits<Mesh>::face_descriptor g,
                     const Mesh& m, const VPM& vpm)
{
  typedef typename boost::property_traits<VPM>::value_type Point_3;
  typedef typename CGAL::Kernel_traits<Point_3>::Kernel K;
  typedef typename K::Triangle_3 Triangle_3;
  typedef typename K::Segment_3 Segment_3;
  auto h = halfedge(f, m);
  const auto g0 = halfedge(g, m);
  typename boost::graph_traits<Mesh>::vertex_descriptor hv[3] = {target(h, m), target(next(h, m), m), source(h, m)};
  typename boost::graph_traits<Mesh>::vertex_descriptor gv[3] = {target(g0, m), target(next(g0, m), m), source(g0, m)};
  for(int i = 0; i < 3; ++i, h = next(h, m)) {
    const auto o = opposite(h, m);
    if(face(o, m) != g) continue;
    // a shared edge (hv[i+2], hv[i]): they meet when coplanar and on the same side of it
    const Point_3 &p = get(vpm, hv[(i + 2) % 3]), &q = get(vpm, hv[i]), &r = get(vpm, hv[(i + 1) % 3]), &s = get(vpm, target(next(o, m), m));
    return CGAL::coplanar(q, r, p, s) && CGAL::coplanar_orientation(p, q, r, s) == CGAL::POSITIVE;
  }
  for(int i = 0; i < 3; ++i)
    for(int j = 0; j < 3; ++j) {
      if(hv[i] != gv[j]) continue;
      // a shared vertex: they meet when the edge of one opposite it meets the other
      const Triangle_3 t1(get(vpm, hv[0]), get(vpm, hv[1]), get(vpm, hv[2])), t2(get(vpm, gv[0]), get(vpm, gv[1]), get(vpm, gv[2]));
      return CGAL::do_intersect(t1, Segment_3(get(vpm, gv[(j + 1) % 3]), get(vpm, gv[(j + 2) % 3])))
          || CGAL::do_intersect(t2, Segment_3(get(vpm, hv[(i + 1) % 3]), get(vpm, hv[(i + 2) % 3])));
    }
  return CGAL::do_intersect(Triangle_3(get(vpm, hv[0]), get(vpm, hv[1]), get(vpm, hv[2])),
                            Triangle_3(get(vpm, gv[0]), get(vpm, gv[1]), get(vpm, gv[2])));
}

} // namespace self_intersection_detail

/// The intersecting pairs among the faces of `range` of the triangle mesh m (points `vpm`), as
/// CGAL's self_intersections(range, m) finds them, each pair as (smaller, larger), sorted. The
/// search stops at `bound` pairs (a mesh that cuts itself everywhere): then only their number
/// tells (which they are depends on the order of the search). The pairs never depend on the
/// number of threads. Where the faces are far from equal in
/// size (an input mesh, not the relaxation's) the grid would hold too many faces per cell, and
/// CGAL's box sweep gives the candidate pairs instead (`used_grid`, if given, tells which).
template <class ConcurrencyTag = CGAL::Sequential_tag, class Mesh, class FaceRange, class VPM>
std::vector<std::pair<typename boost::graph_traits<Mesh>::face_descriptor, typename boost::graph_traits<Mesh>::face_descriptor>>
intersecting_face_pairs(const Mesh& m, const FaceRange& range, const VPM& vpm,
                        std::size_t bound = (std::numeric_limits<std::size_t>::max)(), bool* used_grid = nullptr)
{
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  typedef std::pair<face_descriptor, face_descriptor> Pair;
  std::vector<Pair> out;
  if(used_grid != nullptr) *used_grid = false;
  if(bound == 0) return out;
  auto finish = [&]() {
    for(Pair& p : out) if(p.second < p.first) std::swap(p.first, p.second);
    std::sort(out.begin(), out.end());
    return out;
  };

  // the faces' boxes; a zero-area face is a pair with itself and has no box (as in CGAL)
  // (each face's corners, box and zero-area test at once with CGAL::Parallel_tag, then taken in
  // in the order of `range`)
  std::vector<face_descriptor> fs(std::begin(range), std::end(range));
  std::vector<CGAL::Bbox_3> boxes(fs.size());
  std::vector<std::array<vertex_descriptor, 3>> corners(fs.size());
  std::vector<std::int8_t> flat(fs.size());
  for_each_index<ConcurrencyTag>(fs.size(), [&](std::size_t i) {
    const auto h = halfedge(fs[i], m);
    corners[i] = {target(h, m), target(next(h, m), m), source(h, m)};
    const auto &p = get(vpm, corners[i][0]), &q = get(vpm, corners[i][1]), &r = get(vpm, corners[i][2]);
    flat[i] = CGAL::collinear(p, q, r) ? 1 : 0;
    if(!flat[i]) boxes[i] = p.bbox() + q.bbox() + r.bbox();
  });
  std::size_t kept = 0;
  for(std::size_t i = 0; i < fs.size(); ++i) {
    if(flat[i]) {
      out.emplace_back(fs[i], fs[i]);
      if(out.size() == bound) return finish();
      continue;
    }
    fs[kept] = fs[i];
    corners[kept] = corners[i];
    boxes[kept] = boxes[i];
    ++kept;
  }
  fs.resize(kept);
  corners.resize(kept);
  boxes.resize(kept);
  const std::size_t n = fs.size();
  if(n < 2) return finish();

  // The grid: cells as large as the largest face's box, but at most twice the box of the face
  // larger than nine tenths of the faces (and 1% more: the margin keeps rounding from moving a
  // neighbour two cells away). A face larger than 0.99 cell is a "big" face, checked against every box.
  std::vector<double> extent(n);
  CGAL::Bbox_3 all;
  for(std::size_t i = 0; i < n; ++i) {
    const CGAL::Bbox_3& b = boxes[i];
    extent[i] = (std::max)({b.xmax() - b.xmin(), b.ymax() - b.ymin(), b.zmax() - b.zmin()});
    all += b;
  }
  std::vector<double> sorted_extent = extent;
  const std::size_t tenth_largest = n - 1 - n / 10;
  std::nth_element(sorted_extent.begin(), sorted_extent.begin() + tenth_largest, sorted_extent.end());
  double cell = (std::min)(*std::max_element(extent.begin(), extent.end()), 2 * sorted_extent[tenth_largest]) / 0.99;
  const double span = (std::max)({all.xmax() - all.xmin(), all.ymax() - all.ymin(), all.zmax() - all.zmin()});
  cell = (std::max)(cell, span / double(1 << 20));   // (at most 2^20 cells a side: 21-bit keys)
  if(!(cell > 0)) cell = 1;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> filed;   // (cell key, face index)
  std::vector<std::uint32_t> big;
  filed.reserve(n);
  auto coordinate = [&](double c, double lo) { return std::uint64_t(std::floor((c - lo) / cell)) + 1; };   // (>= 1: a neighbour at -1 stays >= 0)
  for(std::uint32_t i = 0; i < n; ++i) {
    if(extent[i] > 0.99 * cell) { big.push_back(i); continue; }
    const CGAL::Bbox_3& b = boxes[i];
    const std::uint64_t x = coordinate(0.5 * (b.xmin() + b.xmax()), all.xmin()), y = coordinate(0.5 * (b.ymin() + b.ymax()), all.ymin()),
                        z = coordinate(0.5 * (b.zmin() + b.zmax()), all.zmin());
    filed.emplace_back((x << 42) | (y << 21) | z, i);
  }
  stable_sort_by_key(filed);   // (filed in index order: std::sort's order of the pairs)
  // the occupied cells: (key, first, end) in `filed`
  struct Cell { std::uint64_t key; std::uint32_t first, end; };
  std::vector<Cell> cells;
  std::size_t crowding = 0;   // (the sum of the squared cell counts: the pairs a cell holds)
  for(std::uint32_t i = 0; i < filed.size();) {
    std::uint32_t j = i + 1;
    while(j < filed.size() && filed[j].first == filed[i].first) ++j;
    cells.push_back(Cell{filed[i].first, i, j});
    crowding += std::size_t(j - i) * (j - i);
    i = j;
  }

  // Too crowded a grid (faces of very unequal sizes) or too many big faces: CGAL's box sweep finds
  // the candidates instead. (On the relaxation's meshes a cell holds a few faces and there are no
  // big faces.)
  const std::size_t most_crowding = 32 * n, most_big = 8 + n / 64;
  const bool grid = crowding <= most_crowding && big.size() <= most_big;
  if(used_grid != nullptr) *used_grid = grid;

  // which vertices' stars project one-to-one (asked of the corners of the searched faces)
  auto state = get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), m);   // 0: not a corner; else 1 + its place in corner_list
  auto searched = get(CGAL::dynamic_face_property_t<bool>(), m);
  std::vector<vertex_descriptor> corner_list;
  std::vector<std::uint32_t> corner_faces;   // (how many searched faces have it as a corner)
  for(const auto& c : corners) for(vertex_descriptor v : c) put(state, v, 0u);
  for(std::size_t i = 0; i < n; ++i) {
    put(searched, fs[i], true);
    for(vertex_descriptor v : corners[i]) {
      if(get(state, v) == 0) { corner_list.push_back(v); corner_faces.push_back(0); put(state, v, std::uint32_t(corner_list.size())); }
      ++corner_faces[get(state, v) - 1];
    }
  }
  // (every face around a corner given a value before the threads read them: a map that is not an
  // array, as for Polyhedron_3, inserts what it is asked of and misses)
  for(vertex_descriptor v : corner_list)
    for(auto h : CGAL::halfedges_around_target(halfedge(v, m), m))
      if(!is_border(h, m)) put(searched, face(h, m), bool(get(searched, face(h, m))));
  std::vector<std::int8_t> one_to_one(corner_list.size());
  for_each_index<ConcurrencyTag>(corner_list.size(), [&](std::size_t i) {
    one_to_one[i] = self_intersection_detail::star_projects_one_to_one(corner_list[i], m, vpm, [&](face_descriptor f) { return get(searched, f); },
                                                                       corner_faces[i]) ? 1 : 0;
  });
  std::vector<std::array<bool, 3>> corner_safe(n);   // (a corner whose star projects one-to-one)
  for(std::size_t i = 0; i < n; ++i)
    for(int k = 0; k < 3; ++k) corner_safe[i][k] = one_to_one[get(state, corners[i][k]) - 1] == 1;

  // the pairs to test exactly: boxes that meet, sharing no vertex whose star projects one-to-one;
  // tested as they are found (a block at a time in parallel with CGAL::Parallel_tag), the search
  // given up once `bound` pairs intersect (a mesh that cuts itself everywhere: every box meets
  // every other, and finding them all would be quadratic)
  struct Bound_reached {};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
  std::vector<std::int8_t> meets;
  // (in sequence, each pair at once: the bound stops the search at the pair that reaches it)
  const std::size_t block = is_parallel<ConcurrencyTag>() ? 4096 : 1;
  auto flush = [&]() {
    meets.assign(candidates.size(), 0);
    for_each_index<ConcurrencyTag>(candidates.size(), [&](std::size_t i) {
      meets[i] = self_intersection_detail::faces_intersect(fs[candidates[i].first], fs[candidates[i].second], m, vpm) ? 1 : 0;
    }, 16);
    for(std::size_t i = 0; i < candidates.size() && out.size() < bound; ++i)
      if(meets[i]) out.emplace_back(fs[candidates[i].first], fs[candidates[i].second]);
    candidates.clear();
    if(out.size() >= bound) throw Bound_reached();
  };
  // (whether a pair sharing a safe corner can be left out; reads only)
  auto shares_safe_corner = [&](std::uint32_t a, std::uint32_t b) {
    for(int k = 0; k < 3; ++k)
      if(corner_safe[a][k])
        for(int l = 0; l < 3; ++l) if(corners[a][k] == corners[b][l]) return true;
    return false;
  };
  // (whether a pair of the grid's is a candidate: its boxes meet, and no safe corner leaves it out)
  auto is_candidate = [&](std::uint32_t a, std::uint32_t b) {
    const CGAL::Bbox_3 &x = boxes[a], &y = boxes[b];
    if(x.xmax() < y.xmin() || y.xmax() < x.xmin() || x.ymax() < y.ymin() || y.ymax() < x.ymin() || x.zmax() < y.zmin() || y.zmax() < x.zmin()) return false;
    return !shares_safe_corner(a, b);
  };
  auto take = [&](std::uint32_t a, std::uint32_t b) {
    candidates.emplace_back(a, b);
    if(candidates.size() == block) flush();
  };
  auto consider_meeting = [&](std::uint32_t a, std::uint32_t b) { if(!shares_safe_corner(a, b)) take(a, b); };
  // (the grid's faces cell by cell, each with its box, its vertices and whether the faces around
  // each of them project one-to-one: the search reads them in that order from one array, where
  // `filed` only names them)
  struct Filed_face
  {
    CGAL::Bbox_3 box;
    std::array<vertex_descriptor, 3> corners;
    std::array<bool, 3> safe;
    std::uint32_t index;
  };
  std::vector<Filed_face> in_cells;
  auto is_candidate_in_cells = [&](const Filed_face& a, const Filed_face& b) {
    const CGAL::Bbox_3 &x = a.box, &y = b.box;
    if(x.xmax() < y.xmin() || y.xmax() < x.xmin() || x.ymax() < y.ymin() || y.ymax() < x.ymin() || x.zmax() < y.zmin() || y.zmax() < x.zmin()) return false;
    for(int k = 0; k < 3; ++k)
      if(a.safe[k])
        for(int l = 0; l < 3; ++l) if(a.corners[k] == b.corners[l]) return false;
    return true;
  };
  auto consider = [&](std::uint32_t a, std::uint32_t b) { if(is_candidate(a, b)) take(a, b); };
  try {
    if(!grid) {
      typedef CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t, CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS> Box;
      std::vector<Box> sweep_boxes;
      sweep_boxes.reserve(n);
      for(std::uint32_t i = 0; i < n; ++i) sweep_boxes.emplace_back(boxes[i], i);
      std::vector<const Box*> sweep;   // (pointers: the sweep reorders them, the boxes keep their addresses, their ids)
      for(const Box& b : sweep_boxes) sweep.push_back(&b);
      CGAL::box_self_intersection_d<CGAL::Sequential_tag>(sweep.begin(), sweep.end(), [&](const Box* a, const Box* b) { consider_meeting(a->info(), b->info()); },
                                                         std::ptrdiff_t(2000));
    } else {
      in_cells.reserve(filed.size());
      for(const auto& x : filed) in_cells.push_back(Filed_face{boxes[x.second], corners[x.second], corner_safe[x.second], x.second});
      // (each cell's box, of its faces' boxes: a face whose box misses a neighbouring cell's meets
      // none of its faces' boxes, and its pairs there are passed over without a test each)
      std::vector<CGAL::Bbox_3> cell_box(cells.size());
      for(std::size_t c = 0; c < cells.size(); ++c)
        for(std::uint32_t i = cells[c].first; i < cells[c].end; ++i) cell_box[c] += in_cells[i].box;
      // each cell against itself and one neighbour of each opposite pair (13 of its 26: the
      // opposite one takes this cell in its own turn), found in an open-addressing table of the
      // occupied cells
      int table_bits = 4;
      while((std::size_t(1) << table_bits) < 2 * cells.size()) ++table_bits;
      const std::size_t table_size = std::size_t(1) << table_bits;
      const std::uint32_t empty = (std::numeric_limits<std::uint32_t>::max)();
      std::vector<std::uint32_t> table(table_size, empty);
      // (Fibonacci hashing: the product's top bits, which every bit of the key reaches; its middle
      // bits would not depend on x, the key's top bits, and a row of cells along x would share a slot)
      auto slot = [&](std::uint64_t key) { return std::size_t((key * 0x9E3779B97F4A7C15ull) >> (64 - table_bits)); };
      for(std::uint32_t c = 0; c < cells.size(); ++c) {
        std::size_t s = slot(cells[c].key);
        while(table[s] != empty) s = (s + 1) & (table_size - 1);
        table[s] = c;
      }
      auto find = [&](std::uint64_t key) -> const Cell* {
        for(std::size_t s = slot(key);; s = (s + 1) & (table_size - 1)) {
          if(table[s] == empty) return nullptr;
          if(cells[table[s]].key == key) return &cells[table[s]];
        }
      };
      static const int one_of_each_pair[13][3] = {{1, 0, 0}, {1, 1, 0},  {1, -1, 0}, {0, 1, 0},  {1, 0, 1},   {1, 1, 1}, {1, -1, 1},
                                                  {0, 1, 1}, {0, 0, 1},  {-1, 1, 1}, {-1, 0, 1}, {-1, -1, 1}, {0, -1, 1}};
      const std::uint64_t mask = (std::uint64_t(1) << 21) - 1;
      // the candidate pairs of a cell, in the order the whole search takes them (reads only)
      auto cell_pairs = [&](const Cell& c, auto emit) {
        for(std::uint32_t i = c.first; i < c.end; ++i)
          for(std::uint32_t j = i + 1; j < c.end; ++j)
            if(is_candidate_in_cells(in_cells[i], in_cells[j])) emit(in_cells[i].index, in_cells[j].index);
        const std::int64_t x = std::int64_t(c.key >> 42), y = std::int64_t((c.key >> 21) & mask), z = std::int64_t(c.key & mask);
        for(const auto& d : one_of_each_pair) {
          const std::uint64_t key = (std::uint64_t(x + d[0]) << 42) | (std::uint64_t(y + d[1]) << 21) | std::uint64_t(z + d[2]);
          const Cell* other = find(key);
          if(other == nullptr) continue;
          const CGAL::Bbox_3& other_box = cell_box[std::size_t(other - cells.data())];
          if(!CGAL::do_overlap(cell_box[std::size_t(&c - cells.data())], other_box)) continue;
          for(std::uint32_t i = c.first; i < c.end; ++i) {
            if(!CGAL::do_overlap(in_cells[i].box, other_box)) continue;
            for(std::uint32_t j = other->first; j < other->end; ++j)
              if(is_candidate_in_cells(in_cells[i], in_cells[j])) emit(in_cells[i].index, in_cells[j].index);
          }
        }
      };
      if constexpr(is_parallel<ConcurrencyTag>()) {
        // (the cells a group at a time, each group's runs of cells by TBB's threads into lists of
        // their own, taken in in the cells' order: the same candidates in the same order as in
        // sequence, and a search that reaches `bound` stops within a group)
        const std::size_t run = 64, group = 64 * run;
        std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found((group + run - 1) / run);
        for(std::size_t g = 0; g < cells.size(); g += group) {
          const std::size_t runs = ((std::min)(cells.size(), g + group) - g + run - 1) / run;
          for_each_index<ConcurrencyTag>(runs, [&](std::size_t r) {
            found[r].clear();
            const std::size_t first = g + r * run, end = (std::min)(cells.size(), first + run);
            for(std::size_t c = first; c < end; ++c) cell_pairs(cells[c], [&](std::uint32_t a, std::uint32_t b) { found[r].emplace_back(a, b); });
          }, 1);
          for(std::size_t r = 0; r < runs; ++r)
            for(const auto& ab : found[r]) take(ab.first, ab.second);
        }
      } else {
        for(const Cell& c : cells) cell_pairs(c, take);
      }
      // the few big faces against every box (each big pair once)
      for(std::size_t k = 0; k < big.size(); ++k) {
        for(const auto& x : filed) consider(big[k], x.second);
        for(std::size_t l = k + 1; l < big.size(); ++l) consider(big[k], big[l]);
      }
    }

    flush();
  } catch(const Bound_reached&) {}
  return finish();
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_SELF_INTERSECTIONS_H
