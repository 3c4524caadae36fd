// The factory and the interface contract shared by the on-policy algorithms: the
// right class per `alg`, the docs/algorithms.md#logged-columns column sets in order, a column set
// that does not change between epochs, and the state round trip.
#include "algos/training/make_algorithm.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "../algorithm_test_support.h"
#include "algos/first_order/make_first_order_algorithm.h"
#include "algos/trust_region/make_trust_region_algorithm.h"

namespace bsg::algos {
namespace {

using testing::SyntheticBatch;

std::vector<std::string> with_common(std::vector<std::string> specific) {
  std::vector<std::string> names = {"Loss/Pi", "Loss/DeltaPi", "Entropy", "KL", "PolicyRatio",
                                    "Misc/AcceptanceStep", "Misc/Alpha", "Misc/FinalStepNorm",
                                    "Misc/gradient_norm", "Misc/xHx", "Misc/H_inv_g"};
  names.insert(names.end(), specific.begin(), specific.end());
  return names;
}

const std::vector<std::string> kCpoColumns = {"Misc/cost_gradient_norm", "Misc/A", "Misc/B", "Misc/q", "Misc/r",
                                              "Misc/s", "Misc/Lambda_star", "Misc/Nu_star", "Misc/OptimCase"};

const std::vector<std::string> kFirstOrderColumns = {"Loss/Pi", "Loss/DeltaPi", "Entropy", "KL", "PolicyRatio",
                                                     "Misc/StopIter", "Misc/gradient_norm"};
std::vector<std::string> first_order_with(std::vector<std::string> specific) {
  std::vector<std::string> names = kFirstOrderColumns;
  names.insert(names.end(), specific.begin(), specific.end());
  return names;
}

const std::vector<Algorithm> kAllAlgorithmsInOrder = testing::on_policy_algorithms();

TEST(MakeAlgorithm, BuildsEachAlgorithmWithTheSpecColumns) {
  const struct {
    Algorithm alg;
    std::string name;
    std::vector<std::string> columns;
    std::size_t state_size;
  } expected[] = {
      {Algorithm::trpo, "trpo", with_common({}), 0},
      {Algorithm::lag_trpo, "lag-trpo", with_common({"LagrangeMultiplier"}), 1},
      {Algorithm::cpo, "cpo", with_common(kCpoColumns), 0},
      {Algorithm::pdo, "pdo", with_common({"Misc/cost_gradient_norm", "LagrangeMultiplier"}), 4},
      {Algorithm::pcpo, "pcpo", with_common(kCpoColumns), 0},
      // First-order: the multiplier's Adam state (4), then PolicyAdam's step count (1) before any step.
      {Algorithm::ppo, "ppo", kFirstOrderColumns, 1},
      {Algorithm::ppo_lag, "ppo-lag", first_order_with({"LagrangeMultiplier"}), 5},
      {Algorithm::focops, "focops", first_order_with({"LagrangeMultiplier"}), 5},
      {Algorithm::cup, "cup", first_order_with({"Misc/SecondStepStopIter", "LagrangeMultiplier"}), 5},
      {Algorithm::p3o, "p3o", first_order_with({"p3o_penalty"}), 1},
      {Algorithm::ipo, "ipo", first_order_with({"ipo_penalty"}), 1},
      {Algorithm::rcpo, "rcpo", with_common({"LagrangeMultiplier"}), 4},
  };
  for (const auto& entry : expected) {
    const RunConfig config = testing::config_for(entry.alg);
    const auto algorithm = make_algorithm(config);
    ASSERT_NE(algorithm, nullptr);
    EXPECT_EQ(algorithm->name(), entry.name);
    EXPECT_EQ(algorithm->diagnostic_names(), entry.columns) << entry.name;
    EXPECT_EQ(algorithm->state().size(), entry.state_size) << entry.name;
    EXPECT_EQ(algorithm->uses_cost_value_function(), !ignores_cost(entry.alg));
  }
}

TEST(MakeAlgorithm, EveryUpdateReportsTheSameColumnsInOrderEveryEpoch) {
  for (Algorithm alg : kAllAlgorithmsInOrder) {
    const auto algorithm = make_algorithm(testing::config_for(alg));
    SyntheticBatch batch(64, 7, 8);
    for (double mean_episode_cost : {40.0, 5.0, 30.0}) {
      PolicySurrogate surrogate = batch.surrogate();
      Rng shuffle(5);
      PolicyUpdateInputs inputs = testing::inputs_for(batch, surrogate, mean_episode_cost, 50.0);
      inputs.minibatch_rng = &shuffle;
      const PolicyUpdateResult result = algorithm->update(inputs);
      std::vector<std::string> names;
      for (const NamedScalar& entry : result.diagnostics) names.push_back(entry.name);
      EXPECT_EQ(names, algorithm->diagnostic_names()) << algorithm->name();
      for (const NamedScalar& entry : result.diagnostics) {
        EXPECT_TRUE(std::isfinite(entry.value)) << algorithm->name() << " " << entry.name;
      }
    }
  }
}

TEST(MakeAlgorithm, StateRoundTripsForEveryAlgorithm) {
  for (Algorithm alg : kAllAlgorithmsInOrder) {
    const RunConfig config = testing::config_for(alg);
    const auto original = make_algorithm(config);
    SyntheticBatch batch(64, 7, 8);
    PolicySurrogate surrogate = batch.surrogate();
    Rng shuffle(5);
    PolicyUpdateInputs inputs = testing::inputs_for(batch, surrogate, 33.0, 50.0);
    inputs.minibatch_rng = &shuffle;
    original->update(inputs);
    const auto restored = make_algorithm(config);
    restored->restore_state(original->state());
    EXPECT_EQ(restored->state(), original->state()) << original->name();
  }
}

// make_algorithm hands each algorithm to its family's factory; a family's factory builds only its own.
TEST(MakeAlgorithm, EachFamilysFactoryBuildsItsOwnAlgorithmsOnly) {
  for (const Algorithm alg : kAllAlgorithmsInOrder) {
    SCOPED_TRACE(std::string(to_string(alg)));
    const RunConfig config = testing::config_for(alg);
    const bool trust_region = algorithm_info(alg).family == AlgorithmFamily::trust_region;
    EXPECT_EQ(make_algorithm(config)->name(), to_string(alg));
    if (trust_region) {
      EXPECT_EQ(make_trust_region_algorithm(config)->name(), to_string(alg));
      EXPECT_THROW(make_first_order_algorithm(config), std::invalid_argument);
    } else {
      EXPECT_EQ(make_first_order_algorithm(config)->name(), to_string(alg));
      EXPECT_THROW(make_trust_region_algorithm(config), std::invalid_argument);
    }
  }
  RunConfig off_policy = testing::config_for(Algorithm::trpo);
  off_policy.alg = Algorithm::sac;
  EXPECT_THROW(make_algorithm(off_policy), std::invalid_argument);
}

TEST(PolicyUpdateResult, ValueNamesTheMissingColumn) {
  PolicyUpdateResult result;
  result.diagnostics = {{"KL", 0.5}};
  EXPECT_EQ(result.value("KL"), 0.5);
  EXPECT_THROW(result.value("Misc/A"), std::out_of_range);
}

}  // namespace
}  // namespace bsg::algos
