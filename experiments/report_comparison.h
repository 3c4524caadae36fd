// `bsg table --compare report`: each cell of a sweep's Table 1 beside the
// report's published value and the difference, for J/J_TRPO and H/d. The
// report's values are data, configs/report_table1.csv (env_id, alg, j_ratio,
// h_ratio, as the report prints them).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "experiments/table1.h"

namespace bsg::experiments {

inline constexpr const char* kReportTable1File = "report_table1.csv";

struct ReportCell {
  double j_ratio = 0.0;  // J / J_TRPO
  double h_ratio = 0.0;  // H / d
};

// (env_id, algorithm name) -> the report's cell.
using ReportTable1 = std::map<std::pair<std::string, std::string>, ReportCell>;

// Reads the CSV ('#' lines are comments). Throws std::runtime_error naming
// the file and line if it is missing or malformed.
ReportTable1 load_report_table1(const std::filesystem::path& path);

// Markdown: one row per environment, per algorithm "ours / report (diff)"
// for J/J_TRPO and for H/d; "-" where either side has no value.
std::string comparison_markdown(const Table1& table, const ReportTable1& report);
// CSV: env_id, alg, ours_j_ratio, report_j_ratio, j_ratio_diff, ours_h_ratio,
// report_h_ratio, h_ratio_diff (empty where a side has no value).
std::string comparison_csv(const Table1& table, const ReportTable1& report);

}  // namespace bsg::experiments
