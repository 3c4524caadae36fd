// The budget methods' decorators in a run (algos/training/budget_decorator.h): the learner
// trains on the decorated signal while progress.csv and the evaluation report the
// environment's own return and cost; a Saute policy is evaluated on the budget it was trained
// with; resuming continues exactly; keys that cannot make a budget are refused in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "../../test_support.h"
#include "algos/training/budget_decorator.h"
#include "algos/training/epoch_log.h"
#include "algos/training/load_policy.h"
#include "algos/training/on_policy_trainer.h"
#include "algos/training/progress_csv_fields.h"
#include "algos/training/progress_csv_reader.h"
#include "algos/training/run_environment.h"
#include "algos/training/run_evaluation.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"
#include "common/seeding.h"
#include "../scripted_env.h"
#include "../scripted_training.h"

namespace bsg::algos {
namespace {

namespace fs = std::filesystem;
using testing::ScriptedEnv;
using testing::TemporaryDirectory;

RunConfig scripted(Algorithm alg, double cost_limit) {
  RunConfig config = testing::scripted_config();  // 400 steps per epoch, episodes of 100 steps
  config.alg = alg;
  config.use_cost_value_function = false;
  config.cost_limit = cost_limit;
  config.epochs = 1;
  return config;
}

// The rows of the run's progress.csv, each by column.
std::vector<std::map<std::string, double>> rows_of(const RunConfig& config, std::unique_ptr<envs::Env> env) {
  TemporaryDirectory dir;
  const RunDirectory run(dir.path() / "run");
  OnPolicyTrainer(config, run, MpiContext::single_process(), {}, std::move(env)).run();
  const ProgressLogText log = read_progress_log(testing::read_text_file(run.progress()), "progress.csv", config.steps_per_epoch);
  const std::vector<std::string> names = split_csv_line(log.header);
  std::vector<std::map<std::string, double>> rows;
  for (const std::string& line : log.rows) {
    const std::vector<std::string> values = split_csv_line(line);
    std::map<std::string, double>& row = rows.emplace_back();
    for (std::size_t i = 0; i < names.size(); ++i) row[names[i]] = std::stod(values[i]);
  }
  return rows;
}

std::map<std::string, double> first_row(const RunConfig& config, std::unique_ptr<envs::Env> env) {
  return rows_of(config, std::move(env)).at(0);
}

// Sum of 1 + 0.01 t over t = from..to: the scripted environment's rewards.
double scripted_return(int from, int to) {
  double sum = 0.0;
  for (int t = from; t <= to; ++t) sum += 1.0 + 0.01 * t;
  return sum;
}

TEST(BudgetDecorator, EarlyTerminationCutsTheLearnersEpisodesAndTheLogKeepsTheTrueReturn) {
  // Cost 1 at every third step, limit 1.5: the sum exceeds it at step 6, where each episode is cut.
  const std::map<std::string, double> row =
      first_row(scripted(Algorithm::ppo_early_terminated, 1.5), std::make_unique<ScriptedEnv>(100, std::nullopt, 3));
  EXPECT_EQ(row.at("episode_length_mean"), 6.0);
  EXPECT_EQ(row.at("episodes"), 66.0);  // 400 steps: 66 whole cut episodes and 4 steps of the next
  EXPECT_NEAR(row.at("episode_return_mean"), 6.21, 1e-12);        // 1.01 + ... + 1.06
  EXPECT_NEAR(row.at("learner_return_mean"), 6.21 - 1.06, 1e-12);  // the cut step's reward is 0
  EXPECT_EQ(row.at("episode_cost_mean"), 2.0);
  EXPECT_EQ(row.at("budget_spent_fraction"), 1.0);
}

TEST(BudgetDecorator, SauteTrainsOnThePenaltyAndTheLogKeepsTheTrueReturn) {
  // Cost 1 at steps 10, 20, ..., 100; d = 0.5, gamma_s = 0.999, T = 100:
  // d~ = 0.5 (1 - 0.999^100) / (0.001 * 100) = 0.476, and z_10 = 0.999^-10 - 0.999^-1 / 0.476 < 0:
  // the budget is spent at step 10 and stays spent (z only falls further, divided by gamma_s).
  RunConfig config = scripted(Algorithm::ppo_saute, 0.5);
  config.budget.unsafe_reward = -1.0;
  const std::map<std::string, double> row = first_row(config, std::make_unique<ScriptedEnv>(100));
  EXPECT_EQ(row.at("episodes"), 4.0);
  EXPECT_NEAR(row.at("episode_return_mean"), scripted_return(1, 100), 1e-9);               // 150.5
  EXPECT_NEAR(row.at("learner_return_mean"), scripted_return(1, 9) - 91.0, 1e-9);          // 9.45 - 91
  EXPECT_EQ(row.at("episode_cost_mean"), 10.0);
  EXPECT_EQ(row.at("budget_spent_fraction"), 1.0);
}

TEST(BudgetDecorator, SimmersBudgetMovesBetweenEpochsAndTheLearnerSpendsEachEpochsBudget) {
  // Cost 1 at steps 10, 20, ..., 100: J = 10 every epoch. d = 20, b_0 = d / 4 = 5; K_P = 0.2 alone,
  // p = 0, in units of d~ = f d, f = (1 - 0.999^100) / (0.001 * 100) = 0.952:
  //   epoch 0: e = f (5 - 10), u = 0.2 e = -f (no clip, f < 1): b_1 = 5 - 1 = 4;
  //   epoch 1: e = f (4 - 10), u = -1.2 f = -1.14, clipped to -1: b_2 = 4 - 1 / f = 2.95.
  RunConfig config = scripted(Algorithm::ppo_simmer, 20.0);
  config.epochs = 3;
  config.budget.simmer_kp = 0.2;
  config.budget.simmer_ki = 0.0;
  config.budget.simmer_kd = 0.0;
  config.budget.simmer_polyak = 0.0;
  config.budget.simmer_initial_budget_fraction = 0.25;
  const std::vector<std::map<std::string, double>> rows = rows_of(config, std::make_unique<ScriptedEnv>(100));
  ASSERT_EQ(rows.size(), 3u);
  const double f = (1.0 - std::pow(0.999, 100)) / (0.001 * 100);
  const double budgets[] = {5.0, 4.0, 4.0 - 1.0 / f};
  // z_t 0.999^t = z_0 - sum_(s <= t) c_s 0.999^(s - 1) / d~ with z_0 = b / d, so the learner's
  // episode spends b once sum_j 0.999^(10 j - 1) reaches f b: 5 f = 4.76 at the 5th cost (sums
  // 3.91, 4.86), 4 f = 3.81 at the 4th (2.94, 3.91), 2.95 f = 2.81 at the 3rd (1.97, 2.94); from
  // that step s on its reward is -1: sum_1^(s-1) (1 + 0.01 t) - (101 - s).
  const int spent_at[] = {50, 40, 30};
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(rows[k].at("simmer_budget"), budgets[k], 1e-9);
    EXPECT_EQ(rows[k].at("episode_cost_mean"), 10.0);
    EXPECT_NEAR(rows[k].at("episode_return_mean"), scripted_return(1, 100), 1e-9);  // the environment's
    EXPECT_NEAR(rows[k].at("learner_return_mean"), scripted_return(1, spent_at[k] - 1) - (101 - spent_at[k]), 1e-9);
    EXPECT_EQ(rows[k].at("budget_spent_fraction"), 1.0);
  }
}

TEST(BudgetDecorator, SimmerWithoutGainsIsSaute) {
  // No gain moves the budget: the budget stays the limit, and training is Saute's bit for bit.
  RunConfig config = scripted(Algorithm::ppo_simmer, 5.0);
  config.epochs = 2;
  config.budget.simmer_kp = config.budget.simmer_ki = config.budget.simmer_kd = 0.0;
  RunConfig saute = config;
  saute.alg = Algorithm::ppo_saute;
  std::vector<std::map<std::string, double>> simmer_rows = rows_of(config, std::make_unique<ScriptedEnv>(100));
  const std::vector<std::map<std::string, double>> saute_rows = rows_of(saute, std::make_unique<ScriptedEnv>(100));
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(simmer_rows[k].at("simmer_budget"), 5.0);
    simmer_rows[k].erase("simmer_budget");
    for (auto& [column, value] : simmer_rows[k]) {
      if (!is_timing_column(column)) {
        EXPECT_EQ(value, saute_rows[k].at(column)) << column;
      }
    }
  }
}

TEST(BudgetDecorator, ARunWithoutABudgetMethodWritesNoLearnerColumns) {
  const std::map<std::string, double> row = first_row(scripted(Algorithm::ppo, 1.5), std::make_unique<ScriptedEnv>(100));
  EXPECT_EQ(row.count("learner_return_mean"), 0u);
  EXPECT_EQ(row.count("budget_spent_fraction"), 0u);
}

TEST(BudgetDecorator, ASauteRunResumedContinuesExactly) {
  TemporaryDirectory dir;
  RunConfig config = scripted(Algorithm::ppo_saute, 2.0);
  config.epochs = 3;
  config.save_freq = 10;
  OnPolicyTrainer whole(config, RunDirectory(dir.path() / "whole"), MpiContext::single_process(), {},
                        std::make_unique<ScriptedEnv>(100));
  whole.run();
  TrainerOptions stop;
  stop.stop_after_epochs = 2;
  OnPolicyTrainer(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), stop,
                  std::make_unique<ScriptedEnv>(100))
      .run();
  TrainerOptions resume;
  resume.resume = true;
  OnPolicyTrainer second(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), resume,
                         std::make_unique<ScriptedEnv>(100));
  second.run();
  EXPECT_EQ(second.actor_critic().policy.mean_net().parameters(), whole.actor_critic().policy.mean_net().parameters());
  EXPECT_EQ(second.actor_critic().observation_normalizer.mean(), whole.actor_critic().observation_normalizer.mean());
}

TEST(BudgetDecorator, ASimmerRunResumedContinuesExactly) {
  TemporaryDirectory dir;
  RunConfig config = scripted(Algorithm::ppo_simmer, 20.0);
  config.epochs = 4;
  config.save_freq = 10;
  config.budget.simmer_kp = 0.1;  // the budget moves every epoch; K_I and K_D act too
  config.budget.simmer_ki = 0.05;
  config.budget.simmer_kd = 0.3;
  config.budget.simmer_polyak = 0.5;
  config.budget.simmer_initial_budget_fraction = 0.3;
  OnPolicyTrainer whole(config, RunDirectory(dir.path() / "whole"), MpiContext::single_process(), {},
                        std::make_unique<ScriptedEnv>(100, std::nullopt, 7));
  whole.run();
  TrainerOptions stop;
  stop.stop_after_epochs = 2;
  OnPolicyTrainer(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), stop,
                  std::make_unique<ScriptedEnv>(100, std::nullopt, 7))
      .run();
  TrainerOptions resume;
  resume.resume = true;
  OnPolicyTrainer second(config, RunDirectory(dir.path() / "split"), MpiContext::single_process(), resume,
                         std::make_unique<ScriptedEnv>(100, std::nullopt, 7));
  second.run();
  EXPECT_EQ(second.actor_critic().policy.mean_net().parameters(), whole.actor_critic().policy.mean_net().parameters());
  EXPECT_EQ(second.algorithm().state(), whole.algorithm().state());  // the controller's budget, errors and steps
  const auto columns = [](const fs::path& progress) {
    const ProgressLogText log = read_progress_log(testing::read_text_file(progress), "progress.csv", 400);
    std::vector<std::string> budgets;
    const std::vector<std::string> names = split_csv_line(log.header);
    const auto column = static_cast<std::size_t>(std::find(names.begin(), names.end(), "simmer_budget") - names.begin());
    for (const std::string& row : log.rows) budgets.push_back(split_csv_line(row).at(column));
    return budgets;
  };
  const std::vector<std::string> budgets = columns(RunDirectory(dir.path() / "whole").progress());
  ASSERT_EQ(budgets.size(), 4u);
  EXPECT_NE(budgets[1], budgets[0]);
  EXPECT_EQ(columns(RunDirectory(dir.path() / "split").progress()), budgets);
}

RunConfig ball_circle(const std::vector<std::string>& settings) {
  RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "epochs=1", "steps_per_epoch=1000", "eval_episodes=2",
                           "hidden_sizes=[8, 8]", "max_ep_len=100"};
  request.set_arguments.insert(request.set_arguments.end(), settings.begin(), settings.end());
  return resolve_run_config(request).config;
}

TEST(BudgetDecorator, ASautePolicyIsEvaluatedOnTheBudgetItWasTrainedWith) {
  const TemporaryDirectory dir;
  const RunDirectory run(dir.path() / "run");
  const RunConfig config = ball_circle({"alg=ppo-saute"});
  const TrainingOutcome outcome = OnPolicyTrainer(config, run, MpiContext::single_process(), {}).run();
  ASSERT_TRUE(outcome.evaluation.has_value());

  const std::unique_ptr<LoadedPolicy> policy = load_policy(run);
  std::unique_ptr<envs::Env> env = make_run_env(config);
  ASSERT_EQ(policy->observation_size(), env->spec().observation_dim + 1);

  // The evaluation by hand: the raw environment, the budget z beside its observation, updated as
  // z <- (z - c / d~) / gamma_s with d~ = 25 (1 - 0.999^100) / (0.001 * 100).
  const double gamma = 0.999;
  const double normalized_budget = 25.0 * (1.0 - std::pow(gamma, 100)) / (1.0 - gamma) / 100.0;
  const std::uint64_t seed = derive_seed(static_cast<std::uint64_t>(config.seed), SeedStream::evaluation_environment, 0);
  std::vector<double> returns, costs;
  Rng unused(0);
  std::vector<double> action(static_cast<std::size_t>(policy->action_size()));
  for (int episode = 0; episode < 2; ++episode) {
    std::span<const double> observation = episode == 0 ? env->reset(seed) : env->reset();
    double z = 1.0, episode_return = 0.0, episode_cost = 0.0;
    for (int t = 1;; ++t) {
      std::vector<double> input(observation.begin(), observation.end());
      input.push_back(z);
      policy->act(input, ActionMode::mean, unused, action);
      const envs::StepResult step = env->step(action);
      episode_return += step.reward;
      episode_cost += step.cost;
      z = (z - step.cost / normalized_budget) / gamma;
      if (step.terminated || step.truncated || t >= 100) break;
      observation = step.observation;
    }
    returns.push_back(episode_return);
    costs.push_back(episode_cost);
  }
  const RunEvaluation evaluated = evaluate_run_directory(run, 2, MpiContext::single_process());
  ASSERT_EQ(evaluated.summary.episodes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(evaluated.summary.episodes[i].episode_return, returns[i], 1e-9 * (1 + std::abs(returns[i]))) << i;
    EXPECT_EQ(evaluated.summary.episodes[i].episode_cost, costs[i]) << i;
    // The training's own final evaluation agrees with bsg eval's.
    EXPECT_EQ(outcome.evaluation->episodes[i].episode_return, evaluated.summary.episodes[i].episode_return) << i;
  }
}

TEST(BudgetDecorator, ASimmerPolicyIsEvaluatedWithItsWholeBudgetByTrainingAndBsgEvalAlike) {
  // A budget started at 0.4 d and moved by a quick controller: after training, the run's own
  // evaluation starts each episode at z = 1 (the limit), as bsg eval's does (decorate_for_budget).
  const TemporaryDirectory dir;
  const RunDirectory run(dir.path() / "run");
  const RunConfig config = ball_circle({"alg=ppo-simmer", "epochs=2", "simmer_kp=0.05", "simmer_ki=0.005",
                                        "simmer_polyak=0.5", "simmer_initial_budget_fraction=0.4"});
  const TrainingOutcome outcome = OnPolicyTrainer(config, run, MpiContext::single_process(), {}).run();
  ASSERT_TRUE(outcome.evaluation.has_value());
  const RunEvaluation evaluated = evaluate_run_directory(run, 2, MpiContext::single_process());
  ASSERT_EQ(evaluated.summary.episodes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(outcome.evaluation->episodes[i].episode_return, evaluated.summary.episodes[i].episode_return) << i;
    EXPECT_EQ(outcome.evaluation->episodes[i].episode_cost, evaluated.summary.episodes[i].episode_cost) << i;
  }
}

// A ConfigError of one line that names `key`.
void expect_refused(const std::vector<std::string>& settings, const std::string& key) {
  try {
    ball_circle(settings);
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(key), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(BudgetDecorator, KeysThatCannotMakeABudgetAreRefusedInOneLine) {
  expect_refused({"alg=ppo-saute", "cost_limit=0"}, "cost_limit");
  expect_refused({"alg=trpo-saute", "constraints=[{terms: all, limit: 0}]"}, "constraints");
  expect_refused({"alg=ppo-saute", "saute_gamma=1"}, "saute_gamma");
  expect_refused({"alg=ppo", "unsafe_reward=-2"}, "unsafe_reward");
  expect_refused({"alg=ppo-early-terminated", "saute_gamma=0.9"}, "saute_gamma");
  EXPECT_EQ(ball_circle({"alg=ppo-early-terminated", "cost_limit=0"}).cost_limit, 0.0);  // ET can keep a zero budget
  expect_refused({"alg=ppo-simmer", "cost_limit=0"}, "cost_limit");
  expect_refused({"alg=trpo-simmer", "simmer_polyak=1"}, "simmer_polyak");
  expect_refused({"alg=ppo-simmer", "simmer_kp=-0.1"}, "simmer_kp");
  expect_refused({"alg=ppo-simmer", "simmer_initial_budget_fraction=0"}, "simmer_initial_budget_fraction");
  expect_refused({"alg=ppo-simmer", "simmer_initial_budget_fraction=1.5"}, "simmer_initial_budget_fraction");
  expect_refused({"alg=ppo-saute", "simmer_ki=0.1"}, "simmer_ki");  // Saute has no controller
}

}  // namespace
}  // namespace bsg::algos
