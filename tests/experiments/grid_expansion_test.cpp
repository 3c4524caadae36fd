// Expanding a grid into runs: the count is envs x (sum over algorithms of the
// product of their axis sizes) x seeds, the loop order is env, algorithm,
// axes (first outermost), seed, and every run's directory names its
// settings. The shipped grids expand and resolve against configs/.
#include "experiments/grid_expansion.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <utility>

#include "common/algorithms.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"
#include "common/run_config_yaml.h"
#include "experiments/sweep_manifest.h"
#include "experiments/sweep_plan.h"
#include "../test_support.h"

namespace bsg::experiments {
namespace {

const std::filesystem::path kConfigs = std::filesystem::path(BSG_SOURCE_DIR) / "configs";

const char* const kTwoAlgorithms =
    "envs: [SafetyBallCircle-v0, SafetyCarRun-v0]\n"
    "seeds: [0, 1, 2]\n"
    "fixed: {epochs: 2, lambda_lr: 0.5}\n"
    "algorithms:\n"
    "  lag-trpo:\n"
    "    axes:\n"
    "      target_kl: [0.0001, 0.001, 0.01]\n"
    "      lambda_lr: [0.001, 0.1]\n"
    "  trpo:\n";

TEST(GridExpansion, CountIsTheProductOfAxesTimesSeedsSummedOverAlgorithms) {
  const GridSpec grid = parse_grid(kTwoAlgorithms, "g.yaml");
  EXPECT_EQ(configuration_count(grid.algorithms[0]), 6u);
  EXPECT_EQ(configuration_count(grid.algorithms[1]), 1u);
  EXPECT_EQ(expand_grid(grid).size(), 2u * (6u + 1u) * 3u);
}

TEST(GridExpansion, LoopOrderAndDirectoryNames) {
  const std::vector<GridRun> runs = expand_grid(parse_grid(kTwoAlgorithms, "g.yaml"));
  std::vector<std::string> dirs;
  for (const GridRun& run : runs) dirs.push_back(run.relative_dir().generic_string());
  EXPECT_EQ(dirs[0], "SafetyBallCircle-v0/lag-trpo/target_kl=0.0001,lambda_lr=0.001/seed=0");
  EXPECT_EQ(dirs[1], "SafetyBallCircle-v0/lag-trpo/target_kl=0.0001,lambda_lr=0.001/seed=1");
  EXPECT_EQ(dirs[3], "SafetyBallCircle-v0/lag-trpo/target_kl=0.0001,lambda_lr=0.1/seed=0");
  EXPECT_EQ(dirs[6], "SafetyBallCircle-v0/lag-trpo/target_kl=0.001,lambda_lr=0.001/seed=0");
  EXPECT_EQ(dirs[17], "SafetyBallCircle-v0/lag-trpo/target_kl=0.01,lambda_lr=0.1/seed=2");
  EXPECT_EQ(dirs[18], "SafetyBallCircle-v0/trpo/default/seed=0");
  EXPECT_EQ(dirs[21], "SafetyCarRun-v0/lag-trpo/target_kl=0.0001,lambda_lr=0.001/seed=0");
  EXPECT_EQ(std::set<std::string>(dirs.begin(), dirs.end()).size(), dirs.size()) << "names must be unique";
  EXPECT_EQ(runs[3].config_name, "target_kl=0.0001,lambda_lr=0.1");
  EXPECT_EQ(runs[3].seed, 0);
  EXPECT_EQ(runs[3].alg, Algorithm::lag_trpo);
}

TEST(GridExpansion, SetArgumentsLayerFixedThenAlgorithmThenAxes) {
  const std::vector<GridRun> runs = expand_grid(parse_grid(kTwoAlgorithms, "g.yaml"));
  EXPECT_EQ(runs[4].set_arguments,
            (std::vector<std::string>{"env_id=SafetyBallCircle-v0", "alg=lag-trpo", "seed=1", "epochs=2",
                                      "lambda_lr=0.5", "target_kl=0.0001", "lambda_lr=0.1"}));
  // lambda_lr does not apply to TRPO: the grid-wide fixed value is left out.
  EXPECT_EQ(runs[18].set_arguments,
            (std::vector<std::string>{"env_id=SafetyBallCircle-v0", "alg=trpo", "seed=0", "epochs=2"}));
}

TEST(GridExpansion, RunsResolveAgainstTheConfigsDirectory) {
  const std::vector<GridRun> runs = expand_grid(parse_grid(kTwoAlgorithms, "g.yaml"));
  const RunConfig lag = resolve_grid_run(runs[4], kConfigs, "g.yaml");
  EXPECT_EQ(lag.alg, Algorithm::lag_trpo);
  EXPECT_EQ(lag.seed, 1);
  EXPECT_EQ(lag.epochs, 2);
  EXPECT_DOUBLE_EQ(lag.trust_region.target_kl, 0.0001);
  EXPECT_DOUBLE_EQ(lag.multiplier.lambda_lr, 0.1);  // the axis wins over the grid-wide fixed value
  EXPECT_EQ(lag.steps_per_epoch, 32000);  // from configs/envs (Table 3)
  const RunConfig car = resolve_grid_run(runs.back(), kConfigs, "g.yaml");
  EXPECT_EQ(car.env_id, "SafetyCarRun-v0");
  EXPECT_EQ(car.max_ep_len, 500);
}

TEST(GridExpansion, ARunFileResolvesToTheGridsValuesWhereTheAlgorithmFileSaysOtherwise) {
  // sac-lag.yaml and td3-lag.yaml step their multipliers per update round. A grid that asks for
  // the epoch schedule must train with it: the run's run.yaml, layered over those files by
  // `bsg train run.yaml`, has to name the keys a run directory's config.yaml leaves unsaid.
  const GridSpec grid = parse_grid(
      "envs: [SafetyBallCircle-v0]\n"
      "seeds: [0]\n"
      "algorithms:\n"
      "  sac-lag:\n"
      "    fixed: {epochs: 3, steps_per_epoch: 2000, multiplier_schedule: epoch, pid_ki: 0.05}\n"
      "  td3-lag:\n"
      "    fixed: {multiplier_schedule: epoch, multiplier_window: 7, tensorboard: false}\n",
      "g.yaml");
  const testing::TemporaryDirectory sweep;
  for (const GridRun& run : expand_grid(grid)) {
    SCOPED_TRACE(run.relative_dir().string());
    PlannedRun planned;
    planned.run = run;
    planned.config = resolve_grid_run(run, kConfigs, "g.yaml");
    planned.dir = sweep.path() / run.relative_dir();
    prepare_run_directory(planned);
    RunConfigRequest request;
    request.configs_dir = kConfigs;
    request.run_file = planned.dir / kSweepRunFileName;
    const RunConfig trained = resolve_run_config(request).config;
    EXPECT_EQ(trained.off_policy.multiplier_schedule, MultiplierSchedule::epoch);
    EXPECT_EQ(to_run_file_yaml(trained), to_run_file_yaml(planned.config));
  }
}

TEST(GridExpansion, AnUnknownEnvironmentFailsNamingTheGridAndTheRun) {
  const GridSpec grid = parse_grid("envs: [SafetyBallFly-v0]\nseeds: [0]\nalgorithms: {trpo: }\n", "g.yaml");
  try {
    resolve_grid_run(expand_grid(grid).front(), kConfigs, "g.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("g.yaml: run SafetyBallFly-v0/trpo/default/seed=0"), std::string::npos) << message;
    EXPECT_NE(message.find("SafetyBallFly-v0"), std::string::npos) << message;
  }
}

TEST(GridExpansion, TheReportGridHasTheAppendixConfigurationsOverSixteenEnvironmentsAndFourSeeds) {
  const GridSpec grid = load_grid_file(kConfigs / "grids" / "report.yaml");
  ASSERT_EQ(grid.algorithms.size(), 5u);
  std::vector<std::size_t> counts;
  for (const AlgorithmGrid& algorithm : grid.algorithms) counts.push_back(configuration_count(algorithm));
  EXPECT_EQ(counts, (std::vector<std::size_t>{2, 9, 9, 9, 9}));
  EXPECT_EQ(grid.env_ids.size(), 16u);
  EXPECT_EQ(grid.seeds, (std::vector<std::int64_t>{0, 1, 2, 3}));
  const std::vector<GridRun> runs = expand_grid(grid);
  EXPECT_EQ(runs.size(), 38u * 16u * 4u);
  // Spot checks against the Appendix and Table 3.
  for (const GridRun& run : runs) {
    if (run.relative_dir().generic_string() == "SafetyAntReach-v0/cpo/target_kl=0.0005,lam_c=0.9/seed=3") {
      const RunConfig config = resolve_grid_run(run, kConfigs, "report.yaml");
      EXPECT_DOUBLE_EQ(config.trust_region.target_kl, 0.0005);
      EXPECT_DOUBLE_EQ(config.lam_c, 0.9);
      EXPECT_EQ(config.epochs, 1500);
      EXPECT_EQ(config.steps_per_epoch, 64000);
      EXPECT_DOUBLE_EQ(config.cost_limit, 25.0);
    }
  }
  // Every run resolves (one seed per configuration is enough: seeds only set `seed`), and PDO
  // keeps the original's Adam multiplier and reward-only line search (Q14), which its shipped
  // defaults no longer are (docs/algorithms.md#pdo).
  for (const char* file : {"report.yaml", "report_corrected.yaml"}) {
    for (const GridRun& run : expand_grid(load_grid_file(kConfigs / "grids" / file))) {
      if (run.seed != 0) continue;
      RunConfig config;
      ASSERT_NO_THROW(config = resolve_grid_run(run, kConfigs, file)) << file << " " << run.relative_dir();
      if (run.alg != Algorithm::pdo) continue;
      EXPECT_EQ(config.multiplier.lambda_optimizer, LambdaOptimizer::adam) << file << " " << run.relative_dir();
      EXPECT_TRUE(config.trust_region.pdo_line_search) << file << " " << run.relative_dir();
    }
  }
}

TEST(GridExpansion, ThePidGridRunsTheReportProtocolWithThePidMultiplier) {
  const GridSpec report = load_grid_file(kConfigs / "grids" / "report.yaml");
  const GridSpec grid = load_grid_file(kConfigs / "grids" / "pid.yaml");
  EXPECT_EQ(grid.env_ids, report.env_ids);
  EXPECT_EQ(grid.seeds, report.seeds);
  ASSERT_EQ(grid.algorithms.size(), 2u);
  EXPECT_EQ(grid.algorithms[0].alg, Algorithm::lag_trpo);
  EXPECT_EQ(grid.algorithms[1].alg, Algorithm::pdo);
  const std::vector<GridRun> runs = expand_grid(grid);
  EXPECT_EQ(runs.size(), 18u * 16u * 4u);
  for (const GridRun& run : runs) {
    if (run.seed != 0) continue;
    const RunConfig config = resolve_grid_run(run, kConfigs, "pid.yaml");
    EXPECT_EQ(config.multiplier.lambda_optimizer, LambdaOptimizer::pid) << run.relative_dir();
    if (run.alg == Algorithm::pdo) {
      EXPECT_TRUE(config.trust_region.pdo_line_search) << run.relative_dir();
    }
    if (run.relative_dir().generic_string() == "SafetyCarRun-v0/pdo/target_kl=0.01,pid_ki=0.001/seed=0") {
      EXPECT_DOUBLE_EQ(config.trust_region.target_kl, 0.01);
      EXPECT_DOUBLE_EQ(config.multiplier.pid_ki, 0.001);
    }
  }
}

TEST(GridExpansion, TheFirstOrderGridRunsTheReportProtocolWithTheFourConstrainedBaselines) {
  const GridSpec report = load_grid_file(kConfigs / "grids" / "report.yaml");
  const GridSpec grid = load_grid_file(kConfigs / "grids" / "first_order.yaml");
  EXPECT_EQ(grid.env_ids, report.env_ids);
  EXPECT_EQ(grid.seeds, report.seeds);
  ASSERT_EQ(grid.algorithms.size(), 3u);
  EXPECT_EQ(grid.algorithms[0].alg, Algorithm::ppo_lag);
  EXPECT_EQ(grid.algorithms[1].alg, Algorithm::focops);
  EXPECT_EQ(grid.algorithms[2].alg, Algorithm::cup);
  const std::vector<GridRun> runs = expand_grid(grid);
  EXPECT_EQ(runs.size(), 4u * 16u * 4u);
  int pid = 0;
  for (const GridRun& run : runs) {
    if (run.seed != 0) continue;
    const RunConfig config = resolve_grid_run(run, kConfigs, "first_order.yaml");
    pid += config.multiplier.lambda_optimizer == LambdaOptimizer::pid;
  }
  EXPECT_EQ(pid, 16);  // CPPO-PID on every environment
}

TEST(GridExpansion, TheBallRunFloorGridIsTheReportsTrpoLGridWithTheCorrectedLearnerAndASigmaFloor) {
  const std::vector<GridRun> runs = expand_grid(load_grid_file(kConfigs / "grids" / "ballrun_lagtrpo_floor.yaml"));
  ASSERT_EQ(runs.size(), 9u * 4u);
  for (const GridRun& run : runs) {
    const RunConfig config = resolve_grid_run(run, kConfigs, "ballrun_lagtrpo_floor.yaml");
    EXPECT_EQ(config.env_id, "SafetyBallRun-v0");
    EXPECT_EQ(config.alg, Algorithm::lag_trpo);
    EXPECT_EQ(config.epochs, 100);  // Table 3: 100 epochs of 32 000 steps
    EXPECT_EQ(config.steps_per_epoch, 32000);
    EXPECT_EQ(config.exploration_std_floor, 0.1);
    EXPECT_TRUE(config.value_time_input);  // the corrected learner (Q20 among its switches)
    EXPECT_TRUE(config.consistent_return_statistic);
    EXPECT_FALSE(config.sampled_evaluation);  // the report's evaluation
  }
}

TEST(GridExpansion, TheQuickGridIsTwoConfigurationsTimesTwoSeeds) {
  const std::vector<GridRun> runs = expand_grid(load_grid_file(kConfigs / "grids" / "quick.yaml"));
  ASSERT_EQ(runs.size(), 4u);
  for (const GridRun& run : runs) {
    const RunConfig config = resolve_grid_run(run, kConfigs, "quick.yaml");
    EXPECT_EQ(config.env_id, "SafetyBallCircle-v0");
    EXPECT_LE(config.epochs, 10);
  }
}

// The benchmark grids (configs/benchmarks/): each learner at its shipped defaults, so a run
// sets nothing but the budget and the cost limit; the all-task grid leaves out no constrained
// online learner of the algorithm table.
std::set<std::string> benchmark_keys_of(const GridRun& run) {
  std::set<std::string> keys;
  for (const std::string& setting : run.set_arguments) keys.insert(setting.substr(0, setting.find('=')));
  return keys;
}

TEST(GridExpansion, TheBallBenchmarkRunsEveryConstrainedBaselineAtThreeLimitsOnItsBudget) {
  const std::vector<GridRun> runs = expand_grid(load_grid_file(kConfigs / "benchmarks" / "ball.yaml"));
  ASSERT_EQ(runs.size(), 360u);  // 12 configurations x 3 limits x 2 environments x 5 seeds
  std::set<std::string> algorithms;
  for (const GridRun& run : runs) {
    algorithms.insert(std::string(algorithm_info(run.alg).name));
    if (run.seed != 0) continue;
    const RunConfig config = resolve_grid_run(run, kConfigs, "ball.yaml");
    const std::int64_t steps = config.epochs * config.steps_per_epoch;
    EXPECT_EQ(steps, is_off_policy(run.alg) ? 300000 : 1500000) << run.relative_dir();
    EXPECT_TRUE(config.cost_limit == 10 || config.cost_limit == 25 || config.cost_limit == 40) << run.relative_dir();
    std::set<std::string> allowed{"env_id", "alg", "seed", "epochs", "steps_per_epoch", "cost_limit", "lambda_optimizer"};
    for (const std::string& key : benchmark_keys_of(run)) EXPECT_TRUE(allowed.count(key)) << key;
  }
  const std::set<std::string> baselines{"lag-trpo", "cpo",    "pdo",     "pcpo",    "crpo",    "ppo-lag",
                                        "focops",   "cup",    "sac-lag", "td3-lag", "ddpg-lag"};
  EXPECT_EQ(algorithms, baselines);
}

// ball_small.yaml is ball.yaml cut to what two cores run in a session: seeds 0-2, the
// non-Lagrangian learners at d = 25 only, TD3-Lag and DDPG-Lag at 60 000 steps; every run of it
// is a run of ball.yaml but for TD3-Lag's and DDPG-Lag's budget.
TEST(GridExpansion, TheSmallBallBenchmarkIsTheBallBenchmarkCut) {
  const std::vector<GridRun> small = expand_grid(load_grid_file(kConfigs / "benchmarks" / "ball_small.yaml"));
  const std::vector<GridRun> full = expand_grid(load_grid_file(kConfigs / "benchmarks" / "ball.yaml"));
  std::set<std::string> full_dirs;
  for (const GridRun& run : full) full_dirs.insert(run.relative_dir().generic_string());
  ASSERT_EQ(small.size(), 180u);  // 30 configurations x 2 environments x 3 seeds
  std::set<std::string> algorithms;
  for (const GridRun& run : small) {
    algorithms.insert(std::string(algorithm_info(run.alg).name));
    EXPECT_LE(run.seed, 2);
    const RunConfig config = resolve_grid_run(run, kConfigs, "ball_small.yaml");
    const bool slow_off_policy = run.alg == Algorithm::td3_lag || run.alg == Algorithm::ddpg_lag;
    EXPECT_EQ(config.epochs * config.steps_per_epoch,
              slow_off_policy ? 60000 : (is_off_policy(run.alg) ? 300000 : 1500000))
        << run.relative_dir();
    if (!slow_off_policy) {
      EXPECT_TRUE(full_dirs.count(run.relative_dir().generic_string())) << run.relative_dir();
    }
    if (!has_lagrange_multiplier(run.alg)) {
      EXPECT_EQ(config.cost_limit, 25.0) << run.relative_dir();
    }
    std::set<std::string> allowed{"env_id", "alg", "seed", "epochs", "steps_per_epoch", "cost_limit", "lambda_optimizer"};
    for (const std::string& key : benchmark_keys_of(run)) EXPECT_TRUE(allowed.count(key)) << key;
  }
  EXPECT_EQ(algorithms.size(), 11u);
}

TEST(GridExpansion, TheAllTaskBenchmarkHasEveryConstrainedOnlineLearnerOnTheSixteenTasksAtTheirBudgets) {
  const std::vector<GridRun> runs = expand_grid(load_grid_file(kConfigs / "benchmarks" / "all_tasks.yaml"));
  std::set<std::string> algorithms;
  std::set<std::string> envs;
  for (const GridRun& run : runs) {
    algorithms.insert(std::string(algorithm_info(run.alg).name));
    envs.insert(run.env_id);
    std::set<std::string> allowed{"env_id", "alg", "seed", "lambda_optimizer"};
    for (const std::string& key : benchmark_keys_of(run)) EXPECT_TRUE(allowed.count(key)) << key;
  }
  std::set<std::string> constrained_online;  // single-agent: the sixteen tasks are single-agent ids
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.constrained && !is_offline(info.alg) && !is_multi_agent(info.alg)) {
      constrained_online.insert(std::string(info.name));
    }
  }
  EXPECT_EQ(algorithms, constrained_online);
  EXPECT_EQ(envs.size(), 16u);
  EXPECT_EQ(runs.size(), 16u * 5u * (constrained_online.size() + 1));  // PPO-Lag twice: Adam and PID
  const std::vector<GridRun> car = expand_grid(load_grid_file(kConfigs / "benchmarks" / "car_off_policy.yaml"));
  ASSERT_EQ(car.size(), 90u);
  for (const GridRun& run : car) {
    const RunConfig config = resolve_grid_run(run, kConfigs, "car_off_policy.yaml");
    EXPECT_TRUE(is_off_policy(run.alg));
    EXPECT_EQ(config.epochs * config.steps_per_epoch, 1000000);
  }
}

TEST(GridExpansion, TheMultiAgentBenchmarksRunEveryMultiAgentLearnerBesideAJointPpoLag) {
  std::set<std::string> expected{"ppo-lag"};
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (is_multi_agent(info.alg)) expected.insert(std::string(info.name));
  }
  for (const auto& [file, epochs] : {std::pair{"multi_agent.yaml", 1000}, std::pair{"multi_agent_small.yaml", 60}}) {
    const std::vector<GridRun> runs = expand_grid(load_grid_file(kConfigs / "benchmarks" / file));
    ASSERT_EQ(runs.size(), 30u) << file;  // 5 configurations x 2 environments x 3 seeds
    std::set<std::string> algorithms;
    for (const GridRun& run : runs) {
      algorithms.insert(std::string(algorithm_info(run.alg).name));
      const RunConfig config = resolve_grid_run(run, kConfigs, file);
      EXPECT_EQ(config.joint_control, run.alg == Algorithm::ppo_lag) << run.relative_dir();
      EXPECT_EQ(config.epochs, epochs) << run.relative_dir();
      EXPECT_EQ(config.steps_per_epoch, 10000) << run.relative_dir();
      std::set<std::string> allowed{"env_id", "alg", "seed", "epochs", "joint_control"};
      for (const std::string& key : benchmark_keys_of(run)) EXPECT_TRUE(allowed.count(key)) << file << " " << key;
    }
    EXPECT_EQ(algorithms, expected) << file;
  }
}

TEST(GridExpansion, TheOfflineBenchmarksRunEveryOfflineLearnerOnTheBallAndCarDatasets) {
  std::set<std::string> offline_learners;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (is_offline(info.alg)) offline_learners.insert(std::string(info.name));
  }
  for (const char* file : {"offline.yaml", "offline_small.yaml"}) {
    const std::vector<GridRun> runs = expand_grid(load_grid_file(kConfigs / "benchmarks" / file));
    std::set<std::string> algorithms;
    std::set<std::string> families;
    for (const GridRun& run : runs) {
      algorithms.insert(std::string(algorithm_info(run.alg).name));
      const RunConfig config = resolve_grid_run(run, kConfigs, file);
      EXPECT_FALSE(config.offline.dataset.empty()) << run.relative_dir();
      families.insert(run.env_id.substr(6, run.env_id.find('-') - 6));  // "Safety" + agent and task
    }
    EXPECT_EQ(algorithms, offline_learners) << file;
    // At least Circle, Run, one Reach and one Gather on the Ball, and Circle and Run on the Car.
    for (const char* family : {"BallCircle", "BallRun", "BallReach", "BallGather", "CarCircle", "CarRun"}) {
      EXPECT_EQ(families.count(family), 1u) << file << " " << family;
    }
  }
}

}  // namespace
}  // namespace bsg::experiments
