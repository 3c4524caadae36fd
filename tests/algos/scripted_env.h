// A scripted environment for testing the training loop without physics:
// observation (t, episode step, seed-dependent offset), reward 1 + 0.01 t,
// cost 1 on every `cost_period`-th episode step, truncation after
// `episode_length` steps and an optional termination after
// `terminate_after` steps. It records every reset. Setting
// `nan_reward_after_steps` makes every reward after that many steps (in
// total) NaN, to test the training loop's safety net.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "envs/env.h"

namespace bsg::testing {

class ScriptedEnv : public envs::Env {
 public:
  ScriptedEnv(int episode_length, std::optional<int> terminate_after = std::nullopt, int cost_period = 10)
      : terminate_after_(terminate_after), cost_period_(cost_period) {
    spec_.id = "Scripted-v0";
    spec_.observation_dim = 3;
    spec_.action_dim = 2;
    spec_.max_episode_steps = episode_length;
    observation_.resize(3);
  }

  const envs::EnvSpec& spec() const override { return spec_; }

  std::span<const double> reset(std::uint64_t seed) override {
    seeded_resets.push_back(seed);
    offset_ = static_cast<double>(seed % 97);
    return start_episode();
  }
  std::span<const double> reset() override {
    ++unseeded_resets;
    offset_ += 1.0;
    return start_episode();
  }
  std::span<const double> reset_to(const envs::Layout& layout) override {
    layout_ = layout;
    return start_episode();
  }
  const envs::Layout& layout() const override { return layout_; }

  envs::StepResult step(std::span<const double> action) override {
    if (action.size() != 2) throw std::invalid_argument("ScriptedEnv: action size");
    ++episode_step_;
    ++total_steps;
    envs::StepResult result;
    result.reward = 1.0 + 0.01 * static_cast<double>(episode_step_);
    if (nan_reward_after_steps && total_steps > *nan_reward_after_steps) result.reward = std::nan("");
    result.cost = episode_step_ % cost_period_ == 0 ? 1.0 : 0.0;
    result.terminated = terminate_after_ && episode_step_ >= *terminate_after_;
    result.truncated = !result.terminated && episode_step_ >= spec_.max_episode_steps;
    write_observation();
    result.observation = observation_;
    return result;
  }

  envs::EnvState state() const override { return {}; }
  void teleport_agent(const envs::Vec3&) override {}

  std::vector<std::uint64_t> seeded_resets;
  int unseeded_resets = 0;
  long long total_steps = 0;
  std::optional<long long> nan_reward_after_steps;

 private:
  std::span<const double> start_episode() {
    episode_step_ = 0;
    write_observation();
    return observation_;
  }
  void write_observation() {
    observation_[0] = 0.1 * static_cast<double>(episode_step_);
    observation_[1] = offset_;
    observation_[2] = 1.0;
  }

  envs::EnvSpec spec_;
  envs::Layout layout_;
  std::optional<int> terminate_after_;
  int cost_period_;
  int episode_step_ = 0;
  double offset_ = 0.0;
  std::vector<double> observation_;
};

}  // namespace bsg::testing
