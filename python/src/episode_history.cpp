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
    complete_ = false;
    resets_ = {};
    actions_ = {};  // frees the memory
    return;
  }
  actions_.insert(actions_.end(), action.begin(), action.end());
}

}  // namespace bsg::python
