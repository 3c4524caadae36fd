#include "experiments/run_results.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/config_scalar.h"

namespace bsg::experiments {

const char* to_string(RunState state) {
  switch (state) {
    case RunState::fresh: return "fresh";
    case RunState::resumable: return "resumable";
    case RunState::finished: return "finished";
  }
  return "?";
}

RunState run_state(const algos::RunDirectory& directory) {
  std::error_code error;
  if (std::filesystem::is_regular_file(directory.evaluation(), error)) return RunState::finished;
  if (std::filesystem::is_regular_file(directory.checkpoint(), error) &&
      std::filesystem::is_regular_file(directory.config(), error)) {
    return RunState::resumable;
  }
  return RunState::fresh;
}

int logged_epochs(const algos::RunDirectory& directory) {
  std::ifstream in(directory.progress());
  int rows = 0;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) ++rows;
  }
  return rows > 0 ? rows - 1 : 0;  // minus the header
}

std::optional<RecordedEvaluation> read_run_evaluation(const algos::RunDirectory& directory) {
  const std::filesystem::path path = directory.evaluation();
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;
  // JSON objects of numbers are YAML; yaml-cpp reads them.
  YAML::Node document;
  try {
    document = YAML::LoadFile(path.string());
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path.string() + ": malformed JSON: " + e.what());
  }
  if (!document.IsMap()) throw std::runtime_error(path.string() + ": expected a JSON object");
  auto number = [&](const char* key) {
    const YAML::Node value = document[key];
    if (!value) throw std::runtime_error(path.string() + ": missing \"" + key + "\"");
    if (value.IsNull()) return std::numeric_limits<double>::quiet_NaN();
    const std::optional<double> parsed = value.IsScalar() ? parse_config_real(value.Scalar()) : std::nullopt;
    if (!parsed) throw std::runtime_error(path.string() + ": \"" + key + "\" is not a number");
    return *parsed;
  };
  RecordedEvaluation evaluation;
  evaluation.mean_return = number("mean_return");
  evaluation.mean_cost = number("mean_cost");
  evaluation.episodes = static_cast<long long>(number("episodes"));
  evaluation.cost_rate = document["cost_rate"] ? number("cost_rate") : std::numeric_limits<double>::quiet_NaN();
  if (const YAML::Node constraints = document["constraints"]) {
    if (!constraints.IsSequence()) throw std::runtime_error(path.string() + ": \"constraints\" is not a list");
    for (const YAML::Node& constraint : constraints) {
      const auto field = [&](const char* key) {
        const YAML::Node value = constraint[key];
        if (!value.IsDefined() || value.IsNull()) return std::numeric_limits<double>::quiet_NaN();
        const std::optional<double> parsed = value.IsScalar() ? parse_config_real(value.Scalar()) : std::nullopt;
        if (!parsed) throw std::runtime_error(path.string() + ": a constraint's \"" + key + "\" is not a number");
        return *parsed;
      };
      evaluation.constraint_costs.push_back(field("mean_cost"));
      evaluation.constraint_limits.push_back(field("limit"));
    }
  }
  return evaluation;
}

std::vector<double> read_value_per_line(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::vector<double> values;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::optional<double> value = parse_config_real(line);
    // format_csv_number writes non-finite values as nan, inf, -inf.
    if (line == "nan") value = std::numeric_limits<double>::quiet_NaN();
    if (line == "inf" || line == "-inf") {
      value = (line == "inf" ? 1.0 : -1.0) * std::numeric_limits<double>::infinity();
    }
    if (!value) {
      throw std::runtime_error(path.string() + ":" + std::to_string(line_number) + ": '" + line +
                               "' is not a number");
    }
    values.push_back(*value);
  }
  return values;
}

}  // namespace bsg::experiments
