// `bsg table SWEEP_DIR`: applies the report's selection rule (experiments/
// selection.h) per environment and algorithm of a sweep and prints Table 1
// (experiments/table1_render.h) as Markdown; writes table1.md, table1.csv,
// table1.tex and configurations.csv into the sweep directory (or --output).
#include <CLI/CLI.hpp>

#include <iostream>

#include "commands.h"
#include "experiments/sweep_results.h"
#include "experiments/table1.h"
#include "experiments/table1_render.h"

namespace bsg::cli {

namespace {

struct TableOptions {
  std::string sweep_dir;
  std::string score = "mean";
  std::string output_dir;
};

int run_table(const TableOptions& options) {
  const SelectionScore score = parse_selection_score(options.score);
  const std::filesystem::path sweep_dir(options.sweep_dir);
  const std::vector<ConfigurationResults> results =
      load_sweep_results(sweep_dir, score == SelectionScore::mean_minus_std);
  const Table1 table = build_table1(results, score);

  const std::filesystem::path out =
      options.output_dir.empty() ? sweep_dir : std::filesystem::path(options.output_dir);
  write_table1_files(table, out);
  std::cout << table1_markdown(table);
  std::cerr << "bsg table: wrote table1.md, table1.csv, table1.tex and configurations.csv to "
            << out.string() << "\n";
  return 0;
}

}  // namespace

void add_table_command(CLI::App& app, Action& run) {
  auto options = std::make_shared<TableOptions>();
  CLI::App* table = app.add_subcommand(
      "table", "Select the best configuration per environment and algorithm of a sweep; print Table 1");
  table->add_option("SWEEP_DIR", options->sweep_dir, "the --out directory of bsg sweep")->required();
  table->add_option("--score", options->score,
                    "selection score: mean (the report's rule) or mean_minus_std (the original plot "
                    "script's --best, quirk Q17)")
      ->check(CLI::IsMember({"mean", "mean_minus_std"}));
  table->add_option("--output", options->output_dir, "where to write the files (default: SWEEP_DIR)");
  table->callback([options, &run] { run = [options] { return run_table(*options); }; });
}

}  // namespace bsg::cli
