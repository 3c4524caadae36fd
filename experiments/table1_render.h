// Table 1 (table1.h) as text: Markdown as the report prints it (J/J_TRPO
// with H/d in parentheses, the best constrained algorithm in bold), CSV and
// LaTeX, and the list of every configuration with its score as CSV.
//
// Cell marks: "missing" when no run of the (environment, algorithm) has
// finished; a dagger when no configuration met the cost limit (the lowest
// violation is shown); "[k/n]" when only k of the n seeds have finished;
// "J=" with the raw return when TRPO's J is missing or zero.
#pragma once

#include <filesystem>
#include <string>

#include "experiments/table1.h"

namespace bsg::experiments {

std::string table1_markdown(const Table1& table);
std::string table1_latex(const Table1& table);
// One line per (environment, algorithm): env_id, alg, status (feasible |
// infeasible | unconstrained (TRPO) | missing), config, its directory, seeds,
// J, H, d, J/J_TRPO, H/d, whether H <= d, best constrained, the column label
// (e.g. "TRPO-L", "TRPO-PID"). configurations.csv ends with the label too.
std::string table1_csv(const Table1& table);
std::string configurations_csv(const Table1& table);

// Writes table1.md, table1.csv, table1.tex and configurations.csv into
// `out_dir` (created if missing), each atomically.
void write_table1_files(const Table1& table, const std::filesystem::path& out_dir);

}  // namespace bsg::experiments
