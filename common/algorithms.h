// The algorithms as the rest of bsg knows them before any update runs: the
// spelling in configs, the label in tables, the family of update and what the
// algorithm constrains. One row per algorithm: the run configuration's schema
// (which keys apply to which algorithms), the run checks and the experiments'
// tables read this table, so adding an algorithm is one row here plus its
// update in algos/ (docs/architecture.md#adding-things).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace bsg {

// The five trust-region algorithms spelled in configs as the original code
// spells them (plus "pcpo", which the original lacks), then the first-order
// baselines spelled as OmniSafe spells them (docs/algorithms.md#first-order-updates), then the
// off-policy learners with a replay buffer (docs/algorithms.md#off-policy-learners).
enum class Algorithm { trpo, lag_trpo, cpo, pdo, pcpo, ppo, ppo_lag, focops, cup, sac, td3, ddpg, sac_lag, td3_lag, ddpg_lag };

// Which update the policy takes: the natural-gradient step with a line search
// (algos/trust_region), minibatch Adam passes (algos/first_order), or gradient
// steps on batches from a replay buffer with critics of Q (algos/off_policy).
enum class AlgorithmFamily { trust_region, first_order, off_policy };

struct AlgorithmInfo {
  Algorithm alg;
  std::string_view name;       // in configs and on the command line: "lag-trpo"
  std::string_view label;      // in tables and figures: "TRPO-L"
  std::string_view pid_label;  // with lambda_optimizer PID; "" without a multiplier
  AlgorithmFamily family;
  bool constrained;            // false: maximises the return alone, its cost only judges it
  bool lagrange_multiplier;    // keeps multipliers (lambda_lr, lambda_optimizer, pid_*)
  bool clipped_surrogate;      // PPO's clipped ratio (the clip key)
};

inline constexpr std::array<AlgorithmInfo, 15> kAlgorithms = {{
    // alg                 name        label      pid_label     family                        constr lagr  clip
    {Algorithm::trpo,     "trpo",     "TRPO",    "",           AlgorithmFamily::trust_region, false, false, false},
    {Algorithm::lag_trpo, "lag-trpo", "TRPO-L",  "TRPO-PID",   AlgorithmFamily::trust_region, true,  true,  false},
    {Algorithm::cpo,      "cpo",      "CPO",     "",           AlgorithmFamily::trust_region, true,  false, false},
    {Algorithm::pdo,      "pdo",      "PDO",     "PDO-PID",    AlgorithmFamily::trust_region, true,  true,  false},
    {Algorithm::pcpo,     "pcpo",     "PCPO",    "",           AlgorithmFamily::trust_region, true,  false, false},
    {Algorithm::ppo,      "ppo",      "PPO",     "",           AlgorithmFamily::first_order,  false, false, true},
    // CPPO-PID: Stooke, Achiam and Abbeel's name for PPO with the PID multiplier.
    {Algorithm::ppo_lag,  "ppo-lag",  "PPO-Lag", "CPPO-PID",   AlgorithmFamily::first_order,  true,  true,  true},
    {Algorithm::focops,   "focops",   "FOCOPS",  "FOCOPS-PID", AlgorithmFamily::first_order,  true,  true,  false},
    {Algorithm::cup,      "cup",      "CUP",     "CUP-PID",    AlgorithmFamily::first_order,  true,  true,  true},
    {Algorithm::sac,      "sac",      "SAC",     "",           AlgorithmFamily::off_policy,   false, false, false},
    {Algorithm::td3,      "td3",      "TD3",     "",           AlgorithmFamily::off_policy,   false, false, false},
    {Algorithm::ddpg,     "ddpg",     "DDPG",    "",           AlgorithmFamily::off_policy,   false, false, false},
    // SAC-PID, TD3-PID, DDPG-PID: OmniSafe's names for the PID multiplier forms.
    {Algorithm::sac_lag,  "sac-lag",  "SAC-Lag", "SAC-PID",    AlgorithmFamily::off_policy,   true,  true,  false},
    {Algorithm::td3_lag,  "td3-lag",  "TD3-Lag", "TD3-PID",    AlgorithmFamily::off_policy,   true,  true,  false},
    {Algorithm::ddpg_lag, "ddpg-lag", "DDPG-Lag", "DDPG-PID",  AlgorithmFamily::off_policy,   true,  true,  false},
}};

constexpr const AlgorithmInfo& algorithm_info(Algorithm alg) { return kAlgorithms[static_cast<std::size_t>(alg)]; }

// The rows are in the enum's order (algorithm_info indexes by it).
static_assert([] {
  for (std::size_t i = 0; i < kAlgorithms.size(); ++i) {
    if (static_cast<std::size_t>(kAlgorithms[i].alg) != i) return false;
  }
  return true;
}());

// The config spellings in enum order: the choices of the `alg` key.
inline constexpr std::array<std::string_view, kAlgorithms.size()> kAlgorithmNames = [] {
  std::array<std::string_view, kAlgorithms.size()> names{};
  for (std::size_t i = 0; i < kAlgorithms.size(); ++i) names[i] = kAlgorithms[i].name;
  return names;
}();

// Whether the algorithm maximises the return alone (TRPO, PPO): its cost
// only judges the policy, it is not constrained.
constexpr bool ignores_cost(Algorithm alg) { return !algorithm_info(alg).constrained; }

// Whether the algorithm takes the first-order update rather than the trust-region step.
constexpr bool is_first_order(Algorithm alg) {
  return algorithm_info(alg).family == AlgorithmFamily::first_order;
}

// Whether the algorithm learns from a replay buffer (algos/off_policy) rather than on-policy batches.
constexpr bool is_off_policy(Algorithm alg) {
  return algorithm_info(alg).family == AlgorithmFamily::off_policy;
}

// Whether the algorithm keeps Lagrange multipliers (and so can use the PID rule).
constexpr bool has_lagrange_multiplier(Algorithm alg) { return algorithm_info(alg).lagrange_multiplier; }

}  // namespace bsg
