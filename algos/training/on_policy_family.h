// The on-policy family (docs/algorithms.md#the-epoch-loop, design.md "Learning"): the trust-region
// and first-order algorithms. Per epoch k, on every rank:
//   1. sigma_k (docs/algorithms.md#exploration-noise) into the policy;
//   2. collect N = B / R steps from this rank's environment (rollout.h):
//      normalised observations, V and V_C, log-probs, GAE for reward and
//      cost with reward scaling, bootstrap at time-outs and the epoch cut;
//   3. pool the episode statistics over ranks (J_C, L; J_Ci of every
//      constraint with `constraints:`), algorithm.update();
//   4. fit V, and every V_Ci if the algorithm uses them (docs/algorithms.md#value-fits schedule);
//   5. update the observation and return normalisers (last, docs/algorithms.md#the-epoch-loop);
//   6. check that every parameter is finite (and, every check_freq epochs,
//      that the ranks agree); the run skeleton (trainer.h) then logs the epoch and saves a
//      checkpoint after epochs 0, save_freq, 2 save_freq, ... and the last.
// Advantages enter the update unnormalised (Q6) unless
// use_standardized_advantages is set, and uncentred unless center_advantages is.
// After the last epoch: the deterministic evaluation (evaluation.h).
//
// Seeding (common/seeding.h, derive_seed(run seed, stream, rank, index)):
//   network init     (network_init, rank 0, 0) on every rank, then the
//                    parameters are broadcast from rank 0 anyway;
//   environment      (environment, rank, k): reset at the start of epoch k;
//   action noise     (action_noise, rank, k): reseeded at the start of epoch k;
//   V/V_C shuffles   (minibatch_shuffle, rank, k): reseeded likewise;
//   evaluation env   (evaluation_environment, rank, 0).
// Each epoch's randomness is thus a function of (seed, rank, k) only, and a
// run resumed from a checkpoint taken after epoch k reproduces an
// uninterrupted run with the same seed and rank count exactly. (The
// original seeds one stream per rank with seed + 10000 rank; a run therefore
// does not reproduce the original's random numbers, only its statistics.)
#pragma once

#include <memory>
#include <vector>

#include "algos/core/actor_critic.h"
#include "algos/core/algorithm.h"
#include "algos/core/buffer.h"
#include "algos/core/value_function.h"
#include "algos/training/epoch_log.h"
#include "algos/training/rollout.h"
#include "algos/training/training_family.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

class OnPolicyFamily final : public TrainingFamily {
 public:
  // Builds the actor-critic and the algorithm of `config` for `env` (checked: not null, non-empty spaces).
  OnPolicyFamily(const RunConfig& config, const MpiContext& mpi, std::unique_ptr<envs::Env> env);
  ~OnPolicyFamily() override;

  std::string_view epoch_phases() const override { return "the epoch's rollout, update or value fits"; }
  bool checkpoints_after(int epoch) const override { return epoch % config_.save_freq == 0; }
  void start_new_run() override;
  TrainingProgress load_checkpoint(const std::filesystem::path& path) override;
  void save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) override;
  FamilyEpoch run_epoch(int epoch, bool checkpoint_follows) override;
  std::vector<NamedScalar> progress_row(const EpochAccounts& accounts) override;
  std::vector<std::string> progress_columns() const override;
  EvaluationSummary evaluate(int epochs_completed) override;

  const ActorCritic& actor_critic() const { return *actor_critic_; }
  const OnPolicyAlgorithm& algorithm() const { return *algorithm_; }

 private:
  // What the policy step of an epoch leaves for the log.
  struct EpochPolicyStep {
    EpisodeStatistics episodes;                   // this epoch's completed episodes, pooled over ranks
    std::vector<ConstraintEstimate> constraints;  // J_Ci and d_i, as the update saw them
    PolicyUpdateResult update;
  };

  // run_epoch's steps, in order (docs/algorithms.md#the-epoch-loop).
  void set_exploration_noise(int epoch);
  void collect_rollout(int epoch);
  EpochPolicyStep update_policy(int epoch, EpochTimings& timings);
  std::vector<ValueFitStats> fit_values(int epoch, EpochTimings& timings);  // V first, then each V_Ci trained
  void update_normalizers(int epoch);
  FamilyEpoch epoch_result(const EpochTimings& timings);
  void check_rollout_finite(int epoch) const;
  void check_parameters_finite(int epoch) const;
  void check_ranks_agree(int epoch) const;

  RunConfig config_;
  MpiContext mpi_;
  std::unique_ptr<envs::Env> env_;
  std::unique_ptr<ActorCritic> actor_critic_;
  std::unique_ptr<OnPolicyAlgorithm> algorithm_;
  int local_steps_;  // this rank's steps per epoch: steps_per_epoch / ranks
  Buffer buffer_;
  RolloutCollector collector_;
  Eigen::MatrixXd normalized_observations_;
  Eigen::MatrixXd value_inputs_;  // normalized_observations_ and the time left (value_time_input only)
  Eigen::MatrixXd returns_column_;
  Eigen::VectorXd advantages_;       // A_t as the update sees them (copy, optionally standardised or centred)
  Eigen::MatrixXd cost_advantages_;  // A^Ci_t likewise, one column per constraint
  Rng noise_rng_;
  Rng shuffle_rng_;
  // The last epoch's step and fits, kept for its progress.csv row.
  EpochPolicyStep last_step_;
  std::vector<ValueFitStats> last_fits_;
  EpochTimings last_timings_;
};

}  // namespace bsg::algos
