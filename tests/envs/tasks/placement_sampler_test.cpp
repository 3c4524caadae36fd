// The obstacle placement sampler (docs/environments.md#placement-sampling): clearances, order, and the
// attempt guard that replaces the original's endless loop.
#include "envs/tasks/placement_sampler.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bsg::envs {
namespace {

TEST(PlacementSampler, PointsStayInTheSevenMetreSquareOnTheGround) {
  Rng rng(1);
  for (int i = 0; i < 1000; ++i) {
    const btVector3 p = uniform_room_point(rng);
    EXPECT_LE(std::abs(p.x()), 7);
    EXPECT_LE(std::abs(p.y()), 7);
    EXPECT_EQ(p.z(), 0);
  }
}

TEST(PlacementSampler, KeepsAgentAndPairwiseClearancesIncludingTheGoal) {
  Rng rng(2);
  for (int trial = 0; trial < 50; ++trial) {
    const btVector3 agent(uniform(rng, -7, 7), uniform(rng, -7, 7), 0.5);
    const btVector3 goal(uniform(rng, -7, 7), uniform(rng, -7, 7), 0);
    const auto positions = sample_obstacle_positions(rng, 9, agent, goal, 2.5, 2.5);
    ASSERT_EQ(positions.size(), 9u);
    for (size_t i = 0; i < positions.size(); ++i) {
      EXPECT_GE(std::hypot(positions[i].x() - agent.x(), positions[i].y() - agent.y()), 2.5);
      EXPECT_GT((positions[i] - goal).length(), 2.5);
      for (size_t j = 0; j < i; ++j) EXPECT_GT((positions[i] - positions[j]).length(), 2.5);
    }
  }
}

TEST(PlacementSampler, ThrowsInsteadOfLoopingForeverWhenTheRoomIsFull) {
  Rng rng(3);
  EXPECT_THROW(sample_obstacle_positions(rng, 100, btVector3(0, 0, 0), std::nullopt, 5.0, 1.0),
               std::runtime_error);
}

TEST(PlacementSampler, PlanarDistanceIgnoresHeight) {
  EXPECT_EQ(planar_distance(btVector3(0, 0, 5), btVector3(3, 4, -2)), 5.0);
}

}  // namespace
}  // namespace bsg::envs
