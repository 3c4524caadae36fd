// The run skeleton (algos/training/trainer.h) with a counting family that neither learns nor steps
// an environment: which epochs it checkpoints after, what progress.csv and the training cost
// accounts hold (summed by hand here), how a resume continues, stops, and refuses a foreign log.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/trainer.h"
#include "common/atomic_file.h"
#include "common/checkpoint_file.h"

namespace {

namespace fs = std::filesystem;
using bsg::algos::CheckpointMark;
using bsg::algos::EpochAccounts;
using bsg::algos::EvaluationSummary;
using bsg::algos::FamilyEpoch;
using bsg::algos::NamedScalar;
using bsg::algos::TrainingProgress;
using bsg::testing::read_csv_columns;
using bsg::testing::TemporaryDirectory;

// What the skeleton asked of the family, in order.
struct FamilyCalls {
  std::vector<int> epochs_run;
  std::vector<int> checkpoints;  // epochs completed at each save
  std::vector<bool> checkpoint_follows;
  int evaluations = 0;
};

// Epoch k costs k + 1 (constraint 1 the same), has J_C = 10 k against d = 25 and a row (epoch, k^2).
class CountingFamily final : public bsg::algos::TrainingFamily {
 public:
  CountingFamily(FamilyCalls& calls, std::vector<std::string> columns = {"epoch", "square"})
      : calls_(calls), columns_(std::move(columns)) {}

  std::string_view epoch_phases() const override { return "counting"; }
  bool checkpoints_after(int epoch) const override { return epoch % 3 == 0; }
  void start_new_run() override {}
  TrainingProgress load_checkpoint(const fs::path& path) override {
    std::istringstream in(bsg::testing::read_text_file(path));
    TrainingProgress progress;
    in >> progress.epochs_completed >> progress.num_ranks;
    progress.progress_log = bsg::testing::read_text_file(path.parent_path() / "saved_log.csv");
    progress.training_cost = bsg::algos::TrainingCost::for_constraints(1);
    return progress;
  }
  void save_checkpoint(const fs::path& path, const TrainingProgress& progress) override {
    calls_.checkpoints.push_back(progress.epochs_completed);
    bsg::write_file_atomically(path, std::to_string(progress.epochs_completed) + " " +
                                         std::to_string(progress.num_ranks));
    bsg::write_file_atomically(path.parent_path() / "saved_log.csv", progress.progress_log.value_or(""));
  }
  FamilyEpoch run_epoch(int epoch, bool checkpoint_follows) override {
    calls_.epochs_run.push_back(epoch);
    calls_.checkpoint_follows.push_back(checkpoint_follows);
    check_finite(epoch, "counted cost", epoch == fail_in_epoch ? std::nan("") : 1.0);
    FamilyEpoch result;
    result.epoch_cost = epoch + 1;
    result.epoch_constraint_costs = Eigen::VectorXd::Constant(1, epoch + 1);
    result.constraints = {{10.0 * epoch, 25.0}};
    return result;
  }
  std::vector<NamedScalar> progress_row(const EpochAccounts& accounts) override {
    cumulative_seen = accounts.training_cost->cumulative_cost;
    return {{"epoch", static_cast<double>(accounts.epoch)}, {"square", static_cast<double>(accounts.epoch * accounts.epoch)}};
  }
  std::vector<std::string> progress_columns() const override { return columns_; }
  EvaluationSummary evaluate(int) override {
    ++calls_.evaluations;
    EvaluationSummary summary;
    summary.episodes = {{7.0, 1.0, 10, {1.0}, {}}};
    summary.mean_return = 7.0;
    summary.mean_cost = 1.0;
    summary.mean_length = 10;
    summary.mean_constraint_costs = {1.0};
    return summary;
  }

  int fail_in_epoch = -1;
  double cumulative_seen = 0.0;

 private:
  FamilyCalls& calls_;
  std::vector<std::string> columns_;
};

bsg::RunConfig counting_config(int epochs) {
  bsg::RunConfig config;
  config.epochs = epochs;
  config.steps_per_epoch = 1000;  // the run checks hold (value-net minibatches of >= 16 samples)
  config.max_ep_len = 100;
  config.eval_episodes = 1;
  return config;
}

bsg::algos::Trainer make(const bsg::RunConfig& config, const fs::path& root, FamilyCalls& calls,
                         bsg::algos::TrainerOptions options = {}, std::unique_ptr<CountingFamily> family = nullptr) {
  if (family == nullptr) family = std::make_unique<CountingFamily>(calls);
  return bsg::algos::Trainer(config, bsg::algos::RunDirectory(root), bsg::MpiContext::single_process(),
                             std::move(options), std::move(family));
}

}  // namespace

TEST(RunSkeleton, SavesAtTheFamilysCadenceTheLastEpochAndTheStartAndSumsTheCosts) {
  TemporaryDirectory dir;
  FamilyCalls calls;
  auto family = std::make_unique<CountingFamily>(calls);
  CountingFamily* seen = family.get();
  bsg::algos::Trainer trainer(counting_config(5), bsg::algos::RunDirectory(dir.path() / "run"),
                              bsg::MpiContext::single_process(), {}, std::move(family));
  const bsg::algos::TrainingOutcome outcome = trainer.run();
  EXPECT_TRUE(outcome.finished);
  EXPECT_EQ(calls.epochs_run, (std::vector<int>{0, 1, 2, 3, 4}));
  // The initial model, after epochs 0 and 3 (k % 3 == 0), and after the last.
  EXPECT_EQ(calls.checkpoints, (std::vector<int>{0, 1, 4, 5}));
  EXPECT_EQ(calls.checkpoint_follows, (std::vector<bool>{true, false, false, true, true}));
  EXPECT_EQ(calls.evaluations, 1);
  EXPECT_DOUBLE_EQ(seen->cumulative_seen, 1 + 2 + 3 + 4 + 5);
  const auto columns = read_csv_columns(dir.path() / "run" / "progress.csv");
  EXPECT_EQ(columns.at("square"), (std::vector<double>{0, 1, 4, 9, 16}));
  EXPECT_TRUE(fs::exists(dir.path() / "run" / "evaluation.json"));
  EXPECT_TRUE(fs::exists(dir.path() / "run" / "config.yaml"));
  EXPECT_TRUE(fs::exists(dir.path() / "run" / "build.txt"));
}

TEST(RunSkeleton, StopsAfterTheAskedEpochsWithACheckpointAndResumesFromIt) {
  TemporaryDirectory dir;
  FamilyCalls first;
  bsg::algos::TrainerOptions stop;
  stop.stop_after_epochs = 2;
  const bsg::algos::TrainingOutcome stopped = make(counting_config(5), dir.path() / "run", first, stop).run();
  EXPECT_FALSE(stopped.finished);
  EXPECT_EQ(stopped.epochs_completed, 2);
  EXPECT_EQ(first.checkpoints, (std::vector<int>{0, 1, 2}));  // epoch 1 is the stop: saved
  EXPECT_EQ(first.evaluations, 0);

  FamilyCalls second;
  bsg::algos::TrainerOptions resume;
  resume.resume = true;
  std::ostringstream log;
  resume.log = &log;
  // A temporary of a write killed two days ago (common/atomic_file.h's naming).
  const fs::path stale = dir.path() / "run" / ("returns.csv.tmp." + std::to_string(::getpid()) + ".zzzzzz");
  bsg::testing::write_text_file(stale, "torn");
  fs::last_write_time(stale, fs::file_time_type::clock::now() - std::chrono::hours(48));
  const bsg::algos::TrainingOutcome finished = make(counting_config(5), dir.path() / "run", second, resume).run();
  EXPECT_TRUE(finished.finished);
  EXPECT_EQ(second.epochs_run, (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(second.checkpoints, (std::vector<int>{4, 5}));
  const auto columns = read_csv_columns(dir.path() / "run" / "progress.csv");
  EXPECT_EQ(columns.at("epoch"), (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(fs::exists(stale), false);
  EXPECT_NE(log.str().find("stale temporary"), std::string::npos) << log.str();
}

TEST(RunSkeleton, AResumeRefusesAProgressLogWithOtherColumns) {
  TemporaryDirectory dir;
  FamilyCalls first;
  bsg::algos::TrainerOptions stop;
  stop.stop_after_epochs = 1;
  make(counting_config(3), dir.path() / "run", first, stop).run();
  FamilyCalls second;
  bsg::algos::TrainerOptions resume;
  resume.resume = true;
  try {
    make(counting_config(3), dir.path() / "run", second, resume,
         std::make_unique<CountingFamily>(second, std::vector<std::string>{"epoch", "cube"}));
    FAIL() << "expected a CheckpointError";
  } catch (const bsg::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("column 2 is square, this run writes cube"), std::string::npos) << e.what();
  }
}

TEST(RunSkeleton, ANonFiniteValueNamesTheEpochAndTheKeptCheckpoint) {
  TemporaryDirectory dir;
  FamilyCalls calls;
  auto family = std::make_unique<CountingFamily>(calls);
  family->fail_in_epoch = 2;
  bsg::algos::Trainer trainer(counting_config(5), bsg::algos::RunDirectory(dir.path() / "run"),
                              bsg::MpiContext::single_process(), {}, std::move(family));
  try {
    trainer.run();
    FAIL() << "expected a NonFiniteError";
  } catch (const bsg::algos::NonFiniteError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("counted cost"), std::string::npos) << message;
    EXPECT_NE(message.find("epoch 2"), std::string::npos) << message;
    EXPECT_NE(message.find("after 1 epochs"), std::string::npos) << message;  // the checkpoint after epoch 0
  }
}

TEST(RunSkeleton, NoEvaluationEpisodesStillMarksTheRunFinished) {
  TemporaryDirectory dir;
  FamilyCalls calls;
  bsg::RunConfig config = counting_config(2);
  config.eval_episodes = 0;
  std::ostringstream log;
  bsg::algos::TrainerOptions options;
  options.log = &log;
  make(config, dir.path() / "run", calls, options).run();
  EXPECT_EQ(calls.evaluations, 0);
  EXPECT_TRUE(fs::exists(dir.path() / "run" / "evaluation.json"));
  EXPECT_NE(log.str().find("evaluation skipped"), std::string::npos) << log.str();
}
