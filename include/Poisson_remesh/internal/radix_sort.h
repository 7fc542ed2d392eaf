// Poisson_remesh/internal/radix_sort.h
//
// A stable sort of (64-bit key, index) pairs by key (internal), for the grids of the crossing
// search (internal/self_intersections.h) and of the near points (internal/near_points.h): their
// pairs are made in increasing index order, so a stable sort by key gives what std::sort of the
// pairs gives, in linear time. Our own code, as neither the standard library nor CGAL has a
// radix sort: the grids are sorted on one thread, which the parallel mode's others wait for.

#ifndef POISSON_REMESH_INTERNAL_RADIX_SORT_H
#define POISSON_REMESH_INTERNAL_RADIX_SORT_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// Sorts `v` by the pairs' first members, keeping the order of equal keys (least significant
/// byte first; the bytes in which all keys agree are skipped).
template <class Index>
void stable_sort_by_key(std::vector<std::pair<std::uint64_t, Index>>& v)
{
  if(v.size() < 2) return;
  std::uint64_t all_and = ~std::uint64_t(0), all_or = 0;
  for(const auto& x : v) { all_and &= x.first; all_or |= x.first; }
  const std::uint64_t differ = all_and ^ all_or;   // (the bits in which some keys differ)
  std::vector<std::pair<std::uint64_t, Index>> other(v.size());
  for(int shift = 0; shift < 64; shift += 8) {
    if(((differ >> shift) & 0xff) == 0) continue;
    std::array<std::size_t, 257> start{};
    for(const auto& x : v) ++start[((x.first >> shift) & 0xff) + 1];
    for(std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    for(const auto& x : v) other[start[(x.first >> shift) & 0xff]++] = x;
    v.swap(other);
  }
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_RADIX_SORT_H
