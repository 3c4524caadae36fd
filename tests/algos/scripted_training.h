// Shared pieces of the trainer tests on the scripted environment: a small
// TRPO-L configuration (5 epochs of 4 episodes of 100 steps) and the sigma
// each epoch of a run used.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "../test_support.h"
#include "algos/training/on_policy_trainer.h"
#include "scripted_env.h"

namespace bsg::testing {

inline RunConfig scripted_config() {
  RunConfig config;
  config.env_id = "Scripted-v0";
  config.alg = Algorithm::lag_trpo;
  config.use_cost_value_function = true;
  config.hidden_sizes = {16, 16};
  config.epochs = 5;
  config.steps_per_epoch = 400;  // 4 episodes of 100 steps
  config.max_ep_len = 100;
  config.save_freq = 1;
  config.eval_episodes = 2;
  config.cost_limit = 5;
  return config;
}

// Trains `config` on the scripted environment and returns the policy's sigma in each epoch.
inline std::vector<double> sigma_of_each_epoch(const RunConfig& config) {
  TemporaryDirectory dir;
  std::vector<double> sigmas;
  algos::TrainerOptions options;
  algos::OnPolicyTrainer* running = nullptr;
  options.on_epoch_timed = [&](const algos::EpochTimings&) { sigmas.push_back(running->actor_critic().policy.std()); };
  algos::OnPolicyTrainer trainer(config, algos::RunDirectory(dir.path() / "run"), MpiContext::single_process(), options,
                          std::make_unique<ScriptedEnv>(100));
  running = &trainer;
  trainer.run();
  return sigmas;
}

}  // namespace bsg::testing
