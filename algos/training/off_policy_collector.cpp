#include "algos/training/off_policy_collector.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

const envs::EnvSpec& checked_spec(const std::vector<std::unique_ptr<envs::Env>>& envs, int num_envs) {
  if (static_cast<int>(envs.size()) != num_envs || envs.empty()) {
    throw std::invalid_argument("OffPolicyTrainer: " + std::to_string(envs.size()) + " environments for num_envs = " +
                                std::to_string(num_envs));
  }
  for (const auto& env : envs) {
    if (env == nullptr) throw std::invalid_argument("OffPolicyTrainer: no environment");
  }
  const envs::EnvSpec& spec = envs.front()->spec();
  if (spec.observation_dim <= 0 || spec.action_dim <= 0) {
    throw std::runtime_error("environment " + spec.id + " reports an empty observation or action space");
  }
  return spec;
}

// The constraints' step costs, bound to the environment's cost terms when some constraint names
// terms (checked before the run directory is touched).
StepCostSelector bound_cost_selector(const RunConfig& config, const envs::EnvSpec& spec) {
  StepCostSelector selector(config);
  if (selector.needs_terms()) selector.bind(spec.cost_term_names, spec.id);
  return selector;
}

std::span<const double> span_of(const Eigen::VectorXd& vector) {
  return {vector.data(), static_cast<std::size_t>(vector.size())};
}

}  // namespace

OffPolicyEpochEpisodes::OffPolicyEpochEpisodes(int constraint_count)
    : constraint_costs(static_cast<std::size_t>(constraint_count)),
      epoch_constraint_costs(Eigen::VectorXd::Zero(constraint_count)) {}

OffPolicyCollector::OffPolicyCollector(const RunConfig& config, std::vector<std::unique_ptr<envs::Env>> envs,
                                       int critic_cost_count)
    : config_(config),
      envs_(std::move(envs)),
      observation_size_(checked_spec(envs_, config.off_policy.num_envs).observation_dim),
      constraint_count_(constraint_count(config)),
      critic_cost_count_(critic_cost_count),
      cost_selector_(bound_cost_selector(config, envs_.front()->spec())) {
  const int action_size = spec().action_dim;
  const std::size_t n = envs_.size();
  for (std::size_t j = 0; j < n; ++j) {
    accumulators_.emplace_back(config_.off_policy.n_step, config_.gamma, observation_size_, action_size,
                               critic_cost_count_);
  }
  observations_.assign(n, Eigen::VectorXd(observation_size_));
  episode_returns_.assign(n, 0.0);
  episode_costs_.assign(n, 0.0);
  episode_lengths_.assign(n, 0);
  episode_constraint_costs_.assign(n, Eigen::VectorXd::Zero(constraint_count_));
  step_costs_.resize(constraint_count_);
}

std::span<const double> OffPolicyCollector::observation(int j) const {
  return span_of(observations_[static_cast<std::size_t>(j)]);
}

void OffPolicyCollector::restart(int j, std::uint64_t seed) {
  const std::size_t jj = static_cast<std::size_t>(j);
  const std::span<const double> first = envs_[jj]->reset(seed);
  observations_[jj] = Eigen::Map<const Eigen::VectorXd>(first.data(), observation_size_);
  episode_returns_[jj] = episode_costs_[jj] = 0.0;
  episode_lengths_[jj] = 0;
  episode_constraint_costs_[jj].setZero();
  accumulators_[jj].clear();
}

envs::StepResult OffPolicyCollector::step(int j, std::span<const double> action) {
  return envs_[static_cast<std::size_t>(j)]->step(action);
}

void OffPolicyCollector::record(int j, std::span<const double> action, const envs::StepResult& step, bool cut,
                                ReplayBuffer& buffer, OffPolicyEpochEpisodes& epoch) {
  const std::size_t jj = static_cast<std::size_t>(j);
  cost_selector_.select(step, step_costs_);
  episode_returns_[jj] += step.reward;
  episode_costs_[jj] += step.cost;
  episode_constraint_costs_[jj] += step_costs_;
  ++episode_lengths_[jj];
  epoch.epoch_cost += step.cost;
  epoch.epoch_constraint_costs += step_costs_;
  const bool time_out = step.truncated || episode_lengths_[jj] >= config_.max_ep_len;
  const bool episode_over = step.terminated || time_out;
  // A termination ends the return; a time-out and the epoch's cut bootstrap from s'.
  const std::span<const double> critic_costs(step_costs_.data(), static_cast<std::size_t>(critic_cost_count_));
  accumulators_[jj].add(span_of(observations_[jj]), action, step.reward, critic_costs, step.observation,
                        step.terminated, episode_over || cut, buffer);
  if (episode_over) {
    epoch.episodes.returns.push_back(episode_returns_[jj]);
    epoch.episodes.costs.push_back(episode_costs_[jj]);
    epoch.episodes.lengths.push_back(episode_lengths_[jj]);
    for (int i = 0; i < constraint_count_; ++i) {
      epoch.constraint_costs[static_cast<std::size_t>(i)].push_back(episode_constraint_costs_[jj](i));
    }
    episode_returns_[jj] = episode_costs_[jj] = 0.0;
    episode_lengths_[jj] = 0;
    episode_constraint_costs_[jj].setZero();
    if (!cut) {
      const std::span<const double> first = envs_[jj]->reset();  // continues the environment's stream
      observations_[jj] = Eigen::Map<const Eigen::VectorXd>(first.data(), observation_size_);
    }
  } else {
    observations_[jj] = Eigen::Map<const Eigen::VectorXd>(step.observation.data(), observation_size_);
  }
}

void OffPolicyCollector::flush(ReplayBuffer& buffer) {
  for (std::size_t j = 0; j < envs_.size(); ++j) accumulators_[j].flush(span_of(observations_[j]), buffer);
}

}  // namespace bsg::algos
