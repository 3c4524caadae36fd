// RunConfig: the resolved description of one training run (environment,
// algorithm, seed, hyper-parameters, quirk switches), as read from configs/
// by run_config_resolve.h and written to a run directory by run_config_yaml.h.
//
// The keys every family reads (the run, the environment settings, networks,
// returns and advantages, value networks, bookkeeping) are RunConfig's own
// members; a family's keys, and its algorithms' own, are a group of their own,
// each in its header beside the rows of its keys:
//   trust_region  TrustRegionKeys  common/trust_region_keys.h/.cpp (trpo .. crpo)
//   multiplier    MultiplierKeys   common/multiplier_keys.h/.cpp   (the Lagrangian ones)
//   first_order   FirstOrderKeys   common/first_order_keys.h/.cpp  (ppo .. cup)
//   off_policy    OffPolicyKeys    common/off_policy_keys.h/.cpp   (sac .. ddpg-lag)
//   offline       OfflineKeys      common/offline_keys.h/.cpp      (bc-all, bc-safe)
//   budget        BudgetKeys       common/budget_keys.h/.cpp       (ppo-saute, trpo-saute, ppo-simmer, trpo-simmer)
//   multi_agent   MultiAgentKeys   common/multi_agent_keys.h/.cpp  (mappo, mappo-lag, happo, macpo)
// In YAML every key is flat (`cg_iters: 10`, not nested under its group).
//
// Parameters: every key, its type, where its default comes from, its valid
// range and meaning are listed in one table, run_config_schema.h, whose rows
// run_config_schema.cpp assembles from the groups' files in one fixed order
// (`bsg train --print-config` and configs/README.md show the same). The key
// names are those of the original (docs/algorithms.md#hyper-parameters, #quirk-switches) and of its
// code. A default-constructed RunConfig holds the TRPO defaults on
// SafetyBallCircle-v0, which a test checks against configs/.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/activation.h"
#include "common/algorithms.h"
#include "common/budget_keys.h"
#include "common/constraint_config.h"
#include "common/first_order_keys.h"
#include "common/multi_agent_keys.h"
#include "common/multiplier_keys.h"
#include "common/off_policy_keys.h"
#include "common/offline_keys.h"
#include "common/physics_model.h"
#include "common/dtype.h"
#include "common/trust_region_keys.h"

namespace bsg {

// Which learner a run uses (docs/algorithms.md#quirk-switches): the original's
// (every quirk switch as set by the layers) or the corrected one, which turns
// on every "corrected" switch (Q1, Q4, Q5, Q10, Q19, Q20) unless the run file or
// --set names that switch itself.
enum class Learner { faithful, corrected };
inline constexpr std::array<std::string_view, 2> kLearnerNames = {"faithful", "corrected"};

std::string_view to_string(Algorithm alg);
std::string_view to_string(Learner learner);

struct RunConfig {
  // --- run (the run file or --set) ---
  std::string env_id = "SafetyBallCircle-v0";
  Algorithm alg = Algorithm::trpo;
  std::int64_t seed = 0;
  std::string log_dir = "runs";
  // TensorBoard event files beside progress.csv (algos/training/event_file.h); config.yaml names
  // the key only when it is off, so a default run's files are as before the key.
  bool tensorboard = true;
  // A single-agent learner on a multi-agent env_id controls every agent jointly
  // (envs/joint_control_env.h, docs/multi_agent.md#one-learner-for-the-whole-team); config.yaml
  // names the key only when it is on.
  bool joint_control = false;

  // --- environment settings (report Table 3, docs/reproducing.md#environment-settings) ---
  double cost_limit = 25.0;        // d: limit on the undiscounted episode cost
  // Several constraints (docs/algorithms.md#several-constraints); empty: one,
  // the environment's cost against cost_limit.
  std::vector<ConstraintConfig> constraints{};
  int epochs = 500;                // E
  int steps_per_epoch = 32000;     // B: env steps per epoch summed over ranks
  int max_ep_len = 250;            // episode time limit in steps
  PhysicsModel physics = PhysicsModel::kFaithful;  // common/physics_model.h
  Learner learner = Learner::faithful;  // the `learner:` preset (run file, --set, grid)
  // The `env:` block: parameters of the environment's description as
  // (key, value text), applied to env_id's description in this order
  // (envs/description/env_parameters.h). A run directory's config.yaml holds the whole
  // resolved description once the run has any (algos/training/run_environment.h).
  std::vector<std::pair<std::string, std::string>> env;

  // --- networks (docs/algorithms.md#networks) ---
  std::vector<int> hidden_sizes = {64, 64};
  Activation activation = Activation::tanh;
  bool zero_bias_init = false;     // Q1
  Dtype dtype = Dtype::float32;    // arithmetic of the learner's batch passes (common/dtype.h)

  // --- returns and advantages (docs/algorithms.md#normalisers, #rollout-and-gae) ---
  double gamma = 0.99;
  double lam = 0.95;               // GAE lambda, rewards
  double lam_c = 0.95;             // GAE lambda, costs
  bool use_exploration_noise_anneal = true;
  int exploration_anneal_epochs = 0;  // > 0: sigma reaches 0.01 after this many epochs and holds it; 0 = E
  double exploration_std_floor = 0.0; // sigma_k = max(schedule, floor); 0 = the schedule alone
  bool use_standardized_obs = true;
  bool use_reward_scaling = true;
  bool use_standardized_advantages = false;  // Q6
  bool center_advantages = false;            // Q6 too: subtract the pooled mean of every advantage
  double obs_clip = 0.0;                     // Q3: 0 = no clipping
  bool exact_parallel_variance = false;      // Q4
  bool consistent_return_statistic = false;  // Q5: the statistic's bootstrap value in raw units
  bool rescale_value_output = false;         // Q19: V's output layer follows the statistic (PopArt)
  int reward_scale_warmup_epochs = 0;        // > 0: the statistic is frozen after this many epochs
  bool timeout_bootstrap = true;             // bootstrap V at time-outs (false: a time-out ends the return)
  bool value_time_input = false;             // V and V_C also see the fraction of max_ep_len left

  // --- the families' groups (their headers list the keys) ---
  TrustRegionKeys trust_region;    // trust-region tools and the variants' switches
  MultiplierKeys multiplier;       // Lagrange multipliers (the Lagrangian algorithms)
  FirstOrderKeys first_order;      // first-order updates
  OffPolicyKeys off_policy;        // off-policy learners
  OfflineKeys offline;             // offline learners (the dataset, steps per epoch)
  BudgetKeys budget;               // the budget methods (Saute's discount and unsafe reward, Simmer's controller)
  MultiAgentKeys multi_agent;      // the multi-agent learners

  // --- value networks (docs/algorithms.md#value-fits) ---
  bool use_cost_value_function = false;
  double vf_lr = 0.001;
  int train_v_iterations = 5;      // Q15
  int num_mini_batches = 16;       // Q15

  // --- bookkeeping (docs/algorithms.md#the-epoch-loop, docs/reproducing.md#evaluation) ---
  int save_freq = 10;
  int check_freq = 25;
  int eval_episodes = 128;
  bool sampled_evaluation = false;  // evaluate a = mu + sigma eps at the last epoch's sigma (else a = mu)

  bool operator==(const RunConfig&) const = default;
};

}  // namespace bsg
