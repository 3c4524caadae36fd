#include "experiments/selection.h"

#include <cmath>
#include <stdexcept>

namespace bsg::experiments {

std::string_view to_string(SelectionScore score) {
  return score == SelectionScore::mean_return ? "mean" : "mean_minus_std";
}

SelectionScore parse_selection_score(std::string_view text) {
  if (text == "mean") return SelectionScore::mean_return;
  if (text == "mean_minus_std") return SelectionScore::mean_minus_std;
  throw std::invalid_argument("unknown selection score '" + std::string(text) +
                              "'; valid: mean, mean_minus_std");
}

ConfigurationScore score_configuration(const ConfigurationResults& config, SelectionScore score) {
  const std::string name = config.env_id + "/" + std::string(to_string(config.alg)) + "/" +
                           config.config_name;
  if (config.seeds.empty()) {
    throw std::invalid_argument("configuration " + name + " has no finished run to score");
  }
  ConfigurationScore result;
  const std::size_t m = config.constraint_limits.size();
  result.mean_constraint_costs.assign(m, 0.0);
  for (const SeedResult& seed : config.seeds) {
    result.mean_return += seed.mean_return;
    result.mean_cost += seed.mean_cost;
    result.mean_cost_rate += seed.cost_rate;
    if (m > 0 && seed.constraint_costs.size() != m) {
      throw std::invalid_argument("configuration " + name + ", seed " + std::to_string(seed.seed) + ": " +
                                  std::to_string(seed.constraint_costs.size()) + " constraint costs in its "
                                  "evaluation, the configuration has " + std::to_string(m) + " constraints");
    }
    for (std::size_t i = 0; i < m; ++i) result.mean_constraint_costs[i] += seed.constraint_costs[i];
  }
  const double n = static_cast<double>(config.seeds.size());
  result.mean_return /= n;  // J: mean over seeds (report §5-6)
  result.mean_cost /= n;    // H
  result.mean_cost_rate /= n;
  if (m == 0) {
    result.feasible = result.mean_cost <= config.cost_limit;
  } else {  // every constraint must hold
    result.feasible = true;
    for (std::size_t i = 0; i < m; ++i) {
      result.mean_constraint_costs[i] /= n;
      result.feasible = result.feasible && result.mean_constraint_costs[i] <= config.constraint_limits[i];
    }
  }

  if (score == SelectionScore::mean_return) {
    result.score = result.mean_return;
    return result;
  }
  // Q17: all evaluation returns of all seeds pooled, mean - std (numpy's
  // default population std, as plot.py computes it).
  double sum = 0.0;
  std::size_t count = 0;
  for (const SeedResult& seed : config.seeds) {
    if (seed.episode_returns.empty()) {
      throw std::invalid_argument("configuration " + name + ", seed " + std::to_string(seed.seed) +
                                  ": no evaluation returns for the mean_minus_std score");
    }
    for (const double value : seed.episode_returns) sum += value;
    count += seed.episode_returns.size();
  }
  const double mean = sum / static_cast<double>(count);
  double squares = 0.0;
  for (const SeedResult& seed : config.seeds) {
    for (const double value : seed.episode_returns) squares += (value - mean) * (value - mean);
  }
  result.score = mean - std::sqrt(squares / static_cast<double>(count));
  return result;
}

std::optional<Selection> select_configuration(const std::vector<ConfigurationResults>& candidates,
                                              SelectionScore score) {
  std::optional<Selection> best_feasible;  // TRPO: every configuration counts as feasible
  std::optional<Selection> least_violating;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].seeds.empty()) continue;  // missing, not zero
    const ConfigurationScore s = score_configuration(candidates[i], score);
    const bool counts_as_feasible = ignores_cost(candidates[i].alg) || s.feasible;
    if (counts_as_feasible) {
      if (!best_feasible || s.score > best_feasible->score.score) best_feasible = Selection{i, s, true};
    } else if (!least_violating || s.mean_cost < least_violating->score.mean_cost) {
      least_violating = Selection{i, s, false};
    }
  }
  return best_feasible ? best_feasible : least_violating;
}

}  // namespace bsg::experiments
