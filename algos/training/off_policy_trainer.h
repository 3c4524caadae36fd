// The off-policy training loop (docs/algorithms.md#the-off-policy-loop, design.md "Off-policy and
// offline learning") beside the on-policy one (trainer.h), sharing its run directory, progress.csv,
// evaluation files, training-cost accounts, Lagrange multipliers and constraint costs. Per epoch k,
// on every rank:
//   1. reseed the action-noise and batch-sampling streams with (action_noise, rank, k) and
//      (minibatch_shuffle, rank, k); in the first epoch after a checkpoint (and the first of all)
//      reset the rank's num_envs environments with the seeds (environment, rank, k num_envs + j);
//   2. steps_per_epoch / (ranks num_envs) rounds, each stepping every environment once: uniform random
//      actions while fewer than start_steps environment steps (all ranks) have been taken, else the
//      actor's exploring action; every step goes through its environment's n-step accumulator into
//      the rank's replay buffer; an episode ends at a termination (no bootstrap), a truncation or
//      max_ep_len (bootstrapped); episodes run on into the next epoch, except in an epoch that ends
//      with a checkpoint, whose last round cuts them (bootstrapped, not counted as episodes);
// After the last epoch: deterministic evaluation episodes (the actor's tanh(mu)) and evaluation.json.
//
// Resuming: the checkpoint (off_policy_checkpoint.h) holds the networks, optimisers, temperature,
// multipliers and the update schedule's carry, and every rank's replay buffer is in its append-only
// record (replay_buffer_log.h); with the seeds above a run resumed from a checkpoint the
// uninterrupted run also took (every save_freq epochs) reproduces it exactly. A stop by signal or
// --stop-after saves (and cuts) at its own epoch, where the uninterrupted run did not.
//
// progress.csv columns: epoch, total_env_steps, episode_{return,cost,length}_{mean,std,min,max},
// episodes, updates (gradient steps this epoch, per rank), reward_critic_loss (summed over the twin
// critics), q_reward_mean, then per constraint cost_critic_loss and q_cost_mean (constraint_<i>_ prefixed
// with several), actor_loss, alpha (SAC), the multipliers' columns (lagrange_multiplier, pid_*_term),
// constraint_<i>_cost and _limit with several constraints, time_collect_s, time_update_s, time_s, fps,
// cumulative_cost, cost_rate. Losses and Q values are means over the epoch's gradient steps, averaged over ranks.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "algos/core/constraint_costs.h"
#include "algos/lagrange/constraint_multipliers.h"
#include "algos/off_policy/n_step_returns.h"
#include "algos/off_policy/off_policy_learner.h"
#include "algos/off_policy/replay_buffer.h"
#include "algos/training/progress_csv.h"
#include "algos/training/replay_buffer_log.h"
#include "algos/training/run_directory.h"
#include "algos/training/trainer.h"
#include "algos/training/training_checkpoint.h"
#include "common/mpi_context.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

// The update schedule's state carried across epochs (and checkpoints).
struct OffPolicySchedule {
  long long steps_since_update = 0;  // environment steps of this rank since the last round of updates
  double owed_updates = 0.0;         // the fraction of a gradient step carried to the next round
};

class OffPolicyTrainer {
 public:
  // As OnPolicyTrainer: a new run writes config.yaml and an initial checkpoint; a resumed run loads it.
  OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options);
  // With given environments (tests); `envs` must hold num_envs of them.
  OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options,
                   std::vector<std::unique_ptr<envs::Env>> envs);
  ~OffPolicyTrainer();

  TrainingOutcome run();

  const OffPolicyLearner& learner() const { return *learner_; }
  const ReplayBuffer& buffer() const { return buffer_; }
  int epochs_completed() const { return progress_.epochs_completed; }

 private:
  struct EpochAccounts;
  void run_epoch(int epoch);
  void collect_step(int epoch, int env_index, bool random_action, bool cut, EpochAccounts& accounts);
  void train(int updates, EpochAccounts& accounts);
  void save_checkpoint();
  TrainingSafety training_safety() const;
  void check_finite(int epoch, const char* quantity, double value) const;

  RunConfig config_;
  RunDirectory directory_;
  MpiContext mpi_;
  TrainerOptions options_;
  std::vector<std::unique_ptr<envs::Env>> envs_;
  int observation_size_;
  int action_size_;
  int constraint_count_;   // m: constraints logged (and constrained by the -lag algorithms)
  int critic_cost_count_;  // m for the -lag algorithms, 0 otherwise
  int local_steps_;
  StepCostSelector cost_selector_;
  std::unique_ptr<OffPolicyLearner> learner_;
  std::optional<LagrangeMultipliers> multipliers_;
  std::vector<double> lambdas_;
  ReplayBuffer buffer_;
  ReplayBufferLog buffer_log_;
  std::vector<NStepAccumulator> accumulators_;
  OffPolicySchedule schedule_;
  Rng noise_rng_;
  Rng sample_rng_;
  // per environment: the current observation and the running episode's sums
  std::vector<Eigen::VectorXd> observations_;
  std::vector<double> episode_returns_;
  std::vector<double> episode_costs_;
  std::vector<int> episode_lengths_;
  std::vector<Eigen::VectorXd> episode_constraint_costs_;
  Eigen::VectorXd action_;
  Eigen::VectorXd step_costs_;
  ReplayBatch batch_;
  OffPolicyStepStats step_stats_;
  std::vector<std::int64_t> slots_;
  TrainingProgress progress_;
  std::optional<ProgressCsv> progress_csv_;
  int checkpoint_epochs_ = 0;
  double seconds_this_process_ = 0.0;
  int epochs_this_process_ = 0;
};

}  // namespace bsg::algos
