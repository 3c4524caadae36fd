// Statistical equivalence of the lean and the faithful physics (env.h): for
// every environment with a lean model, 30 whole episodes with the random and
// with the zero policy in each model; mean episode return and mean episode cost
// must agree within 4 standard errors of their paired difference, or within 5 %
// of the faithful mean. Trajectories themselves part after a few hundred steps
// (chaos amplifies rounding), so only statistics can be compared. Episode k
// starts from the same layout in both models, so pairing takes the layouts'
// spread out of the error: 30 paired episodes bound the difference more tightly
// than 100 unpaired ones did (Car Run, random policy: 4 standard errors of 4.5
// against 26.9), at under a third of the steps.
// One ctest entry per (environment, policy), so that ctest -j spreads them.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "common/random.h"
#include "envs/env.h"
#include "sample_mean.h"

namespace bsg::envs {
namespace {
namespace lean_physics_statistics_test {

constexpr int kEpisodes = 30;

struct Sample {
  std::vector<double> returns;
  std::vector<double> costs;
};

// As `bsg rollout`: the first reset with `seed`, later ones continue the
// environment's stream; the random policy has its own generator.
Sample play(const std::string& id, PhysicsModel physics, bool random_policy, std::uint64_t seed) {
  const std::unique_ptr<Env> env = make(id, {.physics = physics});
  Rng policy_rng(seed ^ 0x9e3779b97f4a7c15ULL);
  std::vector<double> action(static_cast<size_t>(env->spec().action_dim), 0.0);
  Sample sample;
  for (int k = 0; k < kEpisodes; ++k) {
    if (k == 0) {
      env->reset(seed);
    } else {
      env->reset();
    }
    double episode_return = 0;
    double episode_cost = 0;
    for (bool done = false; !done;) {
      if (random_policy) {
        for (double& a : action) a = uniform(policy_rng, -1, 1);
      }
      const StepResult step = env->step(action);
      episode_return += step.reward;
      episode_cost += step.cost;
      done = step.terminated || step.truncated;
    }
    sample.returns.push_back(episode_return);
    sample.costs.push_back(episode_cost);
  }
  return sample;
}

using bsg::testing::MeanAndError;
using bsg::testing::mean_and_error;

// Episode k of both models starts from the same layout with the same first
// actions, so the comparison is paired: the mean of the per-episode
// differences against its own standard error.
void expect_equivalent(const std::vector<double>& faithful, const std::vector<double>& lean,
                       const std::string& what) {
  std::vector<double> differences;
  for (std::size_t k = 0; k < faithful.size(); ++k) differences.push_back(lean[k] - faithful[k]);
  const MeanAndError f = mean_and_error(faithful);
  const MeanAndError l = mean_and_error(lean);
  const MeanAndError d = mean_and_error(differences);
  const double difference = std::abs(d.mean);
  const double standard_error = std::sqrt(d.variance_of_mean);
  const bool within_errors = difference <= 4 * standard_error;
  const bool within_percent = difference <= 0.05 * std::abs(f.mean);
  EXPECT_TRUE(within_errors || within_percent)
      << what << ": faithful mean " << f.mean << ", lean mean " << l.mean << ", mean paired difference "
      << d.mean << " > 4 standard errors (" << 4 * standard_error << ") and > 5 % ("
      << 0.05 * std::abs(f.mean) << ")";
  std::printf("%s: faithful %.4f, lean %.4f, |diff| %.4f, 4 SE paired %.4f, 4 SE unpaired %.4f\n", what.c_str(), f.mean,
              l.mean, difference, 4 * standard_error, 4 * std::sqrt(f.variance_of_mean + l.variance_of_mean));
}

struct Case {
  std::string id;
  bool random_policy;
};

// So that gtest names the case in its listing instead of dumping its bytes.
void PrintTo(const Case& c, std::ostream* out) {
  *out << c.id << (c.random_policy ? ", random policy" : ", zero policy");
}

class LeanPhysicsStatistics : public ::testing::TestWithParam<Case> {};

TEST_P(LeanPhysicsStatistics, MeanReturnAndCostAgreeWithFaithful) {
  const Case& c = GetParam();
  ASSERT_TRUE(has_lean_model(c.id));
  constexpr std::uint64_t kSeed = 2024;
  const Sample faithful = play(c.id, PhysicsModel::kFaithful, c.random_policy, kSeed);
  const Sample lean = play(c.id, PhysicsModel::kLean, c.random_policy, kSeed);
  expect_equivalent(faithful.returns, lean.returns, c.id + " return");
  expect_equivalent(faithful.costs, lean.costs, c.id + " cost");
}

std::vector<Case> cases() {
  std::vector<Case> result;
  for (const std::string& id : registered_ids()) {
    if (!has_lean_model(id) || !id.ends_with("-v0")) continue;  // the fork's differ only in values
    result.push_back({id, true});
    result.push_back({id, false});
  }
  return result;
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string id = info.param.id;
  std::string name;
  for (char ch : id) {
    if (std::isalnum(static_cast<unsigned char>(ch))) name += ch;
  }
  return name + (info.param.random_policy ? "_Random" : "_Zero");
}

INSTANTIATE_TEST_SUITE_P(EveryLeanEnvironment, LeanPhysicsStatistics, ::testing::ValuesIn(cases()),
                         case_name);

}  // namespace lean_physics_statistics_test
}  // namespace
}  // namespace bsg::envs
