// Behaviour cloning (algos/offline/behaviour_cloning.h) on tiny hand-made
// datasets whose actions come from a known linear demonstrator a = A s + b:
// the cloned policy recovers it on states it has not seen; BC-Safe keeps only
// the episodes within the cost limit, so it recovers the safe demonstrator
// where BC-All learns a blend. The normalised score on hand-computed cases.
#include "algos/offline/behaviour_cloning.h"

#include <gtest/gtest.h>

#include "algos/offline/normalized_score.h"
#include "common/random.h"

namespace bsg::algos {
namespace {

const Eigen::Matrix<double, 2, 3> kA = (Eigen::Matrix<double, 2, 3>() << 0.5, -0.2, 0.1, 0.3, 0.4, -0.6).finished();
const Eigen::Vector2d kB(0.1, -0.05);

// One episode of `steps` states uniform in [-1, 1]^3 acted on by a = A s + b,
// with cost `cost_per_step` at every step.
void append_episode(OfflineDataset& d, Rng& rng, int steps, const Eigen::Matrix<double, 2, 3>& a_matrix,
                    double cost_per_step) {
  d.observation_dim = 3;
  d.action_dim = 2;
  for (int t = 0; t < steps; ++t) {
    Eigen::Vector3d s;
    for (int k = 0; k < 3; ++k) s[k] = uniform(rng, -1.0, 1.0);
    const Eigen::Vector2d a = a_matrix * s + kB;
    for (int k = 0; k < 3; ++k) {
      d.observations.push_back(static_cast<float>(s[k]));
      d.next_observations.push_back(0.0f);
    }
    for (int k = 0; k < 2; ++k) d.actions.push_back(static_cast<float>(a[k]));
    d.rewards.push_back(1.0f);
    d.costs.push_back(static_cast<float>(cost_per_step));
    d.terminals.push_back(0.0f);
    d.timeouts.push_back(t == steps - 1 ? 1.0f : 0.0f);
  }
}

// The largest error of the policy against a = A s + b over fresh states.
double worst_error(const ClonedPolicy& policy, const Eigen::Matrix<double, 2, 3>& a_matrix) {
  Rng rng(999);
  double worst = 0.0;
  for (int i = 0; i < 200; ++i) {
    Eigen::Vector3d s;
    for (int k = 0; k < 3; ++k) s[k] = uniform(rng, -0.9, 0.9);
    worst = std::max(worst, (policy.action(s) - (a_matrix * s + kB)).cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(BehaviourCloning, LinearPolicyRecoversTheLinearDemonstrator) {
  OfflineDataset d;
  Rng rng(1);
  append_episode(d, rng, 1000, kA, 0.0);
  BehaviourCloningOptions options;
  options.hidden_sizes = {};  // a linear policy: the demonstrator is in its class
  options.updates = 4000;
  options.batch_size = 64;
  options.learning_rate = 1e-2;
  const BehaviourCloningResult result = train_behaviour_cloning(d, options);
  EXPECT_EQ(result.rows, 1000u);
  EXPECT_LT(worst_error(*result.policy, kA), 2e-3);
  EXPECT_LT(result.final_loss, 1e-6);
}

TEST(BehaviourCloning, TanhNetworkRecoversTheLinearDemonstrator) {
  OfflineDataset d;
  Rng rng(2);
  append_episode(d, rng, 2000, kA, 0.0);
  BehaviourCloningOptions options;
  options.hidden_sizes = {64, 64};
  options.updates = 3000;
  options.batch_size = 128;
  const BehaviourCloningResult result = train_behaviour_cloning(d, options);
  EXPECT_LT(worst_error(*result.policy, kA), 0.05);
}

TEST(BehaviourCloning, SafeVariantKeepsOnlyEpisodesWithinTheLimit) {
  // Episode 1 costs 0 and follows A; episode 2 costs 500 x 0.01 = 5 > 1 and follows -A.
  OfflineDataset d;
  Rng rng(3);
  append_episode(d, rng, 500, kA, 0.0);
  append_episode(d, rng, 500, -kA, 0.01);
  BehaviourCloningOptions options;
  options.hidden_sizes = {};
  options.updates = 4000;
  options.batch_size = 64;
  options.learning_rate = 1e-2;
  options.safe_only = true;
  options.cost_limit = 1.0;
  const BehaviourCloningResult safe = train_behaviour_cloning(d, options);
  EXPECT_EQ(safe.rows, 500u);
  EXPECT_EQ(safe.episodes, 1u);
  EXPECT_LT(worst_error(*safe.policy, kA), 2e-3);
  options.safe_only = false;
  const BehaviourCloningResult all = train_behaviour_cloning(d, options);
  EXPECT_EQ(all.rows, 1000u);
  EXPECT_GT(worst_error(*all.policy, kA), 0.3);  // half the data says -A: the fit is near b alone
  options.safe_only = true;
  options.cost_limit = 0.5;
  d.costs.assign(d.costs.size(), 0.01f);  // now both episodes cost 5
  EXPECT_THROW(train_behaviour_cloning(d, options), std::invalid_argument);
}

TEST(NormalizedScore, HandComputedCases) {
  // Rewards between 100 and 300; 150 is a quarter of the way. Cost 10 of a limit 20 is one half.
  EXPECT_DOUBLE_EQ(normalized_score(150, 10, 20, 100, 300).reward, 0.25);
  EXPECT_DOUBLE_EQ(normalized_score(150, 10, 20, 100, 300).cost, 0.5);
  EXPECT_DOUBLE_EQ(normalized_score(50, 30, 20, 100, 300).reward, -0.25);
  EXPECT_DOUBLE_EQ(normalized_score(50, 30, 20, 100, 300).cost, 1.5);
  // kappa = 0: eps = 1, cost 0 scores 1 and cost 3 scores 4.
  EXPECT_DOUBLE_EQ(normalized_score(100, 0, 0, 100, 300).cost, 1.0);
  EXPECT_DOUBLE_EQ(normalized_score(100, 3, 0, 100, 300).cost, 4.0);
  // kappa = 1: eps = 0.
  EXPECT_DOUBLE_EQ(normalized_score(100, 3, 1, 100, 300).cost, 3.0);
  EXPECT_THROW(normalized_score(1, 1, 1, 5, 5), std::invalid_argument);
  EXPECT_THROW(normalized_score(1, 1, -1, 0, 5), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
