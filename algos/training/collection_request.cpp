#include "algos/training/collection_request.h"

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
#include "envs/env.h"

#ifndef BSG_VERSION
#error "BSG_VERSION is defined by CMakeLists.txt for bsg_algos_training"
#endif

namespace bsg::algos {
namespace {

std::string environment_mismatch(const std::string& run, const envs::EnvDescription& trained,
                                  const envs::EnvDescription& collected) {
  if (trained.name != collected.name) {
    return "checkpoint " + run + " was trained on " + trained.name + ", not on the collection's " + collected.name;
  }
  return "checkpoint " + run + " was trained on a " + trained.name +
         " with other parameters than the collection's (compare its config.yaml env: block with --set)";
}

}  // namespace

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

std::string actions_name(EvaluationActions actions) {
  return actions == EvaluationActions::mean ? "mean" : "sampled";
}

CollectionSummary collect_to_file(const CollectionRequest& request) {
  const auto started = std::chrono::steady_clock::now();
  if (request.episodes.has_value() == request.transitions.has_value()) {
    throw std::invalid_argument("give exactly one of --episodes N and --transitions N");
  }
  const std::int64_t count = request.episodes ? *request.episodes : *request.transitions;
  if (count < 1) {
    throw std::invalid_argument(std::string("--") + (request.episodes ? "episodes" : "transitions") +
                                " must be at least 1, got " + std::to_string(count));
  }
  const std::filesystem::path out(request.out);
  if (std::filesystem::exists(out) && !request.force) {
    throw std::invalid_argument(request.out + " exists (--force replaces it)");
  }
  if (!request.env_overrides.empty() && request.env_id.empty()) {
    throw std::invalid_argument("--set changes the environment named by --env; give --env too");
  }
  const std::vector<PolicySpec>& specs = request.policies;
  std::vector<std::unique_ptr<CheckpointPolicy>> checkpoints(specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].source != "random") checkpoints[i] = load_checkpoint_policy(specs[i].source, request.actions);
  }
  const CheckpointPolicy* first_checkpoint = nullptr;
  for (const auto& c : checkpoints) {
    if (c && !first_checkpoint) first_checkpoint = c.get();
  }

  envs::EnvDescription description;
  if (!request.env_id.empty()) {
    description = envs::describe(request.env_id, request.env_overrides);
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
  std::unique_ptr<envs::Env> env = envs::make(description, {.physics = request.physics});
  const envs::EnvSpec& spec = env->spec();

  // The constraints: the checkpoints' (they must agree), else the environment's whole cost.
  StepCostSelector costs;
  std::vector<ConstraintConfig> constraints{{{std::string(kAllCostTerms)}, spec.cost_limit}};
  if (first_checkpoint) {
    const std::vector<ConstraintConfig> first = effective_constraints(first_checkpoint->config());
    for (std::size_t i = 0; i < specs.size(); ++i) {
      if (!checkpoints[i]) continue;
      std::vector<ConstraintConfig> these = effective_constraints(checkpoints[i]->config());
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
      costs = StepCostSelector(first_checkpoint->config());
      constraints = first;
    }
  }
  if (costs.needs_terms()) costs.bind(spec.cost_term_names, spec.id);
  std::vector<std::string> constraint_names;
  for (const ConstraintConfig& c : constraints) constraint_names.push_back(c.terms_text());

  std::vector<std::unique_ptr<CollectionPolicy>> randoms;
  std::vector<SharedPolicy> shared;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (checkpoints[i]) {
      shared.push_back({checkpoints[i].get(), specs[i].share});
    } else {
      randoms.push_back(make_random_policy(spec.action_dim, spec.action_low, spec.action_high));
      shared.push_back({randoms.back().get(), specs[i].share});
    }
  }
  const CollectionPlan plan{
      request.episodes ? CollectionUnit::episodes : CollectionUnit::transitions, count, request.seed};
  OfflineDataset dataset = collect_dataset(*env, shared, plan, costs, constraint_names);
  dataset.text_attributes["env_id"] = spec.id;
  dataset.text_attributes["env_description"] = envs::to_yaml(description);
  dataset.text_attributes["physics"] = std::string(to_string(request.physics));
  dataset.text_attributes["actions"] = actions_name(request.actions);
  dataset.text_attributes["bsg_version"] = BSG_VERSION;
  dataset.text_attributes["constraints"] = constraint_list_to_yaml(constraints);
  dataset.number_attributes["cost_limit"] = request.cost_limit.value_or(constraints.size() == 1 ? constraints.front().limit
                                                                                            : spec.cost_limit);
  std::filesystem::path directory = out.parent_path();
  if (!directory.empty()) std::filesystem::create_directories(directory);
  write_dataset_file(out, dataset);
  CollectionSummary summary;
  summary.transitions = dataset.size();
  summary.episodes = static_cast<long long>(dataset.number_attributes["episodes"]);
  summary.env_id = spec.id;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  summary.bytes = std::filesystem::file_size(out);
  return summary;
}

}  // namespace bsg::algos

