#include "algos/training/rollout.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace bsg::algos {

RolloutCollector::RolloutCollector(int observation_size, int action_size, RolloutOptions options,
                                   StepCostSelector costs)
    : options_(options),
      costs_(std::move(costs)),
      step_costs_(Eigen::VectorXd::Zero(costs_.count())),
      step_cost_values_(Eigen::VectorXd::Zero(costs_.count())),
      last_cost_values_(Eigen::VectorXd::Zero(costs_.count())),
      raw_observation_(Eigen::VectorXd::Zero(observation_size)),
      normalized_observation_(Eigen::VectorXd::Zero(observation_size)),
      action_(Eigen::VectorXd::Zero(action_size)),
      cost_value_workspaces_(static_cast<std::size_t>(costs_.count())) {
  if (options.local_steps <= 0 || options.max_ep_len <= 0) {
    throw std::invalid_argument("RolloutCollector: local_steps (" + std::to_string(options.local_steps) +
                                ") and max_ep_len (" + std::to_string(options.max_ep_len) + ") must be positive");
  }
}

void RolloutCollector::copy_observation(std::span<const double> observation) {
  if (static_cast<Eigen::Index>(observation.size()) != raw_observation_.size()) {
    throw std::runtime_error("rollout: the environment returned an observation of size " +
                             std::to_string(observation.size()) + ", expected " +
                             std::to_string(raw_observation_.size()));
  }
  raw_observation_ = Eigen::Map<const Eigen::VectorXd>(observation.data(), raw_observation_.size());
}

double RolloutCollector::predict_values(const ActorCritic& actor_critic, int episode_step,
                                        Eigen::VectorXd& cost_values) {
  const Eigen::VectorXd* input = &normalized_observation_;
  if (actor_critic.value_time_limit > 0) {
    actor_critic.value_input(normalized_observation_, episode_step, value_input_);
    input = &value_input_;
  }
  const double value = actor_critic.value.predict(*input, value_workspace_);
  for (int i = 0; i < costs_.count(); ++i) {
    cost_values[i] = actor_critic.cost_value_net(i).predict(*input, cost_value_workspaces_[static_cast<std::size_t>(i)]);
  }
  return value;
}

void RolloutCollector::collect(envs::Env& env, std::uint64_t epoch_env_seed, const ActorCritic& actor_critic,
                               Rng& noise_rng, Buffer& buffer) {
  if (buffer.capacity() != options_.local_steps) {
    throw std::invalid_argument("RolloutCollector::collect: buffer capacity " + std::to_string(buffer.capacity()) +
                                " differs from local_steps " + std::to_string(options_.local_steps));
  }
  if (buffer.constraint_count() != costs_.count() || actor_critic.constraint_count() != costs_.count()) {
    throw std::invalid_argument("RolloutCollector::collect: " + std::to_string(costs_.count()) +
                                " constraints, but the buffer has " + std::to_string(buffer.constraint_count()) +
                                " cost columns and the actor-critic " + std::to_string(actor_critic.constraint_count()) +
                                " cost value nets");
  }
  buffer.reset();
  if (value_input_.size() != actor_critic.value_input_size()) value_input_.setZero(actor_critic.value_input_size());
  const std::optional<double> reward_scale_std =
      options_.use_reward_scaling ? std::optional<double>(actor_critic.return_normalizer.std()[0]) : std::nullopt;
  const std::span<const double> action_view(action_.data(), static_cast<std::size_t>(action_.size()));

  copy_observation(env.reset(epoch_env_seed));  // every epoch starts with a fresh episode (docs/algorithms.md#rollout)
  for (int t = 0; t < options_.local_steps; ++t) {
    actor_critic.normalize_observation(raw_observation_, normalized_observation_);
    const double log_prob =
        actor_critic.policy.sample_action(normalized_observation_, action_, noise_rng, policy_workspace_);
    const double value = predict_values(actor_critic, buffer.current_episode().episode_length, step_cost_values_);

    const envs::StepResult step = env.step(action_view);
    costs_.select(step, step_costs_);
    buffer.store(raw_observation_, action_, step.reward, step.cost, step_costs_, value, step_cost_values_, log_prob);
    if (step.learner) buffer.shape_last_reward(step.learner->reward, step.learner->budget_spent);
    copy_observation(step.observation);  // o_t+1

    // A budget decorator's cut (early termination) ends the learner's episode as a terminal.
    const bool cut = step.learner && step.learner->terminated;
    const bool timeout = !cut && (step.truncated || buffer.current_episode().episode_length >= options_.max_ep_len);
    const bool terminal = step.terminated || cut || timeout;
    const bool epoch_end = t == options_.local_steps - 1;
    if (!terminal && !epoch_end) continue;

    // Bootstrap with (V, V_C)(o_t+1) at a time-out or the epoch cut; a true
    // terminal on the last step is bootstrapped too (Q7: epoch_end wins).
    // Without timeout_bootstrap a time-out ends the return, on the last step too.
    double last_value = 0.0;
    last_cost_values_.setZero();
    const bool bootstrap = timeout ? options_.timeout_bootstrap : epoch_end;
    if (bootstrap) {
      actor_critic.normalize_observation(raw_observation_, normalized_observation_);
      // o_t+1 is episode step episode_length (T at a time-out: no time left).
      last_value = predict_values(actor_critic, buffer.current_episode().episode_length, last_cost_values_);
    }
    buffer.finish_path(last_value, last_cost_values_, reward_scale_std,
                       terminal ? PathEnd::episode_end : PathEnd::epoch_cut);
    // The original also resets after the epoch cut; the next epoch resets
    // again, so that reset is skipped here.
    if (!epoch_end) copy_observation(env.reset());
  }
  buffer.check_ready();
}

}  // namespace bsg::algos
