// The interface of every on-policy algorithm (the trust-region family in
// algos/trust_region/: TRPO, TRPO-L, CPO, PDO, PCPO; the first-order family in
// algos/first_order/: PPO, PPO-Lag, CPPO-PID, FOCOPS, CUP): the on-policy
// loop (docs/algorithms.md#the-epoch-loop) calls `update` once per epoch,
// after the rollout and GAE and before the value fits; the algorithms differ
// only in this update (design.md "Learning"). One file per algorithm
// implements it; algos/training/make_algorithm.h turns a RunConfig into one.
//
// Order inside one epoch (docs/algorithms.md#the-epoch-loop): the loop calls
// update() (which, for the Lagrangian methods, first updates lambda and then
// takes the policy step), then fits V and, if uses_cost_value_function(), V_C,
// then updates the normalisers.
//
// This header also declares the steps every update shares (the surrogates at
// theta_old, the weighted loss, the five common diagnostics); the trust-region
// building blocks are in algos/trust_region/trust_region_steps.h.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "algos/core/gaussian_policy.h"
#include "algos/core/policy_surrogate.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"

namespace bsg::algos {

// One logged scalar (a progress.csv column, docs/algorithms.md#logged-columns) or one saved state value.
struct NamedScalar {
  std::string name;
  double value = 0.0;
  bool operator==(const NamedScalar&) const = default;
};

// The names of a list of columns, in order (an algorithm's diagnostic_names()
// from the function that fills the values, so that each name is written once).
std::vector<std::string> names_of(std::span<const NamedScalar> columns);

// One constraint as an update sees it (docs/algorithms.md#several-constraints).
struct ConstraintEstimate {
  double mean_episode_cost = 0.0;  // J_Ci: pooled mean undiscounted cost of this epoch's completed episodes
  double limit = 0.0;              // d_i
};

// What an update needs. All references must outlive the call.
struct PolicyUpdateInputs {
  GaussianPolicy& policy;       // theta is replaced by theta_old + accepted step
  PolicySurrogate& surrogate;   // this rank's batch: normalised obs, actions, old log-probs, A, A^C1..A^Cm
  double mean_episode_cost;     // J_C: constraint 1's J_Ci (the only one without `constraints:`)
  double mean_episode_length;   // L: pooled mean length of the same episodes
  const MpiContext& mpi;
  // All m constraints in the surrogate's order; empty: the single constraint
  // {mean_episode_cost, cost_limit}. constraint_estimates() gives them either way.
  std::span<const ConstraintEstimate> constraints = {};
  // The rank's minibatch shuffles of the first-order updates (first_order_update.h;
  // the trainer's per-epoch shuffle stream); the trust-region updates draw nothing.
  Rng* minibatch_rng = nullptr;
};

// The update's constraints: inputs.constraints, or the single {J_C, cost_limit}.
std::vector<ConstraintEstimate> constraint_estimates(const PolicyUpdateInputs& inputs, const RunConfig& config);

// Diagnostics of one update, in the fixed order of diagnostic_names(). The
// first kCommonDiagnosticCount entries are the common columns every algorithm
// fills (rank-LOCAL values, to be pooled by the logger as docs/algorithms.md#across-mpi-ranks says):
//   Loss/Pi       loss before the update (TRPO-L: the Lagrangian loss l_L; others l_R)
//   Loss/DeltaPi  loss after minus loss before (true value for CPO too, Q18)
//   Entropy       entropy per action dimension
//   KL            full-batch KL(theta_old || theta) after the update
//   PolicyRatio   mean ratio rho after the update
// The rest are the algorithm's own columns in docs/algorithms.md#logged-columns order (identical on
// all ranks): Misc/AcceptanceStep, Misc/Alpha, Misc/FinalStepNorm,
// Misc/gradient_norm, Misc/xHx, Misc/H_inv_g, then per algorithm
// LagrangeMultiplier (TRPO-L); Misc/cost_gradient_norm, Misc/A, Misc/B, Misc/q,
// Misc/r, Misc/s, Misc/Lambda_star, Misc/Nu_star, Misc/OptimCase (CPO, PCPO);
// Misc/cost_gradient_norm, LagrangeMultiplier (PDO); TRPO-L and PDO with
// lambda_optimizer PID add PID/P, PID/I, PID/D after LagrangeMultiplier.
inline constexpr std::size_t kCommonDiagnosticCount = 5;
// Their names, in order (the values: common_diagnostics).
inline constexpr std::array<std::string_view, kCommonDiagnosticCount> kCommonDiagnosticNames = {
    "Loss/Pi", "Loss/DeltaPi", "Entropy", "KL", "PolicyRatio"};
// Their positions, for reading a result without looking names up.
enum class CommonDiagnostic : std::size_t { loss = 0, loss_delta = 1, entropy = 2, kl = 3, policy_ratio = 4 };

struct PolicyUpdateResult {
  std::vector<NamedScalar> diagnostics;
  // lambda of a Lagrangian update with one constraint (set with the
  // multiplier's columns, algos/lagrange/constraint_multipliers.h); empty otherwise.
  std::optional<double> lagrange_multiplier;
  // The value of the named diagnostic; throws std::out_of_range if absent.
  double value(std::string_view name) const;
  // One of the common columns (empty if the update gave fewer).
  std::optional<double> common(CommonDiagnostic which) const {
    const auto index = static_cast<std::size_t>(which);
    if (index >= diagnostics.size()) return std::nullopt;
    return diagnostics[index].value;
  }
};

class OnPolicyAlgorithm {
 public:
  explicit OnPolicyAlgorithm(const RunConfig& config) : config_(config) {}
  virtual ~OnPolicyAlgorithm() = default;

  // The config spelling: "trpo", "lag-trpo", "cpo", "pdo", "pcpo", "ppo", "ppo-lag", "focops" or "cup".
  virtual std::string_view name() const = 0;

  // One policy update (collective: every rank must call it). On return the
  // policy holds theta_old + accepted step; if no line-search trial was
  // accepted, its parameters are bit-identical to before.
  virtual PolicyUpdateResult update(const PolicyUpdateInputs& inputs) = 0;

  // The names of update()'s diagnostics, in order; never changes.
  virtual std::vector<std::string> diagnostic_names() const = 0;

  // Whether the loop trains the cost value net V_C (RunConfig
  // use_cost_value_function: false for TRPO, true for the others).
  bool uses_cost_value_function() const { return config_.use_cost_value_function; }

  // The state to checkpoint (lambda and its optimiser moments for TRPO-L and
  // PDO; empty for the others, the default here) and its restoration.
  // restore_state throws std::invalid_argument if the names do not match
  // state()'s.
  virtual std::vector<NamedScalar> state() const { return {}; }
  virtual void restore_state(std::span<const NamedScalar> saved);

 protected:
  const RunConfig& config() const { return config_; }

 private:
  RunConfig config_;
};

// ---------------------------------------------------------------------------
// Steps every update shares, trust-region and first-order alike.

// The names of the common columns, in order (Loss/Pi ... PolicyRatio).
std::vector<std::string> common_diagnostic_names();

// Throws std::invalid_argument naming the field if J_C is not finite (used by
// the algorithms that read it).
void check_mean_episode_cost(const PolicyUpdateInputs& inputs, std::string_view algorithm);

// The common first steps of every update (docs/algorithms.md#algorithm-updates): theta_old <- theta, the
// reference means mu_old for the KL, and the surrogates at theta_old.
struct PolicyUpdateStart {
  Eigen::VectorXd theta_old;
  SurrogateValues before;  // L_R, L_C, ratio at theta_old (KL 0)
};
PolicyUpdateStart begin_policy_update(const PolicyUpdateInputs& inputs);

// The loss l = -(reward_weight L_R + cost_weight L_C) of a surrogate evaluation.
double weighted_surrogate_loss(const SurrogateValues& values, double reward_weight, double cost_weight);
// With one weight per constraint: l = -(w_R L_R + sum_j w_j L_Cj).
double weighted_surrogate_loss(const SurrogateValues& values, double reward_weight,
                               std::span<const double> cost_weights);
// The five common columns for that loss.
std::vector<NamedScalar> common_diagnostics(const PolicyUpdateInputs& inputs, const SurrogateValues& before,
                                            double reward_weight, std::span<const double> cost_weights);

// The five common columns, evaluated after the step has been applied: Loss/Pi
// is the weighted loss at theta_old (`before`), Loss/DeltaPi the change at the
// policy's new parameters; KL, PolicyRatio and Entropy at the new parameters.
std::vector<NamedScalar> common_diagnostics(const PolicyUpdateInputs& inputs, const SurrogateValues& before,
                                            double reward_weight, double cost_weight);

}  // namespace bsg::algos
