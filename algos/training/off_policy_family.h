// The off-policy family (docs/algorithms.md#the-off-policy-loop, design.md "Off-policy and offline
// learning"): SAC, TD3, DDPG and their -lag forms. Per epoch k, on every rank:
//   1. reseed the action-noise and batch-sampling streams with (action_noise, rank, k) and
//      (minibatch_shuffle, rank, k); in the first epoch after a checkpoint (and the first of all)
//      restart the rank's num_envs environments with the seeds (environment, rank, k num_envs + j);
//   2. steps_per_epoch / (ranks num_envs) rounds, each stepping every environment once
//      (off_policy_collector.h): uniform random actions while fewer than start_steps environment
//      steps (all ranks) have been taken, else the actor's exploring action; every update_every
//      steps, update_every * updates_per_step gradient steps on sampled batches (the fraction
//      carried over); an epoch that ends with a checkpoint cuts its episodes in its last round;
//      the -lag multipliers step before every such round with multiplier_schedule update_round
//      (off_policy_multipliers.h);
//   3. with multiplier_schedule epoch, one step of the multipliers on the epoch's pooled mean
//      episode costs against the limits;
//   4. the networks checked finite; the run skeleton (trainer.h) logs the epoch
//      (off_policy_epoch_log.h) and saves a checkpoint after save_freq, 2 save_freq, ... epochs.
// After the last epoch: deterministic evaluation episodes (the actor's tanh(mu)), then the same
// episodes with the exploring policy (evaluation.json's "exploring_policy").
//
// Resuming: the checkpoint (off_policy_checkpoint.h) holds the networks, optimisers, temperature,
// multipliers and the update schedule's carry, and every rank's replay buffer is in its append-only
// record (replay_buffer_log.h); with the seeds above a run resumed from a checkpoint the
// uninterrupted run also took (every save_freq epochs) reproduces it exactly. A stop by signal or
// --stop-after saves (and cuts) at its own epoch, where the uninterrupted run did not.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "algos/off_policy/off_policy_learner.h"
#include "algos/off_policy/replay_buffer.h"
#include "algos/training/off_policy_collector.h"
#include "algos/training/off_policy_epoch_log.h"
#include "algos/training/off_policy_multipliers.h"
#include "algos/training/replay_buffer_log.h"
#include "algos/training/run_directory.h"
#include "algos/training/training_family.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

// The update schedule's state carried across epochs (and checkpoints).
struct OffPolicySchedule {
  long long steps_since_update = 0;  // environment steps of this rank since the last round of updates
  double owed_updates = 0.0;         // the fraction of a gradient step carried to the next round
};

class OffPolicyFamily final : public TrainingFamily {
 public:
  // `envs` must hold num_envs environments; each rank's replay buffer record lives in `directory`.
  OffPolicyFamily(const RunConfig& config, const RunDirectory& directory, const MpiContext& mpi,
                  std::vector<std::unique_ptr<envs::Env>> envs);
  ~OffPolicyFamily() override;

  std::string_view epoch_phases() const override { return ""; }
  bool checkpoints_after(int epoch) const override { return (epoch + 1) % config_.save_freq == 0; }
  void start_new_run() override {}
  TrainingProgress load_checkpoint(const std::filesystem::path& path) override;
  void save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) override;
  FamilyEpoch run_epoch(int epoch, bool checkpoint_follows) override;
  std::vector<NamedScalar> progress_row(const EpochAccounts& accounts) override;
  std::vector<std::string> progress_columns() const override { return off_policy_log_columns(log_layout_); }
  EvaluationSummary evaluate(int epochs_completed) override;

  const OffPolicyLearner& learner() const { return *learner_; }
  const ReplayBuffer& buffer() const { return buffer_; }

 private:
  // run_epoch's steps, in order.
  void start_epoch(int epoch);
  void collect_round(int epoch, bool random_action, bool cut, OffPolicyEpochEpisodes& episodes);
  int owed_gradient_steps(bool learning);
  void record_episodes();
  void step_round_multipliers(bool learning);
  void refresh_lambdas();
  void train(int updates);
  std::vector<ConstraintEstimate> update_multipliers(const OffPolicyEpochEpisodes& episodes);
  void check_networks_finite(int epoch);

  RunConfig config_;
  MpiContext mpi_;
  OffPolicyCollector collector_;
  int constraint_count_;   // m: constraints logged (and constrained by the -lag algorithms)
  int critic_cost_count_;  // m for the -lag algorithms, 0 otherwise
  int local_steps_;
  std::unique_ptr<OffPolicyLearner> learner_;
  std::optional<OffPolicyMultipliers> multipliers_;
  std::vector<double> lambdas_;
  ReplayBuffer buffer_;
  ReplayBufferLog buffer_log_;
  OffPolicySchedule schedule_;
  OffPolicyLogLayout log_layout_;
  Rng noise_rng_;
  Rng sample_rng_;
  Eigen::VectorXd action_;
  ReplayBatch batch_;
  OffPolicyStepStats step_stats_;
  std::vector<std::int64_t> slots_;
  // The epoch in progress, kept for its progress.csv row.
  OffPolicyEpochEpisodes epoch_episodes_;
  std::size_t recorded_episodes_ = 0;  // of epoch_episodes_, handed to the multipliers' window
  OffPolicyUpdateTally tally_;
  std::vector<ConstraintEstimate> constraints_;
  long long episode_count_ = 0;
  double collect_seconds_ = 0.0, update_seconds_ = 0.0;
};

}  // namespace bsg::algos
