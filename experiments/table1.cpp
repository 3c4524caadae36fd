#include "experiments/table1.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace bsg::experiments {

namespace {

// Row order of the report's Table 1.
constexpr std::array<const char*, 16> kReportEnvOrder = {
    "SafetyBallCircle-v0", "SafetyCarCircle-v0", "SafetyDroneCircle-v0", "SafetyAntCircle-v0",
    "SafetyBallGather-v0", "SafetyCarGather-v0", "SafetyDroneGather-v0", "SafetyAntGather-v0",
    "SafetyBallReach-v0",  "SafetyCarReach-v0",  "SafetyDroneReach-v0",  "SafetyAntReach-v0",
    "SafetyBallRun-v0",    "SafetyCarRun-v0",    "SafetyDroneRun-v0",    "SafetyAntRun-v0"};

std::size_t report_rank(const std::string& env_id) {
  const auto found = std::find(kReportEnvOrder.begin(), kReportEnvOrder.end(), env_id);
  return static_cast<std::size_t>(found - kReportEnvOrder.begin());  // 16 if not listed
}

// a better than b (both selected, constrained): meeting the limit first, then
// the higher J; if neither meets it, the lower H.
bool better_constrained(const Table1Cell& a, const Table1Cell& b) {
  if (a.constraint_met != b.constraint_met) return a.constraint_met;
  if (a.constraint_met) return a.score.mean_return > b.score.mean_return;
  return a.score.mean_cost < b.score.mean_cost;
}

}  // namespace

std::optional<double> Table1Row::trpo_return(bool corrected_learner) const {
  for (const bool corrected : {false, true}) {
    if (corrected && !corrected_learner) break;
    for (const Table1Cell& cell : cells) {
      if (cell.alg == Algorithm::trpo && cell.corrected_learner == corrected && cell.selected) {
        return cell.score.mean_return;
      }
    }
  }
  return std::nullopt;
}

std::string table1_row_label(const std::string& env_id) {
  std::string label = env_id;
  if (label.rfind("Safety", 0) == 0) label = label.substr(6);
  if (const std::size_t version = label.rfind("-v"); version != std::string::npos) {
    label = label.substr(0, version);
  }
  return label;
}

Table1Column table1_column_of(const Table1Cell& cell) {
  return Table1Column{cell.alg, cell.pid_multiplier, cell.corrected_learner};
}

Table1Column table1_column_of(const ConfigurationSummary& config) {
  return Table1Column{config.alg, config.pid_multiplier, config.corrected_learner};
}

std::string table1_column_label(Table1Column column) {
  if (column.corrected_learner) {
    column.corrected_learner = false;
    return table1_column_label(column) + " corrected";
  }
  if (column.pid_multiplier) return std::string(algorithm_info(column.alg).pid_label);
  return table1_column_label(column.alg);
}

std::string table1_column_label(Algorithm alg) { return std::string(algorithm_info(alg).label); }

Table1 build_table1(const std::vector<ConfigurationResults>& results, SelectionScore score) {
  Table1 table;
  table.score = score;

  // Group configurations by environment and column, keeping grid order.
  std::map<std::string, std::map<Table1Column, std::vector<ConfigurationResults>>> groups;
  std::set<Table1Column> present;  // faithful first; by algorithm, then SGD/Adam before PID
  for (const ConfigurationResults& config : results) {
    const Table1Column column{config.alg, config.pid_multiplier, config.corrected_learner};
    groups[config.env_id][column].push_back(config);
    present.insert(column);
  }
  table.columns.assign(present.begin(), present.end());

  std::vector<std::string> env_ids;
  for (const auto& [env_id, unused] : groups) env_ids.push_back(env_id);
  std::stable_sort(env_ids.begin(), env_ids.end(), [](const std::string& a, const std::string& b) {
    return report_rank(a) < report_rank(b);
  });

  for (const std::string& env_id : env_ids) {
    Table1Row row;
    row.env_id = env_id;
    row.cost_limit = std::numeric_limits<double>::quiet_NaN();
    for (const Table1Column& column : table.columns) {
      const Algorithm alg = column.alg;
      Table1Cell cell;
      cell.alg = alg;
      cell.pid_multiplier = column.pid_multiplier;
      cell.corrected_learner = column.corrected_learner;
      const auto found = groups[env_id].find(column);
      if (found != groups[env_id].end()) {
        const std::vector<ConfigurationResults>& candidates = found->second;
        const std::optional<Selection> selection = select_configuration(candidates, score);
        for (std::size_t i = 0; i < candidates.size(); ++i) {
          const ConfigurationResults& config = candidates[i];
          if (std::isnan(row.cost_limit) && !std::isnan(config.cost_limit)) {
            row.cost_limit = config.cost_limit;
          }
          ConfigurationSummary summary{config.env_id, alg, config.config_name, config.cost_limit,
                                       config.seeds.size(), config.seeds_expected, std::nullopt,
                                       selection && selection->index == i, column.pid_multiplier,
                                       column.corrected_learner};
          if (!config.seeds.empty()) summary.score = score_configuration(config, score);
          table.configurations.push_back(std::move(summary));
        }
        if (selection) {
          const ConfigurationResults& chosen = candidates[selection->index];
          cell.selected = true;
          cell.config_name = chosen.config_name;
          cell.config_dir = !chosen.config_dir.empty()
                                ? chosen.config_dir
                                : env_id + "/" + std::string(to_string(alg)) + "/" + chosen.config_name;
          cell.seeds_finished = chosen.seeds.size();
          cell.seeds_expected = chosen.seeds_expected;
          cell.score = selection->score;
          cell.constraint_met = selection->constraint_met;
        }
      }
      row.cells.push_back(std::move(cell));
    }
    Table1Cell* best = nullptr;
    for (Table1Cell& cell : row.cells) {
      if (ignores_cost(cell.alg) || !cell.selected) continue;
      if (best == nullptr || better_constrained(cell, *best)) best = &cell;
    }
    if (best != nullptr) best->best_constrained = true;
    table.rows.push_back(std::move(row));
  }
  return table;
}

}  // namespace bsg::experiments
