// The run skeleton shared by every family of learners (design.md "Families and the run skeleton";
// docs/algorithms.md#the-run-skeleton), written once:
//   new run: config.yaml, build.txt, an empty progress.csv and the initial checkpoint;
//   resume:  the checkpoint restores the family and the progress; notes when another build or rank
//            count wrote it (or a refusal, for a family that cannot change rank count), stale
//            temporaries of interrupted writes removed and reported, progress.csv checked and
//            trimmed to the checkpoint's epochs;
//   each epoch: the family's epoch, then the accounts (training cost, time), the progress.csv row
//            and the progress line (rank 0), a checkpoint at the family's cadence, after the last
//            epoch and on a stop; stop signals honoured between epochs;
//   after the last epoch: the family's evaluation and evaluation.json / returns.csv / costs.csv.
// A family (training_family.h) supplies its epoch, its state and its evaluation; make_trainer.h
// chooses the family from the config.
//
// Errors: non-finite data or parameters throw NonFiniteError naming the quantity and the epoch
// before anything of that epoch is saved, so the last checkpoint stays good. Any other error
// inside an epoch is rethrown as std::runtime_error with the epoch prepended.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "algos/training/evaluation.h"
#include "algos/training/evaluation_files.h"
#include "algos/training/event_file.h"
#include "algos/training/progress_csv.h"
#include "algos/training/run_directory.h"
#include "algos/training/training_checkpoint.h"
#include "algos/training/training_family.h"
#include "common/mpi_context.h"
#include "common/run_config.h"

namespace bsg::algos {

class NonFiniteError : public std::runtime_error {
 public:
  explicit NonFiniteError(const std::string& message) : std::runtime_error(message) {}
};

// The error of a non-finite `quantity` (value `value`) in `epoch`: training
// stops and names the last good checkpoint, which covers `checkpoint_epochs`
// epochs and is kept.
NonFiniteError non_finite_error(int epoch, const char* quantity, double value,
                                const std::filesystem::path& checkpoint, int checkpoint_epochs);

// Runs one epoch: a NonFiniteError passes through, any other error is rethrown as
// std::runtime_error with the epoch prepended (and `phases`, what the epoch does, named for an
// out-of-memory error).
void run_epoch_naming_errors(int epoch, std::string_view phases, const std::function<void()>& run_epoch);

struct TrainerOptions {
  bool resume = false;          // continue from the directory's checkpoint
  int stop_after_epochs = 0;    // > 0: stop (with a checkpoint) once this many epochs are done
  std::ostream* log = nullptr;  // progress lines on rank 0; null: quiet
  // Asked on every rank after each epoch (a collective point: it must give
  // every rank the same answer); true: save a checkpoint and stop there, as
  // stop_after_epochs does. `bsg train` stops on SIGTERM / SIGINT this way.
  std::function<bool()> stop_requested;
  std::function<void(const EpochTimings&)> on_epoch_timed;  // called on every rank after each epoch; may be empty
  // Called on rank 0 with each epoch's progress.csv row, after it is written (bsg.train's
  // callback); may be empty.
  std::function<void(int epoch, const std::vector<NamedScalar>& row)> on_progress_row;
};

struct TrainingOutcome {
  int epochs_completed = 0;
  bool finished = false;                      // all epochs done
  bool stop_requested = false;                // stopped early by options.stop_requested
  std::optional<EvaluationSummary> evaluation;  // rank 0, if evaluated
};

class Trainer {
 public:
  // A new run writes config.yaml and an initial checkpoint into `directory`
  // (which must not hold a run); a resumed run loads the checkpoint, which
  // must match `config`.
  Trainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options,
          std::unique_ptr<TrainingFamily> family);
  virtual ~Trainer();
  Trainer(const Trainer&) = delete;
  Trainer& operator=(const Trainer&) = delete;

  TrainingOutcome run();

  int epochs_completed() const { return progress_.epochs_completed; }
  const TrainingFamily& family() const { return *family_; }

 private:
  void start_new_run();
  void resume();
  void run_epoch(int epoch);
  void record_epoch(int epoch, const FamilyEpoch& result, double epoch_seconds, double epoch_cpu_seconds);
  void save_checkpoint();
  void finish(TrainingOutcome& outcome);
  void note_another_build() const;
  void report_stale_temporaries() const;
  void check_progress_columns(const TrainingProgress& saved) const;
  TrainingSafety training_safety() const;  // what evaluation.json reports of the training
  std::ostream& notes() const;             // options_.log, or std::cerr when quiet

  RunConfig config_;
  RunDirectory directory_;
  MpiContext mpi_;
  TrainerOptions options_;
  std::unique_ptr<TrainingFamily> family_;
  TrainingProgress progress_;
  std::optional<ProgressCsv> progress_csv_;  // rank 0
  std::optional<EventFile> events_;          // rank 0, with the key tensorboard
  CheckpointMark checkpoint_;                // the last checkpoint saved or loaded
  // The epochs of this process that pace the later ones (FamilyEpoch::paces_later_epochs), for the ETA.
  double pacing_seconds_this_process_ = 0.0;
  int pacing_epochs_this_process_ = 0;
};

}  // namespace bsg::algos
