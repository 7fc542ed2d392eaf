// Poisson_remesh/progress.h
//
// Progress reports and cancellation of the long entry points (poisson_remesh(),
// poisson_disk_sample()), through two optional named parameters:
//   - `progress`: a callable `bool(const Poisson_remesh::Progress&)`, told the stage and how far
//     it is (samples placed against those expected, relaxation round k of n, ...);
//   - `callback` (CGAL's): a callable `bool(double)`, told the fraction of the whole run done, as
//     CGAL's long algorithms do.
// Either returning false stops the run: the entry point throws Poisson_remesh::Cancelled (its
// output is then unspecified but valid to destroy or clear). Both are called at most a few
// hundred times per stage, so a callback may print without slowing the run.

#ifndef POISSON_REMESH_PROGRESS_H
#define POISSON_REMESH_PROGRESS_H

#include <Poisson_remesh/parameters.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>

namespace Poisson_remesh {

/// Where a long run is: given to the `progress` named parameter.
struct Progress
{
  const char* stage = "";   ///< "features", "sampling", "tessellation", "relaxation", "optimization"
  std::size_t done = 0;     ///< work units of the stage done
  std::size_t total = 0;    ///< work units of the stage expected (0: unknown); `done` may pass it
};

/// Thrown by the entry points when a `progress` or `callback` named parameter returned false.
class Cancelled : public std::runtime_error
{
public:
  /// `stage`: the stage that was running.
  explicit Cancelled(const std::string& stage)
    : std::runtime_error("cancelled by the caller during " + stage) {}
};

namespace internal {

// Forwards the stages' reports to the user's callables, throttled, and throws Cancelled when one
// returns false. A default-constructed reporter does nothing (and costs a branch).
class Progress_reporter
{
public:
  Progress_reporter() = default;

  template <class NamedParameters>
  explicit Progress_reporter(const NamedParameters& np)
  {
    using parameters::get_parameter;
    using parameters::is_default_parameter;
    if constexpr(!is_default_parameter<NamedParameters, internal_np::progress_t>::value)
      progress_ = get_parameter(np, internal_np::progress);
    if constexpr(!is_default_parameter<NamedParameters, CGAL::internal_np::callback_t>::value)
      callback_ = get_parameter(np, CGAL::internal_np::callback);
  }

  bool active() const { return bool(progress_) || bool(callback_); }

  // The share of the whole run that each stage takes (roughly, for CGAL's fraction), set by the
  // entry point: stage k of the run spans [begin, end) of it.
  void set_span(double begin, double end) { begin_ = begin; end_ = end; }

  // Reports `done` of `total` in `stage`; the user is called when the stage changes, at the end,
  // or when `done` passed another 1/200 of `total` (each call when total is 0).
  void operator()(const char* stage, std::size_t done, std::size_t total)
  {
    if(!active()) return;
    const bool new_stage = stage != stage_;
    const std::size_t step = total / 200 + 1;
    if(!new_stage && total > 0 && done < total && done < last_ + step) return;
    stage_ = stage;
    last_ = done;
    if(progress_) {
      Progress p;
      p.stage = stage;
      p.done = done;
      p.total = total;
      if(!progress_(p)) throw Cancelled(stage);
    }
    if(callback_) {
      const double f = total > 0 ? std::min(1.0, double(done) / double(total)) : 0.0;
      if(!callback_(begin_ + f * (end_ - begin_))) throw Cancelled(stage);
    }
  }

private:
  std::function<bool(const Progress&)> progress_;
  std::function<bool(double)> callback_;
  const char* stage_ = nullptr;
  std::size_t last_ = 0;
  double begin_ = 0, end_ = 1;
};

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_PROGRESS_H
