// What a Python environment did since its last seeded reset (or since it was
// built): that seed, every action since, and where the unseeded resets fell.
// Replaying it on a new environment rebuilds the full physics state bit for
// bit, since every reset and step is deterministic; that is how bsg.Env
// pickles and copies (Bullet cannot snapshot its whole state: the solver's and
// broadphase's caches are not serialised). A seeded reset makes a fresh start
// (PythonEnv rebuilds the environment), so the history restarts there.
//
// Parameters:
//   kMaxSteps  100 000 steps: beyond it the actions are dropped (at most 6.4 MB
//              for the Ant's 8 entries) and copying raises RuntimeError asking
//              for a seeded reset first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace bsg::python {

class EpisodeHistory {
 public:
  static constexpr std::size_t kMaxSteps = 100000;

  void seeded_reset(std::uint64_t seed);
  void reset();
  void step(std::span<const double> action);
  // The environment was stepped behind the history's back (a benchmark).
  void lose();

  // False once more than kMaxSteps steps were taken since the seeded reset,
  // or after lose().
  bool complete() const { return complete_; }
  const std::optional<std::uint64_t>& seed() const { return seed_; }
  // Number of steps taken before each unseeded reset, in order.
  const std::vector<std::int64_t>& resets() const { return resets_; }
  // The actions, row after row.
  const std::vector<double>& actions() const { return actions_; }
  std::int64_t steps() const { return steps_; }

 private:
  std::optional<std::uint64_t> seed_;
  std::vector<std::int64_t> resets_;
  std::vector<double> actions_;
  std::int64_t steps_ = 0;
  bool complete_ = true;
};

}  // namespace bsg::python
