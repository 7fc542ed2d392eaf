// Poisson_remesh/Relaxation/Relaxation_statistics.h
//
// What the relaxation did: counts of the moves, flips and changes of each step.

#ifndef POISSON_REMESH_RELAXATION_RELAXATION_STATISTICS_H
#define POISSON_REMESH_RELAXATION_RELAXATION_STATISTICS_H

#include <array>
#include <chrono>
#include <cstddef>
#include <utility>

namespace Poisson_remesh {

/// Seconds spent in each step of `Lloyd_relaxer::relax()` (wall clock, each step's rounds summed;
/// a step run inside another, as the Delaunay flips after an angle optimization, counts for itself
/// alone).
struct Relaxation_times
{
  /// the paper's steps
  /// @{
  double lloyd = 0, delaunay_flips = 0, valence_flips = 0;
  /// @}
  /// the operators beyond the paper (Postprocessing/)
  /// @{
  double sliver_collapse = 0, fidelity = 0, angle_smoothing = 0, regularity = 0,
         angle_optimization = 0, refinement = 0, final_regularity = 0, pinned_optimization = 0, untangling = 0,
         local_repair = 0;
  /// @}

  /// calls `f(name, seconds)` for each step, in the schedule's order
  template <class F>
  void for_each(F f) const
  {
    for(const auto& [name, member] : steps()) f(name, this->*member);
  }
  /// the sum over the steps
  double total() const { double t = 0; for_each([&](const char*, double s) { t += s; }); return t; }
  /// adds the times of `o` (the attempts of a remesh)
  Relaxation_times& operator+=(const Relaxation_times& o)
  {
    for(const auto& step : steps()) this->*step.second += o.*step.second;
    return *this;
  }

private:
  typedef std::pair<const char*, double Relaxation_times::*> Step;
  static const std::array<Step, 13>& steps()
  {
    static const std::array<Step, 13> s = {{
      {"lloyd", &Relaxation_times::lloyd}, {"delaunay_flips", &Relaxation_times::delaunay_flips},
      {"valence_flips", &Relaxation_times::valence_flips},
      {"sliver_collapse", &Relaxation_times::sliver_collapse}, {"fidelity", &Relaxation_times::fidelity},
      {"angle_smoothing", &Relaxation_times::angle_smoothing}, {"regularity", &Relaxation_times::regularity},
      {"angle_optimization", &Relaxation_times::angle_optimization}, {"refinement", &Relaxation_times::refinement},
      {"final_regularity", &Relaxation_times::final_regularity}, {"pinned_optimization", &Relaxation_times::pinned_optimization},
      {"untangling", &Relaxation_times::untangling}, {"local_repair", &Relaxation_times::local_repair}}};
    return s;
  }
};

namespace internal {

// Charges the time between switches to one step at a time: timed(field, f) runs f with its time
// going to `field`, the step that called it paused meanwhile (exclusive times: they add up to
// the relaxation's).
class Step_clock
{
  typedef std::chrono::steady_clock Clock;
public:
  template <class F>
  auto timed(double& field, F f)
  {
    double* outer = switch_to(&field);
    struct Back { Step_clock& c; double* outer; ~Back() { c.switch_to(outer); } } back{*this, outer};
    return f();
  }
private:
  double* switch_to(double* field)
  {
    const auto t = Clock::now();
    if(current_ != nullptr) *current_ += std::chrono::duration<double>(t - since_).count();
    since_ = t;
    double* previous = current_;
    current_ = field;
    return previous;
  }
  double* current_ = nullptr;
  Clock::time_point since_ = Clock::now();
};

} // namespace internal

/// What `Lloyd_relaxer::relax()` did.
struct Relaxation_statistics
{
  /// Lloyd moves made and refused, Delaunay and valence flips, sliver collapses
  /// @{
  std::size_t moves = 0, refused_moves = 0, delaunay_flips = 0, valence_flips = 0, collapses = 0;
  /// @}
  std::size_t angle_moves = 0;   ///< moves of the final angle optimization
  std::size_t fidelity_insertions = 0;   ///< input vertices inserted where the mesh cut across the input
  std::size_t refinement_insertions = 0;   ///< vertices inserted beside triangles still sharper than sliver_angle
  /// the other changes of the refinement: flips and vertex removals
  /// @{
  std::size_t refinement_flips = 0, refinement_removals = 0;
  /// @}
  std::size_t untangle_changes = 0;   ///< moves and flips that left fewer crossing face pairs
  std::size_t repair_changes = 0;   ///< changes of the local repair kept (a flip, a split or moves, with the moves after it)
  std::size_t unchanged_stars = 0;   ///< smoothing searches not made again: the star as it was when its search moved nothing
  Relaxation_times seconds;   ///< the time of each step
};

} // namespace Poisson_remesh

#endif // POISSON_REMESH_RELAXATION_RELAXATION_STATISTICS_H
