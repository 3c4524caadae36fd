#include "experiments/result_intervals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "experiments/statistics/performance_profile.h"
#include "experiments/statistics/seed_summary.h"

namespace bsg::experiments {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr PointStatistic kStatistics[] = {PointStatistic::mean, PointStatistic::median, PointStatistic::iqm};

// The values of one metric over the seeds of a configuration.
using SeedValues = std::vector<double>;

struct ConfigurationMetrics {
  std::vector<std::pair<std::string, SeedValues>> values;  // metric -> one value per finished seed
  std::size_t feasible = 0;
  std::optional<SeedValues> margin;  // (d - H) / d, the worst constraint's
};

const Table1Row* row_of(const Table1& table, const std::string& env_id) {
  for (const Table1Row& row : table.rows) {
    if (row.env_id == env_id) return &row;
  }
  return nullptr;
}

// J_TRPO of the configuration's row, if there is one to divide by.
std::optional<double> trpo_return_of(const Table1& table, const ConfigurationResults& config) {
  const Table1Row* row = row_of(table, config.env_id);
  if (row == nullptr) return std::nullopt;
  const std::optional<double> trpo = row->trpo_return(config.corrected_learner);
  if (!trpo || *trpo == 0.0 || !std::isfinite(*trpo)) return std::nullopt;
  return trpo;
}

ConfigurationMetrics metrics_of(const ConfigurationResults& config, std::optional<double> trpo_return) {
  ConfigurationMetrics metrics;
  SeedValues j, j_over_trpo, h, h_over_d, margin;
  std::vector<SeedValues> h_i_over_d_i(config.constraint_limits.size());
  bool margin_defined = true;
  for (const SeedResult& seed : config.seeds) {
    j.push_back(seed.mean_return);
    if (trpo_return) j_over_trpo.push_back(seed.mean_return / *trpo_return);  // J / J_TRPO, as Table 1
    h.push_back(seed.mean_cost);
    if (seed_feasible(config, seed)) ++metrics.feasible;
    double worst_margin = std::numeric_limits<double>::infinity();
    if (config.constraint_limits.empty()) {
      if (config.cost_limit > 0.0) {
        h_over_d.push_back(seed.mean_cost / config.cost_limit);
        worst_margin = (config.cost_limit - seed.mean_cost) / config.cost_limit;
      } else {
        margin_defined = false;
      }
    } else {
      for (std::size_t i = 0; i < config.constraint_limits.size(); ++i) {
        const double d_i = config.constraint_limits[i];
        const double h_i = i < seed.constraint_costs.size() ? seed.constraint_costs[i] : kNaN;
        if (d_i > 0.0 && std::isfinite(h_i)) {
          h_i_over_d_i[i].push_back(h_i / d_i);
          worst_margin = std::min(worst_margin, (d_i - h_i) / d_i);
        } else {
          margin_defined = false;
        }
      }
    }
    margin.push_back(worst_margin);
  }
  metrics.values.emplace_back("J", j);
  if (trpo_return) metrics.values.emplace_back("J_over_trpo", j_over_trpo);
  metrics.values.emplace_back("H", h);
  if (!h_over_d.empty()) metrics.values.emplace_back("H_over_d", h_over_d);
  for (std::size_t i = 0; i < h_i_over_d_i.size(); ++i) {
    if (h_i_over_d_i[i].size() == config.seeds.size()) {
      metrics.values.emplace_back("H" + std::to_string(i + 1) + "_over_d" + std::to_string(i + 1), h_i_over_d_i[i]);
    }
  }
  if (margin_defined) metrics.margin = margin;
  return metrics;
}

IntervalRow row_for(const ConfigurationResults& config, const Table1& table) {
  IntervalRow row;
  row.env_id = config.env_id;
  row.column = column_label_of(config);
  row.config = config.config_name;
  row.config_dir = config_dir_of(config);
  row.cost_limit = config.cost_limit;
  row.selected = is_selected(table, config);
  row.seeds = config.seeds.size();
  return row;
}

void add_seed_rows(std::vector<IntervalRow>& rows, const IntervalRow& base, const std::string& metric,
                   const SeedValues& values, const BootstrapOptions& options) {
  const SeedSummary summary = summarise_seeds(values, options);
  for (const PointStatistic statistic : kStatistics) {
    IntervalRow row = base;
    row.metric = metric;
    row.statistic = std::string(to_string(statistic));
    row.estimate = statistic == PointStatistic::mean     ? summary.mean
                   : statistic == PointStatistic::median ? summary.median
                                                          : summary.iqm;
    rows.push_back(std::move(row));
  }
}

// The selected configurations of one column, by environment (report order).
struct ColumnStrata {
  std::string column;
  std::vector<std::string> env_ids;
  std::map<std::string, Strata> metric_strata;  // metric -> one stratum per environment
  std::size_t feasible = 0;
  std::size_t seeds = 0;
  std::set<double> cost_limits;
};

std::vector<double> thresholds_over(const std::vector<const Strata*>& all, std::size_t count) {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  for (const Strata* strata : all) {
    for (const double value : pooled_values(*strata)) {
      low = std::min(low, value);
      high = std::max(high, value);
    }
  }
  const double pad = high > low ? 0.05 * (high - low) : 0.5;  // a little room either side of the runs
  return evenly_spaced(low - pad, high + pad, count);
}

}  // namespace

std::string column_label_of(const ConfigurationResults& config) {
  return table1_column_label(Table1Column{config.alg, config.pid_multiplier, config.corrected_learner});
}

std::string config_dir_of(const ConfigurationResults& config) {
  return !config.config_dir.empty() ? config.config_dir
                                    : config.env_id + "/" + std::string(to_string(config.alg)) + "/" + config.config_name;
}

bool is_selected(const Table1& table, const ConfigurationResults& config) {
  const Table1Row* row = row_of(table, config.env_id);
  if (row == nullptr) return false;
  const std::string dir = config_dir_of(config);
  return std::any_of(row->cells.begin(), row->cells.end(),
                     [&](const Table1Cell& cell) { return cell.selected && cell.config_dir == dir; });
}

bool seed_feasible(const ConfigurationResults& config, const SeedResult& seed) {
  if (config.constraint_limits.empty()) return seed.mean_cost <= config.cost_limit;
  for (std::size_t i = 0; i < config.constraint_limits.size(); ++i) {
    if (!(i < seed.constraint_costs.size() && seed.constraint_costs[i] <= config.constraint_limits[i])) return false;
  }
  return true;
}

ResultIntervals build_result_intervals(const std::vector<ConfigurationResults>& results, const Table1& table,
                                       const BootstrapOptions& options, std::size_t profile_thresholds) {
  check_bootstrap_options(options);
  ResultIntervals out;
  out.confidence = options.confidence;
  std::size_t most_seeds = 0;
  std::set<std::string> unnormalised_envs;
  std::map<std::string, ColumnStrata> columns;  // selected configurations, by column label
  std::vector<std::string> column_order;
  // Selected configurations by environment, for the differences.
  std::map<std::string, std::vector<const ConfigurationResults*>> selected_by_env;

  std::size_t unfinished = 0;  // configurations without a finished seed: counted, not listed
  for (const ConfigurationResults& config : results) {
    most_seeds = std::max(most_seeds, config.seeds.size());
    if (config.seeds.empty()) {
      ++unfinished;
      continue;
    }
    if (config.seeds.size() < 2) {
      out.notes.push_back(config_dir_of(config) + ": 1 finished seed(s); no interval (at least 2 are needed)");
      continue;
    }
    const std::optional<double> trpo = trpo_return_of(table, config);
    if (!trpo) unnormalised_envs.insert(config.env_id);
    const ConfigurationMetrics metrics = metrics_of(config, trpo);
    const IntervalRow base = row_for(config, table);
    for (const auto& [metric, values] : metrics.values) add_seed_rows(out.configurations, base, metric, values, options);
    IntervalRow feasible = base;
    feasible.metric = "feasible";
    feasible.statistic = "proportion";
    feasible.estimate = wilson_interval(metrics.feasible, config.seeds.size(), options.confidence);
    out.configurations.push_back(feasible);

    if (!base.selected) continue;
    selected_by_env[config.env_id].push_back(&config);
    auto [it, inserted] = columns.try_emplace(base.column);
    ColumnStrata& column = it->second;
    if (inserted) {
      column.column = base.column;
      column_order.push_back(base.column);
    }
    column.env_ids.push_back(config.env_id);
    column.feasible += metrics.feasible;
    column.seeds += config.seeds.size();
    column.cost_limits.insert(config.cost_limit);
    for (const auto& [metric, values] : metrics.values) {
      if (metric == "J_over_trpo" || metric == "H_over_d") column.metric_strata[metric].push_back(values);
    }
    if (metrics.margin) column.metric_strata["feasibility_margin"].push_back(*metrics.margin);
  }
  if (most_seeds < 2) {
    throw std::invalid_argument("no configuration has two finished seeds (the most is " + std::to_string(most_seeds) +
                                "): an interval across seeds needs at least 2; a sweep with one seed has none");
  }
  if (unfinished > 0) {
    out.notes.push_back(std::to_string(unfinished) + " configuration(s) without a finished seed (missing, not zero)");
  }
  for (const std::string& env_id : unnormalised_envs) {
    out.notes.push_back(env_id + ": no TRPO run to normalise by; J / J_TRPO and its profile are left out");
  }

  // Across environments: the selected configurations of each column, one stratum per environment.
  for (const std::string& label : column_order) {
    const ColumnStrata& column = columns[label];
    for (const auto& [metric, strata] : column.metric_strata) {
      if (metric == "feasibility_margin" || strata.size() != column.env_ids.size()) continue;
      for (const PointStatistic statistic : kStatistics) {
        IntervalRow row;
        row.column = label;
        row.cost_limit = column.cost_limits.size() == 1 ? *column.cost_limits.begin() : kNaN;
        row.selected = true;
        row.environments = strata.size();
        row.seeds = pooled_values(strata).size();
        row.metric = metric;
        row.statistic = std::string(to_string(statistic));
        row.estimate = stratified_bootstrap_interval(strata, pooled_statistic(statistic), options);
        out.aggregates.push_back(std::move(row));
      }
    }
    IntervalRow feasible;
    feasible.column = label;
    feasible.cost_limit = column.cost_limits.size() == 1 ? *column.cost_limits.begin() : kNaN;
    feasible.selected = true;
    feasible.environments = column.env_ids.size();
    feasible.seeds = column.seeds;
    feasible.metric = "feasible";
    feasible.statistic = "proportion";
    feasible.estimate = wilson_interval(column.feasible, column.seeds, options.confidence);
    out.aggregates.push_back(feasible);
  }

  // Within each environment: every two columns' selected configurations.
  for (const auto& [env_id, configs] : selected_by_env) {
    for (std::size_t a = 0; a < configs.size(); ++a) {
      for (std::size_t b = a + 1; b < configs.size(); ++b) {
        for (const char* metric : {"J", "H"}) {
          Strata groups(2);
          for (std::size_t k = 0; k < 2; ++k) {
            for (const SeedResult& seed : configs[k == 0 ? a : b]->seeds) {
              groups[k].push_back(metric == std::string("J") ? seed.mean_return : seed.mean_cost);
            }
          }
          DifferenceRow row;
          row.env_id = env_id;
          row.metric = metric;
          row.column_a = column_label_of(*configs[a]);
          row.column_b = column_label_of(*configs[b]);
          row.seeds_a = groups[0].size();
          row.seeds_b = groups[1].size();
          row.difference = stratified_bootstrap_interval(groups, difference_statistic(PointStatistic::mean), options);
          row.distinguishable = row.difference.low > 0.0 || row.difference.high < 0.0;
          out.differences.push_back(std::move(row));
        }
      }
    }
  }

  // Performance profiles on one grid of thresholds per metric, shared by the columns.
  for (const char* metric : {"J_over_trpo", "feasibility_margin"}) {
    std::vector<const Strata*> all;
    for (const std::string& label : column_order) {
      const auto found = columns[label].metric_strata.find(metric);
      if (found != columns[label].metric_strata.end() && !found->second.empty()) all.push_back(&found->second);
    }
    if (all.empty()) continue;
    const std::vector<double> taus = thresholds_over(all, profile_thresholds);
    for (const std::string& label : column_order) {
      const auto found = columns[label].metric_strata.find(metric);
      if (found == columns[label].metric_strata.end() || found->second.empty()) continue;
      const std::vector<IntervalEstimate> band = performance_profile(found->second, taus, options);
      for (std::size_t i = 0; i < taus.size(); ++i) {
        out.profiles.push_back(ProfileRow{label, metric, found->second.size(), pooled_values(found->second).size(),
                                          taus[i], band[i]});
      }
    }
  }
  return out;
}

}  // namespace bsg::experiments
