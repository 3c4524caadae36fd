#include "dataset_collection.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/core/constraint_costs.h"
#include "algos/training/checkpoint_policy.h"
#include "algos/offline/collection.h"
#include "algos/offline/dataset_file.h"
#include "common/constraint_config.h"
#include "env_set_arguments.h"
#include "envs/env.h"

namespace bsg::cli {
namespace {


struct PolicySpec {
  std::string source;  // "random" or a run directory
  double share = 1.0;
};

// "runs/x=3" -> (runs/x, 3); a trailing "=..." that is not a number is an error.
PolicySpec parse_policy_spec(const std::string& text) {
  PolicySpec spec{text, 1.0};
  const std::size_t equals = text.rfind('=');
  if (equals != std::string::npos) {
    spec.source = text.substr(0, equals);
    const std::string share = text.substr(equals + 1);
    std::size_t used = 0;
    try {
      spec.share = std::stod(share, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != share.size() || share.empty() || !(spec.share > 0.0) || !std::isfinite(spec.share)) {
      throw std::invalid_argument("--policy " + text + ": the share after '=' must be a positive number");
    }
  }
  if (spec.source.empty()) throw std::invalid_argument("--policy " + text + ": names no policy");
  return spec;
}

std::string environment_mismatch(const std::string& run, const envs::EnvDescription& trained,
                                  const envs::EnvDescription& collected) {
  if (trained.name != collected.name) {
    return "checkpoint " + run + " was trained on " + trained.name + ", not on the collection's " + collected.name;
  }
  return "checkpoint " + run + " was trained on a " + trained.name +
         " with other parameters than the collection's (compare its config.yaml env: block with --set)";
}

}  // namespace

CollectSummary collect_to_file(const CollectArguments& args) {
  const auto started = std::chrono::steady_clock::now();
  if (args.episodes.has_value() == args.transitions.has_value()) {
    throw std::invalid_argument("give exactly one of --episodes N and --transitions N");
  }
  const std::int64_t count = args.episodes ? *args.episodes : *args.transitions;
  if (count < 1) {
    throw std::invalid_argument(std::string("--") + (args.episodes ? "episodes" : "transitions") +
                                " must be at least 1, got " + std::to_string(count));
  }
  const std::filesystem::path out(args.out);
  if (std::filesystem::exists(out) && !args.force) {
    throw std::invalid_argument("" + args.out + " exists (--force replaces it)");
  }
  if (!args.set_arguments.empty() && args.env_id.empty()) {
    throw std::invalid_argument("--set changes the environment named by --env; give --env too");
  }
  const algos::EvaluationActions actions =
      args.actions == "mean" ? algos::EvaluationActions::mean : algos::EvaluationActions::sampled;

  std::vector<PolicySpec> specs;
  for (const std::string& text : args.policies) specs.push_back(parse_policy_spec(text));
  std::vector<std::unique_ptr<algos::CheckpointPolicy>> checkpoints(specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].source != "random") checkpoints[i] = algos::load_checkpoint_policy(specs[i].source, actions);
  }
  const algos::CheckpointPolicy* first_checkpoint = nullptr;
  for (const auto& c : checkpoints) {
    if (c && !first_checkpoint) first_checkpoint = c.get();
  }

  envs::EnvDescription description;
  if (!args.env_id.empty()) {
    description = envs::describe(args.env_id, parse_env_set_arguments(args.set_arguments));
  } else if (first_checkpoint) {
    description = first_checkpoint->env_description();
  } else {
    throw std::invalid_argument("name the environment with --env (the random policy has none of its own)");
  }
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (checkpoints[i] && !(checkpoints[i]->env_description() == description)) {
      throw std::invalid_argument(environment_mismatch(specs[i].source, checkpoints[i]->env_description(), description));
    }
  }
  std::unique_ptr<envs::Env> env = envs::make(description, {.physics = envs::parse_physics_model(args.physics)});
  const envs::EnvSpec& spec = env->spec();

  // The constraints: the checkpoints' (they must agree), else the environment's whole cost.
  algos::StepCostSelector costs;
  std::vector<ConstraintConfig> constraints{{{std::string(kAllCostTerms)}, spec.cost_limit}};
  if (first_checkpoint) {
    const std::vector<ConstraintConfig> first = algos::effective_constraints(first_checkpoint->config());
    for (std::size_t i = 0; i < specs.size(); ++i) {
      if (!checkpoints[i]) continue;
      std::vector<ConstraintConfig> these = algos::effective_constraints(checkpoints[i]->config());
      const auto terms_only = [](std::vector<ConstraintConfig> list) {
        for (ConstraintConfig& c : list) c.limit = 0.0;  // limits may differ: a grid over cost limits
        return list;
      };
      if (terms_only(these) != terms_only(first)) {
        throw std::invalid_argument("checkpoint " + specs[i].source + " has other constraints than the first one (" +
                                    constraint_list_to_yaml(these) + " vs " + constraint_list_to_yaml(first) + ")");
      }
    }
    if (first.size() > 1 || !first.front().sums_all_terms()) {
      costs = algos::StepCostSelector(first_checkpoint->config());
      constraints = first;
    }
  }
  if (costs.needs_terms()) costs.bind(spec.cost_term_names, spec.id);
  std::vector<std::string> constraint_names;
  for (const ConstraintConfig& c : constraints) constraint_names.push_back(c.terms_text());

  std::vector<std::unique_ptr<algos::CollectionPolicy>> randoms;
  std::vector<algos::SharedPolicy> shared;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (checkpoints[i]) {
      shared.push_back({checkpoints[i].get(), specs[i].share});
    } else {
      randoms.push_back(algos::make_random_policy(spec.action_dim, spec.action_low, spec.action_high));
      shared.push_back({randoms.back().get(), specs[i].share});
    }
  }
  const algos::CollectionPlan plan{
      args.episodes ? algos::CollectionUnit::episodes : algos::CollectionUnit::transitions, count, args.seed};
  algos::OfflineDataset dataset = algos::collect_dataset(*env, shared, plan, costs, constraint_names);
  dataset.text_attributes["env_id"] = spec.id;
  dataset.text_attributes["env_description"] = envs::to_yaml(description);
  dataset.text_attributes["physics"] = args.physics;
  dataset.text_attributes["actions"] = args.actions;
  dataset.text_attributes["bsg_version"] = BSG_VERSION;
  dataset.text_attributes["constraints"] = constraint_list_to_yaml(constraints);
  dataset.number_attributes["cost_limit"] = args.cost_limit.value_or(constraints.size() == 1 ? constraints.front().limit
                                                                                            : spec.cost_limit);
  std::filesystem::path directory = out.parent_path();
  if (!directory.empty()) std::filesystem::create_directories(directory);
  algos::write_dataset_file(out, dataset);
  CollectSummary summary;
  summary.transitions = dataset.size();
  summary.episodes = static_cast<long long>(dataset.number_attributes["episodes"]);
  summary.env_id = spec.id;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  summary.bytes = std::filesystem::file_size(out);
  return summary;
}

}  // namespace bsg::cli

