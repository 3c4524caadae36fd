// The report's selection rule (report §6.1, docs/reproducing.md#selection-rule) over the configurations
// of one (environment, algorithm) of a grid. Each configuration's J and H are
// the deterministic-evaluation means, averaged over its finished seeds.
//
//   constrained algorithms: among feasible configurations, the best score;
//     feasible: H <= d, or with several constraints (docs/reproducing.md#selection-rule)
//     every constraint's mean H_i <= d_i;
//     if none, the lowest H (the lowest cost violation), marked infeasible;
//   TRPO (unconstrained): the best score, whatever the cost (it is the
//     normaliser J_TRPO of Table 1).
//
// The score is mean J (the report's rule) or, as the original plot script's
// `--best` does (quirk Q17), mean - std of all evaluation returns of all
// seeds pooled. Configurations without a finished seed take no part: they
// are missing, never zero. Ties keep the first configuration in grid order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/run_config.h"

namespace bsg::experiments {

enum class SelectionScore { mean_return, mean_minus_std };
std::string_view to_string(SelectionScore score);
// "mean" or "mean_minus_std"; throws std::invalid_argument naming the text.
SelectionScore parse_selection_score(std::string_view text);

// The evaluation of one finished run.
struct SeedResult {
  std::int64_t seed = 0;
  double mean_return = 0.0;              // J, mean over its evaluation episodes
  double mean_cost = 0.0;                // H
  std::vector<double> episode_returns;   // needed only for mean_minus_std
  double cost_rate = 0.0;                // training cost rate (NaN if the run predates it)
  std::vector<double> constraint_costs{};  // H_i of the evaluation.json constraints list (may be empty)
  std::filesystem::path run_dir{};         // where its progress.csv is (empty: not known)
};

// One configuration of one (environment, algorithm).
struct ConfigurationResults {
  std::string env_id;
  Algorithm alg = Algorithm::trpo;
  std::string config_name;
  double cost_limit = 0.0;          // d
  std::size_t seeds_expected = 0;   // runs the grid asks for
  std::vector<SeedResult> seeds;    // the finished ones
  // TRPO-L or PDO with lambda_optimizer PID: a Table 1 column of its own
  // ("TRPO-PID", "PDO-PID"), selected apart from the SGD / Adam configurations.
  bool pid_multiplier = false;
  // Trained with `learner: corrected` (docs/algorithms.md#quirk-switches): a
  // column of its own ("TRPO corrected", ...), beside the faithful one.
  bool corrected_learner = false;
  // "<env_id>/<alg>/<config>" relative to the sweep (or, for a table of
  // several sweeps, prefixed with its sweep); empty: built from the fields.
  std::string config_dir;
  // d_i of the run's `constraints:` (empty: the single constraint H <= cost_limit).
  std::vector<double> constraint_limits{};
};

struct ConfigurationScore {
  double mean_return = 0.0;  // mean over seeds of J
  double mean_cost = 0.0;    // mean over seeds of H
  double score = 0.0;        // what the selection maximises
  bool feasible = false;     // mean_cost <= cost_limit, or every mean_constraint_costs[i] <= constraint_limits[i]
  double mean_cost_rate = 0.0;               // mean over seeds of the training cost rate (NaN if unknown)
  std::vector<double> mean_constraint_costs{};  // mean over seeds of H_i (with constraint_limits)
};

// Throws std::invalid_argument if the configuration has no finished seed, or
// (mean_minus_std) a seed without episode returns.
ConfigurationScore score_configuration(const ConfigurationResults& config, SelectionScore score);

struct Selection {
  std::size_t index = 0;  // into the candidates
  ConfigurationScore score;
  bool constraint_met = false;  // false: no configuration is feasible (fallback)
};

// Applies the rule to the candidates (one environment and algorithm);
// nullopt if none has a finished seed.
std::optional<Selection> select_configuration(const std::vector<ConfigurationResults>& candidates,
                                              SelectionScore score);

}  // namespace bsg::experiments
