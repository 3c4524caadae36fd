// The acting policies (algos/core/acting_policy.h): the on-policy one normalises the raw
// observation with the frozen statistics and acts with the mean, or with mu + sigma eps from the
// caller's stream; both refuse observations and actions of other sizes, naming them.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "../scripted_training.h"
#include "algos/core/actor_critic.h"
#include "algos/core/actor_critic_acting.h"
#include "common/random.h"

namespace {

// An actor-critic whose mean net gives mu = 0 and whose policy has sigma = 0.25.
bsg::algos::ActorCritic zero_mean_actor_critic() {
  bsg::RunConfig config = bsg::testing::scripted_config();
  bsg::Rng init(5);
  bsg::algos::ActorCritic ac(3, 2, config, init);
  ac.policy.mean_net().set_parameters(Eigen::VectorXd::Zero(ac.policy.mean_net().num_parameters()));
  ac.policy.set_std(0.25);
  return ac;
}

}  // namespace

TEST(ActorCriticActing, MeanActionsAreMuAndSampledOnesAddSigmaTimesTheCallersNormals) {
  const bsg::algos::ActorCritic ac = zero_mean_actor_critic();
  bsg::algos::ActorCriticActing acting(ac);
  EXPECT_EQ(acting.observation_size(), 3);
  EXPECT_EQ(acting.action_size(), 2);
  const std::vector<double> observation = {0.5, -1.0, 2.0};
  std::vector<double> action(2, 7.0);
  bsg::Rng unused(1);
  acting.act(observation, bsg::algos::ActionMode::mean, unused, action);
  EXPECT_EQ(action, (std::vector<double>{0.0, 0.0}));

  bsg::Rng noise(42);
  bsg::Rng expected(42);  // the same stream, drawn by hand
  for (int step = 0; step < 3; ++step) {
    acting.act(observation, bsg::algos::ActionMode::sampled, noise, action);
    for (double a : action) EXPECT_NEAR(a, 0.25 * bsg::standard_normal(expected), 1e-15) << step;
  }
}

TEST(ActorCriticActing, RefusesAnObservationOrActionOfAnotherSize) {
  const bsg::algos::ActorCritic ac = zero_mean_actor_critic();
  bsg::algos::ActorCriticActing acting(ac);
  std::vector<double> action(2);
  bsg::Rng noise(1);
  try {
    acting.act(std::vector<double>(4, 0.0), bsg::algos::ActionMode::mean, noise, action);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("takes 3 observations and gives 2 actions, the environment has 4 and 2"),
              std::string::npos)
        << e.what();
  }
  std::vector<double> wide(3);
  EXPECT_THROW(acting.act(std::vector<double>(3, 0.0), bsg::algos::ActionMode::mean, noise, wide),
               std::invalid_argument);
}
