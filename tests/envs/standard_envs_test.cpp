// The face's view of the standard environments (envs/standard_envs.h): the step
// duration it gives the programs above it is the physics' own and that of every
// standard description, 1/60 s (PyBullet's 240 Hz engine, four engine steps per
// environment step; Reach one step of 1/60 s).
#include <gtest/gtest.h>

#include <vector>

#include "envs/physics/world.h"
#include "envs/standard_envs.h"

namespace bsg::envs {
namespace {

TEST(StandardEnvs, StepDurationIsThePhysicsOwnSixtiethOfASecond) {
  static_assert(kStandardEnvStepSeconds == World::kEnvStepSeconds);
  EXPECT_DOUBLE_EQ(kStandardEnvStepSeconds * 60.0, 1.0);
}

TEST(StandardEnvs, EveryStandardDescriptionStepsTheFacesDuration) {
  const std::vector<EnvDescription> descriptions = standard_descriptions();
  ASSERT_EQ(descriptions.size(), 16u);
  for (const EnvDescription& description : descriptions) {
    EXPECT_DOUBLE_EQ(description.env_step_seconds(), kStandardEnvStepSeconds) << description.name;
  }
}

}  // namespace
}  // namespace bsg::envs
