// Poisson_remesh/internal/parallel.h
//
// The parallel mode (internal): CGAL's concurrency tags (CGAL::Sequential_tag, CGAL::Parallel_tag,
// CGAL::Parallel_if_available_tag) mapped to a loop over indices, with TBB when the tag asks for
// it; and the rounds that let the relaxation's vertex passes run in parallel with the result of
// the sequential pass.
//
// Why rounds: the Lloyd step and the angle searches move one vertex at a time, in the order of the
// mesh's vertices, each reading only its one-ring (and the input, read-only). A vertex's move
// depends on the moves of its neighbours before it in that order and on no other; the vertices
// whose earlier neighbours have all moved can move at once. Grouped so (dependency_rounds), the
// parallel pass gives the sequential pass's result exactly, for any number of threads.

#ifndef POISSON_REMESH_INTERNAL_PARALLEL_H
#define POISSON_REMESH_INTERNAL_PARALLEL_H

#include <CGAL/tags.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Dynamic_property_map.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#endif

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace Poisson_remesh {
namespace internal {

/// whether `ConcurrencyTag` asks for parallel loops (CGAL::Parallel_tag, or
/// CGAL::Parallel_if_available_tag with TBB)
template <class ConcurrencyTag>
constexpr bool is_parallel()
{
#ifdef CGAL_LINKED_WITH_TBB
  return std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;
#else
  static_assert(!std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "Poisson_remesh: CGAL::Parallel_tag needs TBB (define CGAL_LINKED_WITH_TBB and link TBB, e.g. with "
                "CMake's CGAL::TBB_support target); use CGAL::Parallel_if_available_tag to fall back to one thread");
  return false;
#endif
}

/// f(i) for i in [0, n): in order, or by TBB's threads (`ConcurrencyTag`); each f(i) must touch
/// only its own data. `grain`: the fewest calls a task takes (the default suits cheap calls:
/// below a few hundred a task costs more than it saves; 1 for a few long ones)
template <class ConcurrencyTag, class F>
void for_each_index(std::size_t n, F f, std::size_t grain = 64)
{
#ifdef CGAL_LINKED_WITH_TBB
  if constexpr(is_parallel<ConcurrencyTag>()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
      for(std::size_t i = r.begin(); i != r.end(); ++i) f(i);
    });
    return;
  }
#endif
  (void)is_parallel<ConcurrencyTag>();
  (void)grain;
  for(std::size_t i = 0; i < n; ++i) f(i);
}

/// `main()` and `beside()` at once (tbb::parallel_invoke) when `ConcurrencyTag` asks for parallel
/// loops (they must write no data in common, and neither may read what the other writes); else
/// `main()`, then `beside()`. Returns when both are done; an exception of either is thrown again.
template <class ConcurrencyTag, class Beside, class Main>
void run_beside(Beside beside, Main main)
{
#ifdef CGAL_LINKED_WITH_TBB
  if constexpr(is_parallel<ConcurrencyTag>()) {
    tbb::parallel_invoke(main, beside);
    return;
  }
#endif
  main();
  beside();
}

/// The vertices of `order` (vertices of `m`, each once) in rounds, so that moving each round's
/// vertices at once gives what moving them one by one in `order` gives, when a vertex's move reads
/// only its one-ring: a vertex's round comes after the rounds of its neighbours earlier in `order`
/// (their moves are seen) and before those of its neighbours later in it (theirs are not). No two
/// vertices of a round are neighbours. Each round keeps the order of `order`. (The tessellation
/// numbers the vertices as the sampling front grew: a chain of neighbours in ascending order is
/// short, so the rounds are few and large.)
template <class Mesh, class VertexRange>
std::vector<std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>> dependency_rounds(const Mesh& m, const VertexRange& order)
{
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  auto round = get(CGAL::dynamic_vertex_property_t<int>(), m);
  for(vertex_descriptor v : vertices(m)) put(round, v, -1);   // (-1: not in `order`, or not yet seen)
  std::vector<std::vector<vertex_descriptor>> rounds;
  for(vertex_descriptor v : order) {
    int r = 0;
    if(halfedge(v, m) != boost::graph_traits<Mesh>::null_halfedge())
      for(auto h : CGAL::halfedges_around_target(v, m)) r = (std::max)(r, get(round, source(h, m)) + 1);
    if(std::size_t(r) == rounds.size()) rounds.emplace_back();
    rounds[std::size_t(r)].push_back(v);
    put(round, v, r);
  }
  return rounds;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_PARALLEL_H
