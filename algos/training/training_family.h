// What a family of learners supplies to the run skeleton (trainer.h, design.md "Families and the
// run skeleton"): its epoch, its state for the checkpoint, its progress.csv columns and its final
// evaluation. The skeleton does everything else once for every family: new run or resume, the
// accounts of every epoch (training cost, time), progress.csv and the progress line, the checkpoint
// cadence, stop signals, the error naming and the evaluation files. The on-policy family is
// on_policy_family.h, the off-policy one off_policy_family.h.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/training/evaluation.h"
#include "algos/training/progress_line.h"
#include "algos/training/training_checkpoint.h"
#include "algos/training/training_cost.h"

namespace bsg::algos {

// Wall-clock seconds of one epoch's phases on this rank (bsg bench --train).
struct EpochTimings {
  int epoch = 0;
  double collect_seconds = 0.0;        // rollout with GAE (on-policy), environment steps (off-policy)
  double policy_update_seconds = 0.0;  // the policy update (off-policy: every gradient step)
  double value_fit_seconds = 0.0;      // V and V_C fits (on-policy)
  double update_seconds = 0.0;         // everything after the rollout (policy, value fits, normalisers, checks)
  double total_seconds = 0.0;          // the whole epoch before logging and saving
  // Processor time of the process over the same spans: on a machine shared
  // with other jobs, wall time includes waiting for a core, this does not.
  double update_cpu_seconds = 0.0;
  double total_cpu_seconds = 0.0;
};

// The last checkpoint as the skeleton knows it: where it is and how many epochs it covers. A family
// reads it to name the checkpoint that stays good when an epoch fails (check_finite), and the
// off-policy family to restart its environments after every checkpoint.
struct CheckpointMark {
  std::filesystem::path path;
  int epochs = 0;
};

// What one epoch of a family leaves for the skeleton's accounts. Collective values are the same on
// every rank.
struct FamilyEpoch {
  double epoch_cost = 0.0;                      // the environment's cost over every step, all ranks
  Eigen::VectorXd epoch_constraint_costs;       // each constraint's, all ranks
  std::vector<ConstraintEstimate> constraints;  // J_Ci and d_i of this epoch's episodes
  ProgressLineInputs line;                      // mean return, cost, limit, lambda, KL; the skeleton adds the rest
  EpochTimings timings;                         // the family's phases; the skeleton adds epoch and totals
  // Whether this epoch's time predicts the later epochs' (the ETA counts only such epochs): false
  // for an off-policy epoch that began before start_steps, whose random steps take no gradient steps.
  bool paces_later_epochs = true;
};

// What the skeleton knows after an epoch's accounts, for the progress.csv row.
struct EpochAccounts {
  int epoch = 0;
  double epoch_seconds = 0.0;            // this epoch, this process
  double elapsed_seconds = 0.0;          // training seconds since the run started (time_s)
  const TrainingCost* training_cost = nullptr;  // after this epoch
};

class TrainingFamily {
 public:
  virtual ~TrainingFamily() = default;

  // What an epoch does, named in an out-of-memory error ("" for nothing).
  virtual std::string_view epoch_phases() const = 0;
  // Whether the epoch after `epoch` follows a periodic checkpoint (save_freq): the on-policy loop
  // saves after epochs 0, save_freq, 2 save_freq, ... as the original does; the off-policy loop
  // after save_freq, 2 save_freq, ... epochs. The skeleton adds the last epoch and a stop.
  virtual bool checkpoints_after(int epoch) const = 0;

  // A new run, before the run directory is written (collective).
  virtual void start_new_run() = 0;
  // Restores the family's state from `path`; returns the run's progress (collective). A family
  // that cannot continue with another rank count throws CheckpointError saying why; the skeleton
  // notes the change for the others.
  virtual TrainingProgress load_checkpoint(const std::filesystem::path& path) = 0;
  // Writes the checkpoint with `progress` (collective; which ranks write is the family's affair).
  virtual void save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) = 0;

  // One epoch (collective). `checkpoint_follows`: a checkpoint is saved after it.
  virtual FamilyEpoch run_epoch(int epoch, bool checkpoint_follows) = 0;
  // The epoch's progress.csv row (collective; every rank gets it), after run_epoch.
  virtual std::vector<NamedScalar> progress_row(const EpochAccounts& accounts) = 0;
  // The row's column names, which a resumed progress.csv must have.
  virtual std::vector<std::string> progress_columns() const = 0;

  // The final evaluation after the last epoch (collective; the summary on rank 0).
  virtual EvaluationSummary evaluate(int epochs_completed) = 0;

  // The skeleton shows its last checkpoint to the family before anything runs.
  void show_checkpoint(const CheckpointMark& mark) { checkpoint_mark_ = &mark; }

 protected:
  const CheckpointMark& checkpoint_mark() const;
  // Throws NonFiniteError (trainer.h) naming `quantity`, `epoch` and the kept checkpoint if `value`
  // is not finite.
  void check_finite(int epoch, const char* quantity, double value) const;

 private:
  const CheckpointMark* checkpoint_mark_ = nullptr;
};

}  // namespace bsg::algos
