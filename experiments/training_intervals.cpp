#include "experiments/training_intervals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "common/algorithms.h"
#include "experiments/progress_columns.h"
#include "experiments/statistics/seed_summary.h"

namespace bsg::experiments {

namespace {

constexpr PointStatistic kStatistics[] = {PointStatistic::mean, PointStatistic::median, PointStatistic::iqm};

// One cost the run is constrained by: its columns in progress.csv and its limit.
struct CostChannel {
  std::string prefix;  // "" for the single constraint, "constraint_<i>_" for several
  std::string episode_cost_column;
  std::string cumulative_column;
  std::string rate_column;
  double limit = 0.0;
};

std::vector<CostChannel> cost_channels(const ConfigurationResults& config) {
  if (config.constraint_limits.empty()) {
    return {{"", "episode_cost_mean", "cumulative_cost", "cost_rate", config.cost_limit}};
  }
  std::vector<CostChannel> channels;
  for (std::size_t i = 0; i < config.constraint_limits.size(); ++i) {
    const std::string prefix = "constraint_" + std::to_string(i + 1) + "_";
    channels.push_back({prefix, prefix + "cost", prefix + "cumulative_cost", prefix + "cost_rate",
                        config.constraint_limits[i]});
  }
  return channels;
}

std::vector<ProgressColumns> read_seed_logs(const ConfigurationResults& config) {
  std::vector<ProgressColumns> logs;
  for (const SeedResult& seed : config.seeds) {
    if (seed.run_dir.empty()) continue;
    ProgressColumns log = read_progress_columns(seed.run_dir / "progress.csv");
    if (log.epochs() > 0) logs.push_back(std::move(log));
  }
  return logs;
}

// The last value of `column` in each log, or nullopt if a log lacks it (a run from before the column).
std::optional<std::vector<double>> last_values(const std::vector<ProgressColumns>& logs, const std::string& column) {
  std::vector<double> values;
  for (const ProgressColumns& log : logs) {
    if (!log.has(column)) return std::nullopt;
    values.push_back(log.column(column).back());
  }
  return values;
}

void add_rows(std::vector<IntervalRow>& rows, IntervalRow base, const std::string& metric,
              const std::vector<double>& values, const BootstrapOptions& options) {
  const SeedSummary summary = summarise_seeds(values, options);
  base.metric = metric;
  for (const PointStatistic statistic : kStatistics) {
    base.statistic = std::string(to_string(statistic));
    base.estimate = statistic == PointStatistic::mean     ? summary.mean
                    : statistic == PointStatistic::median ? summary.median
                                                           : summary.iqm;
    rows.push_back(base);
  }
}

void add_curves(std::vector<CurveRow>& curves, const ConfigurationResults& config,
                const std::vector<ProgressColumns>& logs, const BootstrapOptions& options) {
  std::size_t epochs = logs.front().epochs();
  for (const ProgressColumns& log : logs) epochs = std::min(epochs, log.epochs());
  const std::pair<const char*, const char*> metrics[] = {{"return", "episode_return_mean"},
                                                        {"cost", "episode_cost_mean"},
                                                        {"cost_rate", "cost_rate"},
                                                        {"cumulative_cost", "cumulative_cost"}};
  // The seeds as one stratum of indices: a resample picks whole curves.
  std::vector<double> indices(logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) indices[i] = static_cast<double>(i);
  for (const auto& [metric, column] : metrics) {
    if (!std::all_of(logs.begin(), logs.end(), [&](const ProgressColumns& log) { return log.has(column); })) continue;
    std::vector<const std::vector<double>*> seed_curves;
    for (const ProgressColumns& log : logs) seed_curves.push_back(&log.column(column));
    // Epochs where some seed has no value (NaN: no episode ended) would make the mean undefined: left out.
    std::vector<std::size_t> defined;
    for (std::size_t e = 0; e < epochs; ++e) {
      if (std::all_of(seed_curves.begin(), seed_curves.end(), [&](auto* c) { return std::isfinite((*c)[e]); })) {
        defined.push_back(e);
      }
    }
    if (defined.empty()) continue;
    const std::vector<IntervalEstimate> band = stratified_bootstrap_bands(
        Strata{indices},
        [&](const Strata& picked) {
          std::vector<double> means(defined.size(), 0.0);
          for (const double index : picked.front()) {
            const std::vector<double>& curve = *seed_curves[static_cast<std::size_t>(index)];
            for (std::size_t k = 0; k < defined.size(); ++k) means[k] += curve[defined[k]];
          }
          for (double& mean : means) mean /= static_cast<double>(picked.front().size());
          return means;
        },
        options);
    for (std::size_t k = 0; k < defined.size(); ++k) {
      curves.push_back(CurveRow{config.env_id, column_label_of(config), config.config_name, metric, defined[k],
                                logs.size(), band[k]});
    }
  }
}

}  // namespace

TrainingIntervals build_training_intervals(const std::vector<ConfigurationResults>& results, const Table1& table,
                                           const BootstrapOptions& options) {
  check_bootstrap_options(options);
  TrainingIntervals out;
  std::vector<std::string> column_order;
  std::map<std::string, Strata> over_limit_by_column;  // selected configurations, one stratum per environment
  std::map<std::string, std::set<double>> limits_by_column;
  for (const ConfigurationResults& config : results) {
    if (config.seeds.size() < 2) continue;  // result_intervals notes it
    const std::vector<ProgressColumns> logs = read_seed_logs(config);
    if (logs.size() < 2) {
      out.notes.push_back(config_dir_of(config) + ": fewer than 2 seeds with a progress.csv; no training intervals");
      continue;
    }
    IntervalRow base;
    base.env_id = config.env_id;
    base.column = column_label_of(config);
    base.config = config.config_name;
    base.config_dir = config_dir_of(config);
    base.cost_limit = config.cost_limit;
    base.selected = is_selected(table, config);
    base.seeds = logs.size();
    for (const CostChannel& channel : cost_channels(config)) {
      const std::optional<std::vector<double>> cumulative = last_values(logs, channel.cumulative_column);
      const std::optional<std::vector<double>> rate = last_values(logs, channel.rate_column);
      if (!cumulative || !rate) {
        // An offline run steps no environment while it learns: it has no training cost to miss.
        if (!is_offline(config.alg)) out.notes.push_back(base.config_dir + ": progress.csv without " + channel.cumulative_column +
                            " (a run from before it); no cumulative cost");
      } else {
        add_rows(out.safety, base, channel.prefix + "cumulative_cost", *cumulative, options);
        add_rows(out.safety, base, channel.prefix + "cost_rate", *rate, options);
      }
      std::vector<double> over_limit;  // the fraction of epochs whose mean episode cost exceeds d
      for (const ProgressColumns& log : logs) {
        if (!log.has(channel.episode_cost_column)) break;
        std::vector<double> costs;
        for (const double cost : log.column(channel.episode_cost_column)) {
          if (std::isfinite(cost)) costs.push_back(cost);  // an epoch without a finished episode has none
        }
        if (!costs.empty()) over_limit.push_back(fraction_above(costs, channel.limit));
      }
      if (over_limit.size() == logs.size()) {
        add_rows(out.safety, base, channel.prefix + "epochs_over_limit", over_limit, options);
        if (base.selected && channel.prefix.empty()) {
          if (!over_limit_by_column.count(base.column)) column_order.push_back(base.column);
          over_limit_by_column[base.column].push_back(over_limit);
          limits_by_column[base.column].insert(channel.limit);
        }
      }
    }
    if (base.selected) add_curves(out.curves, config, logs, options);
  }
  for (const std::string& column : column_order) {
    const Strata& strata = over_limit_by_column[column];
    IntervalRow row;
    row.column = column;
    row.cost_limit = limits_by_column[column].size() == 1 ? *limits_by_column[column].begin()
                                                          : std::numeric_limits<double>::quiet_NaN();
    row.selected = true;
    row.environments = strata.size();
    row.seeds = pooled_values(strata).size();
    row.metric = "epochs_over_limit";
    for (const PointStatistic statistic : kStatistics) {
      row.statistic = std::string(to_string(statistic));
      row.estimate = stratified_bootstrap_interval(strata, pooled_statistic(statistic), options);
      out.safety_aggregates.push_back(row);
    }
  }
  return out;
}

}  // namespace bsg::experiments
