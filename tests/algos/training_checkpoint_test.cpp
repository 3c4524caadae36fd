// The training checkpoint (algos/training_checkpoint.h): save -> load gives
// back every parameter, optimiser moment, normaliser statistic and the
// algorithm's state bit for bit; a checkpoint of another configuration or a
// damaged file is an error naming the file.
#include <gtest/gtest.h>

#include <filesystem>

#include "../test_support.h"
#include "algos/actor_critic.h"
#include "algos/make_algorithm.h"
#include "algos/training_checkpoint.h"
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
void advance(bsg::ActorCritic& ac, bsg::TrustRegionAlgorithm& algorithm, bsg::Rng& rng) {
  const bsg::MpiContext mpi = bsg::MpiContext::single_process();
  Eigen::MatrixXd observations(64, ac.observation_size());
  for (Eigen::Index i = 0; i < observations.size(); ++i) observations.data()[i] = bsg::standard_normal(rng);
  Eigen::VectorXd targets = observations.col(0) * 2.0;
  bsg::ValueFitOptions options{1, 4, 16};
  ac.value.fit(observations, targets, rng, mpi, options);
  ac.cost_value.fit(observations, -targets, rng, mpi, options);
  ac.observation_normalizer.update(observations, mpi);
  ac.return_normalizer.update(targets, mpi);
  ac.policy.mean_net().set_parameters(ac.policy.mean_net().parameters() * 1.5);
  std::vector<bsg::NamedScalar> state = algorithm.state();
  for (bsg::NamedScalar& entry : state) entry.value += 0.25;
  algorithm.restore_state(state);
}

void expect_same(const bsg::ActorCritic& a, const bsg::ActorCritic& b) {
  EXPECT_EQ(a.policy.mean_net().parameters(), b.policy.mean_net().parameters());
  EXPECT_EQ(a.value.net().parameters(), b.value.net().parameters());
  EXPECT_EQ(a.cost_value.net().parameters(), b.cost_value.net().parameters());
  for (const auto* pair : {&a.value, &a.cost_value}) {
    const bsg::ValueFunction& other = pair == &a.value ? b.value : b.cost_value;
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
  config.lambda_optimizer = bsg::LambdaOptimizer::pid;
  config.pid_kd = 0.2;
  config.pid_d_delay = 3;
  config.pid_delta_p_ema_alpha = 0.5;
  config.pid_delta_d_ema_alpha = 0.5;
  return config;
}

class TrainingCheckpointOfEveryMultiplier : public ::testing::TestWithParam<bsg::RunConfig> {};

INSTANTIATE_TEST_SUITE_P(SgdAndPid, TrainingCheckpointOfEveryMultiplier,
                         ::testing::Values(lag_trpo_config(), pid_config()));

TEST_P(TrainingCheckpointOfEveryMultiplier, SaveThenLoadRestoresEverythingExactly) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = GetParam();
  bsg::Rng rng_a(1);
  bsg::ActorCritic saved(5, 2, config, rng_a);
  auto algorithm = bsg::make_algorithm(config);
  ASSERT_FALSE(algorithm->state().empty()) << "TRPO-L has lambda to save";
  advance(saved, *algorithm, rng_a);
  const bsg::TrainingProgress progress{7, 12.5, 2};
  const fs::path path = dir.path() / "checkpoint.bin";
  bsg::save_training_checkpoint(path, config, progress, saved, *algorithm);

  bsg::Rng rng_b(99);  // a different initialisation, overwritten by the load
  bsg::ActorCritic loaded(5, 2, config, rng_b);
  auto loaded_algorithm = bsg::make_algorithm(config);
  const bsg::TrainingProgress loaded_progress =
      bsg::load_training_checkpoint(path, config, loaded, *loaded_algorithm);
  EXPECT_EQ(loaded_progress.epochs_completed, 7);
  EXPECT_EQ(loaded_progress.elapsed_seconds, 12.5);
  EXPECT_EQ(loaded_progress.num_ranks, 2);
  expect_same(saved, loaded);
  EXPECT_EQ(algorithm->state(), loaded_algorithm->state());
  EXPECT_EQ(algorithm->state().size(), config.lambda_optimizer == bsg::LambdaOptimizer::pid ? 1u + 3u + 3u : 1u);
  // Saving the loaded state reproduces the file byte for byte.
  EXPECT_EQ(bsg::encode_training_checkpoint(config, progress, saved, *algorithm),
            bsg::encode_training_checkpoint(config, loaded_progress, loaded, *loaded_algorithm));
}

TEST(TrainingCheckpoint, ACheckpointOfAnotherConfigurationIsRejected) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::make_algorithm(config);
  const fs::path path = dir.path() / "checkpoint.bin";
  bsg::save_training_checkpoint(path, config, {}, ac, *algorithm);

  bsg::RunConfig other = config;
  other.target_kl = 0.02;
  auto other_algorithm = bsg::make_algorithm(other);
  const std::string message =
      error_of([&] { bsg::load_training_checkpoint(path, other, ac, *other_algorithm); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("different configuration"), std::string::npos) << message;
}

TEST(TrainingCheckpoint, TruncatedPayloadsAreErrorsNamingTheFile) {
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::make_algorithm(config);
  const std::string payload = bsg::encode_training_checkpoint(config, {}, ac, *algorithm);
  // Payloads cut anywhere (as if the container's checks were bypassed) never load.
  for (std::size_t length = 0; length < payload.size(); length += 97) {
    const std::string message = error_of([&] {
      bsg::decode_training_checkpoint(std::string_view(payload).substr(0, length), "run/checkpoint.bin", config, ac,
                                      *algorithm);
    });
    EXPECT_NE(message.find("run/checkpoint.bin"), std::string::npos) << "length " << length << ": " << message;
  }
}

TEST(TrainingCheckpoint, NetworksOfAnotherShapeAreRejected) {
  TemporaryDirectory dir;
  const bsg::RunConfig config = lag_trpo_config();
  bsg::Rng rng(1);
  bsg::ActorCritic ac(5, 2, config, rng);
  auto algorithm = bsg::make_algorithm(config);
  const std::string payload = bsg::encode_training_checkpoint(config, {}, ac, *algorithm);
  bsg::ActorCritic wider(6, 2, config, rng);  // another observation size, same config text
  const std::string message =
      error_of([&] { bsg::decode_training_checkpoint(payload, "ckpt", config, wider, *algorithm); });
  EXPECT_NE(message.find("policy parameters"), std::string::npos) << message;
}
