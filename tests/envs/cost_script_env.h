// An environment that plays back a script: at episode step t (1-based) its reward is 10 + t
// and its cost terms are script[t - 1] (term "a", term "b"); its cost is term a. The
// observation is (episode step, 7). For the budget decorators' tests.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "envs/cost_budgets.h"
#include "envs/env.h"

namespace bsg::testing {

class CostScriptEnv final : public envs::Env {
 public:
  explicit CostScriptEnv(std::vector<std::array<double, 2>> script) : script_(std::move(script)) {
    spec_.id = "CostScript-v0";
    spec_.observation_dim = 2;
    spec_.action_dim = 1;
    spec_.max_episode_steps = static_cast<int>(script_.size());
    spec_.cost_term_names = {"a", "b"};
  }

  const envs::EnvSpec& spec() const override { return spec_; }
  std::span<const double> reset(std::uint64_t) override { return start(); }
  std::span<const double> reset() override { return start(); }
  std::span<const double> reset_to(const envs::Layout&) override { return start(); }
  const envs::Layout& layout() const override { return layout_; }
  envs::StepResult step(std::span<const double>) override {
    if (step_ >= static_cast<int>(script_.size())) throw std::logic_error("CostScriptEnv: past the script");
    const std::array<double, 2>& costs = script_[static_cast<std::size_t>(step_)];
    ++step_;
    terms_ = {envs::CostTerm{"a", costs[0]}, envs::CostTerm{"b", costs[1]}};
    observation_ = {static_cast<double>(step_), 7.0};
    envs::StepResult result;
    result.observation = observation_;
    result.reward = 10.0 + step_;
    result.cost = costs[0];
    result.truncated = step_ == static_cast<int>(script_.size());
    result.cost_terms = terms_;
    return result;
  }
  envs::EnvState state() const override { return {}; }
  void teleport_agent(const envs::Vec3&) override {}

 private:
  std::span<const double> start() {
    step_ = 0;
    observation_ = {0.0, 7.0};
    return observation_;
  }

  std::vector<std::array<double, 2>> script_;
  envs::EnvSpec spec_;
  envs::Layout layout_;
  int step_ = 0;
  std::array<double, 2> observation_{};
  std::array<envs::CostTerm, 2> terms_{};
};

// Budget i's cost is term i.
inline envs::CostBudgets term_budgets(std::vector<double> limits) {
  return {std::move(limits), [](const envs::StepResult& step, std::span<double> costs) {
            for (std::size_t i = 0; i < costs.size(); ++i) costs[i] = step.cost_terms[i].value;
          }};
}

}  // namespace bsg::testing
