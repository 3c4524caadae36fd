#include "experiments/report_comparison.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "common/csv_text.h"

namespace bsg::experiments {

namespace {

double parse_number(const std::string& text, const std::string& where) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value)) {
    throw std::runtime_error(where + ": '" + text + "' is not a number");
  }
  return value;
}

struct OurCell {
  std::optional<double> j_ratio;
  std::optional<double> h_ratio;
};

OurCell our_cell(const Table1Row& row, const Table1Cell& cell) {
  OurCell ours;
  if (!cell.selected) return ours;
  const std::optional<double> trpo = row.trpo_return(cell.corrected_learner);
  if (trpo && *trpo != 0.0) ours.j_ratio = cell.score.mean_return / *trpo;
  if (std::isfinite(row.cost_limit) && row.cost_limit > 0.0) ours.h_ratio = cell.score.mean_cost / row.cost_limit;
  return ours;
}

std::string number(std::optional<double> value) {
  if (!value) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", *value);
  return text;
}

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

std::string signed_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f", value);
  return text;
}

// The CSV's alg field: the config spelling, or the column label for a PID
// column (which the report does not have).
std::string comparison_alg_name(const Table1Column& column) {
  return column.pid_multiplier || column.corrected_learner ? table1_column_label(column)
                                                           : std::string(to_string(column.alg));
}

const ReportCell* find(const ReportTable1& report, const std::string& env_id, const Table1Column& column) {
  if (column.pid_multiplier || column.corrected_learner) return nullptr;  // the report has neither column
  const auto found = report.find({env_id, std::string(to_string(column.alg))});
  return found == report.end() ? nullptr : &found->second;
}

std::string side_by_side(std::optional<double> ours, const ReportCell* report, double ReportCell::*field) {
  // Appended piece by piece (GCC 12 warns falsely on "literal" + std::string).
  std::string text = ours ? short_number(*ours) : std::string(1, '-');
  text += " / ";
  text += report != nullptr ? short_number(report->*field) : std::string(1, '-');
  if (ours && report != nullptr) {
    text += " (";
    text += signed_number(*ours - report->*field);
    text += ')';
  }
  return text;
}

}  // namespace

ReportTable1 load_report_table1(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read the report's Table 1 " + path.string());
  ReportTable1 table;
  std::string line;
  int number = 0;
  bool header = true;
  while (std::getline(file, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    const std::string where = path.string() + " line " + std::to_string(number);
    const std::vector<std::string> fields = parse_csv_fields(line);
    if (fields.size() != 4) throw std::runtime_error(where + ": expected env_id,alg,j_ratio,h_ratio");
    table[{fields[0], fields[1]}] = ReportCell{parse_number(fields[2], where), parse_number(fields[3], where)};
  }
  if (table.empty()) throw std::runtime_error(path.string() + " holds no cell");
  return table;
}

std::string comparison_markdown(const Table1& table, const ReportTable1& report) {
  std::string text = "Each cell: ours / the report's (ours - report's).\n\n| Env | quantity |";
  std::string rule = "|---|---|";
  for (const Table1Column& column : table.columns) {
    text += ' ';
    text += table1_column_label(column);
    text += " |";
    rule += "---|";
  }
  text += '\n';
  text += rule;
  text += '\n';
  for (const Table1Row& row : table.rows) {
    for (const bool j : {true, false}) {
      text += "| ";
      if (j) text += table1_row_label(row.env_id);
      text += j ? " | J/J_TRPO |" : " | H/d |";
      for (std::size_t c = 0; c < table.columns.size(); ++c) {
        const OurCell ours = our_cell(row, row.cells[c]);
        const ReportCell* theirs = find(report, row.env_id, table.columns[c]);
        text += ' ';
        text += j ? side_by_side(ours.j_ratio, theirs, &ReportCell::j_ratio)
                  : side_by_side(ours.h_ratio, theirs, &ReportCell::h_ratio);
        text += " |";
      }
      text += "\n";
    }
  }
  return text;
}

std::string comparison_csv(const Table1& table, const ReportTable1& report) {
  std::string text =
      "env_id,alg,ours_j_ratio,report_j_ratio,j_ratio_diff,ours_h_ratio,report_h_ratio,h_ratio_diff\n";
  for (const Table1Row& row : table.rows) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      const OurCell ours = our_cell(row, row.cells[c]);
      const ReportCell* theirs = find(report, row.env_id, table.columns[c]);
      const auto report_j = theirs ? std::optional<double>(theirs->j_ratio) : std::nullopt;
      const auto report_h = theirs ? std::optional<double>(theirs->h_ratio) : std::nullopt;
      const auto diff = [](std::optional<double> a, std::optional<double> b) {
        return a && b ? std::optional<double>(*a - *b) : std::nullopt;
      };
      text += csv_field(row.env_id) + "," + comparison_alg_name(table.columns[c]) + "," + number(ours.j_ratio) +
              "," + number(report_j) + "," + number(diff(ours.j_ratio, report_j)) + "," + number(ours.h_ratio) + "," +
              number(report_h) + "," + number(diff(ours.h_ratio, report_h)) + "\n";
    }
  }
  return text;
}

}  // namespace bsg::experiments
