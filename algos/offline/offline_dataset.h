// An offline safe-RL dataset in memory (docs/datasets.md): N transitions with
// DSRL's arrays (liuzuxin/DSRL, whose loader mirrors D4RL's), each row the
// step s -> a -> (r, c, s'), plus the attributes that say how the data was
// made. Every array is float32 as DSRL's files are; matrices are row-major
// (row t is transition t). An episode ends at a row whose `terminals` or
// `timeouts` is 1: terminals when the environment ended it (the agent died,
// Gather's apples are all eaten), timeouts when it was cut (the time limit,
// or the end of a collection counted in transitions).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace bsg::algos {

struct OfflineDataset {
  int observation_dim = 0;
  int action_dim = 0;
  std::vector<float> observations;       // N x observation_dim
  std::vector<float> next_observations;  // N x observation_dim
  std::vector<float> actions;            // N x action_dim, as given to the environment
  std::vector<float> rewards;            // N
  std::vector<float> costs;              // N; with several constraints the sum of their costs
  std::vector<float> terminals;          // N, 0 or 1
  std::vector<float> timeouts;           // N, 0 or 1
  // With several constraints (m > 1): N x m, constraint i's cost of each step
  // (key `constraint_costs`), and their names; empty with one constraint.
  std::vector<float> constraint_costs;
  std::vector<std::string> constraint_names;
  // How the data was made (file attributes): text (environment description,
  // policies, seeds, bsg version) and numbers (the normalisation constants).
  std::map<std::string, std::string> text_attributes;
  std::map<std::string, double> number_attributes;

  std::size_t size() const { return rewards.size(); }
  int constraint_count() const { return constraint_names.empty() ? 1 : static_cast<int>(constraint_names.size()); }
};

// Throws std::invalid_argument naming the array whose length does not fit N
// and the dimensions, or a flag that is not 0 or 1.
void check_dataset_shapes(const OfflineDataset& dataset);

// One episode of a dataset: rows [begin, end).
struct DatasetEpisode {
  std::size_t begin = 0;
  std::size_t end = 0;
  double reward_return = 0.0;  // sum of rewards (in double)
  double cost_return = 0.0;    // sum of costs
  bool terminated = false;     // ended by the environment, not cut
};

// The episodes, split after every row with terminals or timeouts set (as
// DSRL's pre_process_data does). Rows after the last such row belong to no
// complete episode and are left out.
std::vector<DatasetEpisode> dataset_episodes(const OfflineDataset& dataset);

// The constants of DSRL's normalised score for a dataset: the smallest and
// largest episode reward and cost return over its complete episodes.
struct ReturnRanges {
  double min_episode_reward = 0.0;
  double max_episode_reward = 0.0;
  double min_episode_cost = 0.0;
  double max_episode_cost = 0.0;
};
// Throws std::invalid_argument if the dataset holds no complete episode.
ReturnRanges return_ranges(const std::vector<DatasetEpisode>& episodes);

}  // namespace bsg::algos
