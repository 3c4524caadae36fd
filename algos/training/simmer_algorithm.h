// Simmer over PPO or TRPO (ppo-simmer, trpo-simmer; Sootla et al. 2022, "Effects of Safety State
// Augmentation on Safe Exploration"; OmniSafe's simmer/ppo_simmer_pid.py and trpo_simmer_pid.py):
// Saute (envs/saute_env.h) with a budget that a PID controller (simmer_budget_controller.h) moves
// once per epoch. Like OmniSafe's _update, each update first steps one controller per constraint
// with the epoch's mean episode cost J_i (pooled over the ranks, so every rank holds the same
// budgets) and then takes the base algorithm's update unchanged. The controllers work in Saute's
// normalised units, b~ and J~ = J (1 - gamma_s^T) / ((1 - gamma_s) T), with the constraint's limit
// d_i as the ceiling and b_0 = simmer_initial_budget_fraction d_i.
//
// The next epoch's episodes start with z_i,0 = b_i / d_i (start_fractions(), set on the Saute
// environment by budget_decorator.h's apply_budget_schedule), so their reward is replaced once
// their discounted cost reaches b_i. (OmniSafe's adapter divides each cost by b~_k while starting
// at b~_k / b~_max, which spends the budget at b_k^2 / d_max; here costs are divided by d~ as in
// Saute, so an episode spends exactly its scheduled b_k.) The diagnostic Simmer/Budget
// (progress.csv's simmer_budget; simmer_budget_i with several constraints) is the b_i, in units of
// the episode cost, that the epoch's episodes were collected with. The controllers' state follows
// the base algorithm's in state(), so the checkpoint holds it.
#pragma once

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/training/simmer_budget_controller.h"

namespace bsg::algos {

class SimmerAlgorithm final : public OnPolicyAlgorithm {
 public:
  // `base`: the update of PPO or TRPO for config.alg ppo-simmer or trpo-simmer. Throws
  // std::invalid_argument if alg schedules no budget or the controller's keys are refused.
  SimmerAlgorithm(const RunConfig& config, std::unique_ptr<OnPolicyAlgorithm> base);

  std::string_view name() const override { return base_->name(); }
  PolicyUpdateResult update(const PolicyUpdateInputs& inputs) override;
  std::vector<std::string> diagnostic_names() const override;
  std::vector<NamedScalar> state() const override;
  void restore_state(std::span<const NamedScalar> saved) override;

  // b_i / d_i: z_i,0 of the next episodes, one per constraint.
  std::vector<double> start_fractions() const;
  // b_i in units of the episode cost.
  std::vector<double> budgets() const;

 private:
  std::unique_ptr<OnPolicyAlgorithm> base_;
  std::vector<double> normalized_limits_;  // d~_i, the ceilings
  std::vector<SimmerBudgetController> controllers_;
};

}  // namespace bsg::algos
