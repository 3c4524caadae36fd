// `bsg table SWEEP_DIR...`: applies the report's selection rule (experiments/
// selection.h) per environment and algorithm of a sweep and prints Table 1
// (experiments/table1_render.h) as Markdown; writes table1.md, table1.csv,
// table1.tex and configurations.csv into the sweep directory (or --output).
// Several sweeps (e.g. sweeps/report and sweeps/pid) make one table of all
// their configurations; their files then go to --output, which is required.
// --compare report also prints each cell beside the report's Table 1
// (configs/report_table1.csv) and writes table1_compare.md and .csv.
#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "common/atomic_file.h"
#include "configs_search.h"
#include "experiments/report_comparison.h"
#include "experiments/sweep_results.h"
#include "experiments/table1.h"
#include "experiments/table1_render.h"

namespace bsg::cli {

namespace {

struct TableOptions {
  std::vector<std::string> sweep_dirs;
  std::string score = "mean";
  std::string output_dir;
  std::string compare;
  std::string configs_dir;
  std::string metric = "return-cost";
};

int run_table(const TableOptions& options) {
  const experiments::SelectionScore score = experiments::parse_selection_score(options.score);
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
  table->callback([options, &run] { run = [options] { return run_table(*options); }; });
}

}  // namespace bsg::cli
