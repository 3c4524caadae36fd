#include "experiments/cost_limit_frontier.h"

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "common/config_scalar.h"
#include "common/csv_text.h"
#include "experiments/result_intervals.h"
#include "experiments/statistics/seed_summary.h"

namespace bsg::experiments {

namespace {

// The limits of a configuration, one per constraint.
std::vector<double> limits_of(const ConfigurationResults& config) {
  return config.constraint_limits.empty() ? std::vector<double>{config.cost_limit} : config.constraint_limits;
}

double seed_cost(const ConfigurationResults& config, const SeedResult& seed, std::size_t constraint) {
  if (config.constraint_limits.empty()) return seed.mean_cost;
  return constraint < seed.constraint_costs.size() ? seed.constraint_costs[constraint]
                                                   : std::numeric_limits<double>::quiet_NaN();
}

std::string limits_text(const std::set<std::vector<double>>& limits) {
  std::string text;
  for (const std::vector<double>& set : limits) {
    if (!text.empty()) text += "; ";
    std::vector<std::string> parts;
    for (const double d : set) parts.push_back(format_config_real(d));
    for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? ", " : "") + parts[i];
  }
  return text.empty() ? "none" : text;
}

}  // namespace

std::string frontier_family(const std::string& config_name) {
  const std::vector<std::string> items = parse_csv_fields(config_name);
  std::string family;
  for (const std::string& item : items) {
    if (item.starts_with("cost_limit=")) continue;
    family += (family.empty() ? "" : ",") + item;
  }
  return family.empty() ? "default" : family;
}

CostLimitFrontier build_cost_limit_frontier(const std::vector<ConfigurationResults>& results,
                                            const BootstrapOptions& options) {
  check_bootstrap_options(options);
  CostLimitFrontier frontier;
  using FamilyKey = std::tuple<std::string, std::string, std::string>;  // env, column, family
  std::map<FamilyKey, std::vector<const ConfigurationResults*>> families;
  std::vector<FamilyKey> order;
  std::set<std::vector<double>> all_limits;
  for (const ConfigurationResults& config : results) {
    const FamilyKey key{config.env_id, column_label_of(config), frontier_family(config.config_name)};
    all_limits.insert(limits_of(config));
    if (config.seeds.size() == 1) {
      frontier.notes.push_back(config_dir_of(config) + ": 1 finished seed; left out of the frontier (an interval needs 2)");
    }
    if (config.seeds.size() < 2) continue;
    if (!families.count(key)) order.push_back(key);
    families[key].push_back(&config);
  }
  for (const FamilyKey& key : order) {
    std::vector<const ConfigurationResults*>& configs = families[key];
    std::set<std::vector<double>> limits;
    for (const ConfigurationResults* config : configs) limits.insert(limits_of(*config));
    if (limits.size() < 2) {
      frontier.notes.push_back(std::get<0>(key) + " " + std::get<1>(key) + " " + std::get<2>(key) +
                               ": one cost limit (" + limits_text(limits) + "); no frontier");
      continue;
    }
    std::stable_sort(configs.begin(), configs.end(), [](const ConfigurationResults* a, const ConfigurationResults* b) {
      return limits_of(*a) < limits_of(*b);
    });
    const std::size_t constraints = limits_of(*configs.front()).size();
    for (std::size_t c = 0; c < constraints; ++c) {
      for (const ConfigurationResults* config : configs) {
        std::vector<double> returns;
        std::vector<double> costs;
        std::size_t feasible = 0;
        for (const SeedResult& seed : config->seeds) {
          returns.push_back(seed.mean_return);
          costs.push_back(seed_cost(*config, seed, c));
          if (seed_feasible(*config, seed)) ++feasible;
        }
        FrontierPoint point;
        point.env_id = std::get<0>(key);
        point.column = std::get<1>(key);
        point.family = std::get<2>(key);
        point.config = config->config_name;
        point.constraint = c + 1;
        point.cost_limit = limits_of(*config).at(c);
        point.seeds = config->seeds.size();
        point.mean_return = summarise_seeds(returns, options).mean;
        point.mean_cost = summarise_seeds(costs, options).mean;
        point.feasible = wilson_interval(feasible, config->seeds.size(), options.confidence);
        frontier.points.push_back(std::move(point));
      }
    }
  }
  if (frontier.points.empty()) {
    throw std::invalid_argument(
        "no cost-limit frontier: it needs configurations that differ only in their cost limit, at two limits or "
        "more with 2 finished seeds each (a grid axis such as cost_limit: [5, 10, 25, 40, 60]); the sweep's limits: " +
        limits_text(all_limits));
  }
  return frontier;
}

}  // namespace bsg::experiments
