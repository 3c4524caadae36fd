#include "algos/offline/offline_dataset.h"

#include <algorithm>
#include <stdexcept>

namespace bsg::algos {
namespace {

void check_length(const std::vector<float>& array, const char* name, std::size_t expected) {
  if (array.size() != expected) {
    throw std::invalid_argument(std::string("dataset: ") + name + " holds " + std::to_string(array.size()) +
                                " values, expected " + std::to_string(expected));
  }
}

void check_flags(const std::vector<float>& flags, const char* name) {
  for (std::size_t t = 0; t < flags.size(); ++t) {
    if (flags[t] != 0.0f && flags[t] != 1.0f) {
      throw std::invalid_argument(std::string("dataset: ") + name + "[" + std::to_string(t) + "] is " +
                                  std::to_string(flags[t]) + ", expected 0 or 1");
    }
  }
}

}  // namespace

void check_dataset_shapes(const OfflineDataset& dataset) {
  if (dataset.observation_dim <= 0 || dataset.action_dim <= 0) {
    throw std::invalid_argument("dataset: observation and action dimensions must be positive, got " +
                                std::to_string(dataset.observation_dim) + " and " +
                                std::to_string(dataset.action_dim));
  }
  const std::size_t n = dataset.size();
  const auto obs = static_cast<std::size_t>(dataset.observation_dim);
  check_length(dataset.observations, "observations", n * obs);
  check_length(dataset.next_observations, "next_observations", n * obs);
  check_length(dataset.actions, "actions", n * static_cast<std::size_t>(dataset.action_dim));
  check_length(dataset.costs, "costs", n);
  check_length(dataset.terminals, "terminals", n);
  check_length(dataset.timeouts, "timeouts", n);
  if (dataset.constraint_names.size() == 1) {
    throw std::invalid_argument("dataset: a single constraint has no constraint_costs matrix (costs holds it)");
  }
  check_length(dataset.constraint_costs, "constraint_costs", dataset.constraint_names.empty()
                                                                 ? 0
                                                                 : n * dataset.constraint_names.size());
  check_flags(dataset.terminals, "terminals");
  check_flags(dataset.timeouts, "timeouts");
}

std::vector<DatasetEpisode> dataset_episodes(const OfflineDataset& dataset) {
  std::vector<DatasetEpisode> episodes;
  DatasetEpisode current;
  for (std::size_t t = 0; t < dataset.size(); ++t) {
    current.reward_return += dataset.rewards[t];
    current.cost_return += dataset.costs[t];
    const bool terminal = dataset.terminals[t] == 1.0f;
    if (terminal || dataset.timeouts[t] == 1.0f) {
      current.end = t + 1;
      current.terminated = terminal;
      episodes.push_back(current);
      current = DatasetEpisode{.begin = t + 1, .end = t + 1};
    }
  }
  return episodes;
}

ReturnRanges return_ranges(const std::vector<DatasetEpisode>& episodes) {
  if (episodes.empty()) throw std::invalid_argument("dataset: no complete episode (no row ends one)");
  const auto by_reward = [](const DatasetEpisode& a, const DatasetEpisode& b) {
    return a.reward_return < b.reward_return;
  };
  const auto by_cost = [](const DatasetEpisode& a, const DatasetEpisode& b) { return a.cost_return < b.cost_return; };
  const auto [min_r, max_r] = std::minmax_element(episodes.begin(), episodes.end(), by_reward);
  const auto [min_c, max_c] = std::minmax_element(episodes.begin(), episodes.end(), by_cost);
  return {min_r->reward_return, max_r->reward_return, min_c->cost_return, max_c->cost_return};
}

}  // namespace bsg::algos
