// The on-policy training loop shared by the nine algorithms (docs/algorithms.md#the-epoch-loop,
// design.md "Learning"). Per epoch k, on every rank:
//   1. sigma_k (docs/algorithms.md#exploration-noise) into the policy;
//   2. collect N = B / R steps from this rank's environment (rollout.h):
//      normalised observations, V and V_C, log-probs, GAE for reward and
//      cost with reward scaling, bootstrap at time-outs and the epoch cut;
//   3. pool the episode statistics over ranks (J_C, L; J_Ci of every
//      constraint with `constraints:`), algorithm.update();
//   4. fit V, and every V_Ci if the algorithm uses them (docs/algorithms.md#value-fits schedule);
//   5. update the observation and return normalisers (last, docs/algorithms.md#the-epoch-loop);
//   6. check that every parameter is finite (and, every check_freq epochs,
//      that the ranks agree), log the epoch (rank 0 writes progress.csv and
//      prints a line), save a checkpoint every save_freq epochs and after the
//      last epoch.
// Advantages enter the update unnormalised (Q6) unless
// use_standardized_advantages is set, and uncentred unless center_advantages is.
// After the last epoch: the deterministic evaluation (evaluation.h) and its files.
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
//
// Errors: non-finite data from the environment, a non-finite loss or a
// non-finite parameter (a non-finite gradient shows in the parameters or the
// Adam moments) throws NonFiniteError naming the quantity and the epoch
// before anything of that epoch is saved, so the last checkpoint stays good.
// Any other error inside an epoch is rethrown as std::runtime_error with the
// epoch prepended.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "algos/core/actor_critic.h"
#include "algos/core/algorithm.h"
#include "algos/core/buffer.h"
#include "algos/core/value_function.h"
#include "algos/training/evaluation.h"
#include "algos/training/epoch_log.h"
#include "algos/training/evaluation_files.h"
#include "algos/training/progress_csv.h"
#include "algos/training/rollout.h"
#include "algos/training/run_directory.h"
#include "algos/training/training_checkpoint.h"
#include "common/mpi_context.h"
#include "common/run_config.h"
#include "envs/env.h"

namespace bsg::algos {

class NonFiniteError : public std::runtime_error {
 public:
  explicit NonFiniteError(const std::string& message) : std::runtime_error(message) {}
};

// The error of a non-finite `quantity` (value `value`) in `epoch`: training
// stops and names the last good checkpoint, which covers `checkpoint_epochs`
// epochs and is kept (both loops, on-policy and off-policy, say it so).
NonFiniteError non_finite_error(int epoch, const char* quantity, double value,
                                const std::filesystem::path& checkpoint, int checkpoint_epochs);

// Runs one epoch of either loop: a NonFiniteError passes through, any other
// error is rethrown as std::runtime_error with the epoch prepended (and
// `phases`, what the epoch does, named for an out-of-memory error).
void run_epoch_naming_errors(int epoch, std::string_view phases, const std::function<void()>& run_epoch);

// Wall-clock seconds of one epoch's phases on this rank (bsg bench --train).
struct EpochTimings {
  int epoch = 0;
  double collect_seconds = 0.0;        // rollout with GAE
  double policy_update_seconds = 0.0;  // algorithm.update(): gradients, CG with Fisher products, line search
  double value_fit_seconds = 0.0;      // V and V_C fits
  double update_seconds = 0.0;         // everything after the rollout (policy, value fits, normalisers, checks)
  double total_seconds = 0.0;          // the whole epoch before logging and saving
  // Processor time of the process over the same spans: on a machine shared
  // with other jobs, wall time includes waiting for a core, this does not.
  double update_cpu_seconds = 0.0;
  double total_cpu_seconds = 0.0;
};

struct TrainerOptions {
  bool resume = false;          // continue from the directory's checkpoint
  int stop_after_epochs = 0;    // > 0: stop (with a checkpoint) once this many epochs are done
  std::ostream* log = nullptr;  // progress lines on rank 0; null: quiet
  // Asked on every rank after each epoch (a collective point: it must give
  // every rank the same answer); true: save a checkpoint and stop there, as
  // stop_after_epochs does. `bsg train` stops on SIGTERM / SIGINT this way.
  std::function<bool()> stop_requested;
  std::function<void(const EpochTimings&)> on_epoch_timed;  // called on every rank after each epoch; may be empty
};

struct TrainingOutcome {
  int epochs_completed = 0;
  bool finished = false;                      // all epochs done
  bool stop_requested = false;                // stopped early by options.stop_requested
  std::optional<EvaluationSummary> evaluation;  // rank 0, if evaluated
};

class OnPolicyTrainer {
 public:
  // A new run writes config.yaml and an initial checkpoint into `directory`
  // (which must not hold a run); a resumed run loads the checkpoint, which
  // must match `config`.
  OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options);
  // The same with a given environment instead of envs::make(config.env_id)
  // (tests use scripted environments).
  OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options,
                  std::unique_ptr<envs::Env> env);
  ~OnPolicyTrainer();

  TrainingOutcome run();

  const ActorCritic& actor_critic() const { return *actor_critic_; }
  const OnPolicyAlgorithm& algorithm() const { return *algorithm_; }
  int epochs_completed() const { return progress_.epochs_completed; }

 private:
  // The clock readings of one epoch, for the timings hook and the log.
  struct EpochClock {
    std::chrono::steady_clock::time_point epoch_start;
    double epoch_cpu_start = 0.0;
    double collect_seconds = 0.0;
    double policy_update_seconds = 0.0;
    double value_fit_seconds = 0.0;
    double update_seconds = 0.0;  // policy update, value fits and normalisers
    double update_cpu_seconds = 0.0;
  };
  // What the policy step of an epoch leaves for the log.
  struct EpochPolicyStep {
    EpisodeStatistics episodes;                   // this epoch's completed episodes, pooled over ranks
    std::vector<ConstraintEstimate> constraints;  // J_Ci and d_i, as the update saw them
    PolicyUpdateResult update;
  };

  void run_epoch(int epoch);
  // run_epoch's steps, in order (docs/algorithms.md#the-epoch-loop).
  void set_exploration_noise(int epoch);
  void collect_rollout(int epoch);
  EpochPolicyStep update_policy(int epoch, EpochClock& clock);
  std::vector<ValueFitStats> fit_values(int epoch, EpochClock& clock);  // V first, then each V_Ci trained
  void update_normalizers(int epoch);
  void record_epoch(int epoch, const EpochPolicyStep& policy_step, const std::vector<ValueFitStats>& fits,
                    const EpochClock& clock);
  void check_rollout_finite(int epoch) const;
  void check_finite(int epoch, const char* quantity, double value) const;
  void check_parameters_finite(int epoch) const;
  void check_ranks_agree(int epoch) const;
  void save_checkpoint();
  // On resume: a note when build.txt names another build (another compiler,
  // Eigen or vector instruction set), whose numbers differ.
  void note_another_build() const;
  TrainingSafety training_safety() const;  // what evaluation.json reports of the training

  RunConfig config_;
  RunDirectory directory_;
  MpiContext mpi_;
  TrainerOptions options_;
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
  TrainingProgress progress_;
  std::optional<ProgressCsv> progress_csv_;  // rank 0
  int checkpoint_epochs_ = 0;  // epochs covered by the last checkpoint saved or loaded
  double seconds_this_process_ = 0.0;
  int epochs_this_process_ = 0;
};

}  // namespace bsg::algos
