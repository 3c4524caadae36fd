#include "envs/multi_agent_vector_env.h"

#include <algorithm>
#include <stdexcept>

#include "envs/assembly/multi_agent_buffers.h"
#include "envs/worker_pool.h"

namespace bsg::envs {

namespace {

constexpr const char* kOwner = "MultiAgentVectorEnv";

std::ptrdiff_t offset(size_t row, size_t width) { return static_cast<std::ptrdiff_t>(row * width); }

}  // namespace

MultiAgentVectorEnv::MultiAgentVectorEnv(const std::string& id, int num_envs, int num_threads,
                                         const EnvOptions& options)
    : MultiAgentVectorEnv(describe_multi_agent(id), num_envs, num_threads, options) {}

MultiAgentVectorEnv::MultiAgentVectorEnv(const MultiAgentDescription& description, int num_envs,
                                         int num_threads, const EnvOptions& options)
    : description_(description), options_(options), num_envs_(num_envs) {
  if (num_envs < 1) {
    throw std::invalid_argument(description.name + ": " + kOwner +
                                " num_envs must be >= 1, got " + std::to_string(num_envs));
  }
  num_threads_ = resolve_num_threads(num_threads, num_envs, kOwner);
  envs_.reserve(static_cast<size_t>(num_envs));
  for (int i = 0; i < num_envs; ++i) envs_.push_back(make_multi_agent(description_, options_));
  spec_ = envs_.front()->spec();
  agents_ = spec_.agent_count();
  const auto n = static_cast<size_t>(num_envs);
  const auto agents = static_cast<size_t>(agents_);
  for (int agent = 0; agent < agents_; ++agent) {
    const auto dim = static_cast<size_t>(spec_.observation_dims[static_cast<size_t>(agent)]);
    observations_.emplace_back(n * dim, 0.0);
  }
  final_observations_ = observations_;
  states_.assign(n * static_cast<size_t>(spec_.state_dim), 0.0);
  final_states_ = states_;
  rewards_.assign(n * agents, 0.0);
  costs_.assign(n * agents, 0.0);
  cost_terms_.assign(n * agents * spec_.cost_term_names.size(), 0.0);
  terminated_.assign(n, 0);
  truncated_.assign(n, 0);
  used_.assign(n, 0);
  env_actions_.assign(n, std::vector<std::span<const double>>(agents));
  workers_ = std::make_unique<WorkerPool>(num_threads_);
}

MultiAgentVectorEnv::~MultiAgentVectorEnv() = default;

std::span<const double> MultiAgentVectorEnv::observations(int agent) const {
  return observations_.at(static_cast<size_t>(agent));
}

std::span<const double> MultiAgentVectorEnv::final_observations(int agent) const {
  return final_observations_.at(static_cast<size_t>(agent));
}

void MultiAgentVectorEnv::write_row(int index,
                                    std::span<const std::span<const double>> agent_observations,
                                    std::span<const double> state,
                                    std::vector<std::vector<double>>& observations,
                                    std::vector<double>& states) {
  const auto i = static_cast<size_t>(index);
  for (size_t agent = 0; agent < agent_observations.size(); ++agent) {
    const std::span<const double> observation = agent_observations[agent];
    std::copy(observation.begin(), observation.end(),
              observations[agent].begin() + offset(i, observation.size()));
  }
  std::copy(state.begin(), state.end(), states.begin() + offset(i, state.size()));
}

void MultiAgentVectorEnv::reset_one(int index, const std::uint64_t* seed) {
  MultiAgentEnv& env = *envs_[static_cast<size_t>(index)];
  const std::span<const std::span<const double>> first = seed ? env.reset(*seed) : env.reset();
  write_row(index, first, env.global_state(), observations_, states_);
  used_[static_cast<size_t>(index)] = 1;
}

void MultiAgentVectorEnv::reset(std::uint64_t seed) {
  workers_->run(num_envs_, [this, seed](int i) {
    const std::uint64_t own_seed = seed + static_cast<std::uint64_t>(i);
    reset_one(i, &own_seed);
  });
  has_reset_ = true;
}

void MultiAgentVectorEnv::reset() {
  workers_->run(num_envs_, [this](int i) { reset_one(i, nullptr); });
  has_reset_ = true;
}

void MultiAgentVectorEnv::restart(std::uint64_t seed) {
  // Rebuilt on this thread, as VectorEnv::reset_selected does (not on the step path).
  for (size_t i = 0; i < envs_.size(); ++i) {
    if (used_[i]) envs_[i] = make_multi_agent(description_, options_);
  }
  reset(seed);
}

void MultiAgentVectorEnv::check_actions(std::span<const std::span<const double>> actions) {
  if (!has_reset_) throw std::logic_error(spec_.id + ": " + kOwner + " step() called before reset()");
  const auto agents = static_cast<size_t>(agents_);
  if (actions.size() != agents) {
    throw std::invalid_argument(spec_.id + ": " + kOwner + " got " +
                                std::to_string(actions.size()) +
                                " action arrays, expected one per agent (" +
                                std::to_string(agents_) + ")");
  }
  const auto n = static_cast<size_t>(num_envs_);
  for (size_t agent = 0; agent < agents; ++agent) {
    const auto dim = static_cast<size_t>(spec_.action_dims[agent]);
    if (actions[agent].size() != n * dim) {
      throw std::invalid_argument(spec_.id + ": " + kOwner + " " + spec_.agent_names[agent] +
                                  "'s actions have " + std::to_string(actions[agent].size()) +
                                  " entries, expected " + std::to_string(num_envs_) + " x " +
                                  std::to_string(dim));
    }
    for (size_t i = 0; i < n; ++i) env_actions_[i][agent] = actions[agent].subspan(i * dim, dim);
  }
  // Each environment's row as MultiAgentEnv::step checks it (non-finite entries).
  for (size_t i = 0; i < n; ++i) {
    try {
      check_multi_agent_actions(spec_, true, env_actions_[i]);
    } catch (const std::invalid_argument& error) {
      std::string what = error.what();
      const std::string prefix = spec_.id + ": ";
      if (what.starts_with(prefix)) what.erase(0, prefix.size());
      throw std::invalid_argument(spec_.id + ": " + kOwner + " environment " +
                                  std::to_string(i) + ": " + what);
    }
  }
}

void MultiAgentVectorEnv::step_one(int index) {
  const auto i = static_cast<size_t>(index);
  const auto agents = static_cast<size_t>(agents_);
  const size_t terms = spec_.cost_term_names.size();
  MultiAgentEnv& env = *envs_[i];
  const MultiAgentStepResult result = env.step(env_actions_[i]);
  // Everything is copied before an auto-reset, which rewrites the environment's buffers.
  for (size_t agent = 0; agent < agents; ++agent) {
    rewards_[i * agents + agent] = result.rewards[agent];
    costs_[i * agents + agent] = result.costs[agent];
    const std::span<const CostTerm> agent_terms = result.cost_terms[agent];
    if (agent_terms.size() != terms) {
      throw std::logic_error(spec_.id + ": " + spec_.agent_names[agent] + " reported " +
                             std::to_string(agent_terms.size()) + " cost terms, its spec names " +
                             std::to_string(terms));
    }
    for (size_t k = 0; k < terms; ++k) {
      cost_terms_[(i * agents + agent) * terms + k] = agent_terms[k].value;
    }
  }
  terminated_[i] = result.terminated;
  truncated_[i] = result.truncated;
  write_row(index, result.observations, env.global_state(), final_observations_, final_states_);
  if (result.terminated || result.truncated) {
    reset_one(index, nullptr);
  } else {
    write_row(index, result.observations, env.global_state(), observations_, states_);
  }
}

void MultiAgentVectorEnv::step(std::span<const std::span<const double>> actions) {
  check_actions(actions);
  workers_->run(num_envs_, [this](int i) { step_one(i); });
}

}  // namespace bsg::envs
