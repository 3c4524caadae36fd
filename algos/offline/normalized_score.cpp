#include "algos/offline/normalized_score.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {

NormalizedScore normalized_score(double reward, double cost, double cost_limit, double min_episode_reward,
                                 double max_episode_reward) {
  if (max_episode_reward == min_episode_reward) {
    throw std::invalid_argument("normalised score: the dataset's episode rewards span no range (min = max = " +
                                std::to_string(min_episode_reward) + ")");
  }
  if (!(cost_limit >= 0.0)) {
    throw std::invalid_argument("normalised score: the cost limit must be >= 0, got " + std::to_string(cost_limit));
  }
  const double epsilon = cost_limit == 0.0 ? 1.0 : 0.0;
  return {(reward - min_episode_reward) / (max_episode_reward - min_episode_reward),
          (cost + epsilon) / (cost_limit + epsilon)};
}

}  // namespace bsg::algos
