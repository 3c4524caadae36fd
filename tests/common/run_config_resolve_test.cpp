// Resolving a run config: the layer order algorithm <- environment <- run
// file <- --set, and the content of every validation error (key, value,
// file:line or --set argument, valid keys or values).
#include "common/run_config_resolve.h"
#include "shipped_request.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>

#include "../test_support.h"
#include "common/config_error.h"
#include "common/foreign_key_spellings.h"
#include "common/run_config_schema.h"

namespace bsg {
namespace {

namespace fs = std::filesystem;

using testing::kShippedConfigs;

using testing::contains;
using testing::read_text_file;

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  testing::write_text_file(path, text);
}

// Replaces the value of `key: ...` (one line) in a config text.
std::string with_value(const std::string& text, const std::string& key, const std::string& value) {
  const std::regex line("(^|\n)" + key + ":[^\n]*");
  std::string out = std::regex_replace(text, line, "$1" + key + ": " + value);
  EXPECT_NE(out, text) << "key " << key << " not found";
  return out;
}

// A scratch configs directory: algorithms/trpo.yaml, algorithms/cpo.yaml and
// envs/SafetyBallCircle-v0.yaml copied from the shipped ones, and helpers to
// write run files. Removed at the end of the test.
class ScratchConfigs : public ::testing::Test {
 protected:
  void SetUp() override {
    configs_ = root_ / "configs";
    for (const char* alg : {"trpo", "cpo"}) {
      write_text(configs_ / "algorithms" / (std::string(alg) + ".yaml"),
                 read_text_file(kShippedConfigs / "algorithms" / (std::string(alg) + ".yaml")));
    }
    write_text(env_file(), read_text_file(kShippedConfigs / "envs" / "SafetyBallCircle-v0.yaml"));
  }

  fs::path alg_file(const std::string& alg) const {
    return configs_ / "algorithms" / (alg + ".yaml");
  }
  fs::path env_file() const { return configs_ / "envs" / "SafetyBallCircle-v0.yaml"; }

  fs::path write_run(const std::string& text) {
    const fs::path path = root_ / "run.yaml";
    write_text(path, text);
    return path;
  }

  RunConfigRequest request(const fs::path& run_file, std::vector<std::string> sets = {}) const {
    RunConfigRequest r;
    r.configs_dir = configs_;
    r.run_file = run_file;
    r.set_arguments = std::move(sets);
    return r;
  }

  // The ConfigError message of resolving `r`; fails the test if none is thrown.
  std::string error_of(const RunConfigRequest& r) const {
    try {
      resolve_run_config(r);
    } catch (const ConfigError& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected a ConfigError";
    return "";
  }

  const testing::TemporaryDirectory scratch_{"run_config_test"};
  const fs::path root_ = scratch_.path();
  fs::path configs_;
};

constexpr const char* kTrpoRun = "env_id: SafetyBallCircle-v0\nalg: trpo\n";

TEST_F(ScratchConfigs, LaterLayersWinAlgorithmThenEnvironmentThenRunFileThenSet) {
  std::string alg = read_text_file(alg_file("trpo"));
  alg = with_value(alg, "gamma", "0.91");
  alg = with_value(alg, "lam", "0.81");
  alg = with_value(alg, "target_kl", "0.021");
  alg = with_value(alg, "vf_lr", "0.0031");
  write_text(alg_file("trpo"), alg);
  write_text(env_file(),
             "cost_limit: 7.5\nepochs: 11\nsteps_per_epoch: 2000\nmax_ep_len: 100\n"
             "lam: 0.82\ntarget_kl: 0.022\nvf_lr: 0.0032\n");
  const fs::path run = write_run(std::string(kTrpoRun) +
                                 "seed: 5\ntarget_kl: 0.023\nvf_lr: 0.0033\n");

  const ResolvedRunConfig resolved =
      resolve_run_config(request(run, {"vf_lr=0.0034", "epochs=12", "epochs=13"}));
  const RunConfig& c = resolved.config;
  EXPECT_EQ(c.gamma, 0.91);        // algorithm file only
  EXPECT_EQ(c.lam, 0.82);          // environment file beats algorithm file
  EXPECT_EQ(c.trust_region.target_kl, 0.023);   // run file beats both
  EXPECT_EQ(c.vf_lr, 0.0034);      // --set beats all files
  EXPECT_EQ(c.epochs, 13);         // the last --set wins
  EXPECT_EQ(c.cost_limit, 7.5);
  EXPECT_EQ(c.steps_per_epoch, 2000);
  EXPECT_EQ(c.max_ep_len, 100);
  EXPECT_EQ(c.seed, 5);
  EXPECT_EQ(c.log_dir, "runs");    // RunConfig's default
  EXPECT_EQ(c.alg, Algorithm::trpo);
  EXPECT_EQ(c.env_id, "SafetyBallCircle-v0");

  EXPECT_TRUE(contains(resolved.origins.at("gamma"), "trpo.yaml:"));
  EXPECT_TRUE(contains(resolved.origins.at("lam"), "SafetyBallCircle-v0.yaml:5:1"));
  EXPECT_EQ(resolved.origins.at("target_kl"), run.string() + ":4:1");
  EXPECT_EQ(resolved.origins.at("vf_lr"), "--set vf_lr=0.0034");
  EXPECT_EQ(resolved.origins.at("log_dir"), "default");
}

TEST_F(ScratchConfigs, SetAlgChoosesThatAlgorithmsDefaults) {
  const fs::path run = write_run(kTrpoRun);
  const RunConfig c = resolve_run_config(request(run, {"alg=cpo"})).config;
  EXPECT_EQ(c.alg, Algorithm::cpo);
  EXPECT_EQ(c.trust_region.target_kl, 0.01);       // configs/algorithms/cpo.yaml
  EXPECT_EQ(c.trust_region.backtrack_budget, 20);  // Q11
  EXPECT_TRUE(c.use_cost_value_function);
}

TEST_F(ScratchConfigs, SetValuesAreParsedAsYamlAndTypeChecked) {
  const fs::path run = write_run(kTrpoRun);
  const RunConfig c =
      resolve_run_config(request(run, {"hidden_sizes=[32, 16]", "use_reward_scaling=off",
                                       "seed=42", "gamma=1", "log_dir=out/x"}))
          .config;
  EXPECT_EQ(c.hidden_sizes, (std::vector<int>{32, 16}));
  EXPECT_FALSE(c.use_reward_scaling);
  EXPECT_EQ(c.seed, 42);
  EXPECT_EQ(c.gamma, 1.0);
  EXPECT_EQ(c.log_dir, "out/x");

  std::string m = error_of(request(run, {"seed=abc"}));
  EXPECT_TRUE(contains(m, "--set seed=abc"));
  EXPECT_TRUE(contains(m, "'seed'"));
  EXPECT_TRUE(contains(m, "'abc'"));
  EXPECT_TRUE(contains(m, "integer"));

  m = error_of(request(run, {"gamma=0"}));
  EXPECT_TRUE(contains(m, "--set gamma=0"));
  EXPECT_TRUE(contains(m, "out of range"));
  EXPECT_TRUE(contains(m, "(0, 1]"));

  m = error_of(request(run, {"seed=-1"}));
  EXPECT_TRUE(contains(m, "--set seed=-1"));
  EXPECT_TRUE(contains(m, "[0, 4294967295]"));

  m = error_of(request(run, {"epochs="}));
  EXPECT_TRUE(contains(m, "--set epochs="));
  EXPECT_TRUE(contains(m, "no value"));

  m = error_of(request(run, {"use_reward_scaling=maybe"}));
  EXPECT_TRUE(contains(m, "true or false"));
  EXPECT_TRUE(contains(m, "'maybe'"));

  m = error_of(request(run, {"hidden_sizes=[32, 0]"}));
  EXPECT_TRUE(contains(m, "hidden_sizes"));
  EXPECT_TRUE(contains(m, "[1, 4096]"));
}

TEST_F(ScratchConfigs, MalformedSetArgumentsNameTheArgument) {
  const fs::path run = write_run(kTrpoRun);
  std::string m = error_of(request(run, {"gamma"}));
  EXPECT_TRUE(contains(m, "--set gamma"));
  EXPECT_TRUE(contains(m, "key=value"));

  m = error_of(request(run, {"=0.9"}));
  EXPECT_TRUE(contains(m, "--set =0.9"));

  m = error_of(request(run, {"gama=0.9"}));
  EXPECT_TRUE(contains(m, "--set gama=0.9"));
  EXPECT_TRUE(contains(m, "unknown key 'gama'"));
  EXPECT_TRUE(contains(m, "did you mean 'gamma'"));
  EXPECT_TRUE(contains(m, "valid keys: env_id, alg, seed"));

  m = error_of(request(run, {"hidden_sizes=[32, 16"}));
  EXPECT_TRUE(contains(m, "--set hidden_sizes=[32, 16"));
  EXPECT_TRUE(contains(m, "not valid YAML"));
}

// Another library's name for a key points to bsg's key of the same meaning, not to the key
// closest in spelling (tau is one edit from lam, q_lr two from vf_lr).
TEST_F(ScratchConfigs, OtherLibrariesKeyNamesPointToBsgsKey) {
  const fs::path run = write_run(kTrpoRun);
  std::string m = error_of(request(run, {"tau=0.005"}));
  EXPECT_TRUE(contains(m, "unknown key 'tau' (did you mean 'polyak'? tau in Stable-Baselines3, CleanRL and Tianshou)"))
      << m;
  m = error_of(request(run, {"q_lr=0.001"}));
  EXPECT_TRUE(contains(m, "unknown key 'q_lr' (did you mean 'critic_lr'? q_lr in CleanRL)")) << m;
  EXPECT_FALSE(contains(m, "vf_lr'?")) << m;
  // In a run file too.
  m = error_of(request(write_run(std::string(kTrpoRun) + "gae_lambda: 0.95\n")));
  EXPECT_TRUE(contains(m, "did you mean 'lam'?")) << m;
}

// Every other library's name leads to a key of the table, and none is a key itself.
TEST(ForeignKeySpellings, NameKeysOfTheTableAndAreNoneThemselves) {
  for (const ForeignKeySpelling& row : foreign_key_spellings()) {
    EXPECT_NE(find_config_key(row.key), nullptr) << row.spelling << " -> " << row.key;
    EXPECT_EQ(find_config_key(row.spelling), nullptr) << row.spelling;
  }
}

TEST_F(ScratchConfigs, UnknownKeyInRunFileNamesKeyFileLineAndValidKeys) {
  const fs::path run = write_run(std::string(kTrpoRun) + "gama: 0.9\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string() + ":3:1"));
  EXPECT_TRUE(contains(m, "unknown key 'gama'"));
  EXPECT_TRUE(contains(m, "valid keys:"));
  for (const char* key : {"env_id", "alg", "seed", "epochs", "steps_per_epoch", "cost_limit",
                          "target_kl", "gamma", "lam", "lam_c", "lambda_lr", "cg_iters",
                          "cg_damping", "vf_lr", "train_v_iterations",
                          "use_exploration_noise_anneal"}) {
    EXPECT_TRUE(contains(m, std::string(key) + ",")) << key;
  }
}

TEST_F(ScratchConfigs, UnknownKeyInAlgorithmFileNamesThatFileAndLine) {
  write_text(alg_file("trpo"), read_text_file(alg_file("trpo")) + "bogus_key: 1\n");
  const std::size_t lines = [&] {
    std::string text = read_text_file(alg_file("trpo"));
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  }();
  const std::string m = error_of(request(write_run(kTrpoRun)));
  EXPECT_TRUE(contains(m, alg_file("trpo").string() + ":" + std::to_string(lines) + ":1"));
  EXPECT_TRUE(contains(m, "unknown key 'bogus_key'"));
}

TEST_F(ScratchConfigs, WrongTypeNamesKeyValueAndLine) {
  const fs::path run = write_run(std::string(kTrpoRun) + "seed: 1\ngamma: abc\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string() + ":4:1"));
  EXPECT_TRUE(contains(m, "'gamma'"));
  EXPECT_TRUE(contains(m, "'abc'"));
  EXPECT_TRUE(contains(m, "real number"));
}

TEST_F(ScratchConfigs, OutOfRangeValueNamesKeyValueRangeAndLine) {
  const fs::path run = write_run(std::string(kTrpoRun) + "gamma: 1.5\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string() + ":3:1"));
  EXPECT_TRUE(contains(m, "'gamma' = 1.5"));
  EXPECT_TRUE(contains(m, "(0, 1]"));
}

TEST_F(ScratchConfigs, QuotedOrFractionalIntegersAreTypeErrors) {
  std::string m = error_of(request(write_run(std::string(kTrpoRun) + "epochs: '5'\n")));
  EXPECT_TRUE(contains(m, "'epochs'"));
  EXPECT_TRUE(contains(m, "quoted"));
  m = error_of(request(write_run(std::string(kTrpoRun) + "epochs: 2.5\n")));
  EXPECT_TRUE(contains(m, "'epochs' expects an integer"));
  EXPECT_TRUE(contains(m, "'2.5'"));
  m = error_of(request(write_run(std::string(kTrpoRun) + "epochs: [1, 2]\n")));
  EXPECT_TRUE(contains(m, "the sequence [1, 2]"));
}

TEST_F(ScratchConfigs, MalformedYamlNamesFileAndYamlCppMessage) {
  const fs::path run = write_run(std::string(kTrpoRun) + "hidden_sizes: [64, 64\nseed: 1\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string()));
  EXPECT_TRUE(contains(m, "malformed YAML"));
  EXPECT_TRUE(contains(m, "yaml-cpp: error at line"));
}

TEST_F(ScratchConfigs, TopLevelMustBeAMapping) {
  const fs::path run = write_run("- env_id\n- alg\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string()));
  EXPECT_TRUE(contains(m, "mapping"));
}

TEST_F(ScratchConfigs, DuplicateKeyNamesBothLines) {
  const fs::path run = write_run(std::string(kTrpoRun) + "seed: 1\nseed: 2\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string() + ":4:1"));
  EXPECT_TRUE(contains(m, "'seed' appears twice"));
  EXPECT_TRUE(contains(m, run.string() + ":3:1"));
}

TEST_F(ScratchConfigs, MissingFilesNameThePath) {
  const fs::path missing_run = root_ / "no_such_run.yaml";
  EXPECT_TRUE(contains(error_of(request(missing_run)), "not found: " + missing_run.string()));

  const fs::path run = write_run("env_id: SafetyBallCircle-v0\nalg: pdo\n");
  EXPECT_TRUE(contains(error_of(request(run)), "not found: " + alg_file("pdo").string()));
}

TEST_F(ScratchConfigs, UnknownEnvIdListsTheValidOnes) {
  const fs::path run = write_run("env_id: SafetyFooCircle-v0\nalg: trpo\n");
  std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string() + ":1:1"));
  EXPECT_TRUE(contains(m, "unknown env_id 'SafetyFooCircle-v0'"));
  EXPECT_TRUE(contains(m, "valid env ids: SafetyBallCircle-v0"));

  RunConfigRequest with_registry = request(run);
  with_registry.valid_env_ids = {"SafetyBallCircle-v0", "SafetyBallRun-v0"};
  m = error_of(with_registry);
  EXPECT_TRUE(contains(m, "valid env ids: SafetyBallCircle-v0, SafetyBallRun-v0"));
}

TEST_F(ScratchConfigs, UnknownAlgListsTheValidOnes) {
  const fs::path run = write_run("env_id: SafetyBallCircle-v0\nalg: cvpo\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string() + ":2:1"));
  EXPECT_TRUE(contains(m, "'alg' = 'cvpo' is not valid"));
  EXPECT_TRUE(contains(m, "trpo | lag-trpo | cpo | pdo | pcpo | ppo | ppo-lag | focops | cup | sac | td3 | ddpg | "
                          "sac-lag | td3-lag | ddpg-lag"));
}

TEST_F(ScratchConfigs, MissingEnvIdOrAlgSaysWhereToSetIt) {
  std::string m = error_of(request(write_run("env_id: SafetyBallCircle-v0\n")));
  EXPECT_TRUE(contains(m, "no 'alg' given"));
  EXPECT_TRUE(contains(m, "trpo | lag-trpo"));
  m = error_of(request(fs::path(), {"alg=trpo"}));
  EXPECT_TRUE(contains(m, "no 'env_id' given"));
  EXPECT_TRUE(contains(m, "SafetyBallCircle-v0"));
  // Without a run file, --set alone describes the run.
  EXPECT_NO_THROW(resolve_run_config(request(fs::path(), {"alg=trpo",
                                                          "env_id=SafetyBallCircle-v0"})));
}

TEST_F(ScratchConfigs, KeyOfAnotherAlgorithmIsAnError) {
  const fs::path run = write_run(std::string(kTrpoRun) + "lambda_lr: 0.1\n");
  std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, run.string() + ":3:1"));
  EXPECT_TRUE(contains(m, "'lambda_lr' does not apply to alg 'trpo'"));
  EXPECT_TRUE(contains(m, "used by lag-trpo, pdo"));
  // The run file's values are checked against the algorithm chosen by --set.
  m = error_of(request(write_run(std::string(kTrpoRun) + "pcpo_projection: l2\n"), {"alg=cpo"}));
  EXPECT_TRUE(contains(m, "'pcpo_projection' does not apply to alg 'cpo'"));
}

TEST_F(ScratchConfigs, RunKeysCannotBeSetByAlgorithmOrEnvironmentFiles) {
  write_text(env_file(), read_text_file(env_file()) + "alg: cpo\n");
  const std::string m = error_of(request(write_run(kTrpoRun)));
  EXPECT_TRUE(contains(m, env_file().string() + ":6:1"));
  EXPECT_TRUE(contains(m, "'alg' cannot be set in an environment file"));
}

TEST_F(ScratchConfigs, AlgorithmFileMustListEveryKeyOfItsAlgorithm) {
  write_text(alg_file("trpo"), std::regex_replace(read_text_file(alg_file("trpo")),
                                                  std::regex("\ncg_iters:[^\n]*"), ""));
  const std::string m = error_of(request(write_run(kTrpoRun)));
  EXPECT_TRUE(contains(m, "key 'cg_iters' is not set"));
  EXPECT_TRUE(contains(m, alg_file("trpo").string()));
  // ... unless a later layer sets it.
  EXPECT_EQ(resolve_run_config(request(write_run(kTrpoRun), {"cg_iters=7"})).config.trust_region.cg_iters, 7);
}

TEST_F(ScratchConfigs, EnvFromRegistryWithoutFileNeedsEnvironmentKeysFromTheRun) {
  RunConfigRequest r = request(write_run("env_id: TestPointGoal-v0\nalg: trpo\n"));
  r.valid_env_ids = {"SafetyBallCircle-v0", "TestPointGoal-v0"};
  std::string m = error_of(r);
  EXPECT_TRUE(contains(m, "key 'cost_limit' is not set for env_id 'TestPointGoal-v0'"));
  EXPECT_TRUE(contains(m, "TestPointGoal-v0.yaml"));

  r.set_arguments = {"cost_limit=1", "epochs=2", "steps_per_epoch=300", "max_ep_len=100"};
  const RunConfig c = resolve_run_config(r).config;
  EXPECT_EQ(c.env_id, "TestPointGoal-v0");
  EXPECT_EQ(c.steps_per_epoch, 300);
}

TEST_F(ScratchConfigs, EpisodeLongerThanEpochIsAnErrorNamingBothKeys) {
  const fs::path run = write_run(std::string(kTrpoRun) + "steps_per_epoch: 200\n");
  const std::string m = error_of(request(run));
  EXPECT_TRUE(contains(m, "max_ep_len = 250"));
  EXPECT_TRUE(contains(m, "SafetyBallCircle-v0.yaml"));
  EXPECT_TRUE(contains(m, "steps_per_epoch = 200 (" + run.string() + ":3:1)"));
}

TEST_F(ScratchConfigs, AnAnnealingLongerThanTheRunOrWithoutAnnealedSigmaIsAnError) {
  const fs::path run = write_run(std::string(kTrpoRun) + "epochs: 20\n");
  EXPECT_EQ(resolve_run_config(request(run, {"exploration_anneal_epochs=20"})).config.exploration_anneal_epochs, 20);
  std::string m = error_of(request(run, {"exploration_anneal_epochs=21"}));
  EXPECT_TRUE(contains(m, "exploration_anneal_epochs = 21 (--set exploration_anneal_epochs=21) exceeds epochs = 20 (" +
                              run.string() + ":3:1)"));
  m = error_of(request(run, {"exploration_anneal_epochs=10", "use_exploration_noise_anneal=false"}));
  EXPECT_TRUE(contains(m, "exploration_anneal_epochs = 10"));
  EXPECT_TRUE(contains(m, "has no effect: sigma is fixed (use_exploration_noise_anneal: false)"));
  write_text(alg_file("ppo"), read_text_file(kShippedConfigs / "algorithms" / "ppo.yaml"));
  m = error_of(request(run, {"alg=ppo", "exploration_anneal_epochs=10"}));
  EXPECT_TRUE(contains(m, "has no effect: sigma is learned (learn_log_std: true)"));
  EXPECT_EQ(resolve_run_config(request(run, {"alg=ppo", "exploration_anneal_epochs=10", "learn_log_std=false"}))
                .config.exploration_anneal_epochs,
            10);
}

TEST_F(ScratchConfigs, ASigmaFloorWithoutAnnealedSigmaOrBelowZeroIsAnError) {
  const fs::path run = write_run(kTrpoRun);
  EXPECT_EQ(resolve_run_config(request(run, {"exploration_std_floor=0.1"})).config.exploration_std_floor, 0.1);
  std::string m = error_of(request(run, {"exploration_std_floor=0.1", "use_exploration_noise_anneal=false"}));
  EXPECT_TRUE(contains(m, "exploration_std_floor = 0.1 (--set exploration_std_floor=0.1) has no effect: "
                          "sigma is fixed (use_exploration_noise_anneal: false)")) << m;
  write_text(alg_file("ppo"), read_text_file(kShippedConfigs / "algorithms" / "ppo.yaml"));
  m = error_of(request(run, {"alg=ppo", "exploration_std_floor=0.1"}));
  EXPECT_TRUE(contains(m, "has no effect: sigma is learned (learn_log_std: true)")) << m;
  m = error_of(request(run, {"exploration_std_floor=-0.1"}));
  EXPECT_TRUE(contains(m, "exploration_std_floor")) << m;
  EXPECT_FALSE(resolve_run_config(request(run, {})).config.sampled_evaluation);
  EXPECT_TRUE(resolve_run_config(request(run, {"sampled_evaluation=true"})).config.sampled_evaluation);
}

TEST(CheckRunConfigForRanks, AppliesTheSpecsSetupChecks) {
  RunConfig c;
  c.steps_per_epoch = 1000;
  c.max_ep_len = 250;
  c.num_mini_batches = 16;
  EXPECT_NO_THROW(check_run_config_for_ranks(c, 1));  // N = 1000, minibatch 62
  EXPECT_NO_THROW(check_run_config_for_ranks(c, 2));  // N = 500, minibatch 31
  auto error_for = [&](int ranks) -> std::string {
    try {
      check_run_config_for_ranks(c, ranks);
    } catch (const ConfigError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error for " << ranks << " ranks";
    return "";
  };
  EXPECT_TRUE(contains(error_for(3), "steps_per_epoch = 1000 is not divisible by the 3 MPI ranks"));
  EXPECT_TRUE(contains(error_for(4), "floor(250 / num_mini_batches = 16) = 15 is below 16"));
  EXPECT_TRUE(contains(error_for(8), "max_ep_len = 250 exceeds the local steps per rank"));
  EXPECT_TRUE(contains(error_for(0), "at least 1"));
}

}  // namespace
}  // namespace bsg
