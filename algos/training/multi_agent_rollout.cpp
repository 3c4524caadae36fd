#include "algos/training/multi_agent_rollout.h"

#include <span>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

void copy_span(std::span<const double> from, Eigen::VectorXd& to) {
  if (static_cast<Eigen::Index>(from.size()) != to.size()) {
    throw std::runtime_error("the environment returned " + std::to_string(from.size()) + " entries, expected " +
                             std::to_string(to.size()));
  }
  to = Eigen::Map<const Eigen::VectorXd>(from.data(), to.size());
}

}  // namespace

MultiAgentRollout::MultiAgentRollout(const envs::MultiAgentSpec& spec, const MultiAgentRolloutOptions& options,
                                     const BufferOptions& buffer_options)
    : options_(options), states_(options.local_steps, spec.state_dim), state_(spec.state_dim) {
  const int n = spec.agent_count();
  for (int i = 0; i < n; ++i) {
    const auto a = static_cast<std::size_t>(i);
    buffers_.emplace_back(options.local_steps, spec.observation_dims[a], spec.action_dims[a], buffer_options);
    observations_.emplace_back(spec.observation_dims[a]);
    actions_.emplace_back(spec.action_dims[a]);
  }
  values_.setZero(n);
  cost_values_.setZero(n);
}

double MultiAgentRollout::epoch_cost() const {
  double sum = 0.0;
  for (const Buffer& buffer : buffers_) sum += buffer.epoch_cost();
  return sum / static_cast<double>(buffers_.size());
}

void MultiAgentRollout::predict_values(const MultiAgentNetworks& networks) {
  critic_input_.resize(networks.critic_input_size());
  for (int i = 0; i < agent_count(); ++i) {
    const AgentSlot& slot = networks.slot_of_agent(i);
    networks.critic_input(i, state_, critic_input_);
    values_[i] = slot.value.predict(critic_input_, workspace_);
    cost_values_[i] = slot.cost_value ? slot.cost_value->predict(critic_input_, workspace_) : 0.0;
  }
}

void MultiAgentRollout::collect(envs::MultiAgentEnv& env, std::uint64_t epoch_env_seed,
                                const MultiAgentNetworks& networks, Rng& noise) {
  const int n = agent_count();
  if (networks.agent_count() != n) {
    throw std::invalid_argument("MultiAgentRollout: networks for " + std::to_string(networks.agent_count()) +
                                " agents, environment with " + std::to_string(n));
  }
  for (Buffer& buffer : buffers_) buffer.reset();
  policy_inputs_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) policy_inputs_[static_cast<std::size_t>(i)].resize(networks.policy_input_size(i));
  std::vector<std::span<const double>> action_views;
  for (const Eigen::VectorXd& action : actions_) {
    action_views.emplace_back(action.data(), static_cast<std::size_t>(action.size()));
  }
  const auto observe = [&](std::span<const std::span<const double>> observations) {
    for (int i = 0; i < n; ++i) copy_span(observations[static_cast<std::size_t>(i)], observations_[static_cast<std::size_t>(i)]);
    copy_span(env.global_state(), state_);
  };

  observe(env.reset(epoch_env_seed));
  int episode_length = 0;
  std::vector<double> log_probs(static_cast<std::size_t>(n));
  for (int t = 0; t < options_.local_steps; ++t) {
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<std::size_t>(i);
      networks.policy_input(i, observations_[a], policy_inputs_[a]);
      log_probs[a] = networks.slot_of_agent(i).policy.sample_action(policy_inputs_[a], actions_[a], noise, workspace_);
    }
    predict_values(networks);
    states_.row(t) = state_.transpose();
    const envs::MultiAgentStepResult step = env.step(action_views);
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<std::size_t>(i);
      buffers_[a].store(observations_[a], actions_[a], step.rewards[a], step.costs[a], values_[i], cost_values_[i],
                        log_probs[a]);
    }
    observe(step.observations);  // o_t+1 and s_t+1
    ++episode_length;

    const bool timeout = !step.terminated && (step.truncated || episode_length >= options_.max_ep_len);
    const bool terminal = step.terminated || timeout;
    const bool epoch_end = t == options_.local_steps - 1;
    if (!terminal && !epoch_end) continue;
    // As the single-agent rollout (rollout.cpp): bootstrap at a time-out (timeout_bootstrap) and
    // at the epoch cut, also after a terminal on the last step.
    const bool bootstrap = timeout ? options_.timeout_bootstrap : epoch_end;
    if (bootstrap) {
      predict_values(networks);
    } else {
      values_.setZero();
      cost_values_.setZero();
    }
    for (int i = 0; i < n; ++i) {
      buffers_[static_cast<std::size_t>(i)].finish_path(values_[i], cost_values_[i], std::nullopt,
                                                        terminal ? PathEnd::episode_end : PathEnd::epoch_cut);
    }
    if (!epoch_end) {
      observe(env.reset());
      episode_length = 0;
    }
  }
  for (const Buffer& buffer : buffers_) buffer.check_ready();
}

}  // namespace bsg::algos
