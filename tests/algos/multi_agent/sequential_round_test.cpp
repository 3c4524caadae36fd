// A sequential round (algos/multi_agent/sequential_round.h) and its correction factor
// (sequential_correction.h) on three linear Gaussian agents whose steps are set by hand: the
// factor each agent sees is the product of the hand-written density ratios of the agents
// before it, in the drawn order; the KL and step norm of each step; log space keeps a long
// product finite; mismatched batches are refused with one line.
#include "algos/multi_agent/sequential_round.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/multi_agent/sequential_correction.h"
#include "sequential_test_support.h"

namespace bsg::algos {
namespace {
namespace sequential_round_test {

using testing::vector_of;

constexpr int kSamples = 5;

struct ThreeAgents {
  // Agent 0: 2 -> 1, agent 1: 1 -> 1, agent 2: 1 -> 2; each with its own sigma.
  std::vector<double> sigmas{0.5, 0.3, 0.8};
  std::vector<Eigen::VectorXd> theta_old{vector_of({0.4, -0.2, 0.1}), vector_of({0.7, 0.05}),
                                         vector_of({0.3, -0.6, 0.2, -0.1})};
  std::vector<Eigen::VectorXd> theta_new{vector_of({0.5, -0.1, 0.0}), vector_of({0.6, 0.15}),
                                         vector_of({0.35, -0.5, 0.1, 0.0})};
  std::vector<GaussianPolicy> policies;
  std::vector<AgentBatch> batches;

  ThreeAgents() {
    const int observation_sizes[3] = {2, 1, 1};
    const int action_sizes[3] = {1, 1, 2};
    Rng rng(5);
    for (int k = 0; k < 3; ++k) {
      policies.push_back(testing::linear_policy(observation_sizes[k], action_sizes[k], theta_old[k], sigmas[k]));
      Eigen::MatrixXd observations(kSamples, observation_sizes[k]);
      Eigen::MatrixXd eps(kSamples, action_sizes[k]);
      for (Eigen::Index i = 0; i < observations.size(); ++i) observations.data()[i] = standard_normal(rng);
      for (Eigen::Index i = 0; i < eps.size(); ++i) eps.data()[i] = standard_normal(rng);
      batches.push_back(testing::linear_batch(observations, action_sizes[k], theta_old[k], sigmas[k], eps,
                                              Eigen::VectorXd::Ones(kSamples), Eigen::VectorXd::Zero(kSamples)));
    }
  }
};

TEST(SequentialRound, EachAgentSeesTheRatiosOfTheAgentsBeforeIt) {
  ThreeAgents agents;
  const std::vector<int> order{2, 0, 1};
  std::vector<Eigen::VectorXd> seen(3);
  const AgentUpdate set_by_hand = [&](int agent, const CorrectionFactor& factor) {
    seen[static_cast<std::size_t>(agent)] = factor.factor();
    agents.policies[static_cast<std::size_t>(agent)].mean_net().set_parameters(
        agents.theta_new[static_cast<std::size_t>(agent)]);
    return std::vector<NamedScalar>{{"agent", static_cast<double>(agent)}};
  };
  const std::vector<AgentRoundStatistics> statistics =
      sequential_round(testing::pointers_to(agents.policies), agents.batches, order, set_by_hand);

  std::vector<Eigen::VectorXd> ratios;
  for (std::size_t k = 0; k < 3; ++k) {
    ratios.push_back(
        testing::linear_ratios(agents.batches[k], agents.theta_old[k], agents.theta_new[k], agents.sigmas[k]));
  }
  // Order 2, 0, 1: agent 2 sees 1, agent 0 sees agent 2's ratio, agent 1 the product of both.
  const Eigen::VectorXd expected_2 = Eigen::VectorXd::Ones(kSamples);
  const Eigen::VectorXd expected_0 = ratios[2];
  const Eigen::VectorXd expected_1 = (ratios[2].array() * ratios[0].array()).matrix();
  EXPECT_EQ(seen[2], expected_2);
  for (Eigen::Index i = 0; i < kSamples; ++i) {
    EXPECT_NEAR(seen[0][i], expected_0[i], 1e-13 * expected_0[i]);
    EXPECT_NEAR(seen[1][i], expected_1[i], 1e-13 * expected_1[i]);
  }
  EXPECT_GT((expected_1 - Eigen::VectorXd::Ones(kSamples)).cwiseAbs().maxCoeff(), 0.05);  // a real correction

  ASSERT_EQ(statistics.size(), 3u);
  for (std::size_t position = 0; position < 3; ++position) {
    const AgentRoundStatistics& entry = statistics[position];
    const auto k = static_cast<std::size_t>(order[position]);
    EXPECT_EQ(entry.agent, order[position]);
    EXPECT_EQ(entry.position, static_cast<int>(position));
    ASSERT_EQ(entry.diagnostics.size(), 1u);
    EXPECT_EQ(entry.diagnostics[0].value, static_cast<double>(k));
    const Eigen::VectorXd& m = seen[k];
    EXPECT_NEAR(entry.factor.mean, m.mean(), 1e-15);
    EXPECT_EQ(entry.factor.min, m.minCoeff());
    EXPECT_EQ(entry.factor.max, m.maxCoeff());
    // KL(old || new) = 1/(N d_a) sum (mu_old - mu_new)^2 / (2 sigma^2)
    const int d_a = static_cast<int>(agents.batches[k].actions.cols());
    const Eigen::MatrixXd old_means = testing::linear_means(agents.batches[k].observations, d_a, agents.theta_old[k]);
    const Eigen::MatrixXd new_means = testing::linear_means(agents.batches[k].observations, d_a, agents.theta_new[k]);
    const double kl = (old_means - new_means).squaredNorm() / (2.0 * agents.sigmas[k] * agents.sigmas[k]) /
                      static_cast<double>(kSamples * d_a);
    EXPECT_NEAR(entry.kl, kl, 1e-14);
    EXPECT_NEAR(entry.step_norm, (agents.theta_new[k] - agents.theta_old[k]).norm(), 1e-15);
  }
}

TEST(CorrectionFactor, StartsAtOneAndLeavesTheAdvantagesBitForBit) {
  CorrectionFactor factor(3);
  const Eigen::VectorXd advantages = vector_of({0.1, -2.5, 1e-300});
  EXPECT_EQ(factor.corrected(advantages), advantages);
  const CorrectionFactorStatistics statistics = factor.statistics();
  EXPECT_EQ(statistics.mean, 1.0);
  EXPECT_EQ(statistics.min, 1.0);
  EXPECT_EQ(statistics.max, 1.0);
}

TEST(CorrectionFactor, MultipliesRatiosInLogSpace) {
  // Ratios e^800 and e^-800 overflow and underflow as doubles; their product, 1, does not in log space.
  CorrectionFactor factor(2);
  factor.include_agent(vector_of({800.0, 1.0}), vector_of({0.0, 0.5}));
  factor.include_agent(vector_of({-1000.0, 0.25}), vector_of({-200.0, 0.0}));
  const Eigen::VectorXd m = factor.factor();
  EXPECT_NEAR(m[0], 1.0, 1e-12);
  EXPECT_NEAR(m[1], std::exp(0.5) * std::exp(0.25), 1e-15);
  EXPECT_NEAR(factor.corrected(vector_of({2.0, -1.0}))[1], -std::exp(0.75), 1e-14);
}

TEST(SequentialRound, RefusesMismatchedBatchesWithOneLine) {
  const auto message_of = [](auto&& call) {
    try {
      call();
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const AgentUpdate nothing = [](int, const CorrectionFactor&) { return std::vector<NamedScalar>{}; };
  const std::vector<int> order{0, 1, 2};
  const auto round_of = [&](ThreeAgents& agents) {
    return [&] { sequential_round(testing::pointers_to(agents.policies), agents.batches, order, nothing); };
  };
  {
    ThreeAgents agents;
    agents.batches[1].advantages = Eigen::VectorXd::Zero(kSamples + 1);
    const std::string message = message_of(round_of(agents));
    EXPECT_NE(message.find("agent 1's advantages has 6 rows"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  {
    ThreeAgents agents;
    agents.batches[2].actions = Eigen::MatrixXd::Zero(kSamples, 3);
    const std::string message = message_of(round_of(agents));
    EXPECT_NE(message.find("agent 2's batch holds 1-d observations and 3-d actions"), std::string::npos) << message;
  }
  {
    ThreeAgents agents;
    agents.batches.pop_back();
    const std::string message = message_of(round_of(agents));
    EXPECT_NE(message.find("2 agent batches for 3 policies"), std::string::npos) << message;
  }
  {
    ThreeAgents agents;
    std::vector<GaussianPolicy*> with_null = testing::pointers_to(agents.policies);
    with_null[1] = nullptr;
    const std::string message = message_of([&] { sequential_round(with_null, agents.batches, order, nothing); });
    EXPECT_NE(message.find("agent 1's policy is null"), std::string::npos) << message;
    const std::vector<int> bad_order{0, 1, 1};
    EXPECT_THROW(sequential_round(testing::pointers_to(agents.policies), agents.batches, bad_order, nothing),
                 std::invalid_argument);
    EXPECT_THROW(CorrectionFactor(2).include_agent(vector_of({1.0}), vector_of({1.0, 2.0})), std::invalid_argument);
  }
}

}  // namespace sequential_round_test
}  // namespace
}  // namespace bsg::algos
