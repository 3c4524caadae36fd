// The cost-limit frontier (docs/reproducing.md#cost-limit-frontier): a sweep
// with an axis over the cost limit (`cost_limit: [5, 10, 25, 40, 60]`) trains
// each algorithm against several limits d; the frontier is, per algorithm
// (Table 1 column) and family of configurations (the configuration's name
// without its cost_limit=... part), one point per limit: the final policy's
// mean return J and mean cost H over the seeds, each with its bootstrap
// interval, and the proportion of seeds with H <= d (Wilson interval). With
// several constraints each constraint is a panel of its own: H_i against d_i.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "experiments/selection.h"
#include "experiments/statistics/stratified_bootstrap.h"

namespace bsg::experiments {

struct FrontierPoint {
  std::string env_id;
  std::string column;   // "TRPO-L", "CPPO-PID", ...
  std::string family;   // the configuration without its limit ("default" if nothing else)
  std::string config;   // the configuration's own name
  std::size_t constraint = 1;  // 1-based; 1 for the single cost
  double cost_limit = 0.0;     // d (d_i)
  std::size_t seeds = 0;
  IntervalEstimate mean_return;  // J
  IntervalEstimate mean_cost;    // H (H_i)
  IntervalEstimate feasible;     // proportion of seeds with H <= d (every H_i <= d_i)
};

struct CostLimitFrontier {
  std::vector<FrontierPoint> points;  // by environment, column, family, constraint, then limit
  std::vector<std::string> notes;     // points and families left out, and why
};

// "lambda_optimizer=PID" for "lambda_optimizer=PID,cost_limit=10"; "default" for "cost_limit=10".
std::string frontier_family(const std::string& config_name);

// Throws std::invalid_argument when no family has two limits with two
// finished seeds each, saying which limits the sweep has.
CostLimitFrontier build_cost_limit_frontier(const std::vector<ConfigurationResults>& results,
                                            const BootstrapOptions& options);

}  // namespace bsg::experiments
