// The training checkpoint (algos/training/training_checkpoint.h): save -> load gives
// back every parameter, optimiser moment, normaliser statistic and the
// algorithm's state bit for bit; a checkpoint of another configuration or a
// damaged file is an error naming the file.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>

#include "../../test_support.h"
#include "algos/core/actor_critic.h"
#include "algos/training/epoch_log.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/progress_csv.h"
#include "algos/training/training_checkpoint.h"
#include "common/binary_io.h"
#include "common/checkpoint_file.h"

namespace fs = std::filesystem;
using bsg::testing::TemporaryDirectory;

namespace {

bsg::RunConfig lag_trpo_config() {
  bsg::RunConfig config;
  config.alg = bsg::Algorithm::lag_trpo;
  config.use_cost_value_function = true;
  config.hidden_sizes = {16, 16};
  return config;
}

// Moves every part of the state away from its initial value.
void advance(bsg::algos::ActorCritic& ac, bsg::algos::OnPolicyAlgorithm& algorithm, bsg::Rng& rng) {
  const bsg::MpiContext mpi = bsg::MpiContext::single_process();
  Eigen::MatrixXd observations(64, ac.observation_size());
  for (Eigen::Index i = 0; i < observations.size(); ++i) observations.data()[i] = bsg::standard_normal(rng);
  Eigen::VectorXd targets = observations.col(0) * 2.0;
  bsg::algos::ValueFitOptions options{1, 4, 16};
  ac.value.fit(observations, targets, rng, mpi, options);
  ac.cost_value.fit(observations, -targets, rng, mpi, options);
  ac.observation_normalizer.update(observations, mpi);
  ac.return_normalizer.update(targets, mpi);
  ac.policy.mean_net().set_parameters(ac.policy.mean_net().parameters() * 1.5);
  std::vector<bsg::algos::NamedScalar> state = algorithm.state();
  for (bsg::algos::NamedScalar& entry : state) entry.value += 0.25;
  algorithm.restore_state(state);
}

void expect_same(const bsg::algos::ActorCritic& a, const bsg::algos::ActorCritic& b) {
  EXPECT_EQ(a.policy.mean_net().parameters(), b.policy.mean_net().parameters());
  EXPECT_EQ(a.value.net().parameters(), b.value.net().parameters());
  EXPECT_EQ(a.cost_value.net().parameters(), b.cost_value.net().parameters());
  for (const auto* pair : {&a.value, &a.cost_value}) {
    const bsg::algos::ValueFunction& other = pair == &a.value ? b.value : b.cost_value;
    EXPECT_EQ(pair->optimizer().first_moment(), other.optimizer().first_moment());
    EXPECT_EQ(pair->optimizer().second_moment(), other.optimizer().second_moment());
    EXPECT_EQ(pair->optimizer().step_count(), other.optimizer().step_count());
  }
  EXPECT_EQ(a.observation_normalizer.mean(), b.observation_normalizer.mean());
  EXPECT_EQ(a.observation_normalizer.std(), b.observation_normalizer.std());
  EXPECT_EQ(a.observation_normalizer.count(), b.observation_normalizer.count());
  EXPECT_EQ(a.return_normalizer.mean(), b.return_normalizer.mean());
  EXPECT_EQ(a.return_normalizer.std(), b.return_normalizer.std());
  EXPECT_EQ(a.return_normalizer.count(), b.return_normalizer.count());
}

// A progress log of `epochs` rows as the trainer writes it (epoch, total_env_steps = (k + 1) B, a
// value, time_s), the last time_s being `elapsed`; the text a checkpoint records.
std::string progress_log(int epochs, double elapsed, const bsg::RunConfig& config) {
  if (epochs == 0) return "";
  const std::vector<std::string> columns =
      bsg::algos::epoch_log_columns(bsg::algos::epoch_log_layout(config, *bsg::algos::make_algorithm(config)));
  std::string text;
  for (std::size_t i = 0; i < columns.size(); ++i) text += (i > 0 ? "," : "") + columns[i];
  text += "\n";
  for (int k = 0; k < epochs; ++k) {
    const double time = k == epochs - 1 ? elapsed : elapsed * (k + 1) / (epochs + 1);
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const std::string value =
          columns[i] == "epoch"             ? std::to_string(k)
          : columns[i] == "total_env_steps" ? std::to_string(static_cast<long long>(k + 1) * config.steps_per_epoch)
          : columns[i] == "time_s"          ? bsg::algos::format_csv_number(time)
                                            : std::string("0.5");
      text += (i > 0 ? "," : "") + value;
    }
    text += "\n";
  }
  return text;
}

bsg::algos::TrainingProgress progress_of(int epochs, double elapsed, int ranks, const bsg::RunConfig& config) {
  return bsg::algos::TrainingProgress{epochs, elapsed, ranks, progress_log(epochs, elapsed, config)};
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const bsg::CheckpointError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// TRPO-L with the PID multiplier: its integral, EMAs and delay queue are saved.
bsg::RunConfig pid_config() {
  bsg::RunConfig config = lag_trpo_config();
  config.multiplier.lambda_optimizer = bsg::LambdaOptimizer::pid;
  config.multiplier.pid_kd = 0.2;
  config.multiplier.pid_d_delay = 3;
  config.multiplier.pid_delta_p_ema_alpha = 0.5;
  config.multiplier.pid_delta_d_ema_alpha = 0.5;
  return config;
}

class TrainingCheckpointOfEveryMultiplier : public ::testing::TestWithParam<bsg::RunConfig> {};

INSTANTIATE_TEST_SUITE_P(SgdAndPid, TrainingCheckpointOfEveryMultiplier,
                         ::testing::Values(lag_trpo_config(), pid_config()));

TEST_P(TrainingCheckpointOfEveryMultiplier, SaveThenLoadRestoresEverythingExactly) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = GetParam();
  bsg::Rng rng_a(1);
  bsg::algos::ActorCritic saved(5, 2, config, rng_a);
  auto algorithm = bsg::algos::make_algorithm(config);
  ASSERT_FALSE(algorithm->state().empty()) << "TRPO-L has lambda to save";
  advance(saved, *algorithm, rng_a);
  const bsg::algos::TrainingProgress progress = progress_of(7, 12.5, 2, config);
  const fs::path path = dir.path() / "checkpoint.bin";
  bsg::algos::save_training_checkpoint(path, config, progress, saved, *algorithm);

  bsg::Rng rng_b(99);  // a different initialisation, overwritten by the load
  bsg::algos::ActorCritic loaded(5, 2, config, rng_b);
  auto loaded_algorithm = bsg::algos::make_algorithm(config);
  const bsg::algos::TrainingProgress loaded_progress =
      bsg::algos::load_training_checkpoint(path, config, loaded, *loaded_algorithm);
  EXPECT_EQ(loaded_progress.epochs_completed, 7);
  EXPECT_EQ(loaded_progress.elapsed_seconds, 12.5);
  EXPECT_EQ(loaded_progress.num_ranks, 2);
  EXPECT_EQ(loaded_progress.progress_log, progress.progress_log);
  expect_same(saved, loaded);
  EXPECT_EQ(algorithm->state(), loaded_algorithm->state());
  EXPECT_EQ(algorithm->state().size(), config.multiplier.lambda_optimizer == bsg::LambdaOptimizer::pid ? 1u + 3u + 3u : 1u);
  // Saving the loaded state reproduces the file byte for byte.
  EXPECT_EQ(bsg::algos::encode_training_checkpoint(config, progress, saved, *algorithm),
            bsg::algos::encode_training_checkpoint(config, loaded_progress, loaded, *loaded_algorithm));
}

TEST(TrainingCheckpoint, ACheckpointOfAnotherConfigurationIsRejected) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::algos::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  const fs::path path = dir.path() / "checkpoint.bin";
  bsg::algos::save_training_checkpoint(path, config, {}, ac, *algorithm);

  bsg::RunConfig other = config;
  other.trust_region.target_kl = 0.02;
  auto other_algorithm = bsg::algos::make_algorithm(other);
  const std::string message =
      error_of([&] { bsg::algos::load_training_checkpoint(path, other, ac, *other_algorithm); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("different configuration"), std::string::npos) << message;
}

TEST(TrainingCheckpoint, TruncatedPayloadsAreErrorsNamingTheFile) {
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::algos::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  const std::string payload = bsg::algos::encode_training_checkpoint(config, {}, ac, *algorithm);
  // Payloads cut anywhere (as if the container's checks were bypassed) never load.
  for (std::size_t length = 0; length < payload.size(); length += 97) {
    const std::string message = error_of([&] {
      bsg::algos::decode_training_checkpoint(std::string_view(payload).substr(0, length), "run/checkpoint.bin", config, ac,
                                      *algorithm);
    });
    EXPECT_NE(message.find("run/checkpoint.bin"), std::string::npos) << "length " << length << ": " << message;
  }
}

TEST(TrainingCheckpoint, NetworksOfAnotherShapeAreRejected) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::algos::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  const std::string payload = bsg::algos::encode_training_checkpoint(config, {}, ac, *algorithm);
  bsg::algos::ActorCritic wider(6, 2, config, rng);  // another observation size, same config text
  const std::string message =
      error_of([&] { bsg::algos::decode_training_checkpoint(payload, "ckpt", config, wider, *algorithm); });
  EXPECT_NE(message.find("policy parameters"), std::string::npos) << message;
}

// The error of saving then loading `progress` with a TRPO-L actor-critic ("" if none).
std::string round_trip_error(const bsg::algos::TrainingProgress& progress) {
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::algos::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  return error_of([&] {
    bsg::algos::decode_training_checkpoint(bsg::algos::encode_training_checkpoint(config, progress, ac, *algorithm), "ckpt", config,
                                    ac, *algorithm);
  });
}

// Issue 25, reproduction 2: fields out of range were accepted.
class CheckpointFieldOutOfRange : public ::testing::TestWithParam<std::pair<bsg::algos::TrainingProgress, std::string>> {};

bsg::algos::TrainingProgress with_ranks(int ranks) { return progress_of(2, 3.0, ranks, lag_trpo_config()); }
bsg::algos::TrainingProgress with_elapsed(double elapsed) {
  bsg::algos::TrainingProgress progress = progress_of(2, 3.0, 1, lag_trpo_config());
  progress.elapsed_seconds = elapsed;
  return progress;
}
bsg::algos::TrainingProgress with_log_rows(int epochs, int rows) {
  bsg::algos::TrainingProgress progress = progress_of(epochs, 3.0, 1, lag_trpo_config());
  progress.progress_log = progress_log(rows, 3.0, lag_trpo_config());
  return progress;
}

INSTANTIATE_TEST_SUITE_P(
    RanksTimesAndEpochs, CheckpointFieldOutOfRange,
    ::testing::Values(std::pair{with_ranks(0), std::string("rank count 0 lies outside [1, 1048576]")},
                      std::pair{with_ranks(-1), std::string("rank count -1 lies outside")},
                      std::pair{with_elapsed(std::nan("")), std::string("elapsed seconds nan is not a finite")},
                      std::pair{with_elapsed(-1.0), std::string("elapsed seconds -1 is not a finite non-negative")},
                      std::pair{with_elapsed(HUGE_VAL), std::string("elapsed seconds inf")},
                      std::pair{with_log_rows(3, 2), std::string("holds 2 rows for 3 completed epochs")},
                      std::pair{with_log_rows(1, 2), std::string("holds 2 rows for 1 completed epochs")},
                      std::pair{with_log_rows(2, 0), std::string("holds 0 rows for 2 completed epochs")}),
    [](const auto& info) { return "field_" + std::to_string(info.index); });

TEST_P(CheckpointFieldOutOfRange, IsAnErrorNamingTheFieldAndTheFile) {
  const std::string message = round_trip_error(GetParam().first);
  EXPECT_NE(message.find("ckpt: "), std::string::npos) << message;
  EXPECT_NE(message.find(GetParam().second), std::string::npos) << message;
}

TEST(TrainingCheckpoint, ALogWhoseLastTimeIsNotTheElapsedTimeIsRejected) {
  bsg::algos::TrainingProgress progress = progress_of(2, 3.0, 1, lag_trpo_config());
  progress.elapsed_seconds = 4.0;
  const std::string message = round_trip_error(progress);
  EXPECT_NE(message.find("last time_s 3 differs from its elapsed seconds 4"), std::string::npos) << message;
}

TEST(TrainingCheckpoint, ALogWithStepCountsOfAnotherBatchIsRejected) {
  bsg::RunConfig other = lag_trpo_config();
  other.steps_per_epoch /= 2;
  bsg::algos::TrainingProgress progress = progress_of(2, 3.0, 1, lag_trpo_config());
  progress.progress_log = progress_log(2, 3.0, other);
  const std::string message = round_trip_error(progress);
  EXPECT_NE(message.find("its progress log:2: total_env_steps"), std::string::npos) << message;
}

// Format 1 files (no progress log) written before issue 25 still load.
TEST(TrainingCheckpoint, AFormatOnePayloadWithoutAProgressLogStillLoads) {
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::algos::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  std::string payload = bsg::algos::encode_training_checkpoint(config, bsg::algos::TrainingProgress{4, 2.5, 1, ""}, ac, *algorithm);
  // Format 1 is format 2 without the log's string: its 8-byte length (0) after epochs and seconds.
  const std::size_t log_length_at = payload.find("progress") + std::string("progress").size() + 16;
  ASSERT_EQ(payload.substr(log_length_at, 8), std::string(8, '\0'));
  payload.erase(log_length_at, 8);
  const bsg::algos::TrainingProgress loaded =
      bsg::algos::decode_training_checkpoint(payload, "ckpt", config, ac, *algorithm, /*format_version=*/1);
  EXPECT_EQ(loaded.epochs_completed, 4);
  EXPECT_EQ(loaded.elapsed_seconds, 2.5);
  EXPECT_FALSE(loaded.progress_log.has_value());
}

TEST(TrainingCheckpoint, ACheckpointThatIsADirectoryOrAFifoIsCalledWhatItIs) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::algos::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::algos::make_algorithm(config);
  const fs::path directory = dir.path() / "as_directory";
  fs::create_directory(directory);
  const fs::path fifo = dir.path() / "as_fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string as_directory = error_of([&] { bsg::algos::load_training_checkpoint(directory, config, ac, *algorithm); });
  EXPECT_NE(as_directory.find(directory.string() + " is a directory, not a file"), std::string::npos) << as_directory;
  const std::string as_fifo = error_of([&] { bsg::algos::load_training_checkpoint(fifo, config, ac, *algorithm); });
  EXPECT_NE(as_fifo.find(fifo.string() + " is a FIFO, not a file"), std::string::npos) << as_fifo;
  const std::string missing =
      error_of([&] { bsg::algos::load_training_checkpoint(dir.path() / "none", config, ac, *algorithm); });
  EXPECT_NE(missing.find("none is missing"), std::string::npos) << missing;
}
