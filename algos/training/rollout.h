// One epoch of data collection on one rank (docs/algorithms.md#rollout): N steps of the noisy
// policy in one environment, with V and V_C values and log-probabilities,
// paths closed with GAE (reward scaling docs/algorithms.md#reward-scaling) at every episode end and at the
// epoch cut.
//
// Environment seeding: the environment is reset with `epoch_env_seed` at the
// start of every epoch (the rollout resets it anyway, docs/algorithms.md#rollout); later resets
// within the epoch continue the environment's own RNG stream. The epoch's data
// is therefore a function of (parameters, normalisers, sigma, epoch_env_seed,
// noise RNG) alone, which is what makes a resumed run identical to an
// uninterrupted one.
//
// With a budget decorator (budget_decorator.h) the learner's reward (StepResult::learner) goes
// into GAE and the episode ends at its cut, as a terminal; the episode statistics keep the
// environment's reward and cost.
//
// Per-step work uses only buffers preallocated at construction: one
// single-sample forward each of mu, V and V_C, no heap allocation.
//
// Parameters:
//   local_steps        N = B / R
//   max_ep_len         time limit in steps (an env truncation counts too)
//   use_reward_scaling divide rewards by the return normaliser's std for GAE
//   timeout_bootstrap  true (original): a time-out is bootstrapped with (V, V_C)(o_T);
//                      false: it ends the path like a terminal (bootstrap 0)
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "algos/core/actor_critic.h"
#include "algos/core/buffer.h"
#include "algos/core/constraint_costs.h"
#include "common/mlp.h"
#include "common/random.h"
#include "envs/env.h"

namespace bsg::algos {

struct RolloutOptions {
  int local_steps = 0;
  int max_ep_len = 0;
  bool use_reward_scaling = true;
  bool timeout_bootstrap = true;
};

class RolloutCollector {
 public:
  // One constraint, on the environment's cost, unless `costs` says otherwise
  // (it must be bound to the environment if it names terms).
  RolloutCollector(int observation_size, int action_size, RolloutOptions options,
                   StepCostSelector costs = StepCostSelector());

  // Fills `buffer` (reset first) with options.local_steps steps, one cost
  // column per constraint (the buffer's and the actor-critic's m must be the
  // selector's). Episode
  // statistics of the completed episodes end up in buffer.episodes().
  void collect(envs::Env& env, std::uint64_t epoch_env_seed, const ActorCritic& actor_critic, Rng& noise_rng,
               Buffer& buffer);

  const RolloutOptions& options() const { return options_; }
  const StepCostSelector& cost_selector() const { return costs_; }

 private:
  void copy_observation(std::span<const double> observation);
  // V and every V_Ci of normalized_observation_ (normalised already) at
  // `episode_step` (an input of the nets only with the time input).
  double predict_values(const ActorCritic& actor_critic, int episode_step, Eigen::VectorXd& cost_values);

  RolloutOptions options_;
  StepCostSelector costs_;
  Eigen::VectorXd step_costs_;        // c_i,t
  Eigen::VectorXd step_cost_values_;  // V_Ci(s_t)
  Eigen::VectorXd last_cost_values_;  // V_Ci(s_T) at a bootstrap
  Eigen::VectorXd raw_observation_;
  Eigen::VectorXd normalized_observation_;
  Eigen::VectorXd value_input_;  // normalized_observation_ and the time left, with the time input
  Eigen::VectorXd action_;
  MlpSampleWorkspace policy_workspace_;
  MlpSampleWorkspace value_workspace_;
  std::vector<MlpSampleWorkspace> cost_value_workspaces_;  // one per constraint
};

}  // namespace bsg::algos
