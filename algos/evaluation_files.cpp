#include "algos/evaluation_files.h"

#include <cmath>

#include "algos/progress_csv.h"
#include "common/atomic_file.h"

namespace bsg {
namespace {

// JSON has no NaN or infinity: write null for them.
std::string json_number(double value) { return std::isfinite(value) ? format_csv_number(value) : "null"; }

template <typename Field>
std::string json_array(const EvaluationSummary& summary, Field field) {
  std::string text = "[";
  for (std::size_t i = 0; i < summary.episodes.size(); ++i) {
    if (i > 0) text += ", ";
    text += json_number(field(summary.episodes[i]));
  }
  return text + "]";
}

}  // namespace

std::string evaluation_json(const EvaluationSummary& summary, bool per_episode) {
  std::string text = "{\n";
  text += "  \"mean_return\": " + json_number(summary.mean_return) + ",\n";
  text += "  \"mean_cost\": " + json_number(summary.mean_cost) + ",\n";
  text += "  \"episodes\": " + std::to_string(summary.episodes.size()) + ",\n";
  text += "  \"mean_length\": " + json_number(summary.mean_length);
  if (per_episode) {
    text += ",\n  \"returns\": " + json_array(summary, [](const EvaluationEpisode& e) { return e.episode_return; });
    text += ",\n  \"costs\": " + json_array(summary, [](const EvaluationEpisode& e) { return e.episode_cost; });
    text += ",\n  \"lengths\": " +
            json_array(summary, [](const EvaluationEpisode& e) { return static_cast<double>(e.episode_length); });
  }
  return text + "\n}\n";
}

void write_evaluation_files(const RunDirectory& directory, const EvaluationSummary& summary) {
  std::string returns;
  std::string costs;
  for (const EvaluationEpisode& e : summary.episodes) {
    returns += format_csv_number(e.episode_return) + "\n";
    costs += format_csv_number(e.episode_cost) + "\n";
  }
  write_file_atomically(directory.returns(), returns);
  write_file_atomically(directory.costs(), costs);
  write_file_atomically(directory.evaluation(), evaluation_json(summary, false));
}

}  // namespace bsg
