// The PID Lagrange multiplier of Stooke, Achiam and Abbeel ("Responsive Safety
// in Reinforcement Learning by PID Lagrangian Methods", ICML 2020, Algorithm 2),
// as the authors' code (and OmniSafe's PIDLagrangian) computes it. Once per
// epoch, on the pooled mean episode cost J_C and the limit d:
//
//   Delta     = J_C - d
//   I         <- max(0, I + K_I Delta)                       integral, no wind-up below 0
//   Delta_ema <- a_P Delta_ema + (1 - a_P) Delta             P input, smoothed
//   J_ema     <- a_D J_ema + (1 - a_D) J_C                   D input, smoothed
//   P = K_P Delta_ema,  D = K_D max(0, J_ema - J_ema[k - delay])
//   lambda    = min(lambda_max, max(0, P + I + D))           (no upper bound if lambda_max = 0)
//
// The integral alone is the plain SGD rule with K_I as its learning rate: with
// K_P = K_D = 0, lambda_k = I_k = max(0, I_{k-1} + K_I (J_C - d)), the SGD
// multiplier of multiplier.h. The derivative only pushes lambda up
// when the cost rises (it never rewards falling cost), damping the overshoot
// the integral alone gives; the proportional term reacts to the current
// violation without waiting for the integral to build up.
//
// As in the reference code, both EMAs start at 0 and are not bias-corrected
// (with a = 0 there is no smoothing), and the history J_ema[k - delay] before
// the first epoch is 0, so the first epochs' D term sees the cost rise from 0.
// I starts at the initial multiplier (lagrangian_multiplier_init, at least
// 1e-5 as the other rules).
//
// Parameters (RunConfig keys, defaults in configs/algorithms/{lag-trpo,pdo}.yaml):
//   proportional_gain    pid_kp                  K_P >= 0
//   integral_gain        pid_ki                  K_I >= 0
//   derivative_gain      pid_kd                  K_D >= 0
//   derivative_delay     pid_d_delay             epochs between the compared J_ema, >= 1
//   proportional_ema     pid_delta_p_ema_alpha   a_P in [0, 1)
//   derivative_ema       pid_delta_d_ema_alpha   a_D in [0, 1)
//   lambda_max           pid_lambda_max          upper bound on lambda; 0 = none
#pragma once

#include <span>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

struct PidLagrangianOptions {
  double proportional_gain = 0.0;  // K_P
  double integral_gain = 0.0;      // K_I
  double derivative_gain = 0.0;    // K_D
  int derivative_delay = 1;        // delay in epochs
  double proportional_ema = 0.0;   // a_P
  double derivative_ema = 0.0;     // a_D
  double lambda_max = 0.0;         // 0: no upper bound
};

// The options from the pid_* keys of a RunConfig.
PidLagrangianOptions pid_lagrangian_options(const RunConfig& config);

// The three terms of one update and the resulting multiplier.
struct PidTerms {
  double proportional = 0.0;  // P = K_P Delta_ema (may be negative)
  double integral = 0.0;      // I >= 0
  double derivative = 0.0;    // D = K_D max(0, J_ema - J_ema[k - delay]) >= 0
  double lambda = 0.0;        // min(lambda_max, max(0, P + I + D))
};

class PidLagrangian {
 public:
  // Throws std::invalid_argument naming the option (by its config key) if it
  // is out of range, or if initial_integral is negative or not finite.
  PidLagrangian(double initial_integral, const PidLagrangianOptions& options);

  // One epoch: the update above; returns the terms (also kept in last_terms()).
  PidTerms update(double mean_episode_cost, double cost_limit);

  const PidTerms& last_terms() const { return terms_; }

  // "pid_integral", "pid_delta_p_ema", "pid_cost_d_ema", then the delay
  // queue oldest first, "pid_cost_d_history_0" .. "_<delay - 1>" (fixed
  // length: the entries before the first epoch are 0, as the reference's).
  std::vector<NamedScalar> state() const;
  // Throws std::invalid_argument if the names differ from state()'s, a value
  // is not finite or the integral is negative. last_terms() afterwards holds
  // only the integral (the other terms are recomputed by the next update).
  void restore_state(std::span<const NamedScalar> saved);

 private:
  PidLagrangianOptions options_;
  double integral_;                   // I
  double delta_p_ema_ = 0.0;          // Delta_ema
  double cost_d_ema_ = 0.0;           // J_ema
  std::vector<double> cost_history_;  // J_ema of the last `delay` epochs, a ring
  std::size_t history_start_ = 0;     // index of the oldest entry, J_ema[k - delay]
  PidTerms terms_;
};

}  // namespace bsg::algos
