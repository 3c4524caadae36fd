// `bsg table SWEEP_DIR...`: applies the report's selection rule (experiments/
// selection.h) per environment and algorithm of a sweep and prints Table 1
// (experiments/table1_render.h) as Markdown; writes table1.md, table1.csv,
// table1.tex and configurations.csv into the sweep directory (or --output).
// Several sweeps (e.g. sweeps/report and sweeps/pid) make one table of all
// their configurations; their files then go to --output, which is required.
// --compare report also prints each cell beside the report's Table 1
// (configs/report_table1.csv) and writes table1_compare.md and .csv.
// A sweep with offline runs also gets their normalised scores in DSRL's format
// (experiments/offline_scores.h: offline_table.md and .csv).
// --ci adds the results with their uncertainty across seeds (experiments/
// result_intervals.h, training_intervals.h, cost_limit_frontier.h) as CSV
// files beside table1.csv; --frontier requires a cost-limit frontier.
#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "common/atomic_file.h"
#include "configs_search.h"
#include "experiments/cost_limit_frontier.h"
#include "experiments/offline_scores.h"
#include "experiments/report_comparison.h"
#include "experiments/result_intervals.h"
#include "experiments/result_intervals_render.h"
#include "experiments/sweep_results.h"
#include "experiments/table1.h"
#include "experiments/table1_render.h"
#include "experiments/training_intervals.h"

namespace bsg::cli {

namespace {

struct TableOptions {
  std::vector<std::string> sweep_dirs;
  std::string score = "mean";
  std::string output_dir;
  std::string compare;
  std::string configs_dir;
  std::string metric = "return-cost";
  bool intervals = false;  // --ci
  bool frontier = false;   // --frontier: a cost-limit frontier is required
  experiments::BootstrapOptions bootstrap;
};

// --ci: the interval files beside table1.csv, the summary on stdout.
void write_intervals(const TableOptions& options, const std::vector<experiments::ConfigurationResults>& results,
                     const experiments::Table1& table, const std::filesystem::path& out) {
  const experiments::ResultIntervals intervals = experiments::build_result_intervals(results, table, options.bootstrap);
  const experiments::TrainingIntervals training = experiments::build_training_intervals(results, table, options.bootstrap);
  std::optional<experiments::CostLimitFrontier> frontier;
  try {
    frontier = experiments::build_cost_limit_frontier(results, options.bootstrap);
  } catch (const std::invalid_argument& error) {
    if (options.frontier) throw std::runtime_error(std::string("bsg table --frontier: ") + error.what());
  }
  experiments::write_interval_files(intervals, training, frontier, out);
  std::cout << "\n" << experiments::intervals_markdown(intervals, training, frontier);
  std::string names;
  for (const std::string& name : experiments::interval_file_names(frontier.has_value())) names += (names.empty() ? "" : ", ") + name;
  std::cerr << "bsg table: wrote " << names << " to " << out.string() << " (" << options.bootstrap.resamples
            << " bootstrap resamples, seed " << options.bootstrap.seed << ")\n";
}

int run_table(const TableOptions& options) {
  const experiments::SelectionScore score = experiments::parse_selection_score(options.score);
  experiments::check_bootstrap_options(options.bootstrap);
  if (options.sweep_dirs.size() > 1 && options.output_dir.empty()) {
    throw std::runtime_error("bsg table: a table of " + std::to_string(options.sweep_dirs.size()) +
                             " sweeps needs --output DIR (it belongs to none of them)");
  }
  std::vector<experiments::ConfigurationResults> results;
  for (const std::string& dir : options.sweep_dirs) {
    std::vector<experiments::ConfigurationResults> sweep =
        experiments::load_sweep_results(std::filesystem::path(dir), score == experiments::SelectionScore::mean_minus_std);
    for (experiments::ConfigurationResults& config : sweep) {
      if (options.sweep_dirs.size() > 1) config.config_dir = (std::filesystem::path(dir) / config.config_dir).generic_string();
      results.push_back(std::move(config));
    }
  }
  experiments::Table1 table = experiments::build_table1(results, score);
  table.show_cost_rate = options.metric == "cost-rate";

  const std::filesystem::path out = options.output_dir.empty() ? std::filesystem::path(options.sweep_dirs.front())
                                                               : std::filesystem::path(options.output_dir);
  experiments::write_table1_files(table, out);
  std::cout << experiments::table1_markdown(table);
  std::cerr << "bsg table: wrote table1.md, table1.csv, table1.tex and configurations.csv to "
            << out.string() << "\n";
  const experiments::OfflineScores offline = experiments::build_offline_scores(results, options.bootstrap);
  if (!offline.rows.empty()) {
    experiments::write_offline_score_files(offline, out);
    std::cout << "\n" << experiments::offline_scores_markdown(offline);
    std::cerr << "bsg table: wrote offline_table.md and offline_table.csv to " << out.string() << "\n";
  }
  if (options.intervals || options.frontier) write_intervals(options, results, table, out);
  if (options.compare == "report") {
    const std::filesystem::path configs = find_configs(options.configs_dir, {}, "").dir;
    const experiments::ReportTable1 report = experiments::load_report_table1(configs / experiments::kReportTable1File);
    const std::string markdown = experiments::comparison_markdown(table, report);
    write_file_atomically(out / "table1_compare.md", markdown);
    write_file_atomically(out / "table1_compare.csv", experiments::comparison_csv(table, report));
    std::cout << "\nBeside the report's Table 1 (" << (configs / experiments::kReportTable1File).string() << "):\n" << markdown;
    std::cerr << "bsg table: wrote table1_compare.md and table1_compare.csv to " << out.string() << "\n";
  }
  return 0;
}

}  // namespace

void add_table_command(CLI::App& app, Action& run) {
  auto options = std::make_shared<TableOptions>();
  CLI::App* table = app.add_subcommand(
      "table", "Select the best configuration per environment and algorithm of a sweep; print Table 1");
  table->add_option("SWEEP_DIR", options->sweep_dirs,
                    "the --out directory of bsg sweep; several: one table of all their configurations "
                    "(needs --output)")
      ->required();
  table->add_option("--score", options->score,
                    "selection score: mean (the report's rule) or mean_minus_std (the original plot "
                    "script's --best, quirk Q17)")
      ->check(CLI::IsMember({"mean", "mean_minus_std"}));
  table->add_option("--output", options->output_dir,
                    "where to write the files (default: SWEEP_DIR; required with several)");
  table->add_option("--compare", options->compare,
                    "report: each cell beside the report's Table 1 value and the difference "
                    "(table1_compare.md, .csv)")
      ->check(CLI::IsMember({"report"}));
  table->add_option("--configs", options->configs_dir,
                    "configs directory holding report_table1.csv (default: searched as bsg train does)");
  table->add_option("--metric", options->metric,
                    "return-cost: J/J_TRPO (H/d) per cell; cost-rate: also the training cost rate r (all cost "
                    "incurred during training / steps taken, Safety Gym's definition)")
      ->check(CLI::IsMember({"return-cost", "cost-rate"}));
  table->add_flag("--ci", options->intervals,
                  "also the results with their uncertainty across seeds: mean, median and IQM with stratified "
                  "bootstrap intervals, P(H <= d), differences between columns, performance profiles, safety "
                  "during training, learning curves with bands and, for a cost_limit axis, the frontier "
                  "(intervals.csv, aggregates.csv, distinguishable.csv, profiles.csv, training_safety.csv, "
                  "curves.csv, frontier.csv, table1_ci.md)");
  table->add_flag("--frontier", options->frontier,
                  "as --ci, and the sweep must give a cost-limit frontier (two limits or more; an error otherwise)");
  table->add_option("--resamples", options->bootstrap.resamples, "--ci: bootstrap resamples (default 2000)")
      ->check(CLI::Range(std::size_t{100}, std::size_t{1000000}));
  table->add_option("--confidence", options->bootstrap.confidence,
                    "--ci: the intervals' confidence level, in (0, 1) (default 0.95)")
      ->check(CLI::Range(0.0, 1.0));
  table->add_option("--bootstrap-seed", options->bootstrap.seed,
                    "--ci: seed of the resampling; the same seed gives the same intervals (default 0)");
  table->callback([options, &run] { run = [options] { return run_table(*options); }; });
}

}  // namespace bsg::cli
