// Simmer's PID controller of a safety budget (Sootla et al. 2022, "Effects of Safety State
// Augmentation on Safe Exploration"; OmniSafe's common/simmer_agent.py, SimmerPIDAgent). Once per
// epoch it sees the epoch's mean episode cost J_k and moves the budget b_k toward it:
//
//   e_k  = p e_k-1 + (1 - p) (b_k - J_k)               smoothed error, e_-1 = 0
//   u_k  = K_P e_k + K_I (e_k-9 + ... + e_k) + K_D (s_k-1 - u_k-1)   (the last 10 errors; u_-1 = s_-1 = 0)
//   b_k+1 = clip(b_k + clip(u_k, -1, 1), 1e-6, b_max)
//   s_k  = b_k+1 - b_k                                  the step actually taken
//
// so a budget above the cost rises (to at most b_max) and one below it falls. The units are the
// caller's; OmniSafe's are the Saute-normalised ones, d~ (envs/saute_env.h), to which the step
// bound 1 and the floor 1e-6 belong. Its whole state (budget, errors, last steps) is named scalars
// for the training checkpoint, so a resumed run continues exactly.
//
// Parameters (SimmerControllerOptions): kp, ki, kd, polyak p (common/budget_keys.h: OmniSafe's
// control_cfgs), the ceiling b_max and the first budget b_0 (0 < b_0 <= b_max).
#pragma once

#include <deque>
#include <span>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"

namespace bsg::algos {

struct SimmerControllerOptions {
  double kp = 0.0005;
  double ki = 0.00001;
  double kd = 0.0;
  double polyak = 0.995;
  double budget_ceiling = 1.0;  // b_max
  double initial_budget = 1.0;  // b_0
};

class SimmerBudgetController {
 public:
  static constexpr double kStepBound = 1.0;      // |b_k+1 - b_k| <= 1 (OmniSafe's action space (-1, 1))
  static constexpr double kBudgetFloor = 1e-6;   // b_k >= 1e-6 (OmniSafe's eps)
  static constexpr std::size_t kIntegralWindow = 10;  // errors summed by the I term (OmniSafe's deque maxlen)

  // Throws std::invalid_argument naming the option at fault (negative gains, p outside [0, 1),
  // b_0 outside (0, b_max], a ceiling below 1e-6 or not finite).
  explicit SimmerBudgetController(const SimmerControllerOptions& options);

  double budget() const { return budget_; }
  // One epoch: b_k+1 from J_k (finite, else std::invalid_argument); returns b_k+1.
  double step(double mean_episode_cost);

  // The state, each name prefixed by `prefix`, and its restoration from exactly those names in
  // that order (std::invalid_argument otherwise, or on a window size above kIntegralWindow).
  std::vector<NamedScalar> state(const std::string& prefix) const;
  void restore_state(std::span<const NamedScalar> saved, const std::string& prefix);
  static std::size_t state_size() { return 5 + kIntegralWindow; }

 private:
  SimmerControllerOptions options_;
  double budget_;
  double error_ = 0.0;         // e_k-1
  double step_taken_ = 0.0;    // s_k-1
  double raw_step_ = 0.0;      // u_k-1
  std::deque<double> errors_;  // the last kIntegralWindow errors, oldest first
};

}  // namespace bsg::algos
