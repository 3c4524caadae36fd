// DSRL's normalised score of an offline policy (docs/datasets.md#normalised-scores):
//   reward: (R - R_min) / (R_max - R_min), R_min and R_max the dataset's smallest
//           and largest episode reward;
//   cost:   (C + eps) / (kappa + eps), kappa the cost limit, eps = 1 if kappa = 0 else 0.
#pragma once

namespace bsg::algos {

struct NormalizedScore {
  double reward = 0.0;
  double cost = 0.0;
};

// Throws std::invalid_argument if max_episode_reward == min_episode_reward or
// cost_limit < 0.
NormalizedScore normalized_score(double reward, double cost, double cost_limit, double min_episode_reward,
                                 double max_episode_reward);

}  // namespace bsg::algos
