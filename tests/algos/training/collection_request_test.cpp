// A collection as a whole (algos/training/collection_request.h): policy specs
// and their shares; the file a request writes, read back, against the
// environment described independently here (its description, its cost limit,
// its first reset under the documented seed) and the request's own numbers;
// the attributes that say how it was made; one-line refusals that leave no
// file behind.
#include "algos/training/collection_request.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "../../test_support.h"
#include "algos/offline/dataset_file.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

namespace fs = std::filesystem;

std::string error_of(const CollectionRequest& request) {
  try {
    collect_to_file(request);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

std::string policy_error_of(const std::string& text) {
  try {
    parse_policy_spec(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

CollectionRequest random_request(const fs::path& out, const std::string& env_id) {
  CollectionRequest request;
  request.out = out.string();
  request.env_id = env_id;
  request.policies = {{"random", 1.0}};
  request.episodes = 1;
  return request;
}

TEST(CollectionRequest, PolicySpecsNameASourceAndAShare) {
  const PolicySpec plain = parse_policy_spec("runs/ppo_lag");
  EXPECT_EQ(plain.source, "runs/ppo_lag");
  EXPECT_EQ(plain.share, 1.0);
  const PolicySpec weighted = parse_policy_spec("runs/x=3");
  EXPECT_EQ(weighted.source, "runs/x");
  EXPECT_EQ(weighted.share, 3.0);
  EXPECT_EQ(parse_policy_spec("random=0.5").share, 0.5);
  // The share is after the last '=': a directory may hold one.
  const PolicySpec odd = parse_policy_spec("runs/a=b=2.5");
  EXPECT_EQ(odd.source, "runs/a=b");
  EXPECT_EQ(odd.share, 2.5);

  for (const std::string bad : {"random=0", "random=-1", "random=", "random=x", "random=2x", "random=inf",
                                "random=nan"}) {
    EXPECT_EQ(policy_error_of(bad), "--policy " + bad + ": the share after '=' must be a positive number");
  }
  EXPECT_EQ(policy_error_of("=2"), "--policy =2: names no policy");
  EXPECT_EQ(policy_error_of(""), "--policy : names no policy");
}

TEST(CollectionRequest, RandomPolicyFileSaysHowItWasMade) {
  testing::TemporaryDirectory dir("collection_request");
  CollectionRequest request = random_request(dir.path() / "nested" / "gather.hdf5", "SafetyBallGather-v0");
  request.env_overrides = {{"apples", "5"}, {"bombs", "3"}};
  request.episodes = 2;
  request.seed = 11;
  request.actions = EvaluationActions::mean;
  const CollectionSummary summary = collect_to_file(request);

  // The oracle: the environment described and made here, independently of the collection.
  const envs::EnvDescription description = envs::describe("SafetyBallGather-v0", {{"apples", "5"}, {"bombs", "3"}});
  EXPECT_EQ(description.apples, 5);
  std::unique_ptr<envs::Env> oracle = envs::make(description);
  const int T = oracle->spec().max_episode_steps;
  const std::span<const double> first = oracle->reset(derive_seed(11, SeedStream::environment, 0, 0));

  const OfflineDataset d = read_dataset_file(request.out);
  EXPECT_EQ(summary.transitions, d.size());
  EXPECT_EQ(summary.episodes, 2);
  EXPECT_EQ(summary.env_id, "SafetyBallGather-v0");
  EXPECT_EQ(summary.bytes, fs::file_size(request.out));
  EXPECT_GE(summary.seconds, 0.0);
  // Two episodes of at most T steps each (Gather may end one early); the first row is the first reset.
  ASSERT_GT(d.size(), 0u);
  EXPECT_LE(d.size(), static_cast<std::size_t>(2 * T));
  ASSERT_EQ(d.observation_dim, oracle->spec().observation_dim);
  for (int k = 0; k < d.observation_dim; ++k) EXPECT_EQ(d.observations[k], static_cast<float>(first[k])) << k;

  EXPECT_EQ(d.text_attributes.at("env_id"), "SafetyBallGather-v0");
  EXPECT_EQ(d.text_attributes.at("env_description"), envs::to_yaml(description));
  EXPECT_EQ(d.text_attributes.at("physics"), "faithful");
  EXPECT_EQ(d.text_attributes.at("actions"), "mean");
  EXPECT_EQ(d.text_attributes.at("bsg_version"), BSG_VERSION_STRING);
  EXPECT_EQ(d.text_attributes.at("seed"), "11");
  EXPECT_EQ(d.number_attributes.at("episodes"), 2.0);
  // No checkpoint: one constraint, the environment's whole cost at its own limit (Gather's d = 0.2).
  EXPECT_EQ(d.number_attributes.at("cost_limit"), description.cost_limit);
  EXPECT_EQ(d.number_attributes.at("cost_limit"), 0.2);
  EXPECT_NE(d.text_attributes.at("constraints").find("0.2"), std::string::npos) << d.text_attributes.at("constraints");
  EXPECT_TRUE(d.constraint_costs.empty());
}

TEST(CollectionRequest, CountsInTransitionsTheCostLimitAndThePhysicsAsAsked) {
  testing::TemporaryDirectory dir("collection_request");
  CollectionRequest request = random_request(dir.path() / "car.hdf5", "SafetyCarCircle-v0");
  request.episodes.reset();
  request.transitions = 300;
  request.cost_limit = 7.5;
  request.physics = PhysicsModel::kLean;
  request.policies = {{"random", 1.0}, {"random", 3.0}};
  const CollectionSummary summary = collect_to_file(request);
  const OfflineDataset d = read_dataset_file(request.out);
  EXPECT_EQ(d.size(), 300u);
  EXPECT_EQ(summary.transitions, 300u);
  EXPECT_EQ(d.number_attributes.at("cost_limit"), 7.5);
  EXPECT_EQ(d.text_attributes.at("physics"), "lean");
  EXPECT_EQ(d.text_attributes.at("actions"), "sampled");
  EXPECT_EQ(d.text_attributes.at("unit"), "transitions");
  // 300 split 1 : 3 is 75 and 225 transitions.
  const std::string& policies = d.text_attributes.at("policies");
  EXPECT_NE(policies.find(", 75 transitions"), std::string::npos) << policies;
  EXPECT_NE(policies.find(", 225 transitions"), std::string::npos) << policies;
}

TEST(CollectionRequest, TheSameRequestWritesTheSameBytes) {
  testing::TemporaryDirectory dir("collection_request");
  CollectionRequest request = random_request(dir.path() / "a.hdf5", "SafetyBallReach-v0");
  request.episodes = 2;
  request.seed = 4;
  collect_to_file(request);
  request.out = (dir.path() / "b.hdf5").string();
  collect_to_file(request);
  EXPECT_TRUE(testing::read_text_file(dir.path() / "a.hdf5") == testing::read_text_file(dir.path() / "b.hdf5"));
}

TEST(CollectionRequest, RefusalsAreOneLineAndWriteNothing) {
  testing::TemporaryDirectory dir("collection_request");
  const fs::path out = dir.path() / "x.hdf5";
  CollectionRequest both = random_request(out, "SafetyBallCircle-v0");
  both.transitions = 9;
  EXPECT_EQ(error_of(both), "give exactly one of --episodes N and --transitions N");
  CollectionRequest neither = random_request(out, "SafetyBallCircle-v0");
  neither.episodes.reset();
  EXPECT_EQ(error_of(neither), "give exactly one of --episodes N and --transitions N");
  CollectionRequest zero = random_request(out, "SafetyBallCircle-v0");
  zero.episodes = 0;
  EXPECT_EQ(error_of(zero), "--episodes must be at least 1, got 0");
  CollectionRequest negative = random_request(out, "SafetyBallCircle-v0");
  negative.episodes.reset();
  negative.transitions = -5;
  EXPECT_EQ(error_of(negative), "--transitions must be at least 1, got -5");
  CollectionRequest overrides_alone = random_request(out, "");
  overrides_alone.env_overrides = {{"apples", "3"}};
  EXPECT_EQ(error_of(overrides_alone), "--set changes the environment named by --env; give --env too");
  EXPECT_EQ(error_of(random_request(out, "")),
            "name the environment with --env (the random policy has none of its own)");
  EXPECT_NE(error_of(random_request(out, "SafetyBallNowhere-v0")).find("unknown environment id 'SafetyBallNowhere-v0'"),
            std::string::npos);
  CollectionRequest no_run = random_request(out, "SafetyBallCircle-v0");
  no_run.policies = {{(dir.path() / "no_run").string(), 1.0}};
  EXPECT_NE(error_of(no_run).find("no_run"), std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir.path()));

  // An existing file is kept unless the request says force.
  testing::write_text_file(out, "mine");
  EXPECT_EQ(error_of(random_request(out, "SafetyBallCircle-v0")), out.string() + " exists (--force replaces it)");
  EXPECT_EQ(testing::read_text_file(out), "mine");
  CollectionRequest forced = random_request(out, "SafetyBallCircle-v0");
  forced.force = true;
  collect_to_file(forced);
  EXPECT_EQ(read_dataset_file(out).text_attributes.at("env_id"), "SafetyBallCircle-v0");
}

}  // namespace
}  // namespace bsg::algos
