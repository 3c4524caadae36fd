// The algorithms as the rest of bsg knows them before any update runs: the
// spelling in configs, the label in tables, the family of update and what the
// algorithm constrains. One row per algorithm: the run configuration's schema
// (which keys apply to which algorithms), the run checks and the experiments'
// tables and plots read this table, so adding an algorithm is one value and one row here
// plus its update in algos/ (docs/architecture.md#adding-things).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace bsg {

// The five trust-region algorithms spelled in configs as the original code
// spells them (plus "pcpo", which the original lacks), then the first-order
// baselines spelled as OmniSafe spells them (docs/algorithms.md#first-order-updates), then the
// off-policy learners with a replay buffer (docs/algorithms.md#off-policy-learners), then
// later additions. New values go last: the order of the value list in messages
// (`trpo | lag-trpo | ...`) and of the key table's algorithm column follows the enum.
enum class Algorithm {
  trpo, lag_trpo, cpo, pdo, pcpo, ppo, ppo_lag, focops, cup, sac, td3, ddpg, sac_lag, td3_lag, ddpg_lag, crpo,
  bc_all, bc_safe, p3o, ipo, rcpo, cpq,
  ppo_saute, trpo_saute, ppo_early_terminated, trpo_early_terminated,
  ppo_simmer, trpo_simmer, bcq_lag, coptidice,
  mappo, mappo_lag, happo, macpo
};

// Which update the policy takes: the natural-gradient step with a line search
// (algos/trust_region), minibatch Adam passes (algos/first_order), or gradient
// steps on batches from a replay buffer with critics of Q (algos/off_policy), or gradient steps on
// batches of a fixed dataset that never touch an environment (algos/offline), or PPO's clipped
// step for each of several agents acting together in a multi-agent environment (algos/multi_agent).
enum class AlgorithmFamily { trust_region, first_order, off_policy, offline, multi_agent };

// Everything outside the algorithm's own files needs to know of it: the run checks, the
// key table's families, Table 1's labels and PID columns, and the plots (`bsg table`
// writes this table as algorithms.csv beside table1.csv; scripts/plot_curves.py reads it).
struct AlgorithmInfo {
  Algorithm alg;
  std::string_view name;       // in configs and on the command line: "lag-trpo"
  std::string_view label;      // in tables and figures: "TRPO-L"
  std::string_view pid_label;  // with lambda_optimizer PID; "" without a multiplier
  AlgorithmFamily family;
  bool constrained;            // false: maximises the return alone, its cost only judges it
  bool lagrange_multiplier;    // keeps multipliers (lambda_lr, lambda_optimizer, pid_*)
  bool clipped_surrogate;      // PPO's clipped ratio (the clip key)
  std::string_view plot_colour;  // a Matplotlib colour name for its curves
};

inline constexpr auto kAlgorithms = std::to_array<AlgorithmInfo>({
    // alg                 name        label       pid_label     family                        constr lagr  clip   colour
    {Algorithm::trpo,     "trpo",     "TRPO",     "",           AlgorithmFamily::trust_region, false, false, false, "tab:blue"},
    {Algorithm::lag_trpo, "lag-trpo", "TRPO-L",   "TRPO-PID",   AlgorithmFamily::trust_region, true,  true,  false, "tab:orange"},
    {Algorithm::cpo,      "cpo",      "CPO",      "",           AlgorithmFamily::trust_region, true,  false, false, "tab:green"},
    {Algorithm::pdo,      "pdo",      "PDO",      "PDO-PID",    AlgorithmFamily::trust_region, true,  true,  false, "tab:red"},
    {Algorithm::pcpo,     "pcpo",     "PCPO",     "",           AlgorithmFamily::trust_region, true,  false, false, "tab:purple"},
    {Algorithm::ppo,      "ppo",      "PPO",      "",           AlgorithmFamily::first_order,  false, false, true,  "tab:gray"},
    // CPPO-PID: Stooke, Achiam and Abbeel's name for PPO with the PID multiplier.
    {Algorithm::ppo_lag,  "ppo-lag",  "PPO-Lag",  "CPPO-PID",   AlgorithmFamily::first_order,  true,  true,  true,  "tab:brown"},
    {Algorithm::focops,   "focops",   "FOCOPS",   "FOCOPS-PID", AlgorithmFamily::first_order,  true,  true,  false, "tab:pink"},
    {Algorithm::cup,      "cup",      "CUP",      "CUP-PID",    AlgorithmFamily::first_order,  true,  true,  true,  "tab:olive"},
    {Algorithm::sac,      "sac",      "SAC",      "",           AlgorithmFamily::off_policy,   false, false, false, "tab:cyan"},
    {Algorithm::td3,      "td3",      "TD3",      "",           AlgorithmFamily::off_policy,   false, false, false, "navy"},
    {Algorithm::ddpg,     "ddpg",     "DDPG",     "",           AlgorithmFamily::off_policy,   false, false, false, "goldenrod"},
    // SAC-PID, TD3-PID, DDPG-PID: OmniSafe's names for the PID multiplier forms.
    {Algorithm::sac_lag,  "sac-lag",  "SAC-Lag",  "SAC-PID",    AlgorithmFamily::off_policy,   true,  true,  false, "teal"},
    {Algorithm::td3_lag,  "td3-lag",  "TD3-Lag",  "TD3-PID",    AlgorithmFamily::off_policy,   true,  true,  false, "crimson"},
    {Algorithm::ddpg_lag, "ddpg-lag", "DDPG-Lag", "DDPG-PID",   AlgorithmFamily::off_policy,   true,  true,  false, "darkkhaki"},
    {Algorithm::crpo,     "crpo",     "CRPO",     "",           AlgorithmFamily::trust_region, true,  false, false, "darkviolet"},
    // OSRL's behaviour cloning: every row, or the rows of episodes within the cost limit (which BC-Safe
    // constrains by its choice of data).
    {Algorithm::bc_all,   "bc-all",   "BC-All",   "",           AlgorithmFamily::offline,      false, false, false, "sienna"},
    {Algorithm::bc_safe,  "bc-safe",  "BC-Safe",  "",           AlgorithmFamily::offline,      true,  false, false, "seagreen"},
    // The penalty methods of OmniSafe's on-policy table: P3O's exact ReLU penalty and IPO's log
    // barrier over PPO, RCPO's multiplier folded into the reward over the natural-gradient step.
    {Algorithm::p3o,      "p3o",      "P3O",      "",           AlgorithmFamily::first_order,  true,  false, true,  "darkcyan"},
    {Algorithm::ipo,      "ipo",      "IPO",      "",           AlgorithmFamily::first_order,  true,  false, true,  "orchid"},
    {Algorithm::rcpo,     "rcpo",     "RCPO",     "RCPO-PID",   AlgorithmFamily::trust_region, true,  true,  false, "maroon"},
    // Constraints penalised Q-learning (Xu et al. 2022, OSRL's cpq.py): its multiplier is its own (alpha
    // on the out-of-distribution cost), not the Lagrangian keys'.
    {Algorithm::cpq,      "cpq",      "CPQ",      "",           AlgorithmFamily::offline,      true,  false, false, "slategray"},
    // PPO and TRPO on an environment whose budget decorator (algos/training/budget_decorator.h)
    // changes what the learner sees: Saute's budget in the observation, or the episode cut when
    // the budget is spent. OmniSafe's names (saute/, early_terminated/).
    {Algorithm::ppo_saute, "ppo-saute", "PPOSaute", "",         AlgorithmFamily::first_order,  true,  false, true,  "lightcoral"},
    {Algorithm::trpo_saute, "trpo-saute", "TRPOSaute", "",      AlgorithmFamily::trust_region, true,  false, false, "steelblue"},
    {Algorithm::ppo_early_terminated, "ppo-early-terminated", "PPOEarlyTerminated", "",
                                                                AlgorithmFamily::first_order,  true,  false, true,  "mediumseagreen"},
    {Algorithm::trpo_early_terminated, "trpo-early-terminated", "TRPOEarlyTerminated", "",
                                                                AlgorithmFamily::trust_region, true,  false, false, "slateblue"},
    // Saute with a budget that a PID controller moves between epochs (Sootla et al. 2022, "Effects
    // of Safety State Augmentation on Safe Exploration"; OmniSafe's simmer/ PPOSimmerPID, TRPOSimmerPID).
    {Algorithm::ppo_simmer, "ppo-simmer", "PPOSimmerPID", "",   AlgorithmFamily::first_order,  true,  false, true,  "darkorange"},
    {Algorithm::trpo_simmer, "trpo-simmer", "TRPOSimmerPID", "", AlgorithmFamily::trust_region, true,  false, false, "royalblue"},
    // Batch-constrained Q-learning with a cost critic (Fujimoto et al. 2019, OSRL's bcql.py): its multiplier
    // is OSRL's PID controller on the cost critic's estimate (bcq_pid_*), not the Lagrangian keys'.
    {Algorithm::bcq_lag,  "bcq-lag",  "BCQ-Lag",  "",           AlgorithmFamily::offline,      true,  false, false, "chocolate"},
    // Stationary distribution correction with a cost bound (Lee et al. 2022, OSRL's coptidice.py): its
    // multiplier is its own dual variable (coptidice_scalar_lr), not the Lagrangian keys'.
    {Algorithm::coptidice, "coptidice", "COptiDICE", "",        AlgorithmFamily::offline,      true,  false, false, "olivedrab"},
    // Multi-agent PPO with centralised critics (Yu et al. 2022, "The Surprising Effectiveness of PPO in
    // Cooperative Multi-Agent Games") and its Lagrangian form (Gu et al. 2021, "Multi-Agent Constrained
    // Policy Optimisation"; SafePO's multi_agent/mappo.py and mappolag.py), on the multi-agent ids only.
    {Algorithm::mappo,    "mappo",    "MAPPO",    "",           AlgorithmFamily::multi_agent,  false, false, true,  "darkgreen"},
    {Algorithm::mappo_lag, "mappo-lag", "MAPPO-L", "MAPPO-L-PID", AlgorithmFamily::multi_agent, true,  true,  true,  "darkred"},
    // The sequential multi-agent updates, one agent after another in a random order, each seeing the
    // correction of those before it (Kuba et al. 2022, HAPPO; Gu et al. 2021, MACPO's CPO steps; SafePO's
    // multi_agent/happo.py and macpo.py; docs/multi_agent.md#sequential-agent-updates-happo-macpo).
    {Algorithm::happo,    "happo",    "HAPPO",    "",           AlgorithmFamily::multi_agent,  false, false, true,  "lightseagreen"},
    {Algorithm::macpo,    "macpo",    "MACPO",    "",           AlgorithmFamily::multi_agent,  true,  false, false, "indianred"},
});

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

// Whether the algorithm learns from a fixed dataset (algos/offline) without acting in an environment.
constexpr bool is_offline(Algorithm alg) { return algorithm_info(alg).family == AlgorithmFamily::offline; }

// Whether the algorithm trains several agents on a multi-agent environment (algos/multi_agent).
constexpr bool is_multi_agent(Algorithm alg) { return algorithm_info(alg).family == AlgorithmFamily::multi_agent; }

// Whether the multi-agent learner updates its agents one after another (HAPPO, MACPO) rather than all at once.
constexpr bool is_sequential_multi_agent(Algorithm alg) { return alg == Algorithm::happo || alg == Algorithm::macpo; }

// Whether the algorithm keeps Lagrange multipliers (and so can use the PID rule).
constexpr bool has_lagrange_multiplier(Algorithm alg) { return algorithm_info(alg).lagrange_multiplier; }

}  // namespace bsg
