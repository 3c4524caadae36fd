// Table 1 of the report from a sweep's results: per environment (row) and
// algorithm (column; TRPO-L and PDO with the PID Lagrange multiplier are
// columns of their own, "TRPO-PID" and "PDO-PID"), the configuration chosen by the selection rule
// (selection.h), its J normalised by TRPO's selected J, and H / d. The best
// constrained algorithm of each row is marked: one that meets the cost limit
// beats one that does not; then the higher J (or, if none meets it, the lower
// H). Rendering is in table1_render.h.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "common/run_config.h"
#include "experiments/selection.h"

namespace bsg::experiments {

// A column: an algorithm, with TRPO-L and PDO split by their multiplier rule
// (SGD or Adam: the report's columns; PID: one more column each).
struct Table1Column {
  Algorithm alg = Algorithm::trpo;
  bool pid_multiplier = false;
  bool corrected_learner = false;  // `learner: corrected`: after all the faithful columns
  bool operator==(const Table1Column&) const = default;
  auto operator<=>(const Table1Column& other) const {
    return std::tie(corrected_learner, alg, pid_multiplier) <=>
           std::tie(other.corrected_learner, other.alg, other.pid_multiplier);
  }
};

struct Table1Cell {
  Algorithm alg = Algorithm::trpo;
  bool pid_multiplier = false;  // the PID column of TRPO-L or PDO
  bool corrected_learner = false;  // a column of runs with `learner: corrected`
  bool selected = false;  // false: no finished run of any configuration (missing)
  std::string config_name;
  std::string config_dir;  // <env_id>/<alg>/<config>, relative to the sweep
  std::size_t seeds_finished = 0;
  std::size_t seeds_expected = 0;
  ConfigurationScore score;
  bool constraint_met = false;    // false with selected: the lowest-violation fallback
  bool best_constrained = false;  // the row's best constrained algorithm
};

struct Table1Row {
  std::string env_id;
  double cost_limit = 0.0;  // d; NaN if no run of the row has a configuration
  std::vector<Table1Cell> cells;  // one per Table1::columns entry
  // J_TRPO, the mean return of the faithful TRPO's selected configuration, if
  // it has one; for a corrected column (`corrected_learner`) without it, the
  // corrected TRPO's. One reference makes the two learners' columns comparable.
  std::optional<double> trpo_return(bool corrected_learner = false) const;
};

// One line of configurations.csv: every configuration and its score.
struct ConfigurationSummary {
  std::string env_id;
  Algorithm alg = Algorithm::trpo;
  std::string config_name;
  double cost_limit = 0.0;
  std::size_t seeds_finished = 0;
  std::size_t seeds_expected = 0;
  std::optional<ConfigurationScore> score;  // nullopt: no finished run
  bool selected = false;
  bool pid_multiplier = false;
  bool corrected_learner = false;
};

struct Table1 {
  SelectionScore score = SelectionScore::mean_return;
  bool show_cost_rate = false;  // bsg table --metric cost-rate: the training cost rate beside J and H
  // Those in the sweep, in kAlgorithmNames order, each PID column after its algorithm's.
  std::vector<Table1Column> columns;
  std::vector<Table1Row> rows;        // the report's row order, then other ids sorted
  std::vector<ConfigurationSummary> configurations;
};

Table1 build_table1(const std::vector<ConfigurationResults>& results, SelectionScore score);

// "BallCircle" for "SafetyBallCircle-v0" (the report's row labels).
std::string table1_row_label(const std::string& env_id);
// "TRPO", "TRPO-L", "CPO", "PDO", "PCPO", "PPO", "PPO-Lag", "FOCOPS", "CUP";
// "TRPO-PID", "PDO-PID", "CPPO-PID" (ppo-lag with PID), "FOCOPS-PID", "CUP-PID";
// with the corrected learner " corrected" appended ("TRPO-L corrected").
std::string table1_column_label(Table1Column column);
// The column a cell or a configuration belongs to.
Table1Column table1_column_of(const Table1Cell& cell);
Table1Column table1_column_of(const ConfigurationSummary& config);
std::string table1_column_label(Algorithm alg);

}  // namespace bsg::experiments
