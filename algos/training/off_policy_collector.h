// The environment side of the off-policy loop (docs/algorithms.md#the-off-policy-loop), beside the
// on-policy RolloutCollector (rollout.h): a rank's num_envs environments, each with its current
// observation, its running episode's sums and its n-step accumulator, which feeds the replay buffer.
// Episodes run on across epochs; an episode ends at a termination (no bootstrap), a truncation or
// max_ep_len (bootstrapped); a cut (the last round before a checkpoint) ends it bootstrapped and
// uncounted, and the environments start afresh with the next epoch.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "algos/core/constraint_costs.h"
#include "algos/off_policy/n_step_returns.h"
#include "algos/off_policy/replay_buffer.h"
#include "algos/training/off_policy_epoch_log.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

// The episodes one epoch completed on this rank, and its costs over every step.
struct OffPolicyEpochEpisodes {
  OffPolicyEpisodes episodes;
  std::vector<std::vector<double>> constraint_costs;  // per constraint, per completed episode
  double epoch_cost = 0.0;                            // the environment's cost over every step
  Eigen::VectorXd epoch_constraint_costs;             // each constraint's over every step

  explicit OffPolicyEpochEpisodes(int constraint_count);
};

class OffPolicyCollector {
 public:
  // `envs` must hold config.off_policy.num_envs environments of one spec with non-empty spaces (checked).
  // `critic_cost_count` constraints' costs go into the buffer (m for the -lag learners, 0 otherwise).
  OffPolicyCollector(const RunConfig& config, std::vector<std::unique_ptr<envs::Env>> envs, int critic_cost_count);

  const envs::EnvSpec& spec() const { return envs_.front()->spec(); }
  int env_count() const { return static_cast<int>(envs_.size()); }
  envs::Env& env(int j) { return *envs_[static_cast<std::size_t>(j)]; }
  const StepCostSelector& cost_selector() const { return cost_selector_; }
  std::span<const double> observation(int j) const;

  // Every environment starts afresh: env j reset with seed_of(j), sums and pending steps dropped.
  template <typename SeedOf>
  void restart(SeedOf seed_of) {
    for (int j = 0; j < env_count(); ++j) restart(j, seed_of(j));
  }
  // Steps environment j with `action` (the result's spans are valid until the environment steps again).
  envs::StepResult step(int j, std::span<const double> action);
  // Takes the step just made into the episode's sums and, through the n-step accumulator, the
  // buffer; an ended episode is counted in `epoch` and its environment reset (not after a `cut`).
  void record(int j, std::span<const double> action, const envs::StepResult& step, bool cut, ReplayBuffer& buffer,
              OffPolicyEpochEpisodes& epoch);
  // Steps still waiting for their n-step sums go to the buffer as at a truncation (a checkpoint).
  void flush(ReplayBuffer& buffer);

 private:
  void restart(int j, std::uint64_t seed);

  RunConfig config_;
  std::vector<std::unique_ptr<envs::Env>> envs_;
  int observation_size_;
  int constraint_count_;   // m: constraints logged
  int critic_cost_count_;  // m for the -lag learners, 0 otherwise
  StepCostSelector cost_selector_;
  std::vector<NStepAccumulator> accumulators_;
  // per environment: the current observation and the running episode's sums
  std::vector<Eigen::VectorXd> observations_;
  std::vector<double> episode_returns_;
  std::vector<double> episode_costs_;
  std::vector<int> episode_lengths_;
  std::vector<Eigen::VectorXd> episode_constraint_costs_;
  Eigen::VectorXd step_costs_;
};

}  // namespace bsg::algos
