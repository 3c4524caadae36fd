// dataset_environment.h: every registered environment (standard and fork)
// written as the file's env_description (envs::to_yaml) comes back as the
// registry's own description.
#include "algos/offline/dataset_environment.h"

#include <gtest/gtest.h>

namespace bsg::algos {
namespace {

TEST(DatasetEnvironment, EveryRegisteredDescriptionComesBack) {
  for (const std::string& id : envs::registered_ids()) {
    OfflineDataset d;
    d.text_attributes["env_description"] = envs::to_yaml(envs::describe(id));
    EXPECT_TRUE(dataset_env_description(d) == envs::describe(id)) << id;
  }
}

TEST(DatasetEnvironment, ChangedParametersComeBack) {
  const envs::EnvDescription changed = envs::describe("SafetyBallGather-v0", {{"bombs", "3"}});
  OfflineDataset d;
  d.text_attributes["env_description"] = envs::to_yaml(changed);
  EXPECT_TRUE(dataset_env_description(d) == changed);
}

TEST(DatasetEnvironment, MissingOrBadAttributeIsRefused) {
  OfflineDataset d;
  EXPECT_THROW(dataset_env_description(d), std::invalid_argument);
  d.text_attributes["env_description"] = "agent: Boat\n";
  EXPECT_THROW(dataset_env_description(d), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
