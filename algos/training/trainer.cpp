#include "algos/training/trainer.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>
#include <limits>
#include <new>
#include <ostream>

#include "algos/training/evaluation_files.h"
#include "algos/training/progress_csv_fields.h"
#include "algos/training/progress_line.h"
#include "common/atomic_file.h"
#include "common/build_identity.h"
#include "common/checkpoint_file.h"
#include "common/file_reading.h"
#include "common/message_text.h"
#include "common/run_config_checks.h"
#include "common/run_config_yaml.h"

namespace bsg::algos {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

std::unique_ptr<TrainingFamily> checked_family(std::unique_ptr<TrainingFamily> family) {
  if (family == nullptr) throw std::invalid_argument("Trainer: no family of learners");
  return family;
}

}  // namespace

NonFiniteError non_finite_error(int epoch, const char* quantity, double value,
                                const std::filesystem::path& checkpoint, int checkpoint_epochs) {
  return NonFiniteError(std::string("non-finite ") + quantity + " (" + std::to_string(value) + ") in epoch " +
                        std::to_string(epoch) + "; training stopped, the last good checkpoint " +
                        checkpoint.string() + " (after " + std::to_string(checkpoint_epochs) + " epochs) is kept");
}

void run_epoch_naming_errors(int epoch, std::string_view phases, const std::function<void()>& run_epoch) {
  try {
    run_epoch();
  } catch (const NonFiniteError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("epoch " + std::to_string(epoch) + ": out of memory (std::bad_alloc)" +
                             (phases.empty() ? std::string() : " during " + std::string(phases)));
  } catch (const std::exception& e) {
    throw std::runtime_error("epoch " + std::to_string(epoch) + ": " + e.what());
  }
}

const CheckpointMark& TrainingFamily::checkpoint_mark() const {
  if (checkpoint_mark_ == nullptr) throw std::logic_error("TrainingFamily: used outside a Trainer");
  return *checkpoint_mark_;
}

void TrainingFamily::check_finite(int epoch, const char* quantity, double value) const {
  if (!std::isfinite(value)) {
    const CheckpointMark& mark = checkpoint_mark();
    throw non_finite_error(epoch, quantity, value, mark.path, mark.epochs);
  }
}

Trainer::Trainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi, TrainerOptions options,
                 std::unique_ptr<TrainingFamily> family)
    : config_(config),
      directory_(std::move(directory)),
      mpi_(mpi),
      options_(std::move(options)),
      family_(checked_family(std::move(family))) {
  check_run_config_for_ranks(config_, mpi_.size());
  checkpoint_.path = directory_.checkpoint();
  family_->show_checkpoint(checkpoint_);
  progress_.num_ranks = mpi_.size();
  progress_.training_cost = TrainingCost::for_constraints(constraint_count(config_));
  if (options_.resume) {
    resume();
  } else {
    start_new_run();
  }
}

Trainer::~Trainer() = default;

std::ostream& Trainer::notes() const { return options_.log != nullptr ? *options_.log : std::cerr; }

void Trainer::start_new_run() {
  family_->start_new_run();  // docs/algorithms.md#set-up, step 5 (on-policy: the parameters from rank 0)
  if (mpi_.is_root()) {
    prepare_new_run_directory(directory_);
    write_run_config(config_, directory_.config());
    write_file_atomically(directory_.build(), to_text(this_build()));
    progress_csv_.emplace(ProgressCsv::create(directory_.progress()));
    if (config_.tensorboard) events_.emplace(directory_.root);
  }
  mpi_.sum(0.0);      // the directory exists before any rank writes into it
  save_checkpoint();  // docs/algorithms.md#set-up, step 7: the initial model
}

void Trainer::resume() {
  const TrainingProgress saved = family_->load_checkpoint(directory_.checkpoint());
  if (saved.num_ranks != mpi_.size()) {
    if (mpi_.is_root() && options_.log != nullptr) {
      *options_.log << "note: the checkpoint was written by a run with " << saved.num_ranks
                    << " ranks, this one has " << mpi_.size()
                    << "; training continues but will not reproduce the original rank count's numbers\n";
    }
  }
  check_progress_columns(saved);
  if (mpi_.is_root()) note_another_build();
  progress_.epochs_completed = saved.epochs_completed;
  progress_.elapsed_seconds = saved.elapsed_seconds;
  // A checkpoint written before the training cost existed keeps the sums at 0.
  if (!saved.training_cost.constraint_cumulative_costs.empty()) progress_.training_cost = saved.training_cost;
  checkpoint_.epochs = saved.epochs_completed;
  if (mpi_.is_root()) {
    report_stale_temporaries();
    progress_csv_.emplace(ProgressCsv::resume(
        directory_.progress(), ProgressResume{saved.epochs_completed, saved.progress_log, config_.steps_per_epoch,
                                              &notes()}));
    if (config_.tensorboard) {
      // The event file mirrors progress.csv: the kept rows anew, the later ones as they come.
      remove_event_files(directory_.root);
      events_.emplace(directory_.root);
      events_->write_progress_log(progress_csv_->contents());
    }
  }
}

// The checkpoint's progress log must have the columns this run writes: a header with any other
// column, missing or renamed, was not written by a run of this config and family.
void Trainer::check_progress_columns(const TrainingProgress& saved) const {
  if (!saved.progress_log || saved.progress_log->empty()) return;
  const std::string& log = *saved.progress_log;
  const std::vector<std::string> columns = split_csv_line(log.substr(0, log.find('\n')));
  const std::vector<std::string> expected = family_->progress_columns();
  for (std::size_t i = 0; i < std::max(columns.size(), expected.size()); ++i) {
    const std::string got = i < columns.size() ? columns[i] : "(none)";
    const std::string want = i < expected.size() ? expected[i] : "(none)";
    if (got != want) {
      throw CheckpointError(directory_.checkpoint().string() + ": its progress log's column " + std::to_string(i + 1) +
                            " is " + printable_excerpt(got) + ", this run writes " + want);
    }
  }
}

// A write killed half-way (SIGKILL, a lost node) leaves its temporary behind; the target is intact.
void Trainer::report_stale_temporaries() const {
  const std::vector<std::filesystem::path> stale = remove_stale_temporaries(directory_.root);
  if (!stale.empty() && options_.log != nullptr) {
    *options_.log << "removed " << stale.size() << " stale temporary file" << (stale.size() == 1 ? "" : "s")
                  << " left by interrupted writes in " << directory_.root.string() << " (first: "
                  << stale.front().filename().string() << ")\n";
  }
}

// On resume: a note when build.txt names another build (another compiler, Eigen or vector
// instruction set), whose numbers differ.
void Trainer::note_another_build() const {
  // Runs started before builds were recorded have no build.txt: nothing to compare.
  if (!std::filesystem::exists(directory_.build())) return;
  const std::optional<BuildIdentity> recorded = parse_build_identity(read_regular_file(directory_.build(), "build record"));
  std::ostream& out = notes();
  if (!recorded) {
    out << "note: " << directory_.build().string() << " is not a build record this version reads; "
        << "cannot tell whether this build computes the same numbers as the one that started the run\n";
    return;
  }
  const std::string difference = describe_difference(*recorded, this_build());
  if (!difference.empty()) {
    out << "note: the run was started by another build (" << difference
        << "); training continues but the remaining epochs will not be bit-identical to an uninterrupted run "
           "(docs/reproducibility.md)\n";
  }
}

TrainingSafety Trainer::training_safety() const {
  return TrainingSafety{effective_constraints(config_), progress_.training_cost,
                        static_cast<long long>(progress_.epochs_completed) * config_.steps_per_epoch};
}

void Trainer::save_checkpoint() {
  // docs/reproducing.md#run-directory: the rows are restorable from the checkpoint.
  if (mpi_.is_root()) progress_.progress_log = progress_csv_->contents();
  family_->save_checkpoint(directory_.checkpoint(), progress_);
  checkpoint_.epochs = progress_.epochs_completed;
}

void Trainer::run_epoch(int epoch) {
  const auto epoch_start = Clock::now();
  const double epoch_cpu_start = process_cpu_seconds();
  const bool last = epoch == config_.epochs - 1;
  const bool stopping = options_.stop_after_epochs > 0 && epoch + 1 >= options_.stop_after_epochs;
  const bool saves = family_->checkpoints_after(epoch) || last || stopping;
  const FamilyEpoch result = family_->run_epoch(epoch, saves);
  record_epoch(epoch, result, seconds_since(epoch_start), process_cpu_seconds() - epoch_cpu_start);
  if (saves) save_checkpoint();
}

// The epoch's accounts: the timings hook, the training cost, the progress.csv row and line.
void Trainer::record_epoch(int epoch, const FamilyEpoch& result, double epoch_seconds, double epoch_cpu_seconds) {
  if (options_.on_epoch_timed) {
    EpochTimings timings = result.timings;
    timings.epoch = epoch;
    timings.total_seconds = epoch_seconds;
    timings.total_cpu_seconds = epoch_cpu_seconds;
    options_.on_epoch_timed(timings);
  }
  progress_.epochs_completed = epoch + 1;
  progress_.elapsed_seconds += epoch_seconds;
  progress_.training_cost.add_epoch(result.epoch_cost, result.epoch_constraint_costs, result.constraints);
  if (result.paces_later_epochs) {
    pacing_seconds_this_process_ += epoch_seconds;
    ++pacing_epochs_this_process_;
  }

  const std::vector<NamedScalar> row =
      family_->progress_row(EpochAccounts{epoch, epoch_seconds, progress_.elapsed_seconds, &progress_.training_cost});
  if (!mpi_.is_root()) return;
  progress_csv_->write_row(row);
  if (events_) events_->write_scalars(epoch, row);
  if (options_.on_progress_row) options_.on_progress_row(epoch, row);
  if (options_.log == nullptr) return;
  ProgressLineInputs line = result.line;
  line.epoch = epoch;
  line.epochs = config_.epochs;
  line.epoch_seconds = epoch_seconds;
  const int epochs_left = config_.epochs - epoch - 1;
  if (epochs_left == 0) {
    line.eta_seconds = 0.0;
  } else if (pacing_epochs_this_process_ > 0) {
    line.eta_seconds = pacing_seconds_this_process_ / pacing_epochs_this_process_ * epochs_left;
  }
  *options_.log << format_progress_line(line) << std::endl;
}

TrainingOutcome Trainer::run() {
  TrainingOutcome outcome;
  for (int epoch = progress_.epochs_completed; epoch < config_.epochs; ++epoch) {
    if (options_.stop_after_epochs > 0 && progress_.epochs_completed >= options_.stop_after_epochs) break;
    run_epoch_naming_errors(epoch, family_->epoch_phases(), [&] { run_epoch(epoch); });
    if (options_.stop_requested && progress_.epochs_completed < config_.epochs && options_.stop_requested()) {
      if (checkpoint_.epochs != progress_.epochs_completed) save_checkpoint();
      outcome.stop_requested = true;
      break;
    }
  }
  outcome.epochs_completed = progress_.epochs_completed;
  outcome.finished = progress_.epochs_completed == config_.epochs;
  if (outcome.finished) finish(outcome);
  return outcome;
}

// The evaluation after the last epoch (docs/reproducing.md#evaluation) and its files.
void Trainer::finish(TrainingOutcome& outcome) {
  if (config_.eval_episodes / mpi_.size() == 0) {
    // No evaluation episodes: the run is still finished, and evaluation.json
    // says so (0 episodes, null J and H), because sweeps, `bsg sweep --status`
    // and resume take that file as the mark of a finished run.
    if (mpi_.is_root()) {
      constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
      const TrainingSafety safety = training_safety();
      write_evaluation_files(directory_,
                             EvaluationSummary{{}, kNone, kNone, kNone, std::vector<double>(safety.constraints.size(), kNone)},
                             &safety);
      if (options_.log != nullptr) {
        *options_.log << "evaluation skipped (eval_episodes = " << config_.eval_episodes << " for " << mpi_.size()
                      << (mpi_.size() == 1 ? " rank" : " ranks") << "): evaluation.json records 0 episodes"
                      << std::endl;
      }
    }
    return;
  }
  EvaluationSummary summary = family_->evaluate(progress_.epochs_completed);
  if (!mpi_.is_root()) return;
  const TrainingSafety safety = training_safety();
  write_evaluation_files(directory_, summary, &safety);
  if (options_.log != nullptr) {
    *options_.log << "evaluation: " << summary.episodes.size() << " episodes  J (mean return) "
                  << format_csv_number(summary.mean_return) << "  H (mean cost) "
                  << format_csv_number(summary.mean_cost) << "  mean length " << format_csv_number(summary.mean_length)
                  << std::endl;
  }
  outcome.evaluation = std::move(summary);
}

}  // namespace bsg::algos
