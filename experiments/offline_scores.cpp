#include "experiments/offline_scores.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "common/algorithms.h"
#include "common/atomic_file.h"
#include "common/config_scalar.h"
#include "common/csv_text.h"
#include "experiments/progress_columns.h"
#include "experiments/result_intervals.h"

namespace bsg::experiments {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The last epoch always evaluates (offline runs evaluate every eval_every-th
// epoch and the last), so the last finite value is the final evaluation's.
double last_finite(const ProgressColumns& log, const std::string& name) {
  const std::vector<double>& column = log.column(name);
  for (auto it = column.rbegin(); it != column.rend(); ++it) {
    if (std::isfinite(*it)) return *it;
  }
  throw std::runtime_error(log.source.string() + ": no epoch has a finite " + name);
}

IntervalEstimate mean_with_interval(const std::vector<double>& values, const BootstrapOptions& options) {
  if (values.size() < 2) return {mean_of(values), kNaN, kNaN};
  return stratified_bootstrap_interval({values}, pooled_statistic(PointStatistic::mean), options);
}

std::string short_number(double value) {
  if (!std::isfinite(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

std::string cell(const IntervalEstimate& estimate) {
  if (!std::isfinite(estimate.low)) return short_number(estimate.point);
  return short_number(estimate.point) + " [" + short_number(estimate.low) + ", " + short_number(estimate.high) + "]";
}

std::string number(double value) { return std::isfinite(value) ? format_config_real(value) : ""; }

std::string row_label(const OfflineScoreRow& row) {
  return row.config == "default" ? row.column : row.column + " (" + row.config + ")";
}

}  // namespace

OfflineScores build_offline_scores(const std::vector<ConfigurationResults>& results, const BootstrapOptions& options) {
  OfflineScores scores;
  scores.confidence = options.confidence;
  for (const ConfigurationResults& config : results) {
    if (!is_offline(config.alg) || config.seeds.empty()) continue;
    std::vector<double> rewards;
    std::vector<double> costs;
    for (const SeedResult& seed : config.seeds) {
      if (seed.run_dir.empty()) continue;
      const ProgressColumns log = read_progress_columns(seed.run_dir / "progress.csv");
      rewards.push_back(last_finite(log, "normalized_reward"));
      costs.push_back(last_finite(log, "normalized_cost"));
    }
    if (rewards.empty()) continue;
    OfflineScoreRow row;
    row.env_id = config.env_id;
    row.column = column_label_of(config);
    row.config = config.config_name;
    row.cost_limit = config.cost_limit;
    row.seeds = rewards.size();
    row.normalized_reward = mean_with_interval(rewards, options);
    row.normalized_cost = mean_with_interval(costs, options);
    if (rewards.size() < 2) {
      scores.notes.push_back(config_dir_of(config) + ": one finished seed; no interval");
    }
    scores.rows.push_back(std::move(row));
  }
  return scores;
}

std::string offline_scores_markdown(const OfflineScores& scores) {
  if (scores.rows.empty()) return "";
  std::vector<std::string> envs;
  std::vector<std::string> learners;
  std::map<std::pair<std::string, std::string>, const OfflineScoreRow*> by_cell;
  for (const OfflineScoreRow& row : scores.rows) {
    if (std::find(envs.begin(), envs.end(), row.env_id) == envs.end()) envs.push_back(row.env_id);
    const std::string label = row_label(row);
    if (std::find(learners.begin(), learners.end(), label) == learners.end()) learners.push_back(label);
    by_cell[{row.env_id, label}] = &row;
  }
  char confidence[32];
  std::snprintf(confidence, sizeof confidence, "%g %%", 100.0 * scores.confidence);
  std::string text = "Offline learners in DSRL's format: normalised reward and normalised cost (kappa = the run's "
                     "cost_limit) of the final online evaluation, mean over seeds [" + std::string(confidence) +
                     " bootstrap interval]; bold: the highest reward among the safe learners (mean normalised cost "
                     "<= 1) of the dataset; †: unsafe.\n\n| dataset | kappa |";
  for (const std::string& learner : learners) text += " " + learner + " reward | " + learner + " cost |";
  text += "\n|---|---|";
  for (std::size_t i = 0; i < learners.size(); ++i) text += "---|---|";
  text += "\n";
  std::map<std::string, std::pair<double, double>> sums;  // per learner: reward, cost over datasets
  std::map<std::string, std::size_t> counts;
  for (const std::string& env : envs) {
    double best = -std::numeric_limits<double>::infinity();
    double kappa = kNaN;
    for (const std::string& learner : learners) {
      const auto it = by_cell.find({env, learner});
      if (it == by_cell.end()) continue;
      kappa = it->second->cost_limit;
      if (it->second->safe()) best = std::max(best, it->second->normalized_reward.point);
    }
    text += "| " + env + " | " + number(kappa) + " |";
    for (const std::string& learner : learners) {
      const auto it = by_cell.find({env, learner});
      if (it == by_cell.end()) {
        text += " missing | missing |";
        continue;
      }
      const OfflineScoreRow& row = *it->second;
      std::string reward = cell(row.normalized_reward);
      std::string cost = cell(row.normalized_cost);
      if (!row.safe()) {
        reward += " †";
        cost += " †";
      } else if (row.normalized_reward.point == best) {
        reward = "**" + reward + "**";
      }
      text += " " + reward + " | " + cost + " |";
      sums[learner].first += row.normalized_reward.point;
      sums[learner].second += row.normalized_cost.point;
      ++counts[learner];
    }
    text += "\n";
  }
  if (envs.size() > 1) {
    text += "| mean over datasets | |";
    for (const std::string& learner : learners) {
      const std::size_t n = counts[learner];
      text += n == 0 ? std::string(" - | - |")
                     : " " + short_number(sums[learner].first / static_cast<double>(n)) + " (" + std::to_string(n) +
                           ") | " + short_number(sums[learner].second / static_cast<double>(n)) + " |";
    }
    text += "\n";
  }
  if (!scores.notes.empty()) {
    text += "\nNotes:\n";
    for (const std::string& note : scores.notes) text += "- " + note + "\n";
  }
  return text;
}

std::string offline_scores_csv(const OfflineScores& scores) {
  std::string text =
      "env_id,column,config,cost_limit,seeds,normalized_reward,normalized_reward_low,normalized_reward_high,"
      "normalized_cost,normalized_cost_low,normalized_cost_high,safe,confidence\n";
  for (const OfflineScoreRow& row : scores.rows) {
    text += csv_field(row.env_id) + "," + csv_field(row.column) + "," + csv_field(row.config) + "," +
            number(row.cost_limit) + "," + std::to_string(row.seeds) + "," + number(row.normalized_reward.point) + "," +
            number(row.normalized_reward.low) + "," + number(row.normalized_reward.high) + "," +
            number(row.normalized_cost.point) + "," + number(row.normalized_cost.low) + "," +
            number(row.normalized_cost.high) + "," + (row.safe() ? "1" : "0") + "," + number(scores.confidence) + "\n";
  }
  return text;
}

void write_offline_score_files(const OfflineScores& scores, const std::filesystem::path& out_dir) {
  write_file_atomically(out_dir / "offline_table.md", offline_scores_markdown(scores));
  write_file_atomically(out_dir / "offline_table.csv", offline_scores_csv(scores));
}

}  // namespace bsg::experiments
