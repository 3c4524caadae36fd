// Several constraints (docs/algorithms.md#several-constraints) through the learner: each
// constraint's own GAE in the buffer (hand-computed), the step costs from named
// terms, the per-constraint surrogates, m multipliers against hand-computed
// sequences and their checkpointed state, and whole runs on SafetyBallRun-v0
// with two constraints: per-constraint columns, safety during training against
// the run's own per-episode costs, and a resumed run identical to an
// uninterrupted one.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "../algorithm_test_support.h"
#include "algos/core/buffer.h"
#include "algos/core/constraint_costs.h"
#include "algos/trust_region/lag_trpo.h"
#include "algos/lagrange/constraint_multipliers.h"
#include "algos/training/on_policy_trainer.h"
#include "common/config_error.h"

namespace bsg::algos {
namespace {

namespace fs = std::filesystem;

Eigen::VectorXd values(std::initializer_list<double> list) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(list.size()));
  Eigen::Index i = 0;
  for (double x : list) v[i++] = x;
  return v;
}

TEST(SeveralConstraintsBuffer, EachConstraintHasItsOwnGaeAndEpisodeCost) {
  // gamma = 0.5, lam_c = 0.5 (gamma lam = 0.25); one path of 3 steps ending in a terminal (bootstrap 0).
  Buffer buffer(3, 1, 1, BufferOptions{0.5, 0.5, 0.5, 2});
  const Eigen::VectorXd o = values({0.0}), a = values({0.0});
  // step costs (c1, c2) and values (V1, V2)
  buffer.store(o, a, 1.0, 1.0, values({1.0, 0.0}), 0.0, values({0.5, 1.0}), 0.0);
  buffer.store(o, a, 1.0, 0.0, values({0.0, 2.0}), 0.0, values({0.2, 1.0}), 0.0);
  buffer.store(o, a, 1.0, 1.0, values({1.0, 0.0}), 0.0, values({1.0, 0.0}), 0.0);
  buffer.finish_path(0.0, values({0.0, 0.0}), std::nullopt, PathEnd::episode_end);
  // Constraint 1: delta = (1 + 0.5*0.2 - 0.5, 0 + 0.5*1 - 0.2, 1 - 1) = (0.6, 0.3, 0)
  //   A = (0.6 + 0.25*(0.3 + 0.25*0), 0.3, 0) = (0.675, 0.3, 0)
  // Constraint 2: delta = (0 + 0.5*1 - 1, 2 + 0 - 1, 0 - 0) = (-0.5, 1, 0)
  //   A = (-0.5 + 0.25*1, 1, 0) = (-0.25, 1, 0)
  const Eigen::MatrixXd& A = buffer.constraint_cost_advantages();
  EXPECT_NEAR(A(0, 0), 0.675, 1e-15);
  EXPECT_NEAR(A(1, 0), 0.3, 1e-15);
  EXPECT_NEAR(A(2, 0), 0.0, 1e-15);
  EXPECT_NEAR(A(0, 1), -0.25, 1e-15);
  EXPECT_NEAR(A(1, 1), 1.0, 1e-15);
  EXPECT_NEAR(A(2, 1), 0.0, 1e-15);
  EXPECT_NEAR(buffer.constraint_cost_value_targets()(0, 1), -0.25 + 1.0, 1e-15);  // R = A + V
  ASSERT_EQ(buffer.episodes().size(), 1u);
  EXPECT_EQ(buffer.episodes()[0].episode_cost, 2.0);  // the environment's cost
  EXPECT_EQ(buffer.episodes()[0].constraint_costs, (std::vector<double>{2.0, 2.0}));
  EXPECT_EQ(buffer.epoch_cost(), 2.0);
  EXPECT_EQ(buffer.epoch_constraint_costs(), values({2.0, 2.0}));
  Buffer two(3, 1, 1, BufferOptions{0.5, 0.5, 0.5, 2});
  EXPECT_THROW(two.store(o, a, 0, 0, 0, 0, 0), std::invalid_argument);  // the scalar form serves m = 1 only
}

envs::StepResult step_with_terms(const std::vector<envs::CostTerm>& terms, double cost) {
  envs::StepResult step;
  step.cost = cost;
  step.cost_terms = terms;
  return step;
}

TEST(SeveralConstraintsCosts, NamedTermsAreSummedAndAllIsTheEnvironmentsCost) {
  RunConfig config;
  config.constraints = {{{"cost_velocity_violation"}, 5.0},
                        {{"cost_outside_bounds", "cost_velocity_violation"}, 20.0},
                        {{"all"}, 25.0}};
  StepCostSelector selector(config);
  ASSERT_TRUE(selector.needs_terms());
  selector.bind({"cost_outside_bounds", "cost_velocity_violation"}, "SafetyBallRun-v0");
  const std::vector<envs::CostTerm> terms = {{"cost_outside_bounds", 1.0}, {"cost_velocity_violation", 1.0}};
  Eigen::VectorXd costs(3);
  selector.select(step_with_terms(terms, 1.0), costs);
  EXPECT_EQ(costs, values({1.0, 2.0, 1.0}));  // the environment clips its sum at 1, a named pair does not
  EXPECT_EQ(constraint_count(config), 3);
  EXPECT_EQ(constraint_limit(config, 1), 20.0);
  EXPECT_EQ(constraint_count(RunConfig{}), 1);
  EXPECT_EQ(constraint_limit(RunConfig{}, 0), RunConfig{}.cost_limit);
}

TEST(SeveralConstraintsCosts, AnUnknownTermIsAnErrorListingTheEnvironmentsTerms) {
  RunConfig config;
  config.constraints = {{{"cost_collisions"}, 5.0}};
  StepCostSelector selector(config);
  try {
    selector.bind({"cost_outside_bounds", "cost_velocity_violation"}, "SafetyBallRun-v0");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(testing::contains(message, "'cost_collisions'"));
    EXPECT_TRUE(testing::contains(message, "SafetyBallRun-v0"));
    EXPECT_TRUE(testing::contains(message, "cost_outside_bounds, cost_velocity_violation"));
  }
}

TEST(SeveralConstraintsSurrogate, EachCostSurrogateAndTheWeightedGradient) {
  testing::SyntheticBatch batch(64, 3, 4);
  Eigen::MatrixXd cost_advantages(64, 2);
  cost_advantages.col(0) = batch.cost_advantages;
  cost_advantages.col(1) = (-0.5 * batch.advantages).array() + 0.25;
  PolicySurrogate surrogate(batch.observations, batch.actions, batch.old_log_probs, batch.advantages, cost_advantages);
  // At theta_old every ratio is 1: L_Cj = mean(A^Cj).
  const SurrogateValues at_old = surrogate.evaluate(batch.policy);
  EXPECT_NEAR(at_old.cost_surrogates[0], cost_advantages.col(0).mean(), 1e-12);
  EXPECT_NEAR(at_old.cost_surrogates[1], cost_advantages.col(1).mean(), 1e-12);
  // The weighted gradient is linear in the weights: 0.3 grad L_R - 0.2 grad L_C1 + 0.7 grad L_C2.
  const Eigen::Index P = batch.policy.mean_net().num_parameters();
  Eigen::VectorXd g(P), b1(P), b2(P), combined(P);
  const std::vector<double> e1 = {1.0, 0.0}, e2 = {0.0, 1.0}, w = {-0.2, 0.7};
  surrogate.gradient(batch.policy, 1.0, std::vector<double>{0.0, 0.0}, g);
  surrogate.gradient(batch.policy, 0.0, e1, b1);
  surrogate.gradient(batch.policy, 0.0, e2, b2);
  surrogate.gradient(batch.policy, 0.3, w, combined);
  EXPECT_LT((combined - (0.3 * g - 0.2 * b1 + 0.7 * b2)).norm(), 1e-12 * (1.0 + combined.norm()));
  // Constraint 1's gradient is the single-constraint form's.
  Eigen::VectorXd single(P);
  surrogate.gradient(batch.policy, 0.0, 1.0, single);
  EXPECT_EQ(single, b1);
}

TEST(SeveralConstraintsMultipliers, SgdSequencesByHandAndTheirState) {
  RunConfig config;
  config.alg = Algorithm::lag_trpo;
  config.multiplier.lambda_optimizer = LambdaOptimizer::sgd;
  config.multiplier.lagrangian_multiplier_init = 0.001;
  config.multiplier.lambda_lr = 0.05;
  config.constraints = {{{"a"}, 20.0}, {{"b"}, 5.0}};
  LagrangeMultipliers multipliers(config);
  // lambda_j <- max(0, lambda_j + 0.05 (J_j - d_j))
  std::vector<ConstraintEstimate> epoch = {{30.0, 20.0}, {10.0, 5.0}};
  std::vector<double> lambdas = multipliers.update(epoch);
  EXPECT_NEAR(lambdas[0], 0.001 + 0.05 * 10.0, 1e-15);  // 0.501
  EXPECT_NEAR(lambdas[1], 0.001 + 0.05 * 5.0, 1e-15);   // 0.251
  epoch = {{10.0, 20.0}, {2.0, 5.0}};
  lambdas = multipliers.update(epoch);
  EXPECT_NEAR(lambdas[0], 0.501 - 0.5, 1e-15);   // 0.001
  EXPECT_NEAR(lambdas[1], 0.251 - 0.15, 1e-15);  // 0.101
  epoch = {{0.0, 20.0}, {0.0, 5.0}};
  lambdas = multipliers.update(epoch);
  EXPECT_EQ(lambdas[0], 0.0);  // clamped at 0
  EXPECT_EQ(lambdas[1], 0.0);  // 0.101 - 0.25 < 0
  EXPECT_EQ(multipliers.diagnostic_names(), (std::vector<std::string>{"constraint_1_lambda", "constraint_2_lambda"}));

  const std::vector<NamedScalar> saved = multipliers.state();
  EXPECT_EQ(saved[0].name, "constraint_1/lagrange_multiplier");
  LagrangeMultipliers restored(config);
  restored.restore_state(saved);
  EXPECT_EQ(restored.state(), saved);
  std::vector<NamedScalar> renamed = saved;
  renamed[1].name = "constraint_1/lagrange_multiplier";
  EXPECT_THROW(restored.restore_state(renamed), std::invalid_argument);
  EXPECT_EQ(restored.state(), saved);  // unchanged by the failed restore
}

TEST(SeveralConstraintsMultipliers, AdamAndPidKeepOneOptimiserStatePerConstraint) {
  for (const LambdaOptimizer optimizer : {LambdaOptimizer::adam, LambdaOptimizer::pid}) {
    RunConfig config;
    config.alg = Algorithm::pdo;
    config.multiplier.lambda_optimizer = optimizer;
    config.multiplier.lagrangian_multiplier_init = 0.001;
    config.constraints = {{{"a"}, 1.0}, {{"b"}, 1.0}};
    LagrangeMultipliers two(config);
    RunConfig one_config = config;
    one_config.constraints.clear();
    one_config.cost_limit = 1.0;
    LagrangeMultiplier first(one_config), second(one_config);
    // Each multiplier of the pair follows its own single-constraint sequence.
    for (const auto& [j1, j2] : std::vector<std::pair<double, double>>{{3, 0}, {2, 0.5}, {0, 4}, {1, 1}}) {
      const std::vector<ConstraintEstimate> epoch = {{j1, 1.0}, {j2, 1.0}};
      const std::vector<double> lambdas = two.update(epoch);
      EXPECT_EQ(lambdas[0], first.update(j1, 1.0));
      EXPECT_EQ(lambdas[1], second.update(j2, 1.0));
    }
    EXPECT_EQ(two.state().size(), 2 * first.state().size());
  }
}

TEST(SeveralConstraintsMultipliers, OneConstraintKeepsTheSingleMultipliersNames) {
  RunConfig config;
  config.alg = Algorithm::lag_trpo;
  const LagrangeMultipliers one(config);
  EXPECT_EQ(one.state(), LagrangeMultiplier(config).state());
  EXPECT_EQ(one.diagnostic_names(), LagrangeMultiplier(config).diagnostic_names());
}

// Two constraints on SafetyBallRun-v0, a few small epochs.
RunConfig two_constraint_config(Algorithm alg) {
  RunConfig config;
  config.env_id = "SafetyBallRun-v0";
  config.alg = alg;
  config.use_cost_value_function = true;
  config.hidden_sizes = {16, 16};
  config.epochs = 4;
  config.steps_per_epoch = 600;  // 3 episodes of 200 steps
  config.max_ep_len = 200;
  config.save_freq = 1;
  config.eval_episodes = 2;
  config.trust_region.target_kl = 0.001;
  config.constraints = {{{"cost_outside_bounds"}, 20.0}, {{"cost_velocity_violation"}, 5.0}};
  return config;
}

TEST(SeveralConstraintsTraining, ColumnsAndSafetyDuringTrainingAgreeWithTheEpisodeCosts) {
  for (const Algorithm alg : {Algorithm::lag_trpo, Algorithm::cpo, Algorithm::pcpo, Algorithm::pdo}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    testing::TemporaryDirectory dir;
    const RunConfig config = two_constraint_config(alg);
    OnPolicyTrainer trainer(config, RunDirectory(dir.path() / "run"), MpiContext::single_process(), {});
    ASSERT_TRUE(trainer.run().finished);
    auto columns = testing::read_csv_columns(dir.path() / "run" / "progress.csv");
    for (const char* name : {"constraint_1_cost", "constraint_2_limit", "constraint_2_epochs_over_limit",
                             "cumulative_cost", "cost_rate", "constraint_1_cost_rate"}) {
      ASSERT_EQ(columns.count(name), 1u) << name;
    }
    ASSERT_EQ(columns.count(alg == Algorithm::lag_trpo || alg == Algorithm::pdo ? "constraint_2_lambda"
                                                                                : "constraint_2_nu"),
              1u);
    // Every epoch is 3 whole episodes, so the training cost is the sum of the
    // episodes' costs: J_C mean x episodes, per epoch, summed.
    double cumulative = 0.0, cumulative_1 = 0.0, cumulative_2 = 0.0;
    long long over_2 = 0;
    bool second_value_loss_differs = false;  // V_C2's own fit, not V_C1's repeated
    for (std::size_t k = 0; k < columns["epoch"].size(); ++k) {
      const double episodes = columns["episodes"][k];
      ASSERT_EQ(episodes, 3.0);
      cumulative += columns["episode_cost_mean"][k] * episodes;
      cumulative_1 += columns["constraint_1_cost"][k] * episodes;
      cumulative_2 += columns["constraint_2_cost"][k] * episodes;
      if (columns["constraint_2_cost"][k] > 5.0) ++over_2;
      const double steps = columns["total_env_steps"][k];
      EXPECT_NEAR(columns["cumulative_cost"][k], cumulative, 1e-9);
      EXPECT_NEAR(columns["cost_rate"][k], cumulative / steps, 1e-12);
      EXPECT_NEAR(columns["constraint_1_cumulative_cost"][k], cumulative_1, 1e-9);
      EXPECT_NEAR(columns["constraint_2_cost_rate"][k], cumulative_2 / steps, 1e-12);
      EXPECT_EQ(columns["constraint_2_epochs_over_limit"][k], static_cast<double>(over_2));
      EXPECT_EQ(columns["constraint_1_limit"][k], 20.0);
      // Constraint 1's V_C is the net cost_value_loss has always described; constraint 2's
      // loss is a mean of squares.
      EXPECT_EQ(columns["constraint_1_cost_value_loss"][k], columns["cost_value_loss"][k]);
      EXPECT_EQ(columns["constraint_1_cost_value_loss_delta"][k], columns["cost_value_loss_delta"][k]);
      EXPECT_GE(columns["constraint_2_cost_value_loss"][k], 0.0);
      EXPECT_GE(columns["constraint_2_cost_value_loss"][k] + columns["constraint_2_cost_value_loss_delta"][k], 0.0);
      second_value_loss_differs |= columns["constraint_2_cost_value_loss"][k] != columns["cost_value_loss"][k];
    }
    EXPECT_TRUE(second_value_loss_differs);
  }
}

TEST(SeveralConstraintsTraining, AResumedRunIsIdenticalToAnUninterruptedOne) {
  for (const Algorithm alg : {Algorithm::lag_trpo, Algorithm::cpo}) {
    SCOPED_TRACE(std::string(to_string(alg)));
    testing::TemporaryDirectory dir;
    RunConfig config = two_constraint_config(alg);
    config.save_freq = 10;
    OnPolicyTrainer whole(config, RunDirectory(dir.path() / "whole"), MpiContext::single_process(), {});
    whole.run();
    TrainerOptions stop;
    stop.stop_after_epochs = 2;
    {
      OnPolicyTrainer first(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), stop);
      first.run();
    }
    TrainerOptions resume;
    resume.resume = true;
    OnPolicyTrainer second(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), resume);
    second.run();
    EXPECT_EQ(second.actor_critic().policy.mean_net().parameters(),
              whole.actor_critic().policy.mean_net().parameters());
    ASSERT_EQ(second.actor_critic().extra_cost_values.size(), 1u);
    EXPECT_EQ(second.actor_critic().extra_cost_values[0].net().parameters(),
              whole.actor_critic().extra_cost_values[0].net().parameters());
    EXPECT_EQ(second.algorithm().state(), whole.algorithm().state());
    // progress.csv equal but for the timing columns.
    const auto a = testing::read_csv_rows(dir.path() / "whole" / "progress.csv");
    const auto b = testing::read_csv_rows(dir.path() / "split" / "progress.csv");
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t r = 1; r < a.size(); ++r) {
      for (std::size_t c = 0; c < a[0].size(); ++c) {
        if (a[0][c].rfind("time_", 0) == 0 || a[0][c] == "fps") continue;
        EXPECT_EQ(a[r][c], b[r][c]) << a[0][c] << " row " << r;
      }
    }
  }
}

TEST(SeveralConstraintsTraining, AnUnknownTermStopsTheRunBeforeItsDirectoryIsWritten) {
  testing::TemporaryDirectory dir;
  RunConfig config = two_constraint_config(Algorithm::cpo);
  config.constraints[1].terms = {"cost_gathered_bombs"};
  EXPECT_THROW(OnPolicyTrainer(config, RunDirectory(dir.path() / "run"), MpiContext::single_process(), {}),
               ConfigError);
  EXPECT_FALSE(fs::exists(dir.path() / "run" / "config.yaml"));
}

}  // namespace
}  // namespace bsg::algos
