// The schema table: every configuration key in one place. Defaults are not
// here but in configs/ (the layer named in the second column provides them);
// RunConfig's member initialisers repeat the TRPO / SafetyBallCircle-v0 ones.
#include "common/run_config_schema.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <type_traits>
#include <variant>

#include "common/config_error.h"
#include "common/message_text.h"
#include "common/config_scalar.h"

namespace bsg {

namespace {

constexpr double kIntMax = 2147483647.0;

// Access to an enum member through its underlying index into its names.
struct EnumAccess {
  int (*get)(const RunConfig&);
  void (*set)(RunConfig&, int);
};

template <auto Member>
EnumAccess enum_access() {
  return {[](const RunConfig& config) { return static_cast<int>(config.*Member); },
          [](RunConfig& config, int index) {
            using Enum = std::remove_cvref_t<decltype(config.*Member)>;
            config.*Member = static_cast<Enum>(index);
          }};
}

using TextPairs = std::vector<std::pair<std::string, std::string>>;
using FieldAccess =
    std::variant<bool RunConfig::*, int RunConfig::*, std::int64_t RunConfig::*,
                 double RunConfig::*, std::string RunConfig::*, std::vector<int> RunConfig::*,
                 std::vector<ConstraintConfig> RunConfig::*, TextPairs RunConfig::*, EnumAccess>;

struct SchemaRow {
  ConfigKey info;
  FieldAccess field;
};

// The algorithm families the keys apply to, read off the table of algorithms (common/algorithms.h).
constexpr AlgorithmSet algorithms_where(bool AlgorithmInfo::*property) {
  AlgorithmSet set = 0;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.*property) set |= algorithm_bit(info.alg);
  }
  return set;
}
constexpr AlgorithmSet algorithms_in(AlgorithmFamily family) {
  AlgorithmSet set = 0;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.family == family) set |= algorithm_bit(info.alg);
  }
  return set;
}
constexpr AlgorithmSet kLagrangian = algorithms_where(&AlgorithmInfo::lagrange_multiplier);
constexpr AlgorithmSet kTrustRegion = algorithms_in(AlgorithmFamily::trust_region);
constexpr AlgorithmSet kFirstOrder = algorithms_in(AlgorithmFamily::first_order);
constexpr AlgorithmSet kOffPolicy = algorithms_in(AlgorithmFamily::off_policy);
constexpr AlgorithmSet kOffline = algorithms_in(AlgorithmFamily::offline);
constexpr AlgorithmSet kSacFamily = algorithm_bit(Algorithm::sac) | algorithm_bit(Algorithm::sac_lag);
constexpr AlgorithmSet kTd3Family = algorithm_bit(Algorithm::td3) | algorithm_bit(Algorithm::td3_lag);
constexpr AlgorithmSet kDeterministicActor =
    kTd3Family | algorithm_bit(Algorithm::ddpg) | algorithm_bit(Algorithm::ddpg_lag);
constexpr AlgorithmSet kClipped = algorithms_where(&AlgorithmInfo::clipped_surrogate);

SchemaRow boolean(std::string_view key, bool RunConfig::*member, ConfigLayer layer,
                  AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::boolean, layer, {}, {}, used_by, description}, member};
}
template <typename Int>
SchemaRow integer(std::string_view key, Int RunConfig::*member, ConfigLayer layer,
                  NumericRange range, AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::integer, layer, range, {}, used_by, description}, member};
}
SchemaRow real(std::string_view key, double RunConfig::*member, ConfigLayer layer,
               NumericRange range, AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::real, layer, range, {}, used_by, description}, member};
}
SchemaRow text(std::string_view key, std::string RunConfig::*member, ConfigLayer layer,
               std::string_view description, AlgorithmSet used_by = kAllAlgorithms) {
  return {{key, ValueType::text, layer, {}, {}, used_by, description}, member};
}
SchemaRow choice(std::string_view key, EnumAccess access, std::span<const std::string_view> names,
                 ConfigLayer layer, AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::choice, layer, {}, names, used_by, description}, access};
}
SchemaRow constraint_list(std::string_view key, std::vector<ConstraintConfig> RunConfig::*member,
                          AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::constraint_list, ConfigLayer::run, {}, {}, used_by, description}, member};
}
SchemaRow integer_list(std::string_view key, std::vector<int> RunConfig::*member,
                       ConfigLayer layer, NumericRange element_range, AlgorithmSet used_by,
                       std::string_view description) {
  return {{key, ValueType::integer_list, layer, element_range, {}, used_by, description},
          member};
}

// clang-format off
const std::vector<SchemaRow>& schema_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  constexpr AlgorithmSet all = kAllAlgorithms;
  constexpr AlgorithmSet on_policy = kTrustRegion | kFirstOrder;
  static const std::vector<SchemaRow> rows = {
    // --- run ---
    text("env_id", &R::env_id, L::run,
         "environment id, e.g. SafetyBallCircle-v0 (report Table 3)"),
    choice("alg", enum_access<&R::alg>(), kAlgorithmNames, L::run, all,
           "algorithm: trpo, lag-trpo (TRPO-L), cpo, pdo, pcpo, the first-order ppo, ppo-lag, focops, cup, or the "
           "off-policy sac, td3, ddpg, sac-lag, td3-lag, ddpg-lag"),
    integer("seed", &R::seed, L::run, N::closed(0, 4294967295.0), all,
            "base seed; per-rank and per-environment seeds are derived from it (seeding.h)"),
    text("log_dir", &R::log_dir, L::run,
         "directory under which the run directory is created"),
    choice("physics", enum_access<&R::physics>(), kPhysicsModelNames, L::run, all,
           "faithful (the original's model) or lean (equivalent, faster; the Ant and the Car)"),
    choice("learner", enum_access<&R::learner>(), kLearnerNames, L::run, all,
           "preset: faithful (the original's learner) or corrected (every corrected switch on: Q1, Q4, Q5, "
           "Q10, Q19, Q20; a switch the run file or --set names itself keeps that value)"),
    {{"env", ValueType::mapping, L::run, {}, {}, all,
      "environment parameters, e.g. {bombs: 12} (`bsg envs --describe ID` lists them)"}, &R::env},
    constraint_list("constraints", &R::constraints, all,
                    "several constraints, each summing named cost terms (or all) against its own limit: "
                    "[{terms: [cost_outside_bounds], limit: 20}, ...]; absent: the cost against cost_limit"),
    text("dataset", &R::dataset, L::run,
         "offline: the HDF5 dataset (DSRL's layout, e.g. from bsg collect) the policy learns from; its env_id "
         "must be the run's", kOffline),
    // --- environment (report Table 3, docs/reproducing.md#environment-settings) ---
    real("cost_limit", &R::cost_limit, L::environment, N::at_least(0), all,
         "d: limit on the undiscounted episode cost"),
    integer("epochs", &R::epochs, L::environment, N::closed(1, kIntMax), all,
            "E: number of training epochs"),
    integer("steps_per_epoch", &R::steps_per_epoch, L::environment, N::closed(1, kIntMax), all,
            "B: environment steps per epoch, summed over all MPI ranks"),
    integer("max_ep_len", &R::max_ep_len, L::environment, N::closed(1, kIntMax), all,
            "maximum episode length in steps (the environment's time limit)"),
    // --- networks (docs/algorithms.md#networks) ---
    integer_list("hidden_sizes", &R::hidden_sizes, L::algorithm, N::closed(1, 4096), all,
                 "hidden layer widths of the policy net and both value nets"),
    choice("activation", enum_access<&R::activation>(), kActivationNames, L::algorithm, all,
           "hidden-layer activation of all nets"),
    boolean("zero_bias_init", &R::zero_bias_init, L::algorithm, all,
            "Q1: zero initial biases (report) instead of uniform +-1/sqrt(fan_in) (original)"),
    choice("dtype", enum_access<&R::dtype>(), kDtypeNames, L::algorithm, all,
           "arithmetic of the networks' batch passes (surrogate, gradients, Fisher products, line search, "
           "value fits): float32 (the original's PyTorch default; faster, learning within seed spread) or "
           "float64; parameters, optimiser moments and CG vectors stay float64"),
    // --- returns, advantages, normalisation (docs/algorithms.md#normalisers, #rollout-and-gae) ---
    real("gamma", &R::gamma, L::algorithm, N::open_closed(0, 1), all & ~kOffline,
         "discount factor for rewards and costs"),
    real("lam", &R::lam, L::algorithm, N::closed(0, 1), on_policy,
         "GAE lambda for reward advantages"),
    real("lam_c", &R::lam_c, L::algorithm, N::closed(0, 1), on_policy,
         "GAE lambda for cost advantages"),
    boolean("use_exploration_noise_anneal", &R::use_exploration_noise_anneal, L::algorithm, on_policy,
            "anneal the exploration std: sigma_k = 0.499 (1 - k/E) + 0.01 (else fixed 0.5)"),
    integer("exploration_anneal_epochs", &R::exploration_anneal_epochs, L::algorithm, N::closed(0, kIntMax), on_policy,
            "n > 0: the annealing ends at epoch n, sigma_k = 0.499 (1 - min(k, n)/n) + 0.01, and sigma holds "
            "0.01 for the epochs after it; 0 = E, the original's schedule; at most epochs"),
    real("exploration_std_floor", &R::exploration_std_floor, L::algorithm, N::at_least(0), on_policy,
         "sigma_k = max(annealed sigma_k, floor): the noise never falls below the floor (keeps room for a KL "
         "step to move the mean action late in training); 0 = no floor (original)"),
    boolean("use_standardized_obs", &R::use_standardized_obs, L::algorithm, on_policy,
            "normalise observations by the running mean/std"),
    boolean("use_reward_scaling", &R::use_reward_scaling, L::algorithm, on_policy,
            "divide rewards by the running std of discounted returns, clip to +-10"),
    boolean("use_standardized_advantages", &R::use_standardized_advantages, L::algorithm, on_policy,
            "Q6: standardise advantages (the original never does)"),
    boolean("center_advantages", &R::center_advantages, L::algorithm, on_policy,
            "Q6: subtract the batch mean of the reward and cost advantages, keeping their scale "
            "(original: not centred; implied by use_standardized_advantages)"),
    real("obs_clip", &R::obs_clip, L::algorithm, N::at_least(0), on_policy,
         "Q3: clip normalised observations to +-obs_clip; 0 = no clipping (original)"),
    boolean("exact_parallel_variance", &R::exact_parallel_variance, L::algorithm, on_policy,
            "Q4: Chan's exact parallel variance instead of the original's update"),
    boolean("consistent_return_statistic", &R::consistent_return_statistic, L::algorithm, on_policy,
            "Q5: the return statistic's bootstrap value in raw units, V (s_ret + 1e-5), as the rewards "
            "(original: V's scaled value)"),
    boolean("rescale_value_output", &R::rescale_value_output, L::algorithm, on_policy,
            "Q19: when the return statistic changes, scale V's output layer by old/new std so that "
            "V's predictions in raw units are kept (PopArt)"),
    integer("reward_scale_warmup_epochs", &R::reward_scale_warmup_epochs, L::algorithm, N::closed(0, kIntMax), on_policy,
            "update the return statistic only in the first n epochs, then keep it; 0 = every epoch (original)"),
    boolean("timeout_bootstrap", &R::timeout_bootstrap, L::algorithm, on_policy,
            "bootstrap with V (V_C) of the next observation at a time-out (original); false: as a terminal"),
    boolean("value_time_input", &R::value_time_input, L::algorithm, on_policy,
            "Q20: V and V_C also see the fraction of the time limit left, (max_ep_len - t)/max_ep_len at "
            "episode step t; false: the observation alone (original)"),
    // --- trust region (docs/algorithms.md#trust-region-tools) ---
    real("target_kl", &R::target_kl, L::algorithm, N::above(0), on_policy,
         "delta: trust-region size (mean KL per action dimension, Q8); first-order algorithms: the "
         "early-stop KL (per sample summed over action dimensions, averaged over samples)"),
    real("cg_damping", &R::cg_damping, L::algorithm, N::at_least(0), kTrustRegion,
         "damping added to the Fisher-vector product"),
    integer("cg_iters", &R::cg_iters, L::algorithm, N::closed(1, 1000), kTrustRegion,
            "conjugate-gradient iterations"),
    integer("fvp_subsample", &R::fvp_subsample, L::algorithm, N::closed(1, 1000), kTrustRegion,
            "the Fisher-vector product uses every k-th observation of the batch"),
    integer("backtrack_budget", &R::backtrack_budget, L::algorithm, N::closed(1, 1000), kTrustRegion,
            "Q11: line-search steps (original: 15, CPO 20; report: CPO and PCPO 25)"),
    real("backtrack_decay", &R::backtrack_decay, L::algorithm, N::open(0, 1), kTrustRegion,
         "line-search step shrink factor"),
    real("kl_accept_factor", &R::kl_accept_factor, L::algorithm, N::above(0), kTrustRegion,
         "Q13: the line search accepts a step with KL <= kl_accept_factor * target_kl"),
    // --- Lagrange multiplier (docs/algorithms.md#trpo-l, #pdo) ---
    real("lagrangian_multiplier_init", &R::lagrangian_multiplier_init, L::algorithm,
         N::at_least(0), kLagrangian, "initial Lagrange multiplier lambda (PID: the initial integral I)"),
    real("lambda_lr", &R::lambda_lr, L::algorithm, N::above(0), kLagrangian,
         "alpha_lambda: learning rate of the Lagrange multiplier (SGD, Adam; PID uses pid_ki)"),
    choice("lambda_optimizer", enum_access<&R::lambda_optimizer>(), kLambdaOptimizerNames,
           L::algorithm, kLagrangian,
           "update rule of the Lagrange multiplier: SGD or Adam step of lambda_lr on "
           "-lambda (J_C - d), or PID (Stooke et al. 2020) with the pid_* keys"),
    real("lagrangian_upper_bound", &R::lagrangian_upper_bound, L::algorithm, N::at_least(0),
         algorithm_bit(Algorithm::focops),
         "FOCOPS's nu_max: each multiplier is projected onto [0, nu_max] after its update; 0 = no bound"),
    // --- PID Lagrange multiplier (lambda_optimizer PID; algos/lagrange/pid_lagrangian.h) ---
    real("pid_kp", &R::pid_kp, L::algorithm, N::at_least(0), kLagrangian,
         "PID only: K_P, proportional gain on the (smoothed) violation J_C - d"),
    real("pid_ki", &R::pid_ki, L::algorithm, N::at_least(0), kLagrangian,
         "PID only: K_I, integral gain, I <- max(0, I + K_I (J_C - d)) (the SGD rule's lambda_lr)"),
    real("pid_kd", &R::pid_kd, L::algorithm, N::at_least(0), kLagrangian,
         "PID only: K_D, derivative gain on the cost rise max(0, J_ema - J_ema[k - pid_d_delay])"),
    integer("pid_d_delay", &R::pid_d_delay, L::algorithm, N::closed(1, 1000), kLagrangian,
            "PID only: epochs between the two smoothed costs the derivative compares"),
    real("pid_delta_p_ema_alpha", &R::pid_delta_p_ema_alpha, L::algorithm, N::closed_open(0, 1),
         kLagrangian, "PID only: EMA factor a of the P input, x <- a x + (1 - a) (J_C - d); 0 = none"),
    real("pid_delta_d_ema_alpha", &R::pid_delta_d_ema_alpha, L::algorithm, N::closed_open(0, 1),
         kLagrangian, "PID only: EMA factor a of the D input, J_ema <- a J_ema + (1 - a) J_C; 0 = none"),
    real("pid_lambda_max", &R::pid_lambda_max, L::algorithm, N::at_least(0), kLagrangian,
         "PID only: upper bound on lambda; 0 = no bound"),
    // --- algorithm switches (docs/algorithms.md#pdo, #cpo, #pcpo) ---
    choice("cpo_r_sign", enum_access<&R::cpo_r_sign>(), kCpoRSignNames, L::algorithm,
           algorithm_bit(Algorithm::cpo),
           "Q10: sign of r in CPO's dual: original (as the code) or corrected"),
    boolean("cpo_clamp_a", &R::cpo_clamp_a, L::algorithm, algorithm_bit(Algorithm::cpo),
            "clamp CPO's A = q - r^2/s at 0 when rounding makes it negative (else an error)"),
    choice("pcpo_projection", enum_access<&R::pcpo_projection>(), kPcpoProjectionNames,
           L::algorithm, algorithm_bit(Algorithm::pcpo),
           "metric of PCPO's projection: kl (Fisher) or l2"),
    boolean("pcpo_line_search", &R::pcpo_line_search, L::algorithm,
            algorithm_bit(Algorithm::pcpo),
            "run the constrained line search on PCPO's step (false: apply it directly)"),
    boolean("pdo_line_search", &R::pdo_line_search, L::algorithm, algorithm_bit(Algorithm::pdo),
            "Q14: run the TRPO line search on PDO's reward loss (original); false: apply step"),
    real("crpo_tolerance", &R::crpo_tolerance, L::algorithm, N::at_least(0), algorithm_bit(Algorithm::crpo),
         "CRPO's eta (OmniSafe's distance): the step minimises a constraint's cost once J_C > d + eta"),
    // --- first-order updates (docs/algorithms.md#first-order-updates) ---
    real("actor_lr", &R::actor_lr, L::algorithm, N::above(0), kFirstOrder | kOffPolicy | kOffline,
         "Adam step size on the policy (first-order and off-policy updates)"),
    integer("update_iters", &R::update_iters, L::algorithm, N::closed(1, 10000), kFirstOrder,
            "passes over the batch per policy update (fewer after a KL early stop)"),
    integer("policy_minibatch_size", &R::policy_minibatch_size, L::algorithm, N::closed(1, kIntMax), kFirstOrder,
            "samples per policy minibatch, summed over ranks: floor(B / size) minibatches per pass"),
    boolean("kl_early_stop", &R::kl_early_stop, L::algorithm, kFirstOrder,
            "end the passes after one whose mean KL to the update's start exceeds target_kl"),
    real("max_grad_norm", &R::max_grad_norm, L::algorithm, N::at_least(0), kFirstOrder | kOffPolicy,
         "rescale the rank-averaged gradient of each step (first-order: the policy's; off-policy: the twin "
         "reward critics' together, each cost critic's, the actor's) to at most this norm; 0 = never"),
    real("clip", &R::clip, L::algorithm, N::open(0, 1), kClipped,
         "epsilon of PPO's clipped surrogate (ppo, ppo-lag, cup's performance step)"),
    real("focops_lam", &R::focops_lam, L::algorithm, N::above(0), algorithm_bit(Algorithm::focops),
         "FOCOPS's temperature lambda: the loss is KL - rho (A - nu A^C) / lambda"),
    real("focops_eta", &R::focops_eta, L::algorithm, N::above(0), algorithm_bit(Algorithm::focops),
         "FOCOPS's mask: samples whose KL to the old policy exceeds eta leave the loss"),
    boolean("learn_log_std", &R::learn_log_std, L::algorithm, kFirstOrder,
            "learn a log sigma per action dimension with the policy's Adam (replaces the annealed sigma)"),
    real("learned_std_init", &R::learned_std_init, L::algorithm, N::above(0), kFirstOrder,
         "initial sigma of every dimension with learn_log_std"),
    // --- off-policy learners (docs/algorithms.md#off-policy-learners) ---
    integer("num_envs", &R::num_envs, L::algorithm, N::closed(1, 4096), kOffPolicy,
            "environments per rank, stepped in turn; steps_per_epoch / ranks must be a multiple of it"),
    integer("start_steps", &R::start_steps, L::algorithm, N::closed(0, kIntMax), kOffPolicy,
            "uniform random actions for the first start_steps environment steps (summed over ranks); "
            "gradient steps begin after them"),
    integer("update_every", &R::update_every, L::algorithm, N::closed(1, kIntMax), kOffPolicy,
            "environment steps of a rank between rounds of gradient steps"),
    real("updates_per_step", &R::updates_per_step, L::algorithm, N::open_closed(0, 1000), kOffPolicy,
         "gradient steps per environment step of a rank (a round of update_every steps takes "
         "update_every * updates_per_step of them, fractions carried to the next round)"),
    integer("batch_size", &R::batch_size, L::algorithm, N::closed(1, 1000000), kOffPolicy | kOffline,
            "transitions per gradient step, sampled uniformly from the rank's replay buffer"),
    integer("buffer_size", &R::buffer_size, L::algorithm, N::closed(1, kIntMax), kOffPolicy,
            "replay buffer capacity in transitions per rank (the oldest are overwritten)"),
    real("polyak", &R::polyak, L::algorithm, N::open_closed(0, 1), kOffPolicy,
         "tau: target nets <- (1 - tau) target + tau online after each critic (TD3: actor) step"),
    integer("n_step", &R::n_step, L::algorithm, N::closed(1, 1000), kOffPolicy,
            "n-step returns: sum of n discounted rewards, then gamma^n Q of the n-th next state"),
    real("critic_lr", &R::critic_lr, L::algorithm, N::above(0), kOffPolicy,
         "Adam step size of the reward and cost Q networks"),
    real("exploration_noise", &R::exploration_noise, L::algorithm, N::at_least(0), kDeterministicActor,
         "std of the Gaussian noise on the deterministic actor's actions while collecting"),
    real("policy_noise", &R::policy_noise, L::algorithm, N::at_least(0), kTd3Family,
         "TD3: std of the target policy smoothing noise"),
    real("noise_clip", &R::noise_clip, L::algorithm, N::at_least(0), kTd3Family,
         "TD3: the smoothing noise is clipped to +-noise_clip"),
    integer("policy_delay", &R::policy_delay, L::algorithm, N::closed(1, 1000), kOffPolicy,
            "critic steps per actor, temperature and target step (TD3's delay; OmniSafe delays SAC's too)"),
    real("alpha_init", &R::alpha_init, L::algorithm, N::above(0), kSacFamily,
         "SAC: initial entropy temperature alpha"),
    boolean("auto_alpha", &R::auto_alpha, L::algorithm, kSacFamily,
            "SAC: learn log alpha towards the target entropy -|A| (false: alpha stays alpha_init)"),
    real("alpha_lr", &R::alpha_lr, L::algorithm, N::above(0), kSacFamily,
         "SAC: Adam step size of log alpha (auto_alpha)"),
    // --- offline (docs/datasets.md#offline-runs) ---
    integer("updates_per_epoch", &R::updates_per_epoch, L::algorithm, N::closed(1, kIntMax), kOffline,
            "offline: gradient steps per epoch, each on batch_size rows drawn uniformly with replacement"),
    integer("eval_every", &R::eval_every, L::algorithm, N::closed(1, kIntMax), kOffline,
            "offline: evaluate online (eval_episodes episodes) after every eval_every-th epoch and the last"),
    // --- value networks (docs/algorithms.md#value-fits) ---
    boolean("use_cost_value_function", &R::use_cost_value_function, L::algorithm, on_policy,
            "train the cost value net V_C"),
    real("vf_lr", &R::vf_lr, L::algorithm, N::above(0), on_policy,
         "Adam learning rate of the value nets"),
    integer("train_v_iterations", &R::train_v_iterations, L::algorithm, N::closed(1, 10000), on_policy,
            "Q15: passes over the local batch per epoch when fitting the value nets"),
    integer("num_mini_batches", &R::num_mini_batches, L::algorithm, N::closed(1, 100000), on_policy,
            "Q15: minibatches per pass; minibatch size floor(N / num_mini_batches) per rank"),
    // --- bookkeeping (docs/algorithms.md#the-epoch-loop, docs/reproducing.md#evaluation) ---
    integer("save_freq", &R::save_freq, L::algorithm, N::closed(1, kIntMax), all,
            "save a checkpoint every save_freq epochs and after the last"),
    integer("check_freq", &R::check_freq, L::algorithm, N::closed(1, kIntMax), on_policy,
            "check that parameters agree across ranks every check_freq epochs"),
    integer("eval_episodes", &R::eval_episodes, L::algorithm, N::closed(0, kIntMax), all,
            "evaluation episodes after training, split over ranks"),
    boolean("sampled_evaluation", &R::sampled_evaluation, L::algorithm, on_policy,
            "evaluate the policy as it was trained, a = mu + sigma eps at the last epoch's sigma, with "
            "its own noise stream; false = the deterministic mean action (original)"),
  };
  return rows;
}
// clang-format on

const SchemaRow& row_of(const ConfigKey& key) {
  if (const SchemaRow* row = find_row(schema_rows(), key.key)) return *row;
  throw ConfigError("internal: '" + std::string(key.key) + "' is not in the schema table");
}

std::string describe_node(const YAML::Node& node) {
  if (node.IsScalar()) {
    std::string quoted(1, '\'');
    quoted += printable_excerpt(node.Scalar());
    quoted += '\'';
    return quoted;
  }
  if (node.IsNull()) return "no value";
  YAML::Emitter out;
  out << YAML::Flow << node;
  return std::string(node.IsSequence() ? "the sequence " : "the mapping ") + printable_excerpt(out.c_str());
}

std::string expected_text(const ConfigKey& key) {
  switch (key.type) {
    case ValueType::boolean: return "true or false";
    case ValueType::integer: return "an integer in " + key.range.to_string();
    case ValueType::real: return "a real number in " + key.range.to_string();
    case ValueType::text: return "a non-empty string";
    case ValueType::choice: return "one of " + key.valid_values();
    case ValueType::integer_list:
      return "a non-empty list of integers in " + key.range.to_string() + ", e.g. [64, 64]";
    case ValueType::constraint_list: return "a list of {terms, limit}";
    case ValueType::mapping: return "a mapping of parameter: value, e.g. {bombs: 12}";
  }
  return "";
}

[[noreturn]] void throw_type_error(const ConfigKey& key, const YAML::Node& value,
                                   const std::string& origin, const std::string& detail = "") {
  std::string message = origin + ": key '" + std::string(key.key) + "' expects " +
                        expected_text(key) + ", got " + describe_node(value);
  if (!detail.empty()) message += " (" + detail + ")";
  throw ConfigError(message);
}

[[noreturn]] void throw_range_error(const ConfigKey& key, const std::string& value_text,
                                    const std::string& origin) {
  throw ConfigError(origin + ": key '" + std::string(key.key) + "' = " + printable_excerpt(value_text) +
                    " is out of range; valid: " + key.range.to_string());
}

// A plain (unquoted) scalar: quoted text such as '5' is a string, not a number.
bool is_plain_scalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() != "!"; }

// Reads a plain scalar into a bool, integer or real member through the shared
// parser (common/parameter_table.h); fails naming key, value and origin.
template <typename T>
T read_scalar(const ConfigKey& key, const YAML::Node& value, const std::string& origin) {
  if (!is_plain_scalar(value)) {
    throw_type_error(key, value, origin,
                     value.IsScalar() && !std::is_same_v<T, bool> ? "quoted text is a string" : "");
  }
  T parsed{};
  switch (parse_scalar(value.Scalar(), key.range, parsed)) {
    case ScalarProblem::none: break;
    case ScalarProblem::not_a_value: throw_type_error(key, value, origin);
    case ScalarProblem::out_of_range: throw_range_error(key, value.Scalar(), origin);
  }
  return parsed;
}

}  // namespace

std::string_view to_string(ConfigLayer layer) {
  switch (layer) {
    case ConfigLayer::run: return "run";
    case ConfigLayer::algorithm: return "algorithm";
    case ConfigLayer::environment: return "environment";
  }
  return "<invalid>";
}

std::string ConfigKey::valid_values() const {
  switch (type) {
    case ValueType::boolean: return "true | false";
    case ValueType::integer:
    case ValueType::real: return range.to_string();
    case ValueType::integer_list: return "list of " + range.to_string();
    case ValueType::constraint_list: return "list of {terms: [names] or all, limit: >= 0}";
    case ValueType::text: return "non-empty text";
    case ValueType::mapping: return "parameter: value pairs";
    case ValueType::choice: {
      std::string joined;
      for (std::string_view name : choices) {
        if (!joined.empty()) joined += " | ";
        joined += name;
      }
      return joined;
    }
  }
  return "";
}

std::string ConfigKey::used_by_text() const {
  if (used_by == kAllAlgorithms) return "all";
  std::string joined;
  for (std::size_t i = 0; i < kAlgorithmNames.size(); ++i) {
    if ((used_by & (1u << i)) == 0) continue;
    if (!joined.empty()) joined += ", ";
    joined += kAlgorithmNames[i];
  }
  return joined;
}

const std::vector<ConfigKey>& run_config_schema() {
  static const std::vector<ConfigKey> keys = [] {
    std::vector<ConfigKey> out;
    for (const SchemaRow& row : schema_rows()) out.push_back(row.info);
    return out;
  }();
  return keys;
}

std::string config_schema_markdown() {
  auto escape_bars = [](const std::string& text) {  // '|' would split a Markdown cell
    std::string out;
    for (char c : text) {
      if (c == '|') out += '\\';
      out += c;
    }
    return out;
  };
  std::ostringstream table;
  table << "| key | type | default from | valid values | algorithms | description |\n"
        << "|---|---|---|---|---|---|\n";
  for (const ConfigKey& entry : run_config_schema()) {
    table << "| `" << entry.key << "` | " << to_string(entry.type) << " | "
          << to_string(entry.default_source) << " | " << escape_bars(entry.valid_values())
          << " | " << entry.used_by_text() << " | " << entry.description << " |\n";
  }
  return table.str();
}

const ConfigKey* find_config_key(std::string_view key) {
  const SchemaRow* row = find_row(schema_rows(), key);
  return row != nullptr ? &row->info : nullptr;
}

std::string config_key_list() {
  std::string joined;
  for (const ConfigKey& entry : run_config_schema()) {
    if (!joined.empty()) joined += ", ";
    joined += entry.key;
  }
  return joined;
}

std::string closest_config_key(std::string_view unknown) { return closest_row_key(schema_rows(), unknown); }

void set_config_value(RunConfig& config, const ConfigKey& key, const YAML::Node& value,
                      const std::string& origin) {
  const SchemaRow& row = row_of(key);
  std::visit(
      [&](auto&& access) {
        using Access = std::decay_t<decltype(access)>;
        if constexpr (std::is_same_v<Access, bool RunConfig::*> || std::is_same_v<Access, int RunConfig::*> ||
                      std::is_same_v<Access, std::int64_t RunConfig::*> ||
                      std::is_same_v<Access, double RunConfig::*>) {
          using T = std::remove_cvref_t<decltype(config.*access)>;
          config.*access = read_scalar<T>(key, value, origin);
        } else if constexpr (std::is_same_v<Access, std::string RunConfig::*>) {
          if (!value.IsScalar() || value.Scalar().empty()) throw_type_error(key, value, origin);
          config.*access = value.Scalar();
        } else if constexpr (std::is_same_v<Access, TextPairs RunConfig::*>) {
          // Merged into the pairs so far: a later layer changes single keys
          // (the environment checks keys and values when it is built).
          if (value.IsNull()) return;
          if (!value.IsMap()) throw_type_error(key, value, origin);
          for (const auto& pair : value) {
            if (!pair.first.IsScalar() || !pair.second.IsScalar()) throw_type_error(key, value, origin);
            TextPairs& pairs = config.*access;
            const std::string name = pair.first.Scalar();
            const auto same = std::find_if(pairs.begin(), pairs.end(),
                                           [&](const auto& p) { return p.first == name; });
            if (same != pairs.end()) {
              same->second = pair.second.Scalar();
            } else {
              pairs.emplace_back(name, pair.second.Scalar());
            }
          }
        } else if constexpr (std::is_same_v<Access, std::vector<int> RunConfig::*>) {
          if (!value.IsSequence() || value.size() == 0) throw_type_error(key, value, origin);
          std::vector<int> list;
          for (const YAML::Node& element : value) {
            int parsed = 0;
            const ScalarProblem problem = is_plain_scalar(element) ? parse_scalar(element.Scalar(), key.range, parsed)
                                                                   : ScalarProblem::not_a_value;
            if (problem == ScalarProblem::not_a_value) throw_type_error(key, value, origin);
            if (problem == ScalarProblem::out_of_range) {
              throw_range_error(key, describe_node(value) + " (element " + printable_excerpt(element.Scalar()) + ")",
                                origin);
            }
            list.push_back(parsed);
          }
          config.*access = std::move(list);
        } else if constexpr (std::is_same_v<Access, std::vector<ConstraintConfig> RunConfig::*>) {
          config.*access = parse_constraint_list(value, origin, kMaxConstraintCount);
        } else {  // EnumAccess
          if (!value.IsScalar()) throw_type_error(key, value, origin);
          const auto found = std::find(key.choices.begin(), key.choices.end(), value.Scalar());
          if (found == key.choices.end()) {
            throw ConfigError(origin + ": key '" + std::string(key.key) + "' = '" +
                              printable_excerpt(value.Scalar()) + "' is not valid; valid values: " +
                              key.valid_values());
          }
          access.set(config, static_cast<int>(found - key.choices.begin()));
        }
      },
      row.field);
}

std::string config_value_to_yaml(const RunConfig& config, const ConfigKey& key) {
  const SchemaRow& row = row_of(key);
  return std::visit(
      [&](auto&& access) -> std::string {
        using Access = std::decay_t<decltype(access)>;
        if constexpr (std::is_same_v<Access, bool RunConfig::*> || std::is_same_v<Access, int RunConfig::*> ||
                      std::is_same_v<Access, std::int64_t RunConfig::*> ||
                      std::is_same_v<Access, double RunConfig::*>) {
          return scalar_text(config.*access);
        } else if constexpr (std::is_same_v<Access, std::string RunConfig::*>) {
          YAML::Emitter out;  // quotes the text where YAML would misread it
          out << config.*access;
          return out.c_str();
        } else if constexpr (std::is_same_v<Access, std::vector<int> RunConfig::*>) {
          std::ostringstream out;
          out << "[";
          for (std::size_t i = 0; i < (config.*access).size(); ++i) {
            out << (i ? ", " : "") << (config.*access)[i];
          }
          out << "]";
          return out.str();
        } else if constexpr (std::is_same_v<Access, std::vector<ConstraintConfig> RunConfig::*>) {
          return constraint_list_to_yaml(config.*access);
        } else if constexpr (std::is_same_v<Access, TextPairs RunConfig::*>) {
          YAML::Emitter out;  // quotes the text where YAML would misread it
          out << YAML::Flow << YAML::BeginMap;
          for (const auto& [name, text] : config.*access) out << YAML::Key << name << YAML::Value << text;
          out << YAML::EndMap;
          return out.c_str();
        } else {  // EnumAccess
          const int index = access.get(config);
          return std::string(key.choices[static_cast<std::size_t>(index)]);
        }
      },
      row.field);
}

}  // namespace bsg
