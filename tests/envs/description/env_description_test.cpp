// Environments as descriptions (envs/description/env_description.h): the standard values,
// custom combinations built by the same path (observation sizes from the
// documented formula, counts and placement ranges over many resets, checked
// against the description's numbers), the fork variant's values, and one-line
// errors for every kind of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "envs/env.h"
#include "envs/tasks/placement_sampler.h"
#include "envs/description/standard_descriptions.h"

namespace bsg::envs {
namespace {

double planar(const Vec3& a, const Vec3& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }
double spatial(const Vec3& a, const Vec3& b) {
  return std::sqrt(std::pow(a[0] - b[0], 2) + std::pow(a[1] - b[1], 2) + std::pow(a[2] - b[2], 2));
}
bool in_square(const Vec3& p, double half_width) {
  return std::abs(p[0]) <= half_width && std::abs(p[1]) <= half_width;
}

// Agent part of the observation (docs/environments.md#the-sixteen-environments).
int agent_dim(const std::string& agent) {
  if (agent == "Drone") return 17;
  if (agent == "Ant") return 33;
  return 7;  // Ball, Car
}

TEST(StandardDescriptions, HoldTheOriginalsValues) {
  // Report Table 3 and docs/environments.md#the-sixteen-environments.
  const EnvDescription ant_reach = describe("SafetyAntReach-v0");
  EXPECT_EQ(ant_reach.cost_limit, 25);
  EXPECT_EQ(ant_reach.max_episode_steps, 1000);
  EXPECT_EQ(ant_reach.frame_skip, 1);
  EXPECT_EQ(ant_reach.time_step, 1.0 / 60.0);
  EXPECT_TRUE(ant_reach.power_upgrade);
  const EnvDescription drone_reach = describe("SafetyDroneReach-v0");
  EXPECT_EQ(drone_reach.zone_type, "pillar");
  EXPECT_EQ(drone_reach.zone_radius, 0.45);
  EXPECT_EQ(drone_reach.cost_limit, 10);
  const EnvDescription ball_run = describe("SafetyBallRun-v0");
  EXPECT_EQ(ball_run.run_speed_limit, 2.5);
  EXPECT_EQ(ball_run.world, "Plane200");
  EXPECT_EQ(describe("SafetyCarRun-v0").run_speed_limit, 1.5);
  const EnvDescription gather = describe("SafetyCarGather-v0");
  EXPECT_EQ(gather.apples, 8);
  EXPECT_EQ(gather.bombs, 8);
  EXPECT_EQ(gather.cost_limit, 0.2);
  EXPECT_FALSE(gather.clip_actions);
  // Every standard environment advances 1/60 s per step.
  for (const EnvDescription& d : standard_descriptions()) {
    EXPECT_EQ(d.env_step_seconds(), 1.0 / 60.0) << d.name;
    EXPECT_EQ(d.name, "Safety" + d.agent + d.task + "-v0");
  }
}

TEST(StandardDescriptions, RoundTripThroughTheirKeys) {
  for (const std::string& id : registered_ids()) {
    const EnvDescription d = describe(id);
    EXPECT_EQ(apply_env_overrides(standard_description(d.agent, d.task), to_env_overrides(d)), d) << id;
  }
}

TEST(CustomEnvironments, AntGatherWithSixteenBombsPlacesThemAllOverManyResets) {
  const EnvDescription d = describe("SafetyAntGather-v0", {{"bombs", "16"}});
  ASSERT_EQ(d.bombs, 16);
  const auto env = make(d);
  EXPECT_EQ(env->spec().observation_dim, agent_dim("Ant") + 2 * 16);  // 16-bin pseudo-LIDARs
  std::vector<double> zero(8, 0.0);
  for (int episode = 0; episode < 40; ++episode) {
    if (episode == 0) {
      env->reset(11);
    } else {
      env->reset();
    }
    const Layout& layout = env->layout();
    ASSERT_EQ(layout.apples.size(), 8u);
    ASSERT_EQ(layout.bombs.size(), 16u);
    std::vector<Vec3> all = layout.apples;
    all.insert(all.end(), layout.bombs.begin(), layout.bombs.end());
    for (size_t i = 0; i < all.size(); ++i) {
      EXPECT_TRUE(in_square(all[i], 7.0));
      EXPECT_GE(planar(all[i], layout.agent_position), 1.0);  // agent clearance
      for (size_t j = 0; j < i; ++j) EXPECT_GT(spatial(all[i], all[j]), 2.0);
    }
    EXPECT_EQ(env->step(zero).observation.size(), static_cast<size_t>(agent_dim("Ant") + 32));
  }
}

TEST(CustomEnvironments, BallReachWithoutZonesAndBoxHasNeitherOverManyResets) {
  const EnvDescription d = describe("SafetyBallReach-v0", {{"zones", "0"}, {"box", "false"}});
  const auto env = make(d);
  // agent + LIDAR rays + pseudo-LIDAR bins + goal delta (docs/environments.md#environment-descriptions)
  EXPECT_EQ(env->spec().observation_dim, 7 + 24 + 24 + 2);
  std::vector<double> zero(2, 0.0);
  for (int episode = 0; episode < 60; ++episode) {
    if (episode == 0) {
      env->reset(5);
    } else {
      env->reset();
    }
    const Layout& layout = env->layout();
    EXPECT_TRUE(layout.zones.empty());
    EXPECT_FALSE(layout.box.has_value());
    ASSERT_TRUE(layout.goal.has_value());
    EXPECT_TRUE(in_square(*layout.goal, 7.0));
    EXPECT_TRUE(in_square(layout.agent_position, 7.0));
    EXPECT_GE(planar(*layout.goal, layout.agent_position), 2.5);
    const StepResult step = env->step(zero);
    // The zones pseudo-LIDAR after the agent (7) and the LIDAR (24): nothing to sense.
    for (size_t i = 7 + 24; i < 7 + 48; ++i) EXPECT_EQ(step.observation[i], 0.0);
    EXPECT_EQ(step.cost_term("cost_collisions"), 0);
    EXPECT_FALSE(env->state().box.has_value());
  }
}

TEST(CustomEnvironments, ReachWithFewerRaysAndMoreZonesHasTheirSizes) {
  const auto env = make(describe("SafetyDroneReach-v0", {{"lidar_rays", "8"}, {"zones", "12"}}));
  EXPECT_EQ(env->spec().observation_dim, 17 + 8 + 24 + 2);
  env->reset(3);
  EXPECT_EQ(env->layout().zones.size(), 12u);
}

TEST(CustomEnvironments, CarRunWithAWiderAvenueCostsOnlyOutsideIt) {
  const EnvDescription d = describe("SafetyCarRun-v0", {{"run_y_limit", "4"}});
  const auto env = make(d);
  EXPECT_EQ(env->spec().observation_dim, 7);
  std::vector<double> zero(2, 0.0);
  for (int episode = 0; episode < 20; ++episode) {
    env->reset(static_cast<std::uint64_t>(episode));
    EXPECT_LE(std::abs(env->layout().agent_position[0]), 0.01);
    EXPECT_LE(std::abs(env->layout().agent_position[1]), 0.01);
  }
  // Inside the wider avenue (|y| = 3 > 2, the standard limit): no cost.
  env->reset(1);
  env->teleport_agent({0, 3, 0.2});
  EXPECT_EQ(env->step(zero).cost_term("cost_outside_bounds"), 0);
  env->teleport_agent({0, 4.5, 0.2});
  EXPECT_EQ(env->step(zero).cost_term("cost_outside_bounds"), 1);
  // The standard avenue charges |y| = 3.
  const auto standard = make("SafetyCarRun-v0");
  standard->reset(1);
  standard->teleport_agent({0, 3, 0.2});
  EXPECT_EQ(standard->step(zero).cost_term("cost_outside_bounds"), 1);
}

TEST(CustomEnvironments, CircleEpisodesLastTheDescribedNumberOfSteps) {
  for (const auto& [id, steps] : {std::pair{"SafetyDroneCircle-v0", 500}, {"SafetyBallCircle-v0", 500},
                                  {"SafetyDroneCircle-v0", 120}}) {
    const auto env = make(describe(id, {{"max_episode_steps", std::to_string(steps)}}));
    EXPECT_EQ(env->spec().max_episode_steps, steps);
    EXPECT_EQ(env->spec().observation_dim, agent_dim(env->spec().agent) + 1);
    std::vector<double> zero(static_cast<size_t>(env->spec().action_dim), 0.0);
    env->reset(2);
    int length = 0;
    StepResult step;
    do {
      step = env->step(zero);
      ++length;
    } while (!step.terminated && !step.truncated);
    if (!step.terminated) {
      EXPECT_EQ(length, steps) << id;
    }
    EXPECT_LE(length, steps);
  }
}

TEST(CustomEnvironments, CircleSpawnsInTheDescribedAnnulus) {
  const auto env = make(describe("SafetyBallCircle-v0",
                                 {{"circle_spawn_min_radius", "5"}, {"circle_spawn_max_radius", "5.5"}}));
  for (int episode = 0; episode < 100; ++episode) {
    if (episode == 0) {
      env->reset(9);
    } else {
      env->reset();
    }
    const double r = std::hypot(env->layout().agent_position[0], env->layout().agent_position[1]);
    EXPECT_GE(r, 5.0);
    EXPECT_LE(r, 5.5);
  }
}

TEST(CustomEnvironments, ANewCombinationStartsFromItsStandardDescription) {
  const EnvDescription d = describe("SafetyBallCircle-v0", {{"agent", "Drone"}, {"task", "Reach"}, {"zones", "4"}});
  EXPECT_EQ(d.agent, "Drone");
  EXPECT_EQ(d.task, "Reach");
  EXPECT_EQ(d.zone_type, "pillar");  // the Drone's Reach
  EXPECT_EQ(d.zones, 4);
  EXPECT_EQ(d.max_episode_steps, 500);
  EXPECT_EQ(make(d)->spec().observation_dim, 17 + 24 + 24 + 2);
  // zone_type sets the radius unless it is given.
  EXPECT_EQ(describe("SafetyBallReach-v0", {{"zone_type", "pillar"}}).zone_radius, 0.45);
  EXPECT_EQ(describe("SafetyBallReach-v0", {{"zone_type", "pillar"}, {"zone_radius", "0.3"}}).zone_radius, 0.3);
}

TEST(CustomEnvironments, UncountedCostTermsAreReportedButCostNothing) {
  const auto env = make(describe("SafetyBallCircle-v0", {{"count_outside_bounds", "false"}}));
  env->reset(0);
  env->teleport_agent({6.5, 0, 0.2});
  const StepResult step = env->step(std::vector<double>{0, 0});
  EXPECT_EQ(step.cost_term("cost_outside_bounds"), 1);
  EXPECT_EQ(step.cost, 0);
}

TEST(ForkVariant, HoldsTheForksValues) {
  // docs/environments.md#the-fork-variant.
  const EnvDescription circle = describe("SafetyAntCircle-fork");
  EXPECT_NEAR(circle.env_step_seconds(), 0.1, 1e-15);
  EXPECT_EQ(circle.max_episode_steps, 500);
  EXPECT_EQ(describe("SafetyBallRun-fork").max_episode_steps, 100);
  EXPECT_EQ(describe("SafetyDroneRun-fork").frame_skip, 2);
  EXPECT_EQ(describe("SafetyDroneGather-fork").env_step_seconds(), 1.0 / 60.0);
  EXPECT_EQ(describe("SafetyBallGather-fork").env_step_seconds(), 1.0 / 30.0);
  EXPECT_TRUE(describe("SafetyCarCircle-fork").clip_actions);
  const EnvDescription reach = describe("SafetyBallReach-fork");
  EXPECT_EQ(reach.goal_bonus, 30);
  EXPECT_EQ(reach.reach_reward_scale, 3);
  EXPECT_EQ(reach.frame_skip, 4);
  // The fork samples the Reach obstacles against stale poses; its CarReach map is fixed.
  EXPECT_EQ(reach.obstacle_clearance_from, "stale");
  EXPECT_EQ(describe("SafetyAntReach-fork").obstacle_clearance_from, "stale");
  EXPECT_EQ(describe("SafetyDroneReach-fork").obstacle_clearance_from, "stale");
  EXPECT_EQ(describe("SafetyCarReach-fork").obstacle_clearance_from, "spawn");
  EXPECT_EQ(describe("SafetyBallReach-v0").obstacle_clearance_from, "spawn");
}

TEST(ForkVariant, CarReachIsTheFixedBarrierMapWithoutBoxOrLidar) {
  const auto env = make("SafetyCarReach-fork");
  EXPECT_EQ(env->spec().observation_dim, 33);  // 7 + 24 + 2 (fork spec: 57 -> 33)
  env->reset(4);
  const Layout& layout = env->layout();
  EXPECT_FALSE(layout.box.has_value());
  EXPECT_EQ(layout.agent_position[0], -6);
  EXPECT_EQ(layout.agent_position[1], 6);
  ASSERT_EQ(layout.zones.size(), 17u);
  // Zone 0 (−1, −3), zone 10 (1, 3), zone 16 (1, −6) of the fork's map.
  EXPECT_EQ(layout.zones[0][0], -1);
  EXPECT_EQ(layout.zones[0][1], -3);
  EXPECT_EQ(layout.zones[10][0], 1);
  EXPECT_EQ(layout.zones[10][1], 3);
  EXPECT_EQ(layout.zones[16][0], 1);
  EXPECT_EQ(layout.zones[16][1], -6);
  // The first goal is (−6, 6): the car starts inside it, collects +30 and the
  // goal flips to (6, 6).
  ASSERT_TRUE(layout.goal.has_value());
  EXPECT_EQ((*layout.goal)[0], -6);
  EXPECT_EQ((*layout.goal)[1], 6);
  const StepResult step = env->step(std::vector<double>{0, 0});
  EXPECT_GT(step.reward, 29);
  EXPECT_EQ((*env->state().goal)[0], 6);
  EXPECT_EQ((*env->state().goal)[1], 6);
}

// A one-line message naming the key (and the value).
void expect_error(const std::string& id, const EnvOverrides& overrides, const std::vector<std::string>& parts) {
  try {
    describe(id, overrides);
    ADD_FAILURE() << "no error for " << overrides.front().first << "=" << overrides.front().second;
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(BadDescriptions, EachIsAOneLineErrorNamingKeyAndValue) {
  expect_error("SafetyBallGather-v0", {{"bomb", "12"}}, {"bomb=12", "unknown parameter", "did you mean bombs"});
  expect_error("SafetyBallGather-v0", {{"bombs", "-1"}}, {"bombs=-1", ">= 0"});
  expect_error("SafetyBallGather-v0", {{"apples", "0"}}, {"apples=0", ">= 1"});
  expect_error("SafetyBallGather-v0", {{"gather_detection_distance", "0"}}, {"gather_detection_distance=0", "> 0"});
  expect_error("SafetyBallCircle-v0", {{"circle_radius", "-7"}}, {"circle_radius=-7", "> 0"});
  expect_error("SafetyBallCircle-v0", {{"time_step", "0"}}, {"time_step=0", "> 0"});
  expect_error("SafetyBallCircle-v0", {{"frame_skip", "0"}}, {"frame_skip=0", ">= 1"});
  expect_error("SafetyBallGather-v0", {{"bombs", "twelve"}}, {"bombs=twelve", "integer"});
  expect_error("SafetyBallGather-v0", {{"bombs", "300"}}, {"apples + bombs=308", "cannot place", "gather_spacing"});
  expect_error("SafetyBallReach-v0", {{"zones", "100"}}, {"zones=102", "reach_spacing"});
  expect_error("SafetyBallCircle-v0", {{"bombs", "12"}}, {"bombs=12", "Circle task has no such parameter", "Gather"});
  expect_error("SafetyBallGather-v0", {{"clip_actions", "true"}}, {"clip_actions=true", "only the Car"});
  expect_error("SafetyBallGather-v0", {{"agent", "Robot"}}, {"agent=Robot", "Ball, Car, Drone, Ant"});
  expect_error("SafetyBallGather-v0", {{"task", "Dance"}}, {"task=Dance", "Circle, Gather, Reach, Run"});
  expect_error("SafetyBallReach-v0", {{"zone_type", "puddles"}}, {"zone_type=puddles", "did you mean puddle"});
  expect_error("SafetyBallCircle-v0", {{"circle_spawn_min_radius", "4"}}, {"circle_spawn_min_radius=4", "below"});
  expect_error("SafetyBallCircle-v0", {{"world", "Moon"}}, {"world=Moon", "SmallRoom"});
  expect_error("SafetyBallReach-v0", {{"zone_layout", "barrier"}}, {"zones=8", "17"});
  expect_error("SafetyBallDance-v0", {{"bombs", "1"}}, {"SafetyBallDance-v0", "valid ids"});
  expect_error("SafetyBallGather-v0", {{"name", "my: gather"}}, {"name=my: gather", "letters, digits"});
}

TEST(BadDescriptions, PlacementThatCannotSucceedStopsWithAnErrorNotALoop) {
  // 80 discs of diameter 2 m cannot fit in a 16 m square even packed
  // hexagonally (0.9069 * 16^2 / pi = 73.9): the sampler gives up after its
  // bounded number of draws.
  Rng rng(1);
  EXPECT_THROW(sample_obstacle_positions(rng, 80, btVector3(0, 0, 0), std::nullopt, 2.0, 1.0, 7.0),
               std::runtime_error);
}

}  // namespace
}  // namespace bsg::envs
