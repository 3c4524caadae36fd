#include "experiments/result_intervals_render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "common/atomic_file.h"
#include "common/config_scalar.h"
#include "common/csv_text.h"

namespace bsg::experiments {

namespace {

std::string number(double value) {
  return std::isfinite(value) ? format_config_real(value) : "";
}

// Three significant digits for the Markdown summary.
std::string short_number(double value) {
  if (!std::isfinite(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof text, std::fabs(value) >= 100.0 ? "%.0f" : std::fabs(value) >= 10.0 ? "%.1f" : "%.2f",
                value);
  return text;
}

std::string interval_text(const IntervalEstimate& estimate) {
  return short_number(estimate.point) + " [" + short_number(estimate.low) + ", " + short_number(estimate.high) + "]";
}

std::string estimate_fields(const IntervalEstimate& estimate) {
  return number(estimate.point) + "," + number(estimate.low) + "," + number(estimate.high);
}

const IntervalRow* find_row(const std::vector<IntervalRow>& rows, const std::string& env_id, const std::string& column,
                            const std::string& metric, const std::string& statistic, bool selected_only) {
  for (const IntervalRow& row : rows) {
    if (row.env_id == env_id && row.column == column && row.metric == metric && row.statistic == statistic &&
        (!selected_only || row.selected)) {
      return &row;
    }
  }
  return nullptr;
}

std::string percent(double confidence) {
  char text[32];
  std::snprintf(text, sizeof text, "%g %%", 100.0 * confidence);
  return text;
}

}  // namespace

std::string interval_rows_csv(const std::vector<IntervalRow>& rows, double confidence) {
  std::string text =
      "env_id,column,config,config_dir,cost_limit,selected,environments,seeds,metric,statistic,point,low,high,"
      "confidence\n";
  for (const IntervalRow& row : rows) {
    text += csv_field(row.env_id) + "," + csv_field(row.column) + "," + csv_field(row.config) + "," +
            csv_field(row.config_dir) + "," + number(row.cost_limit) + "," + (row.selected ? "true" : "false") + "," +
            std::to_string(row.environments) + "," + std::to_string(row.seeds) + "," + row.metric + "," +
            row.statistic + "," + estimate_fields(row.estimate) + "," + number(confidence) + "\n";
  }
  return text;
}

std::string difference_rows_csv(const std::vector<DifferenceRow>& rows, double confidence) {
  std::string text =
      "env_id,metric,column_a,column_b,seeds_a,seeds_b,difference_of_means,low,high,distinguishable,confidence\n";
  for (const DifferenceRow& row : rows) {
    text += csv_field(row.env_id) + "," + row.metric + "," + csv_field(row.column_a) + "," + csv_field(row.column_b) +
            "," + std::to_string(row.seeds_a) + "," + std::to_string(row.seeds_b) + "," +
            estimate_fields(row.difference) + "," + (row.distinguishable ? "true" : "false") + "," +
            number(confidence) + "\n";
  }
  return text;
}

std::string profile_rows_csv(const std::vector<ProfileRow>& rows, double confidence) {
  std::string text = "column,metric,environments,seeds,tau,fraction_above,low,high,confidence\n";
  for (const ProfileRow& row : rows) {
    text += csv_field(row.column) + "," + row.metric + "," + std::to_string(row.environments) + "," +
            std::to_string(row.seeds) + "," + number(row.tau) + "," + estimate_fields(row.fraction) + "," +
            number(confidence) + "\n";
  }
  return text;
}

std::string curve_rows_csv(const std::vector<CurveRow>& rows, double confidence) {
  std::string text = "env_id,column,config,metric,epoch,seeds,mean,low,high,confidence\n";
  for (const CurveRow& row : rows) {
    text += csv_field(row.env_id) + "," + csv_field(row.column) + "," + csv_field(row.config) + "," + row.metric + "," +
            std::to_string(row.epoch) + "," + std::to_string(row.seeds) + "," + estimate_fields(row.mean) + "," +
            number(confidence) + "\n";
  }
  return text;
}

std::string frontier_csv(const CostLimitFrontier& frontier, double confidence) {
  std::string text =
      "env_id,column,family,config,constraint,cost_limit,seeds,mean_return,return_low,return_high,mean_cost,"
      "cost_low,cost_high,feasible,feasible_low,feasible_high,confidence\n";
  for (const FrontierPoint& point : frontier.points) {
    text += csv_field(point.env_id) + "," + csv_field(point.column) + "," + csv_field(point.family) + "," +
            csv_field(point.config) + "," + std::to_string(point.constraint) + "," + number(point.cost_limit) + "," +
            std::to_string(point.seeds) + "," + estimate_fields(point.mean_return) + "," +
            estimate_fields(point.mean_cost) + "," + estimate_fields(point.feasible) + "," + number(confidence) + "\n";
  }
  return text;
}

std::string intervals_markdown(const ResultIntervals& intervals, const TrainingIntervals& training,
                               const std::optional<CostLimitFrontier>& frontier) {
  const std::string level = percent(intervals.confidence);
  std::string text;
  // 1. The selected configurations, cell by cell.
  std::vector<std::string> envs;
  std::vector<std::string> columns;
  for (const IntervalRow& row : intervals.configurations) {
    if (!row.selected) continue;
    if (std::find(envs.begin(), envs.end(), row.env_id) == envs.end()) envs.push_back(row.env_id);
    if (std::find(columns.begin(), columns.end(), row.column) == columns.end()) columns.push_back(row.column);
  }
  if (!envs.empty()) {
    text += "Selected configurations: IQM over seeds of J/J_TRPO (J without TRPO) and of H/d, each with its " + level +
            " stratified bootstrap interval; p: the proportion of seeds with H <= d [Wilson interval]\n\n| env |";
    for (const std::string& column : columns) text += " " + column + " |";
    text += "\n|---|";
    for (std::size_t i = 0; i < columns.size(); ++i) text += "---|";
    text += "\n";
    for (const std::string& env_id : envs) {
      text += "| " + env_id + " |";
      for (const std::string& column : columns) {
        const IntervalRow* j = find_row(intervals.configurations, env_id, column, "J_over_trpo", "iqm", true);
        if (j == nullptr) j = find_row(intervals.configurations, env_id, column, "J", "iqm", true);
        const IntervalRow* h = find_row(intervals.configurations, env_id, column, "H_over_d", "iqm", true);
        const IntervalRow* p = find_row(intervals.configurations, env_id, column, "feasible", "proportion", true);
        if (j == nullptr) {
          text += " - |";
          continue;
        }
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
        text.append(" ").append(interval_text(j->estimate));
        if (h != nullptr) text.append(" (").append(interval_text(h->estimate)).append(")");
        if (p != nullptr) text.append(" p ").append(interval_text(p->estimate));
        text.append(" n=").append(std::to_string(j->seeds)).append(" |");
      }
      text += "\n";
    }
  }
  // 2. Across environments.
  if (!intervals.aggregates.empty()) {
    text += "\nAcross environments (selected configurations; strata: the environments), " + level + " intervals:\n\n"
            "| column | environments | runs | IQM J/J_TRPO | IQM H/d | P(H <= d) |\n|---|---|---|---|---|---|\n";
    for (const std::string& column : columns) {
      const IntervalRow* j = find_row(intervals.aggregates, "", column, "J_over_trpo", "iqm", false);
      const IntervalRow* h = find_row(intervals.aggregates, "", column, "H_over_d", "iqm", false);
      const IntervalRow* p = find_row(intervals.aggregates, "", column, "feasible", "proportion", false);
      if (p == nullptr) continue;
      text += "| " + column + " | " + std::to_string(p->environments) + " | " + std::to_string(p->seeds) + " | " +
              (j ? interval_text(j->estimate) : "-") + " | " + (h ? interval_text(h->estimate) : "-") + " | " +
              interval_text(p->estimate) + " |\n";
    }
  }
  // 3. Which cells differ.
  if (!intervals.differences.empty()) {
    text += "\nPairs of selected configurations whose difference of mean J or mean H has a " + level +
            " interval excluding 0:\n\n";
    std::size_t shown = 0;
    for (const DifferenceRow& row : intervals.differences) {
      if (!row.distinguishable) continue;
      text += "- " + row.env_id + ": " + row.metric + "(" + row.column_a + ") - " + row.metric + "(" + row.column_b +
              ") = " + interval_text(row.difference) + "\n";
      ++shown;
    }
    text += std::to_string(shown) + " of " + std::to_string(intervals.differences.size()) +
            " comparisons distinguishable (distinguishable.csv has all).\n";
  }
  // 4. Safety during training.
  std::set<std::string> safety_metrics;
  for (const IntervalRow& row : training.safety) safety_metrics.insert(row.metric);
  if (!training.safety.empty()) {
    text += "\nSafety during training (mean over seeds [" + level +
            " interval]): cumulative training cost, fraction of epochs above d\n\n"
            "| configuration | seeds | cumulative cost | epochs over d |\n|---|---|---|---|\n";
    std::set<std::string> done;
    for (const IntervalRow& row : training.safety) {
      if (!done.insert(row.config_dir).second) continue;
      const IntervalRow* cumulative = nullptr;
      const IntervalRow* over = nullptr;
      for (const IntervalRow& other : training.safety) {
        if (other.config_dir != row.config_dir || other.statistic != "mean") continue;
        if (other.metric.ends_with("cumulative_cost") && cumulative == nullptr) cumulative = &other;
        if (other.metric.ends_with("epochs_over_limit") && over == nullptr) over = &other;
      }
      text += "| " + row.config_dir + " | " + std::to_string(row.seeds) + " | " +
              (cumulative ? interval_text(cumulative->estimate) : "-") + " | " +
              (over ? interval_text(over->estimate) : "-") + " |\n";
    }
  }
  if (!training.safety_aggregates.empty()) {
    text += "\nFraction of training epochs whose mean episode cost exceeded d, per column across environments "
            "(selected configurations; strata: the environments), " + level + " intervals:\n\n"
            "| column | environments | runs | mean | IQM |\n|---|---|---|---|---|\n";
    for (const IntervalRow& row : training.safety_aggregates) {
      if (row.statistic != "mean") continue;
      const IntervalRow* iqm = find_row(training.safety_aggregates, "", row.column, row.metric, "iqm", false);
      text += "| " + row.column + " | " + std::to_string(row.environments) + " | " + std::to_string(row.seeds) +
              " | " + interval_text(row.estimate) + " | " + (iqm ? interval_text(iqm->estimate) : "-") + " |\n";
    }
  }
  // 5. The frontier.
  if (frontier) {
    text += "\nCost-limit frontier (mean over seeds [" + level + " interval]):\n\n"
            "| env | column | family | constraint | d | seeds | J | H | P(H <= d) |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const FrontierPoint& point : frontier->points) {
      text += "| " + point.env_id + " | " + point.column + " | " + point.family + " | " +
              std::to_string(point.constraint) + " | " + short_number(point.cost_limit) + " | " +
              std::to_string(point.seeds) + " | " + interval_text(point.mean_return) + " | " +
              interval_text(point.mean_cost) + " | " + interval_text(point.feasible) + " |\n";
    }
  }
  std::vector<std::string> notes = intervals.notes;
  notes.insert(notes.end(), training.notes.begin(), training.notes.end());
  if (frontier) notes.insert(notes.end(), frontier->notes.begin(), frontier->notes.end());
  if (!notes.empty()) {
    text += "\nNotes:\n";
    for (const std::string& note : notes) text += "- " + note + "\n";
  }
  return text;
}

std::vector<std::string> interval_file_names(bool with_frontier) {
  std::vector<std::string> names = {"intervals.csv", "aggregates.csv", "distinguishable.csv", "profiles.csv",
                                    "training_safety.csv", "curves.csv", "table1_ci.md"};
  if (with_frontier) names.push_back("frontier.csv");
  return names;
}

void write_interval_files(const ResultIntervals& intervals, const TrainingIntervals& training,
                          const std::optional<CostLimitFrontier>& frontier, const std::filesystem::path& out_dir) {
  std::filesystem::create_directories(out_dir);
  const double c = intervals.confidence;
  write_file_atomically(out_dir / "intervals.csv", interval_rows_csv(intervals.configurations, c));
  write_file_atomically(out_dir / "aggregates.csv", interval_rows_csv(intervals.aggregates, c));
  write_file_atomically(out_dir / "distinguishable.csv", difference_rows_csv(intervals.differences, c));
  write_file_atomically(out_dir / "profiles.csv", profile_rows_csv(intervals.profiles, c));
  std::vector<IntervalRow> safety = training.safety;  // per configuration, then across environments
  safety.insert(safety.end(), training.safety_aggregates.begin(), training.safety_aggregates.end());
  write_file_atomically(out_dir / "training_safety.csv", interval_rows_csv(safety, c));
  write_file_atomically(out_dir / "curves.csv", curve_rows_csv(training.curves, c));
  write_file_atomically(out_dir / "table1_ci.md", intervals_markdown(intervals, training, frontier));
  if (frontier) write_file_atomically(out_dir / "frontier.csv", frontier_csv(*frontier, c));
}

}  // namespace bsg::experiments
