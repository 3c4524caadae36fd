// Every shipped file under configs/ loads and validates; all 16 environments
// resolve with every on-policy algorithm of the table; the numbers match report Table 3 and the
// per-algorithm defaults of docs/algorithms.md#hyper-parameters and #quirk-switches, typed here from those sources.
#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "common/config_entries.h"
#include "common/run_config.h"
#include "common/run_config_resolve.h"
#include "common/run_config_schema.h"
#include "envs/multi_agent_env.h"
#include "shipped_request.h"

namespace bsg {
namespace {

namespace fs = std::filesystem;

using testing::kShippedConfigs;
// The on-policy algorithms of the table (common/algorithms.h), so that a new row is covered without an edit here.
const std::vector<std::string> kOnPolicyAlgorithms = [] {
  std::vector<std::string> names;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.family == AlgorithmFamily::trust_region || info.family == AlgorithmFamily::first_order) {
      names.emplace_back(info.name);
    }
  }
  return names;
}();
// The offline algorithms, which resolve only with a dataset: key (the file is read by the trainer).
const std::vector<std::string> kOfflineAlgorithms = [] {
  std::vector<std::string> names;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.family == AlgorithmFamily::offline) names.emplace_back(info.name);
  }
  return names;
}();

// The multi-agent learners, which resolve on the multi-agent ids only (docs/multi_agent.md#learners).
const std::vector<std::string> kMultiAgentAlgorithms = [] {
  std::vector<std::string> names;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.family == AlgorithmFamily::multi_agent) names.emplace_back(info.name);
  }
  return names;
}();

struct Table3Row {
  double cost_limit;
  int epochs;
  int batch_size;
  int max_episode_length;
};

// Report Table 3, typed from the report (AntCircle: 1000 epochs, Q16).
const std::map<std::string, Table3Row> kTable3 = {
    {"SafetyBallRun-v0", {25, 100, 32000, 250}},
    {"SafetyCarRun-v0", {25, 200, 32000, 500}},
    {"SafetyDroneRun-v0", {25, 500, 64000, 500}},
    {"SafetyAntRun-v0", {25, 500, 64000, 1000}},
    {"SafetyBallCircle-v0", {25, 500, 32000, 250}},
    {"SafetyCarCircle-v0", {25, 500, 32000, 500}},
    {"SafetyDroneCircle-v0", {25, 1000, 64000, 500}},
    {"SafetyAntCircle-v0", {25, 1000, 64000, 1000}},
    {"SafetyBallGather-v0", {0.2, 500, 32000, 250}},
    {"SafetyCarGather-v0", {0.2, 500, 32000, 500}},
    {"SafetyDroneGather-v0", {0.2, 1000, 64000, 500}},
    {"SafetyAntGather-v0", {0.2, 1000, 64000, 1000}},
    {"SafetyBallReach-v0", {10, 500, 32000, 250}},
    {"SafetyCarReach-v0", {10, 1000, 32000, 500}},
    {"SafetyDroneReach-v0", {10, 1000, 64000, 500}},
    {"SafetyAntReach-v0", {25, 1500, 64000, 1000}},
};

RunConfig resolve_shipped(const std::string& alg, const std::string& env_id) {
  RunConfigRequest request;
  request.configs_dir = kShippedConfigs;
  request.set_arguments = {"alg=" + alg, "env_id=" + env_id};
  return resolve_run_config(request).config;
}

TEST(ShippedConfigs, ThereIsOneEnvironmentFilePerReportEnvironmentAndMultiAgentId) {
  std::vector<std::string> expected = envs::multi_agent_ids();
  for (const auto& [env_id, row] : kTable3) expected.push_back(env_id);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(list_config_env_ids(kShippedConfigs), expected);  // both sorted
}

// Each multi-agent id's file: the robot's d and episode length (its spec), SafePO's batch.
TEST(ShippedConfigs, MultiAgentLearnersResolveOnEveryMultiAgentIdAndListTheirKeys) {
  for (const std::string& env_id : envs::multi_agent_ids()) {
    const envs::MultiAgentSpec spec = envs::make_multi_agent(env_id)->spec();
    for (const std::string& alg : kMultiAgentAlgorithms) {
      SCOPED_TRACE(env_id + " / " + alg);
      const RunConfig c = resolve_shipped(alg, env_id);
      EXPECT_EQ(c.cost_limit, spec.cost_limit);
      EXPECT_EQ(c.max_ep_len, spec.max_episode_steps);
      EXPECT_EQ(c.steps_per_epoch, 10000);
    }
  }
  for (const std::string& alg : kMultiAgentAlgorithms) {
    SCOPED_TRACE(alg);
    const Algorithm id = resolve_shipped(alg, "SafetyBallCircle2-v0").alg;
    std::set<std::string> listed;
    for (const ConfigEntry& entry : read_config_file(algorithm_config_path(kShippedConfigs, id))) listed.insert(entry.key);
    std::set<std::string> expected;
    for (const ConfigKey& key : run_config_schema()) {
      if (key.default_source == ConfigLayer::algorithm && key.applies_to(id)) expected.insert(std::string(key.key));
    }
    EXPECT_EQ(listed, expected);
  }
}

TEST(ShippedConfigs, AllSixteenEnvironmentsResolveWithEveryAlgorithm) {
  for (const auto& [env_id, row] : kTable3) {
    for (const std::string& alg : kOnPolicyAlgorithms) {
      SCOPED_TRACE(env_id + " / " + alg);
      const RunConfig c = resolve_shipped(alg, env_id);
      EXPECT_EQ(c.env_id, env_id);
      EXPECT_EQ(to_string(c.alg), alg);
    }
  }
}

TEST(ShippedConfigs, OfflineAlgorithmsResolveOnEveryEnvironmentWithADatasetAndListTheirKeys) {
  ASSERT_EQ(kOfflineAlgorithms, (std::vector<std::string>{"bc-all", "bc-safe", "cpq", "bcq-lag", "coptidice"}));
  for (const std::string& alg : kOfflineAlgorithms) {
    for (const auto& [env_id, row] : kTable3) {
      SCOPED_TRACE(env_id + " / " + alg);
      RunConfigRequest request;
      request.configs_dir = kShippedConfigs;
      request.set_arguments = {"env_id=" + env_id, "alg=" + alg, "dataset=data.hdf5"};
      const RunConfig c = resolve_run_config(request).config;
      EXPECT_EQ(c.offline.dataset, "data.hdf5");
      EXPECT_EQ(c.epochs, row.epochs);
      // OSRL's BC and BCQ-L: actor_lr 1e-3; its CPQ and COptiDICE: actor_lr 1e-4; all batch_size 512, a_hidden_sizes [256, 256].
      EXPECT_EQ(c.first_order.actor_lr, alg == "cpq" || alg == "coptidice" ? 1e-4 : 1e-3);
      EXPECT_EQ(c.off_policy.batch_size, 512);
      EXPECT_EQ(c.hidden_sizes, (std::vector<int>{256, 256}));
    }
    const Algorithm id = std::find_if(kAlgorithms.begin(), kAlgorithms.end(),
                                      [&](const AlgorithmInfo& info) { return info.name == alg; })->alg;
    std::set<std::string> listed;
    for (const ConfigEntry& entry : read_config_file(algorithm_config_path(kShippedConfigs, id))) {
      listed.insert(entry.key);
    }
    std::set<std::string> expected;
    for (const ConfigKey& key : run_config_schema()) {
      if (key.default_source == ConfigLayer::algorithm && key.applies_to(id)) expected.insert(std::string(key.key));
    }
    EXPECT_EQ(listed, expected);
  }
}

TEST(ShippedConfigs, EnvironmentSettingsMatchReportTable3) {
  for (const auto& [env_id, row] : kTable3) {
    SCOPED_TRACE(env_id);
    const RunConfig c = resolve_shipped("cpo", env_id);
    EXPECT_EQ(c.cost_limit, row.cost_limit);
    EXPECT_EQ(c.epochs, row.epochs);
    EXPECT_EQ(c.steps_per_epoch, row.batch_size);
    EXPECT_EQ(c.max_ep_len, row.max_episode_length);
  }
}

TEST(ShippedConfigs, AlgorithmDefaultsMatchTheSpec) {
  // docs/algorithms.md#hyper-parameters and #quirk-switches (this project's defaults): target_kl, line-search budget, cost
  // value net, and the Lagrange multiplier's optimiser and learning rate.
  struct Expected {
    double target_kl;
    int backtrack_budget;
    bool use_cost_value_function;
  };
  const std::map<std::string, Expected> expected = {
      {"trpo", {0.01, 15, false}},  {"lag-trpo", {0.01, 15, true}}, {"cpo", {0.01, 20, true}},
      {"pdo", {1e-3, 15, true}},    {"pcpo", {0.01, 25, true}},
  };
  for (const auto& [alg, e] : expected) {
    SCOPED_TRACE(alg);
    const RunConfig c = resolve_shipped(alg, "SafetyBallCircle-v0");
    EXPECT_EQ(c.trust_region.target_kl, e.target_kl);
    EXPECT_EQ(c.trust_region.backtrack_budget, e.backtrack_budget);
    EXPECT_EQ(c.use_cost_value_function, e.use_cost_value_function);
    // Shared by all (report Table 2, docs/algorithms.md#hyper-parameters).
    EXPECT_EQ(c.gamma, 0.99);
    EXPECT_EQ(c.lam, 0.95);
    EXPECT_EQ(c.lam_c, 0.95);
    EXPECT_EQ(c.trust_region.cg_damping, 0.1);
    EXPECT_EQ(c.trust_region.cg_iters, 10);
    EXPECT_EQ(c.trust_region.backtrack_decay, 0.8);
    EXPECT_EQ(c.trust_region.kl_accept_factor, 1.5);
    EXPECT_EQ(c.vf_lr, 1e-3);
    EXPECT_EQ(c.train_v_iterations, 5);
    EXPECT_EQ(c.num_mini_batches, 16);
    EXPECT_EQ(c.hidden_sizes, (std::vector<int>{64, 64}));
    EXPECT_TRUE(c.use_exploration_noise_anneal);
    EXPECT_TRUE(c.use_standardized_obs);
    EXPECT_TRUE(c.use_reward_scaling);
    EXPECT_FALSE(c.use_standardized_advantages);
    EXPECT_FALSE(c.zero_bias_init);
    EXPECT_FALSE(c.exact_parallel_variance);
    EXPECT_EQ(c.obs_clip, 0.0);
    EXPECT_EQ(c.save_freq, 10);
    EXPECT_EQ(c.check_freq, 25);
    EXPECT_EQ(c.eval_episodes, 128);
  }
  const RunConfig lag = resolve_shipped("lag-trpo", "SafetyBallCircle-v0");
  EXPECT_EQ(lag.multiplier.lambda_optimizer, LambdaOptimizer::sgd);
  EXPECT_EQ(lag.multiplier.lambda_lr, 0.05);
  EXPECT_EQ(lag.multiplier.lagrangian_multiplier_init, 0.001);
  const RunConfig pdo = resolve_shipped("pdo", "SafetyBallCircle-v0");
  EXPECT_EQ(pdo.multiplier.lambda_optimizer, LambdaOptimizer::sgd);  // TRPO-L's rule (docs/algorithms.md#pdo)
  EXPECT_EQ(pdo.multiplier.lambda_lr, 0.05);
  EXPECT_FALSE(pdo.trust_region.pdo_line_search);
  const RunConfig cpo = resolve_shipped("cpo", "SafetyBallCircle-v0");
  EXPECT_EQ(cpo.trust_region.cpo_r_sign, CpoRSign::original);
  const RunConfig pcpo = resolve_shipped("pcpo", "SafetyBallCircle-v0");
  EXPECT_EQ(pcpo.trust_region.pcpo_projection, PcpoProjection::kl);
  EXPECT_TRUE(pcpo.trust_region.pcpo_line_search);
}

TEST(ShippedConfigs, DefaultConstructedRunConfigIsTrpoOnBallCircle) {
  EXPECT_EQ(RunConfig{}, resolve_shipped("trpo", "SafetyBallCircle-v0"));
}

TEST(ShippedConfigs, EachFileListsExactlyTheKeysOfItsLayer) {
  for (const std::string& alg : kOnPolicyAlgorithms) {
    SCOPED_TRACE(alg);
    const Algorithm id = resolve_shipped(alg, "SafetyBallCircle-v0").alg;
    std::set<std::string> listed;
    for (const ConfigEntry& entry :
         read_config_file(algorithm_config_path(kShippedConfigs, id))) {
      listed.insert(entry.key);
    }
    std::set<std::string> expected;
    for (const ConfigKey& key : run_config_schema()) {
      if (key.default_source == ConfigLayer::algorithm && key.applies_to(id)) {
        expected.insert(std::string(key.key));
      }
    }
    EXPECT_EQ(listed, expected);
  }
  const std::set<std::string> env_keys = {"cost_limit", "epochs", "steps_per_epoch",
                                          "max_ep_len"};
  for (const std::string& env_id : list_config_env_ids(kShippedConfigs)) {
    SCOPED_TRACE(env_id);
    std::set<std::string> listed;
    for (const ConfigEntry& entry :
         read_config_file(environment_config_path(kShippedConfigs, env_id))) {
      listed.insert(entry.key);
    }
    EXPECT_EQ(listed, env_keys);
  }
}

TEST(ShippedConfigs, EveryRunFileResolves) {
  std::size_t count = 0;
  for (const auto& file : fs::directory_iterator(kShippedConfigs / "runs")) {
    if (file.path().extension() != ".yaml") continue;
    SCOPED_TRACE(file.path().string());
    RunConfigRequest request;
    request.configs_dir = kShippedConfigs;
    request.run_file = file.path();
    // bsg train accepts every registered id: the environment files' and the fork's (<name>-fork,
    // docs/environments.md), whose run files set the environment keys themselves.
    request.valid_env_ids = list_config_env_ids(kShippedConfigs);
    for (const std::string& id : list_config_env_ids(kShippedConfigs)) {
      request.valid_env_ids.push_back(id.substr(0, id.size() - 3) + "-fork");  // "-v0" -> "-fork"
    }
    EXPECT_NO_THROW(resolve_run_config(request));
    ++count;
  }
  EXPECT_GE(count, 2u);
}

TEST(ShippedConfigs, TinyJobIsSmallTrpoLOnBallCircleAndRunsOnOneOrTwoRanks) {
  RunConfigRequest request;
  request.configs_dir = kShippedConfigs;
  request.run_file = kShippedConfigs / "runs" / "tiny_ball_circle_trpo_l.yaml";
  const RunConfig c = resolve_run_config(request).config;
  EXPECT_EQ(c.alg, Algorithm::lag_trpo);
  EXPECT_EQ(c.env_id, "SafetyBallCircle-v0");
  EXPECT_LE(c.epochs, 5);
  EXPECT_LE(c.steps_per_epoch, 2000);
  EXPECT_NO_THROW(check_run_config_for_ranks(c, 1));
  EXPECT_NO_THROW(check_run_config_for_ranks(c, 2));

  request.run_file = kShippedConfigs / "runs" / "ball_circle_trpo_l.yaml";
  const RunConfig full = resolve_run_config(request).config;
  EXPECT_EQ(full.alg, Algorithm::lag_trpo);
  EXPECT_EQ(full.epochs, 500);
  EXPECT_EQ(full.steps_per_epoch, 32000);
}

TEST(ConfigSchema, KeysAreUniqueDescribedAndIncludeTheSpecsNames) {
  std::set<std::string_view> seen;
  for (const ConfigKey& key : run_config_schema()) {
    EXPECT_TRUE(seen.insert(key.key).second) << "duplicate " << key.key;
    EXPECT_FALSE(key.description.empty()) << key.key;
    EXPECT_NE(key.used_by, 0u) << key.key;
  }
  for (const char* name :
       {"env_id", "alg", "seed", "epochs", "steps_per_epoch", "cost_limit", "max_ep_len",
        "target_kl", "gamma", "lam", "lam_c", "lambda_lr", "cg_iters", "cg_damping", "vf_lr",
        "train_v_iterations", "use_exploration_noise_anneal", "backtrack_budget",
        "kl_accept_factor", "zero_bias_init", "obs_clip", "exact_parallel_variance",
        "use_standardized_advantages", "cpo_r_sign", "pdo_line_search", "pcpo_projection",
        "num_mini_batches"}) {
    EXPECT_NE(find_config_key(name), nullptr) << name;
  }
}

TEST(ConfigSchema, ConfigsReadmeShowsTheCurrentKeyTable) {
  std::ifstream in(kShippedConfigs / "README.md");
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(config_schema_markdown()), std::string::npos)
      << "regenerate the table in configs/README.md from config_schema_markdown():\n"
      << config_schema_markdown();
}

}  // namespace
}  // namespace bsg
