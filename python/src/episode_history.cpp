#include "episode_history.h"

namespace bsg::python {

void EpisodeHistory::seeded_reset(std::uint64_t seed) {
  *this = EpisodeHistory();
  seed_ = seed;
}

void EpisodeHistory::reset() {
  if (complete_) resets_.push_back(steps_);
}

void EpisodeHistory::step(std::span<const double> action) {
  ++steps_;
  if (!complete_) return;
  if (static_cast<std::size_t>(steps_) > kMaxSteps) {
    lose();
    return;
  }
  actions_.insert(actions_.end(), action.begin(), action.end());
}

void EpisodeHistory::lose() {
  complete_ = false;
  resets_ = {};
  actions_ = {};  // frees the memory
}

}  // namespace bsg::python
