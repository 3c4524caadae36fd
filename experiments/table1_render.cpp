#include "experiments/table1_render.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "common/atomic_file.h"
#include "common/config_scalar.h"
#include "common/csv_text.h"

namespace bsg::experiments {

namespace {

// Two decimals, one for |x| >= 10 (the report's "11.8", "38.9").
std::string short_number(double value) {
  char text[64];
  std::snprintf(text, sizeof text, std::fabs(value) >= 10.0 ? "%.1f" : "%.2f", value);
  return text;
}

std::string csv_number(std::optional<double> value) {
  return value && std::isfinite(*value) ? format_config_real(*value) : "";
}

std::optional<double> normalised_return(const Table1Row& row, const Table1Cell& cell) {
  const std::optional<double> trpo = row.trpo_return(cell.corrected_learner);
  if (!cell.selected || !trpo || *trpo == 0.0) return std::nullopt;
  return cell.score.mean_return / *trpo;  // J / J_TRPO
}

std::optional<double> normalised_cost(const Table1Row& row, const Table1Cell& cell) {
  if (!cell.selected || !(row.cost_limit > 0.0)) return std::nullopt;
  return cell.score.mean_cost / row.cost_limit;  // H / d
}

enum class Format { markdown, latex };

std::string cell_text(const Table1Row& row, const Table1Cell& cell, Format format, bool show_cost_rate) {
  if (!cell.selected) return format == Format::latex ? "\\emph{missing}" : "missing";
  const std::optional<double> j = normalised_return(row, cell);
  const std::optional<double> h = normalised_cost(row, cell);
  std::string text = j ? short_number(*j) : "J=" + short_number(cell.score.mean_return);
  text += " (" + (h ? short_number(*h) : "H=" + short_number(cell.score.mean_cost)) + ")";
  if (show_cost_rate) text += " r=" + short_number(cell.score.mean_cost_rate);  // Safety Gym's cost rate
  if (!ignores_cost(cell.alg) && !cell.constraint_met) {
    text += format == Format::latex ? "$^\\dagger$" : "\u2020";
  }
  if (cell.seeds_finished < cell.seeds_expected) {
    text += " [" + std::to_string(cell.seeds_finished) + "/" + std::to_string(cell.seeds_expected) + "]";
  }
  if (cell.best_constrained) {
    text = format == Format::latex ? "\\textbf{" + text + "}" : "**" + text + "**";
  }
  return text;
}

std::string legend(const Table1& table) {
  return "J/J_TRPO with H/d in parentheses (deterministic evaluation, mean over seeds); bold: the "
         "best constrained algorithm; \u2020: no configuration met the cost limit d, the lowest "
         "violation is shown; [k/n]: k of n seeds finished; missing: no finished run. Selection "
         "score: " + std::string(to_string(table.score)) + "." +
         (table.show_cost_rate ? " r: the training cost rate (all training cost / training steps, mean over seeds)."
                               : "");
}

}  // namespace

std::string table1_markdown(const Table1& table) {
  std::string text = "| Env |";
  std::string rule = "|---|";
  for (const Table1Column& column : table.columns) {
    text.append(" ").append(table1_column_label(column)).append(" |");
    rule += "---|";
  }
  text += "\n" + rule + "\n";
  for (const Table1Row& row : table.rows) {
    text.append("| ").append(table1_row_label(row.env_id)).append(" |");
    for (const Table1Cell& cell : row.cells) {
      text.append(" ").append(cell_text(row, cell, Format::markdown, table.show_cost_rate)).append(" |");
    }
    text += "\n";
  }
  return text + "\n" + legend(table) + "\n";
}

std::string table1_latex(const Table1& table) {
  std::string columns = "l";
  std::string header = "Env";
  std::string units;
  for (const Table1Column& column : table.columns) {
    columns += "c";
    header += " & " + table1_column_label(column);
    units += " & $J/J_{\\mathrm{TRPO}}$ ($H/d$)";
  }
  std::string text = "% Table 1: " + legend(table) + "\n";
  text += "\\begin{tabular}{" + columns + "}\n\\toprule\n" + header + " \\\\\n" + units +
          " \\\\\n\\midrule\n";
  for (const Table1Row& row : table.rows) {
    text += table1_row_label(row.env_id);
    for (const Table1Cell& cell : row.cells) text += " & " + cell_text(row, cell, Format::latex, table.show_cost_rate);
    text += " \\\\\n";
  }
  return text + "\\bottomrule\n\\end{tabular}\n";
}

std::string table1_csv(const Table1& table) {
  std::string text =
      "env_id,alg,status,config,config_dir,seeds_finished,seeds_expected,mean_return,mean_cost,mean_cost_rate,"
      "cost_limit,return_over_trpo,cost_over_limit,feasible,best_constrained,column\n";
  for (const Table1Row& row : table.rows) {
    for (const Table1Cell& cell : row.cells) {
      const std::string status = !cell.selected                ? "missing"
                                 : ignores_cost(cell.alg)      ? "unconstrained"
                                 : cell.constraint_met         ? "feasible"
                                                               : "infeasible";
      text += row.env_id + "," + std::string(to_string(cell.alg)) + "," + status + "," +
              csv_field(cell.config_name) + "," + csv_field(cell.config_dir) + "," +
              std::to_string(cell.seeds_finished) +
              "," + std::to_string(cell.seeds_expected) + ",";
      if (cell.selected) {
        text += csv_number(cell.score.mean_return) + "," + csv_number(cell.score.mean_cost) + "," +
                csv_number(cell.score.mean_cost_rate);  // empty if a seed's evaluation predates the cost rate
      } else {
        text += ",,";
      }
      text += std::string(",") + csv_number(row.cost_limit) + "," + csv_number(normalised_return(row, cell)) + "," +
              csv_number(normalised_cost(row, cell)) + "," +
              (cell.selected ? (cell.score.feasible ? "true" : "false") : "") + "," +
              (cell.best_constrained ? "true" : "false") + "," +
              table1_column_label(table1_column_of(cell)) + "\n";
    }
  }
  return text;
}

std::string configurations_csv(const Table1& table) {
  std::string text =
      "env_id,alg,config,seeds_finished,seeds_expected,mean_return,mean_cost,mean_cost_rate,cost_limit,feasible,"
      "score,selected,column\n";
  for (const ConfigurationSummary& config : table.configurations) {
    text += config.env_id + "," + std::string(to_string(config.alg)) + "," +
            csv_field(config.config_name) + "," +
            std::to_string(config.seeds_finished) + "," + std::to_string(config.seeds_expected) + ",";
    if (config.score) {
      text += csv_number(config.score->mean_return) + "," + csv_number(config.score->mean_cost) + "," +
              csv_number(config.score->mean_cost_rate) + ",";
    } else {
      text += ",,,";
    }
    text += csv_number(config.cost_limit) + "," +
            (config.score ? (config.score->feasible ? "true" : "false") : "") + "," +
            (config.score ? csv_number(config.score->score) : "") + "," +
            (config.selected ? "true" : "false") + "," +
            table1_column_label(table1_column_of(config)) + "\n";
  }
  return text;
}

void write_table1_files(const Table1& table, const std::filesystem::path& out_dir) {
  std::filesystem::create_directories(out_dir);
  write_file_atomically(out_dir / "table1.md", table1_markdown(table));
  write_file_atomically(out_dir / "table1.csv", table1_csv(table));
  write_file_atomically(out_dir / "table1.tex", table1_latex(table));
  write_file_atomically(out_dir / "configurations.csv", configurations_csv(table));
}

}  // namespace bsg::experiments
