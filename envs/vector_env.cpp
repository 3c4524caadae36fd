#include "envs/vector_env.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "envs/worker_pool.h"

namespace bsg::envs {

VectorEnv::VectorEnv(const std::string& id, int num_envs, int num_threads,
                     const EnvOptions& options)
    : VectorEnv(describe(id), num_envs, num_threads, options) {}

VectorEnv::VectorEnv(const EnvDescription& description, int num_envs, int num_threads,
                     const EnvOptions& options)
    : num_envs_(num_envs) {
  if (num_envs < 1) {
    throw std::invalid_argument("VectorEnv: num_envs must be >= 1, got " +
                                std::to_string(num_envs));
  }
  num_threads_ = resolve_num_threads(num_threads, num_envs, "VectorEnv");
  make_env_ = [description, options] { return make(description, options); };
  envs_.reserve(static_cast<size_t>(num_envs));
  for (int i = 0; i < num_envs; ++i) envs_.push_back(make_env_());
  spec_ = envs_.front()->spec();
  const auto n = static_cast<size_t>(num_envs);
  observations_.assign(n * static_cast<size_t>(spec_.observation_dim), 0.0);
  final_observations_.assign(observations_.size(), 0.0);
  rewards_.assign(n, 0.0);
  costs_.assign(n, 0.0);
  terminated_.assign(n, 0);
  truncated_.assign(n, 0);
  env_cost_terms_.resize(n);
  elapsed_steps_.assign(n, 0);
  ended_.assign(n, 0);
  autoreset_envs_.assign(n, 0);
  used_.assign(n, 0);
  workers_ = std::make_unique<WorkerPool>(num_threads_);
}

VectorEnv::~VectorEnv() = default;

void VectorEnv::reset_one(int index, const std::uint64_t* seed) {
  const auto i = static_cast<size_t>(index);
  Env& env = *envs_[i];
  const std::span<const double> observation = seed ? env.reset(*seed) : env.reset();
  std::copy(observation.begin(), observation.end(),
            observations_.begin() + index * spec_.observation_dim);
  elapsed_steps_[i] = 0;
  ended_[i] = 0;
  used_[i] = 1;
}

void VectorEnv::reset(std::uint64_t seed) {
  workers_->run(num_envs_, [this, seed](int i) {
    const std::uint64_t own_seed = seed + static_cast<std::uint64_t>(i);
    reset_one(i, &own_seed);
  });
  has_reset_ = true;
}

void VectorEnv::reset() {
  workers_->run(num_envs_, [this](int i) { reset_one(i, nullptr); });
  has_reset_ = true;
}

void VectorEnv::reset_selected(std::span<const std::uint8_t> mask,
                               std::span<const std::optional<std::uint64_t>> seeds) {
  const auto n = static_cast<size_t>(num_envs_);
  if ((!mask.empty() && mask.size() != n) || (!seeds.empty() && seeds.size() != n)) {
    throw std::invalid_argument(spec_.id + ": VectorEnv reset_selected() needs " +
                                std::to_string(n) + " mask entries and seeds, got " +
                                std::to_string(mask.size()) + " and " +
                                std::to_string(seeds.size()));
  }
  const auto selected = [&](size_t i) { return mask.empty() || mask[i] != 0; };
  const auto seed_of = [&](size_t i) -> const std::optional<std::uint64_t>& {
    static const std::optional<std::uint64_t> kNone;
    return seeds.empty() ? kNone : seeds[i];
  };
  // Rebuilt on this thread (building a world is not on the step path); a new
  // environment needs no rebuilding.
  for (size_t i = 0; i < n; ++i) {
    if (selected(i) && seed_of(i) && used_[i]) envs_[i] = make_env_();
  }
  workers_->run(num_envs_, [&](int index) {
    const auto i = static_cast<size_t>(index);
    if (!selected(i)) return;
    const std::optional<std::uint64_t>& seed = seed_of(i);
    reset_one(index, seed ? &*seed : nullptr);
  });
  has_reset_ = true;
}

void VectorEnv::set_max_episode_steps(int steps) {
  if (steps < 0) {
    throw std::invalid_argument(spec_.id + ": VectorEnv max_episode_steps must be >= 0 (0: the "
                                "environment's own " + std::to_string(spec_.max_episode_steps) +
                                "), got " + std::to_string(steps));
  }
  max_episode_steps_ = steps;
}

void VectorEnv::check_actions(std::span<const double> actions) const {
  if (!has_reset_) throw std::logic_error(spec_.id + ": VectorEnv step() called before reset()");
  const auto expected = static_cast<size_t>(num_envs_) * static_cast<size_t>(spec_.action_dim);
  if (actions.size() != expected) {
    throw std::invalid_argument(spec_.id + ": VectorEnv actions have " +
                                std::to_string(actions.size()) + " entries, expected " +
                                std::to_string(num_envs_) + " x " +
                                std::to_string(spec_.action_dim));
  }
  for (size_t k = 0; k < actions.size(); ++k) {
    if (!std::isfinite(actions[k])) {
      throw std::invalid_argument(
          spec_.id + ": VectorEnv action [" + std::to_string(k / spec_.action_dim) + ", " +
          std::to_string(k % spec_.action_dim) + "] is not finite (" +
          std::to_string(actions[k]) + ")");
    }
  }
}

void VectorEnv::autoreset_one(int index) {
  const auto i = static_cast<size_t>(index);
  const auto obs_dim = static_cast<size_t>(spec_.observation_dim);
  reset_one(index, nullptr);
  rewards_[i] = 0;
  costs_[i] = 0;
  terminated_[i] = 0;
  truncated_[i] = 0;
  std::fill(env_cost_terms_[i].begin(), env_cost_terms_[i].end(), 0.0);
  std::copy_n(observations_.begin() + static_cast<std::ptrdiff_t>(i * obs_dim), obs_dim,
              final_observations_.begin() + static_cast<std::ptrdiff_t>(i * obs_dim));
  autoreset_envs_[i] = 1;
}

void VectorEnv::step_one(int index, std::span<const double> actions) {
  const auto i = static_cast<size_t>(index);
  autoreset_envs_[i] = 0;
  if (ended_[i]) {  // kNextStep: this step resets instead of stepping
    autoreset_one(index);
    return;
  }
  const auto act_dim = static_cast<size_t>(spec_.action_dim);
  const auto obs_dim = static_cast<size_t>(spec_.observation_dim);
  Env& env = *envs_[i];
  const StepResult result = env.step(actions.subspan(i * act_dim, act_dim));
  ++elapsed_steps_[i];
  rewards_[i] = result.reward;
  costs_[i] = result.cost;
  terminated_[i] = result.terminated;
  truncated_[i] = max_episode_steps_ > 0
                      ? !result.terminated && elapsed_steps_[i] >= max_episode_steps_
                      : result.truncated;
  // Copied before an auto-reset, which may reuse the task's buffers.
  std::vector<double>& terms = env_cost_terms_[i];
  terms.resize(result.cost_terms.size());  // allocates on the first step only
  for (size_t k = 0; k < terms.size(); ++k) terms[k] = result.cost_terms[k].value;
  if (index == 0 && cost_term_names_.empty()) {
    for (const CostTerm& term : result.cost_terms) cost_term_names_.emplace_back(term.name);
  }
  std::copy(result.observation.begin(), result.observation.end(),
            final_observations_.begin() + static_cast<std::ptrdiff_t>(i * obs_dim));
  const bool ended = terminated_[i] || truncated_[i];
  if (ended && autoreset_ == AutoReset::kSameStep) {
    reset_one(index, nullptr);
    return;
  }
  std::copy(result.observation.begin(), result.observation.end(),
            observations_.begin() + static_cast<std::ptrdiff_t>(i * obs_dim));
  ended_[i] = ended;
}

void VectorEnv::step(std::span<const double> actions) {
  check_actions(actions);
  workers_->run(num_envs_, [this, actions](int i) { step_one(i, actions); });
  const size_t terms = cost_term_names_.size();
  cost_terms_.resize(static_cast<size_t>(num_envs_) * terms);  // sized at the first step
  for (size_t i = 0; i < env_cost_terms_.size(); ++i) {
    std::copy(env_cost_terms_[i].begin(), env_cost_terms_[i].end(),
              cost_terms_.begin() + static_cast<std::ptrdiff_t>(i * terms));
  }
}

void VectorEnv::for_each_env(const std::function<void(int, const Env&)>& job) {
  workers_->run(num_envs_, [this, &job](int i) { job(i, *envs_[static_cast<size_t>(i)]); });
}

}  // namespace bsg::envs
