// Saute RL's environment (Sootla et al., ICML 2022, "Saute RL: Almost Surely Safe Reinforcement
// Learning Using State Augmentation"; OmniSafe's adapter/saute_adapter.py): the remaining
// safety budget of each constraint joins the observation, and once a budget is spent the
// learner's reward is a fixed penalty. Per budget i, with the normalised budget
//
//   d~_i = d_i (1 - gamma_s^T) / ((1 - gamma_s) T)      (T = max_episode_steps)
//   z_i,0 = 1,   z_i,t+1 = (z_i,t - c_i,t / d~_i) / gamma_s
//   learner reward  r~_t = r_t if every z_i,t+1 > 0, else unsafe_reward
//
// and the observation is (o_t+1, z_1,t+1, ..., z_m,t+1). The step's reward, cost, terms and
// episode end stay the environment's; the learner's reward is StepResult::learner (env_types.h).
// (One budget per constraint; OmniSafe has the one budget of the environment's cost.)
// A schedule of budgets (Simmer: algos/training/simmer_algorithm.h) starts each episode at a
// fraction of d_i instead, z_i,0 = b_i / d_i, so the reward is replaced once the episode's
// discounted cost reaches b_i; the default fraction 1 is Saute's.
//
// Parameters (SauteOptions): saute_gamma gamma_s = 0.999, unsafe_reward = -1 (OmniSafe's
// PPOSaute.yaml and TRPOSaute.yaml), max_episode_steps T (the run's max_ep_len).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "envs/cost_budgets.h"
#include "envs/decorated_env.h"

namespace bsg::envs {

// d~ = d (1 - gamma_s^T) / ((1 - gamma_s) T): a budget d in units of the discounted cost per step.
double saute_normalized_budget(double limit, double saute_gamma, int max_episode_steps);

struct SauteOptions {
  double saute_gamma = 0.999;
  double unsafe_reward = -1.0;
  int max_episode_steps = 1000;
};

class SauteEnv final : public DecoratedEnv {
 public:
  // Throws std::invalid_argument naming the budget or option at fault: no budgets, a limit
  // that is not positive and finite, gamma_s outside (0, 1), T < 1, or an unsafe reward not finite.
  SauteEnv(std::unique_ptr<Env> inner, CostBudgets budgets, SauteOptions options);

  const EnvSpec& spec() const override { return spec_; }
  std::span<const double> reset(std::uint64_t seed) override { return start_episode(inner().reset(seed)); }
  std::span<const double> reset() override { return start_episode(inner().reset()); }
  std::span<const double> reset_to(const Layout& layout) override { return start_episode(inner().reset_to(layout)); }
  StepResult step(std::span<const double> action) override;

  // z_i of the last observation, one per budget.
  std::span<const double> budgets_left() const { return {observation_.data() + inner_size_, budget_count()}; }
  // d~_i.
  const std::vector<double>& normalized_budgets() const { return normalized_budgets_; }
  // z_i,0 of the episodes that start after this call, one per budget (each in (0, 1]; 1 until
  // set). Throws std::invalid_argument naming the budget at fault or the count.
  void set_start_fractions(std::span<const double> fractions);

 private:
  std::size_t budget_count() const { return normalized_budgets_.size(); }
  std::span<const double> start_episode(std::span<const double> observation);
  std::span<const double> augment(std::span<const double> observation);

  CostBudgets budgets_;
  SauteOptions options_;
  EnvSpec spec_;
  std::size_t inner_size_;
  std::vector<double> normalized_budgets_;  // d~_i
  std::vector<double> step_costs_;          // c_i,t
  std::vector<double> start_fractions_;     // z_i,0
  std::vector<double> observation_;         // (o, z_1..z_m)
};

}  // namespace bsg::envs
