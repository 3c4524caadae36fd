// The offline family (docs/datasets.md#offline-runs, design.md "Off-policy and offline learning"):
// BC-All and BC-Safe, and any later algorithm over algos/offline/offline_algorithm.h. It learns from
// the HDF5 file named by `dataset:` (DSRL's layout) and steps an environment only to evaluate.
//
// Set-up: the dataset is read and checked against the run (its env_id and environment description,
// when it records them, must be the run's; its observation and action sizes the environment's); the
// algorithm's training rows (offline_training_rows) give the observation standardisation; the
// network is drawn from the stream (network_init, 0, 0). DSRL's normalisation constants are the
// file's min_episode_reward and max_episode_reward attributes, or the dataset's episodes' extremes.
//
// Epoch k: the batch stream is reseeded with (minibatch_shuffle, 0, k); updates_per_epoch gradient
// steps, each on batch_size rows drawn uniformly with replacement; after every eval_every-th epoch and
// the last, eval_episodes episodes of the policy's action online (evaluation.h, the same seeds as the
// final evaluation), scored with DSRL's normalised reward and cost (normalized_score.h). Its
// progress.csv row: epoch, updates (so far), loss (the mean over the epoch's steps), eval_return,
// eval_cost, eval_length, normalized_reward, normalized_cost (nan in epochs without an evaluation),
// time_update_s, time_s. No environment step is taken while learning: the training cost stays 0.
//
// Checkpoint (checkpoint.bin, rank 0): the run header (run_header.h, RunHeaderLayout::offline), the
// training cost and the algorithm's state (networks, Adam, standardisation). With the per-epoch
// seeds above, a run resumed from any checkpoint reproduces the uninterrupted run exactly.
//
// MPI: an offline run trains on one rank (check_run_config_for_ranks refuses more, saying why).
#pragma once

#include <memory>
#include <optional>

#include "algos/core/constraint_costs.h"
#include "algos/offline/offline_algorithm.h"
#include "algos/offline/offline_batches.h"
#include "algos/offline/offline_dataset.h"
#include "algos/training/training_family.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

// The online evaluation of one epoch, scored.
struct OfflineEpochEvaluation {
  double mean_return = 0.0;
  double mean_cost = 0.0;
  double mean_length = 0.0;
  double normalized_reward = 0.0;
  double normalized_cost = 0.0;
};

class OfflineFamily final : public TrainingFamily {
 public:
  // Throws std::invalid_argument (or the file's error) naming what does not fit.
  OfflineFamily(const RunConfig& config, const MpiContext& mpi, std::unique_ptr<envs::Env> env);
  ~OfflineFamily() override;

  std::string_view epoch_phases() const override { return "offline gradient steps and evaluation"; }
  bool checkpoints_after(int epoch) const override { return (epoch + 1) % config_.save_freq == 0; }
  void start_new_run() override {}
  TrainingProgress load_checkpoint(const std::filesystem::path& path) override;
  void save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) override;
  FamilyEpoch run_epoch(int epoch, bool checkpoint_follows) override;
  std::vector<NamedScalar> progress_row(const EpochAccounts& accounts) override;
  std::vector<std::string> progress_columns() const override;
  EvaluationSummary evaluate(int epochs_completed) override;

  const OfflineAlgorithm& algorithm() const { return *algorithm_; }
  const OfflineDataset& dataset() const { return dataset_; }
  const TrainingRows& training_rows() const { return batches_->rows(); }

 private:
  OfflineEpochEvaluation evaluate_epoch();

  RunConfig config_;
  MpiContext mpi_;
  std::unique_ptr<envs::Env> env_;
  StepCostSelector costs_;
  OfflineDataset dataset_;
  double min_episode_reward_ = 0.0;
  double max_episode_reward_ = 0.0;
  std::optional<OfflineBatches> batches_;
  std::unique_ptr<OfflineAlgorithm> algorithm_;
  Rng sample_rng_;
  OfflineBatch batch_;
  // The epoch in progress, kept for its progress.csv row.
  double loss_ = 0.0;
  std::optional<OfflineEpochEvaluation> evaluation_;
  double update_seconds_ = 0.0;
};

// Loads the algorithm's state from an offline checkpoint (bsg eval, bsg collect); returns the
// progress. Throws CheckpointError naming the file if it is missing, corrupt, not an offline
// checkpoint or written for another configuration.
TrainingProgress load_offline_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                         OfflineAlgorithm& algorithm);

}  // namespace bsg::algos
