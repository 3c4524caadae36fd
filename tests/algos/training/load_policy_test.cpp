// load_policy (algos/training/load_policy.h): a run directory's checkpoint read back as the acting
// policy of the family that trained it acts as the trainer's own policy did at the end of training.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/core/actor_critic_acting.h"
#include "algos/training/load_policy.h"
#include "algos/training/on_policy_trainer.h"
#include "common/run_config_resolve.h"

namespace fs = std::filesystem;
using bsg::testing::TemporaryDirectory;

namespace {

bsg::RunConfig ball_circle(const std::string& alg) {
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=" + alg, "epochs=2", "steps_per_epoch=1000",
                           "eval_episodes=1", "hidden_sizes=[8, 8]", "max_ep_len=100"};
  return bsg::resolve_run_config(request).config;
}

}  // namespace

TEST(LoadPolicy, AnOnPolicyRunsCheckpointActsAsTheTrainersFinalPolicy) {
  const TemporaryDirectory directory;
  const bsg::algos::RunDirectory run(directory.path() / "run");
  bsg::algos::OnPolicyTrainer trainer(ball_circle("lag-trpo"), run, bsg::MpiContext::single_process(), {});
  trainer.run();
  const std::unique_ptr<bsg::algos::LoadedPolicy> loaded = bsg::algos::load_policy(run);
  EXPECT_EQ(loaded->epochs_completed(), 2);
  EXPECT_EQ(loaded->config().alg, bsg::Algorithm::lag_trpo);
  EXPECT_EQ(loaded->action_words(bsg::algos::ActionMode::mean), "mean actions");
  bsg::algos::ActorCriticActing trained(trainer.actor_critic());
  ASSERT_EQ(loaded->observation_size(), trained.observation_size());
  std::vector<double> observation(static_cast<std::size_t>(trained.observation_size()));
  std::vector<double> expected(2), got(2);
  bsg::Rng unused(0);
  for (int k = 0; k < 5; ++k) {
    for (std::size_t i = 0; i < observation.size(); ++i) observation[i] = 0.3 * k - 0.1 * static_cast<double>(i);
    trained.act(observation, bsg::algos::ActionMode::mean, unused, expected);
    loaded->act(observation, bsg::algos::ActionMode::mean, unused, got);
    EXPECT_EQ(got, expected) << k;
  }
  // Sampled actions use the sigma of the last epoch (the annealed exploration noise).
  EXPECT_EQ(loaded->sampled_action_std(), trainer.actor_critic().policy.std());
}

TEST(LoadPolicy, ADirectoryWithoutARunIsAnErrorNamingIt) {
  const TemporaryDirectory directory;
  try {
    bsg::algos::load_policy(bsg::algos::RunDirectory(directory.path() / "nothing"));
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("nothing"), std::string::npos) << e.what();
  }
}
