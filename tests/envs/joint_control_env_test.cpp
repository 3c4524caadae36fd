// A multi-agent environment controlled jointly (envs/joint_control_env.h): the 2x4 Ant seen as
// one agent is the single-agent Ant step for step (its observation the agents' slices of the
// Ant's, written out by hand, its reward and cost the Ant's); two Balls give the agents' means of
// reward, cost and cost terms, summed by hand from a second copy of the team; bad calls are
// refused with one line.
#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"
#include "envs/joint_control_env.h"
#include "envs/multi_agent_env.h"

namespace bsg::envs {
namespace {
// Its own names apart from the other files of its test batch (tests/CMakeLists.txt).
namespace joint_control_env_test {

std::vector<int> range(int first, int last) {  // [first, last]
  std::vector<int> out(static_cast<size_t>(last - first + 1));
  std::iota(out.begin(), out.end(), first);
  return out;
}

// SafetyAntRun2x4-v0's agents observe the Ant's body (0..12), their legs' joints (agent 0: legs 0
// and 1, entries 13..20; agent 1: 21..28) and their feet (29, 30 and 31, 32), in that order.
std::vector<int> ant_2x4_joint_observation() {
  std::vector<int> out;
  for (const std::vector<int>& part :
       {range(0, 12), range(13, 20), range(29, 30), range(0, 12), range(21, 28), range(31, 32)}) {
    out.insert(out.end(), part.begin(), part.end());
  }
  return out;
}

TEST(JointControlEnv, SplitAntIsTheSingleAgentAntStepForStep) {
  std::unique_ptr<Env> joint = make_joint_control(make_multi_agent("SafetyAntRun2x4-v0"));
  std::unique_ptr<Env> single = make("SafetyAntRun-v0");
  const std::vector<int> observed = ant_2x4_joint_observation();
  ASSERT_EQ(joint->spec().observation_dim, static_cast<int>(observed.size()));
  ASSERT_EQ(joint->spec().action_dim, 8);
  EXPECT_EQ(joint->spec().max_episode_steps, single->spec().max_episode_steps);
  EXPECT_EQ(joint->spec().cost_limit, single->spec().cost_limit);
  EXPECT_EQ(joint->spec().cost_term_names, single->spec().cost_term_names);
  const auto expect_observation = [&](std::span<const double> joint_obs, std::span<const double> single_obs) {
    ASSERT_EQ(joint_obs.size(), observed.size());
    for (size_t i = 0; i < observed.size(); ++i) ASSERT_EQ(joint_obs[i], single_obs[static_cast<size_t>(observed[i])]);
  };
  expect_observation(joint->reset(3), single->reset(3));
  Rng rng(9);
  std::vector<double> action(8);
  int steps = 0;
  for (bool ended = false; !ended && steps < 200; ++steps) {
    for (double& a : action) a = uniform(rng, -1, 1);
    const StepResult j = joint->step(action);
    const StepResult s = single->step(action);  // the agents' actions in agent order are the Ant's joints
    expect_observation(j.observation, s.observation);
    ASSERT_EQ(j.reward, s.reward);  // the team's reward, every agent's, so their mean
    ASSERT_EQ(j.cost, s.cost);
    for (size_t t = 0; t < s.cost_terms.size(); ++t) ASSERT_EQ(j.cost_terms[t].value, s.cost_terms[t].value);
    ASSERT_EQ(j.terminated, s.terminated);
    ASSERT_EQ(j.truncated, s.truncated);
    ended = s.terminated || s.truncated;
  }
  EXPECT_GT(steps, 50);
  EXPECT_EQ(joint->state().agent_position, single->state().agent_position);  // one robot: its state
}

TEST(JointControlEnv, TwoBallsGiveTheAgentsMeansOfRewardAndCost) {
  std::unique_ptr<Env> joint = make_joint_control(make_multi_agent("SafetyBallCircle2-v0"));
  std::unique_ptr<MultiAgentEnv> team = make_multi_agent("SafetyBallCircle2-v0");
  const MultiAgentSpec& spec = team->spec();
  ASSERT_EQ(joint->spec().observation_dim, spec.observation_dims[0] + spec.observation_dims[1]);
  ASSERT_EQ(joint->spec().action_dim, 4);
  std::span<const double> observation = joint->reset(7);
  std::span<const std::span<const double>> observations = team->reset(7);
  Rng rng(4);
  std::vector<double> action(4);
  double cost_sum = 0;
  for (int step = 0; step < 250; ++step) {
    const size_t first = observations[0].size();
    for (size_t i = 0; i < observation.size(); ++i) {
      ASSERT_EQ(observation[i], i < first ? observations[0][i] : observations[1][i - first]) << "entry " << i;
    }
    // Full pushes in one direction most of the time: the Balls leave the safe zone and cost.
    for (double& a : action) a = uniform(rng, 0.2, 1.0);
    const std::vector<double> a0 = {action[0], action[1]}, a1 = {action[2], action[3]};
    const std::vector<std::span<const double>> actions = {a0, a1};
    const StepResult j = joint->step(action);
    const MultiAgentStepResult t = team->step(actions);
    ASSERT_EQ(j.reward, (t.rewards[0] + t.rewards[1]) / 2);
    ASSERT_EQ(j.cost, (t.costs[0] + t.costs[1]) / 2);
    ASSERT_EQ(j.cost_terms.size(), spec.cost_term_names.size());
    for (size_t k = 0; k < j.cost_terms.size(); ++k) {
      ASSERT_EQ(j.cost_terms[k].name, spec.cost_term_names[k]);
      ASSERT_EQ(j.cost_terms[k].value, t.cost_terms[0][k].value / 2 + t.cost_terms[1][k].value / 2);
    }
    cost_sum += j.cost;
    observation = j.observation;
    observations = t.observations;
    if (t.terminated || t.truncated) break;
  }
  EXPECT_GT(cost_sum, 0);  // the comparison saw costs, not only zeros
}

TEST(JointControlEnv, RefusesWhatOneAgentCannotDoWithOneLine) {
  std::unique_ptr<Env> joint = make_joint_control(make_multi_agent("SafetyBallCircle2-v0"));
  joint->reset(0);
  const std::vector<double> short_action(3, 0.0);
  try {
    joint->step(short_action);
    FAIL() << "a 3-entry action was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(joint->state(), std::logic_error);  // two robots: no one state
  EXPECT_THROW(joint->layout(), std::logic_error);
  EXPECT_THROW(joint->reset_to(Layout{}), std::logic_error);
  EXPECT_THROW(make_joint_control(nullptr), std::invalid_argument);
}

}  // namespace joint_control_env_test
}  // namespace
}  // namespace bsg::envs
