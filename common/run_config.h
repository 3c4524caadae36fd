// RunConfig: the resolved description of one training run (environment,
// algorithm, seed, hyper-parameters, quirk switches), as read from configs/
// by run_config_resolve.h and written to a run directory by run_config_yaml.h.
//
// Parameters: every key, its type, where its default comes from, its valid
// range and meaning are listed in one table, run_config_schema.cpp
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
#include "common/constraint_config.h"
#include "common/physics_model.h"
#include "common/dtype.h"

namespace bsg {

// Update rule of the Lagrange multiplier (docs/algorithms.md#trpo-l SGD for
// TRPO-L, docs/algorithms.md#pdo Adam for PDO; PID: the PID Lagrangian of Stooke, Achiam and Abbeel 2020, with
// the pid_* keys, algos/lagrange/pid_lagrangian.h).
enum class LambdaOptimizer { sgd, adam, pid };
inline constexpr std::array<std::string_view, 3> kLambdaOptimizerNames = {"SGD", "Adam", "PID"};

// Sign of r in CPO's dual solution (docs/algorithms.md#cpo, quirk Q10).
enum class CpoRSign { original, corrected };
inline constexpr std::array<std::string_view, 2> kCpoRSignNames = {"original", "corrected"};

// Metric of PCPO's projection step (docs/algorithms.md#pcpo): Fisher (KL) or Euclidean (L2).
enum class PcpoProjection { kl, l2 };
inline constexpr std::array<std::string_view, 2> kPcpoProjectionNames = {"kl", "l2"};

// Which learner a run uses (docs/algorithms.md#quirk-switches): the original's
// (every quirk switch as set by the layers) or the corrected one, which turns
// on every "corrected" switch (Q1, Q4, Q5, Q10, Q19, Q20) unless the run file or
// --set names that switch itself.
enum class Learner { faithful, corrected };
inline constexpr std::array<std::string_view, 2> kLearnerNames = {"faithful", "corrected"};

std::string_view to_string(Algorithm alg);
std::string_view to_string(LambdaOptimizer optimizer);
std::string_view to_string(CpoRSign sign);
std::string_view to_string(PcpoProjection projection);
std::string_view to_string(Learner learner);

struct RunConfig {
  // --- run (the run file or --set) ---
  std::string env_id = "SafetyBallCircle-v0";
  Algorithm alg = Algorithm::trpo;
  std::int64_t seed = 0;
  std::string log_dir = "runs";

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

  // --- trust region (docs/algorithms.md#trust-region-tools) ---
  double target_kl = 0.01;         // delta
  double cg_damping = 0.1;
  int cg_iters = 10;
  int fvp_subsample = 4;           // FVP uses every k-th observation
  int backtrack_budget = 15;       // Q11
  double backtrack_decay = 0.8;
  double kl_accept_factor = 1.5;   // Q13

  // --- Lagrange multiplier (TRPO-L, PDO; docs/algorithms.md#trpo-l, #pdo) ---
  double lagrangian_multiplier_init = 0.001;
  double lambda_lr = 0.05;
  LambdaOptimizer lambda_optimizer = LambdaOptimizer::sgd;
  double lagrangian_upper_bound = 0.0;  // FOCOPS's nu_max (every rule); 0 = none
  // PID multiplier (lambda_optimizer PID only; algos/lagrange/pid_lagrangian.h)
  double pid_kp = 0.1;                  // K_P
  double pid_ki = 0.005;                // K_I (replaces lambda_lr)
  double pid_kd = 0.0;                  // K_D
  int pid_d_delay = 10;                 // epochs between the J_ema compared by D
  double pid_delta_p_ema_alpha = 0.0;   // EMA factor of the P input; 0 = none
  double pid_delta_d_ema_alpha = 0.0;   // EMA factor of the D input; 0 = none
  double pid_lambda_max = 0.0;          // upper bound on lambda; 0 = none

  // --- algorithm-specific switches ---
  CpoRSign cpo_r_sign = CpoRSign::original;  // Q10
  bool cpo_clamp_a = false;                  // docs/algorithms.md#cpo degenerate A < 0
  PcpoProjection pcpo_projection = PcpoProjection::kl;
  bool pcpo_line_search = true;
  bool pdo_line_search = true;               // Q14
  double crpo_tolerance = 2.0;               // CRPO's eta: a cost step once J_C > d + eta

  // --- first-order updates (PPO, PPO-Lag, FOCOPS, CUP; docs/algorithms.md#first-order-updates) ---
  double actor_lr = 3e-4;          // Adam step size on the policy
  int update_iters = 40;           // passes over the batch per update
  int policy_minibatch_size = 64;  // samples per minibatch, summed over ranks
  bool kl_early_stop = true;       // stop the passes once the KL exceeds target_kl
  double max_grad_norm = 40.0;     // 0: no gradient rescaling
  double clip = 0.2;               // PPO's epsilon (ppo, ppo-lag, cup's first step)
  double focops_lam = 1.5;         // FOCOPS's temperature lambda
  double focops_eta = 0.02;        // FOCOPS's per-sample KL mask threshold
  bool learn_log_std = false;      // learn a state-independent log sigma per action dimension
  double learned_std_init = 0.509; // its initial sigma (the annealing's first)

  // --- off-policy learners (SAC, TD3, DDPG and their -lag forms; docs/algorithms.md#off-policy-learners) ---
  int num_envs = 1;                // environments per rank, stepped in turn
  int start_steps = 10000;         // uniform random actions for the first start_steps steps (all ranks)
  int update_every = 1;            // environment steps (per rank, over its environments) between rounds of updates
  double updates_per_step = 1.0;   // gradient steps per environment step of a rank
  int batch_size = 256;            // transitions per gradient step and rank
  int buffer_size = 1000000;       // replay buffer capacity in transitions per rank
  double polyak = 0.005;           // tau: target <- (1 - tau) target + tau online
  int n_step = 1;                  // n-step returns
  double critic_lr = 0.001;        // Adam step size of the Q networks
  double exploration_noise = 0.1;  // TD3, DDPG: std of the Gaussian action noise
  double policy_noise = 0.2;       // TD3: std of the target policy smoothing noise
  double noise_clip = 0.5;         // TD3: the smoothing noise is clipped to +-noise_clip
  int policy_delay = 2;            // TD3: critic steps per actor (and target) step
  double alpha_init = 0.2;         // SAC: initial entropy temperature
  bool auto_alpha = false;         // SAC: learn alpha towards the target entropy -|A|
  double alpha_lr = 0.0003;        // SAC: Adam step size of log alpha

  // --- offline (bc-all, bc-safe; docs/datasets.md#offline-runs) ---
  // Also read by the offline family: hidden_sizes, activation, zero_bias_init, dtype, actor_lr (the
  // policy's Adam step size), batch_size (rows per gradient step), cost_limit (BC-Safe's episodes),
  // epochs, eval_episodes, save_freq, seed.
  std::string dataset;             // the HDF5 file (DSRL's layout) the policy learns from
  int updates_per_epoch = 200;     // gradient steps per epoch
  int eval_every = 1;              // online evaluation after every eval_every-th epoch (and the last)

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
