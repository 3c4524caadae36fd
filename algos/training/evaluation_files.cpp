#include "algos/training/evaluation_files.h"

#include <cmath>
#include <string>

#include "algos/training/progress_csv.h"
#include "common/atomic_file.h"

namespace bsg::algos {
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

std::string json_string(const std::string& text) { return "\"" + text + "\""; }  // term names need no escapes

std::string constraints_json(const EvaluationSummary& summary, const TrainingSafety& safety) {
  std::string text = "[";
  for (std::size_t i = 0; i < safety.constraints.size(); ++i) {
    const ConstraintConfig& constraint = safety.constraints[i];
    std::string terms;
    if (constraint.sums_all_terms()) {
      terms = json_string(std::string(kAllCostTerms));
    } else {
      terms = "[";
      for (std::size_t j = 0; j < constraint.terms.size(); ++j) terms += (j ? ", " : "") + json_string(constraint.terms[j]);
      terms += "]";
    }
    const double mean_cost =
        i < summary.mean_constraint_costs.size() ? summary.mean_constraint_costs[i] : std::nan("");
    const double cumulative = safety.training_cost.constraint_cumulative_costs.at(i);
    text += i ? ",\n    " : "\n    ";
    text += "{\"terms\": " + terms + ", \"limit\": " + json_number(constraint.limit) +
            ", \"mean_cost\": " + json_number(mean_cost) + ", \"holds\": " +
            (std::isfinite(mean_cost) ? (mean_cost <= constraint.limit ? "true" : "false") : "null") +
            ", \"cumulative_cost\": " + json_number(cumulative) +
            ", \"cost_rate\": " + json_number(TrainingCost::rate(cumulative, safety.training_steps)) +
            ", \"epochs_over_limit\": " + std::to_string(safety.training_cost.epochs_over_limit.at(i)) + "}";
  }
  return text + "\n  ]";
}

}  // namespace

std::string evaluation_json(const EvaluationSummary& summary, bool per_episode, const TrainingSafety* safety) {
  std::string text = "{\n";
  text += "  \"mean_return\": " + json_number(summary.mean_return) + ",\n";
  text += "  \"mean_cost\": " + json_number(summary.mean_cost) + ",\n";
  text += "  \"episodes\": " + std::to_string(summary.episodes.size()) + ",\n";
  text += "  \"mean_length\": " + json_number(summary.mean_length);
  // Only a sampled evaluation says so: the mean-action file stays as it always was.
  if (summary.action_std > 0.0) text += ",\n  \"action_std\": " + json_number(summary.action_std);
  // An off-policy run's exploring policy beside its deterministic actor (the numbers above).
  if (summary.exploring) {
    const ExploringEvaluation& exploring = *summary.exploring;
    text += ",\n  \"actions\": \"deterministic actor\"";
    text += ",\n  \"exploring_policy\": {\"episodes\": " + std::to_string(exploring.episodes) +
            ", \"mean_return\": " + json_number(exploring.mean_return) +
            ", \"mean_cost\": " + json_number(exploring.mean_cost) +
            ", \"mean_length\": " + json_number(exploring.mean_length) + "}";
  }
  // A multi-agent run's agents, each with its own mean return and cost (J and H are their mean).
  if (!summary.mean_agent_returns.empty()) {
    text += ",\n  \"agents\": [";
    for (std::size_t a = 0; a < summary.mean_agent_returns.size(); ++a) {
      text += std::string(a ? ",\n    " : "\n    ") + "{\"agent\": " + json_string("agent_" + std::to_string(a)) +
              ", \"mean_return\": " + json_number(summary.mean_agent_returns[a]) +
              ", \"mean_cost\": " + json_number(summary.mean_agent_costs[a]) + "}";
    }
    text += "\n  ]";
  }
  if (safety != nullptr) {
    text += ",\n  \"cumulative_cost\": " + json_number(safety->training_cost.cumulative_cost);
    text += ",\n  \"cost_rate\": " +
            json_number(TrainingCost::rate(safety->training_cost.cumulative_cost, safety->training_steps));
    text += ",\n  \"constraints\": " + constraints_json(summary, *safety);
  }
  if (!summary.term_names.empty()) {  // each cost term's mean episode sum
    text += ",\n  \"cost_terms\": {";
    for (std::size_t k = 0; k < summary.term_names.size(); ++k) {
      text += (k ? ", " : "") + json_string(summary.term_names[k]) + ": " + json_number(summary.mean_term_costs[k]);
    }
    text += "}";
  }
  if (per_episode) {
    text += ",\n  \"returns\": " + json_array(summary, [](const EvaluationEpisode& e) { return e.episode_return; });
    text += ",\n  \"costs\": " + json_array(summary, [](const EvaluationEpisode& e) { return e.episode_cost; });
    text += ",\n  \"lengths\": " +
            json_array(summary, [](const EvaluationEpisode& e) { return static_cast<double>(e.episode_length); });
  }
  return text + "\n}\n";
}

void write_evaluation_files(const RunDirectory& directory, const EvaluationSummary& summary,
                            const TrainingSafety* safety) {
  std::string returns;
  std::string costs;
  for (const EvaluationEpisode& e : summary.episodes) {
    returns += format_csv_number(e.episode_return) + "\n";
    costs += format_csv_number(e.episode_cost) + "\n";
  }
  write_file_atomically(directory.returns(), returns);
  write_file_atomically(directory.costs(), costs);
  write_file_atomically(directory.evaluation(), evaluation_json(summary, false, safety));
}

}  // namespace bsg::algos
