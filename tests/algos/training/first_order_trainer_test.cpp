// The first-order algorithms in the training loop (docs/algorithms.md#first-order-updates):
// a run stopped and resumed from its checkpoint (which holds the policy's
// Adam moments) continues with the same numbers as an uninterrupted one, on
// the scripted environment; and a short learning run per algorithm on
// SafetyBallCircle-v0 raises the return, the constrained ones bringing the
// episode cost down towards the limit. RCPO, a trust-region variant, resumes here beside
// P3O and IPO, the other penalty methods.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/on_policy_trainer.h"
#include "common/run_config_resolve.h"
#include "../scripted_env.h"

namespace fs = std::filesystem;
using bsg::testing::ScriptedEnv;
using bsg::testing::TemporaryDirectory;

namespace {

bsg::RunConfig scripted_config(bsg::Algorithm alg) {
  bsg::RunConfig config;
  config.env_id = "Scripted-v0";
  config.alg = alg;
  config.use_cost_value_function = !bsg::ignores_cost(alg);
  config.hidden_sizes = {16, 16};
  config.epochs = 5;
  config.steps_per_epoch = 400;  // 4 episodes of 100 steps
  config.max_ep_len = 100;
  config.save_freq = 10;         // only the stop and the end save
  config.eval_episodes = 0;
  config.cost_limit = 5;
  config.first_order.update_iters = 3;
  config.first_order.policy_minibatch_size = 64;
  config.trust_region.target_kl = 0.02;
  config.multiplier.lambda_optimizer = bsg::LambdaOptimizer::adam;
  config.multiplier.lambda_lr = 0.035;
  return config;
}

TEST(FirstOrderTrainer, ResumingContinuesWithTheSameNumbers) {
  for (const bsg::Algorithm alg :
       {bsg::Algorithm::ppo, bsg::Algorithm::ppo_lag, bsg::Algorithm::focops, bsg::Algorithm::cup, bsg::Algorithm::p3o,
        bsg::Algorithm::ipo, bsg::Algorithm::rcpo}) {
    SCOPED_TRACE(std::string(bsg::to_string(alg)));
    TemporaryDirectory dir;
    const bsg::RunConfig config = scripted_config(alg);
    bsg::algos::OnPolicyTrainer whole(config, bsg::algos::RunDirectory(dir.path() / "whole"), bsg::MpiContext::single_process(),
                               {}, std::make_unique<ScriptedEnv>(100));
    whole.run();
    bsg::algos::TrainerOptions stop;
    stop.stop_after_epochs = 3;
    {
      bsg::algos::OnPolicyTrainer first(config, bsg::algos::RunDirectory(dir.path() / "split"), bsg::MpiContext::single_process(),
                                 stop, std::make_unique<ScriptedEnv>(100));
      EXPECT_EQ(first.run().epochs_completed, 3);
    }
    bsg::algos::TrainerOptions resume;
    resume.resume = true;
    bsg::algos::OnPolicyTrainer second(config, bsg::algos::RunDirectory(dir.path() / "split"), bsg::MpiContext::single_process(),
                                resume, std::make_unique<ScriptedEnv>(100));
    ASSERT_EQ(second.epochs_completed(), 3);
    // The checkpoint brought back the policy's Adam moments, not a fresh optimiser (RCPO: its multiplier's).
    ASSERT_GT(second.algorithm().state().size(), bsg::is_first_order(alg) ? 10u : 3u);
    second.run();
    EXPECT_EQ(second.actor_critic().policy.mean_net().parameters(),
              whole.actor_critic().policy.mean_net().parameters());
    EXPECT_EQ(second.actor_critic().value.net().parameters(), whole.actor_critic().value.net().parameters());
    EXPECT_EQ(second.algorithm().state(), whole.algorithm().state());
  }
}

// Mean of a column over epochs [first, last).
double mean_over(const std::vector<double>& column, std::size_t first, std::size_t last) {
  return std::accumulate(column.begin() + static_cast<long>(first), column.begin() + static_cast<long>(last), 0.0) /
         static_cast<double>(last - first);
}

// A short learning run: 40 epochs of 5000 steps on SafetyBallCircle-v0, d = 25, the shipped
// defaults except PPO-Lag's multiplier step size: at OmniSafe's lambda_lr 0.035 its Adam multiplier
// moves about 0.035 per epoch and is still rising after 40 epochs (cost about 2.5 d there, measured
// with the annealed sigma; the 150-epoch figures of docs/algorithms.md use the default), so these
// tests give it lambda_lr 0.2. The longer runs' figures are in docs/algorithms.md#first-order-updates.
struct ShortRun {
  double first_return;  // mean episode return of the first 5 epochs
  double last_return;   // ... of the last 10
  double last_cost;     // mean episode cost of the last 10 epochs
};

constexpr int kEpochs = 40;
constexpr double kCostLimit = 25.0;

ShortRun short_run(const std::string& alg, int seed) {
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=" + alg, "seed=" + std::to_string(seed),
                           "epochs=" + std::to_string(kEpochs), "steps_per_epoch=5000", "eval_episodes=0"};
  if (alg == "ppo-lag") request.set_arguments.push_back("lambda_lr=0.2");
  const bsg::RunConfig config = bsg::resolve_run_config(request).config;
  const TemporaryDirectory directory;
  bsg::algos::OnPolicyTrainer trainer(config, bsg::algos::RunDirectory(directory.path() / "run"),
                                      bsg::MpiContext::single_process(), {});
  EXPECT_TRUE(trainer.run().finished);
  auto progress = bsg::testing::read_csv_columns(directory.path() / "run" / "progress.csv");
  const ShortRun run{mean_over(progress["episode_return_mean"], 0, 5),
                     mean_over(progress["episode_return_mean"], kEpochs - 10, kEpochs),
                     mean_over(progress["episode_cost_mean"], kEpochs - 10, kEpochs)};
  std::printf("  %s, seed %d: return %.1f -> %.1f, cost over the last 10 epochs %.1f\n", alg.c_str(), seed,
              run.first_return, run.last_return, run.last_cost);
  return run;
}

double median_of_three(double a, double b, double c) { return std::max(std::min(a, b), std::min(std::max(a, b), c)); }

TEST(FirstOrderLearning, PpoRaisesTheReturnOnBallCircleOnAShortBudget) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "training runs are too slow under the sanitizers; the updates run under them above";
#endif
  const ShortRun run = short_run("ppo", 1);
  EXPECT_GT(run.last_return, run.first_return + 50.0);
}

// A constrained algorithm over seeds 1-3: the median run raises the return and keeps the cost
// under 1.5 d. One 40-epoch run is a single draw: a multiplier still catching up with a late rise
// of the cost leaves single runs of FOCOPS and CUP at 2-2.5 d on some seeds (FOCOPS seed 3 on an
// AVX2 and an SSE2 build alike; CUP seed 1 on the SSE2 build, whose rounding makes it another draw,
// docs/reproducibility.md), while the median of three stayed under 0.8 d on both builds.
void expect_median_run_learns_within_the_limit(const std::string& alg) {
  std::vector<ShortRun> runs;
  for (const int seed : {1, 2, 3}) runs.push_back(short_run(alg, seed));
  const auto median = [&](auto field) { return median_of_three(field(runs[0]), field(runs[1]), field(runs[2])); };
  EXPECT_GT(median([](const ShortRun& r) { return r.last_return - r.first_return; }), 50.0);
  EXPECT_LT(median([](const ShortRun& r) { return r.last_cost; }), 1.5 * kCostLimit);
}

TEST(FirstOrderLearning, PpoLagLearnsBallCircleWithinTheLimitOnAShortBudget) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "training runs are too slow under the sanitizers; the updates run under them above";
#endif
  expect_median_run_learns_within_the_limit("ppo-lag");
}

TEST(FirstOrderLearning, FocopsLearnsBallCircleWithinTheLimitOnAShortBudget) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "training runs are too slow under the sanitizers; the updates run under them above";
#endif
  expect_median_run_learns_within_the_limit("focops");
}

TEST(FirstOrderLearning, CupLearnsBallCircleWithinTheLimitOnAShortBudget) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "training runs are too slow under the sanitizers; the updates run under them above";
#endif
  expect_median_run_learns_within_the_limit("cup");
}

}  // namespace
