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

namespace {

// The count of the request's unit, checked; the output file and --set checked against --force and --env.
std::int64_t checked_count(const CollectionRequest& request) {
  if (request.episodes.has_value() == request.transitions.has_value()) {
    throw std::invalid_argument("give exactly one of --episodes N and --transitions N");
  }
  const std::int64_t count = request.episodes ? *request.episodes : *request.transitions;
  if (count < 1) {
    throw std::invalid_argument(std::string("--") + (request.episodes ? "episodes" : "transitions") +
                                " must be at least 1, got " + std::to_string(count));
  }
  if (std::filesystem::exists(std::filesystem::path(request.out)) && !request.force) {
    throw std::invalid_argument(request.out + " exists (--force replaces it)");
  }
  if (!request.env_overrides.empty() && request.env_id.empty()) {
    throw std::invalid_argument("--set changes the environment named by --env; give --env too");
  }
  return count;
}

// The policies' checkpoints (null for the random policy) and the first of them, if any.
struct LoadedCheckpoints {
  std::vector<std::unique_ptr<CheckpointPolicy>> policies;
  const CheckpointPolicy* first = nullptr;
};
LoadedCheckpoints load_checkpoints(const CollectionRequest& request) {
  LoadedCheckpoints loaded;
  loaded.policies.resize(request.policies.size());
  for (std::size_t i = 0; i < request.policies.size(); ++i) {
    if (request.policies[i].source != "random") {
      const std::string& source = request.policies[i].source;
      const std::string name =
          request.checkpoint_names_relative_to.empty()
              ? std::string()
              : std::filesystem::absolute(source)
                    .lexically_normal()
                    .lexically_relative(std::filesystem::absolute(request.checkpoint_names_relative_to).lexically_normal())
                    .string();
      loaded.policies[i] = load_checkpoint_policy(source, request.actions, name);
    }
  }
  for (const auto& c : loaded.policies) {
    if (c && !loaded.first) loaded.first = c.get();
  }
  return loaded;
}

// The environment: --env with its --set, else the first checkpoint's; every checkpoint must have it.
envs::EnvDescription collection_environment(const CollectionRequest& request, const LoadedCheckpoints& loaded) {
  envs::EnvDescription description;
  if (!request.env_id.empty()) {
    description = envs::describe(request.env_id, request.env_overrides);
  } else if (loaded.first) {
    description = loaded.first->env_description();
  } else {
    throw std::invalid_argument("name the environment with --env (the random policy has none of its own)");
  }
  for (std::size_t i = 0; i < loaded.policies.size(); ++i) {
    const auto& checkpoint = loaded.policies[i];
    if (checkpoint && !(checkpoint->env_description() == description)) {
      throw std::invalid_argument(
          environment_mismatch(request.policies[i].source, checkpoint->env_description(), description));
    }
  }
  return description;
}

// The constraints a collection records: the checkpoints' (they must agree), else the environment's
// whole cost; `costs` selects them per step.
std::vector<ConstraintConfig> collection_constraints(const CollectionRequest& request, const LoadedCheckpoints& loaded,
                                                     const envs::EnvSpec& spec, StepCostSelector& costs) {
  std::vector<ConstraintConfig> constraints{{{std::string(kAllCostTerms)}, spec.cost_limit}};
  if (loaded.first) {
    const std::vector<ConstraintConfig> first = effective_constraints(loaded.first->config());
    for (std::size_t i = 0; i < loaded.policies.size(); ++i) {
      if (!loaded.policies[i]) continue;
      std::vector<ConstraintConfig> these = effective_constraints(loaded.policies[i]->config());
      const auto terms_only = [](std::vector<ConstraintConfig> list) {
        for (ConstraintConfig& c : list) c.limit = 0.0;  // limits may differ: a grid over cost limits
        return list;
      };
      if (terms_only(these) != terms_only(first)) {
        throw std::invalid_argument("checkpoint " + request.policies[i].source +
                                    " has other constraints than the first one (" + constraint_list_to_yaml(these) +
                                    " vs " + constraint_list_to_yaml(first) + ")");
      }
    }
    if (first.size() > 1 || !first.front().sums_all_terms()) {
      costs = StepCostSelector(loaded.first->config());
      constraints = first;
    }
  }
  if (costs.needs_terms()) costs.bind(spec.cost_term_names, spec.id);
  return constraints;
}

// The file's attributes beyond DSRL's arrays: what made it, and its cost limit kappa.
void describe_collection(const CollectionRequest& request, const envs::EnvDescription& description,
                         const envs::EnvSpec& spec, const std::vector<ConstraintConfig>& constraints,
                         OfflineDataset& dataset) {
  dataset.text_attributes["env_id"] = spec.id;
  dataset.text_attributes["env_description"] = envs::to_yaml(description);
  dataset.text_attributes["physics"] = std::string(to_string(request.physics));
  dataset.text_attributes["actions"] = actions_name(request.actions);
  dataset.text_attributes["bsg_version"] = BSG_VERSION;
  dataset.text_attributes["constraints"] = constraint_list_to_yaml(constraints);
  dataset.number_attributes["cost_limit"] =
      request.cost_limit.value_or(constraints.size() == 1 ? constraints.front().limit : spec.cost_limit);
}

}  // namespace

CollectionSummary collect_to_file(const CollectionRequest& request) {
  const auto started = std::chrono::steady_clock::now();
  const std::int64_t count = checked_count(request);
  const std::filesystem::path out(request.out);
  const LoadedCheckpoints checkpoints = load_checkpoints(request);
  const envs::EnvDescription description = collection_environment(request, checkpoints);
  std::unique_ptr<envs::Env> env = envs::make(description, {.physics = request.physics});
  const envs::EnvSpec& spec = env->spec();
  StepCostSelector costs;
  const std::vector<ConstraintConfig> constraints = collection_constraints(request, checkpoints, spec, costs);
  std::vector<std::string> constraint_names;
  for (const ConstraintConfig& c : constraints) constraint_names.push_back(c.terms_text());

  std::vector<std::unique_ptr<CollectionPolicy>> randoms;
  std::vector<SharedPolicy> shared;
  for (std::size_t i = 0; i < request.policies.size(); ++i) {
    if (checkpoints.policies[i]) {
      shared.push_back({checkpoints.policies[i].get(), request.policies[i].share});
    } else {
      randoms.push_back(make_random_policy(spec.action_dim, spec.action_low, spec.action_high));
      shared.push_back({randoms.back().get(), request.policies[i].share});
    }
  }
  const CollectionPlan plan{
      request.episodes ? CollectionUnit::episodes : CollectionUnit::transitions, count, request.seed};
  OfflineDataset dataset = collect_dataset(*env, shared, plan, costs, constraint_names);
  describe_collection(request, description, spec, constraints, dataset);
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

