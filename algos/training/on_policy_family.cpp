#include "algos/training/on_policy_family.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "algos/core/actor_critic_acting.h"
#include "algos/core/advantage_normalization.h"
#include "algos/core/constraint_costs.h"
#include "algos/core/epoch_statistics.h"
#include "algos/training/budget_decorator.h"
#include "algos/training/exploration_noise.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/progress_csv_fields.h"
#include "algos/training/training_checkpoint.h"
#include "common/run_config_checks.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

std::uint64_t stream_seed(const RunConfig& config, SeedStream stream, int rank, int index) {
  return derive_seed(static_cast<std::uint64_t>(config.seed), stream, static_cast<std::uint64_t>(rank),
                     static_cast<std::uint64_t>(index));
}

std::unique_ptr<envs::Env> checked_env(std::unique_ptr<envs::Env> env) {
  if (env == nullptr) throw std::invalid_argument("OnPolicyTrainer: no environment");
  if (env->spec().observation_dim <= 0 || env->spec().action_dim <= 0) {
    throw std::runtime_error("environment " + env->spec().id + " reports an empty observation or action space");
  }
  return env;
}

std::unique_ptr<ActorCritic> make_actor_critic(const RunConfig& config, const envs::EnvSpec& spec) {
  Rng init_rng(stream_seed(config, SeedStream::network_init, 0, 0));
  return std::make_unique<ActorCritic>(spec.observation_dim, spec.action_dim, config, init_rng);
}

BufferOptions buffer_options(const RunConfig& config) {
  return BufferOptions{config.gamma, config.lam, config.lam_c, constraint_count(config),
                       config.consistent_return_statistic};
}

// The constraints' step costs, bound to the environment's cost terms when
// some constraint names terms (checked before the run directory is touched).
StepCostSelector bound_cost_selector(const RunConfig& config, envs::Env& env) {
  StepCostSelector selector(config);
  if (selector.needs_terms()) selector.bind(env.spec().cost_term_names, env.spec().id);
  return selector;
}

int local_steps(const RunConfig& config, const MpiContext& mpi) {
  check_run_config_for_ranks(config, mpi.size());
  return config.steps_per_epoch / mpi.size();
}

}  // namespace

OnPolicyFamily::OnPolicyFamily(const RunConfig& config, const MpiContext& mpi, std::unique_ptr<envs::Env> env)
    : config_(config),
      mpi_(mpi),
      env_(checked_env(decorate_for_budget(config, std::move(env)))),
      actor_critic_(make_actor_critic(config, env_->spec())),
      algorithm_(make_algorithm(config)),
      local_steps_(local_steps(config, mpi)),
      buffer_(local_steps_, env_->spec().observation_dim, env_->spec().action_dim, buffer_options(config)),
      collector_(env_->spec().observation_dim, env_->spec().action_dim,
                 RolloutOptions{local_steps_, config.max_ep_len, config.use_reward_scaling, config.timeout_bootstrap},
                 bound_cost_selector(config, *env_)),
      normalized_observations_(local_steps_, env_->spec().observation_dim),
      returns_column_(local_steps_, 1) {}

OnPolicyFamily::~OnPolicyFamily() = default;

void OnPolicyFamily::start_new_run() { actor_critic_->broadcast_from_root(mpi_); }

TrainingProgress OnPolicyFamily::load_checkpoint(const std::filesystem::path& path) {
  return load_training_checkpoint(path, config_, *actor_critic_, *algorithm_);
}

void OnPolicyFamily::save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) {
  if (mpi_.is_root()) save_training_checkpoint(path, config_, progress, *actor_critic_, *algorithm_);
}

std::vector<std::string> OnPolicyFamily::progress_columns() const {
  return epoch_log_columns(epoch_log_layout(config_, *algorithm_));
}

void OnPolicyFamily::check_rollout_finite(int epoch) const {
  if (!buffer_.observations().allFinite()) check_finite(epoch, "observation from the environment", std::nan(""));
  if (!buffer_.rewards().allFinite()) check_finite(epoch, "reward from the environment", std::nan(""));
  if (!buffer_.constraint_costs().allFinite()) check_finite(epoch, "cost from the environment", std::nan(""));
}

void OnPolicyFamily::check_parameters_finite(int epoch) const {
  const char* quantity = actor_critic_->first_non_finite();
  if (*quantity != '\0') check_finite(epoch, quantity, std::nan(""));
  for (const NamedScalar& entry : algorithm_->state()) check_finite(epoch, entry.name.c_str(), entry.value);
}

void OnPolicyFamily::check_ranks_agree(int epoch) const {
  const double sum = actor_critic_->parameter_sum();
  const double low = mpi_.min(sum);
  const double high = mpi_.max(sum);
  if (low != high) {
    throw std::runtime_error("the MPI ranks' parameters disagree after epoch " + std::to_string(epoch) +
                             " (parameter sums from " + format_csv_number(low) + " to " + format_csv_number(high) + ")");
  }
}

// One epoch (docs/algorithms.md#the-epoch-loop) as its steps, in this order on every rank; the
// skeleton logs it (step 6) and saves the checkpoint.
FamilyEpoch OnPolicyFamily::run_epoch(int epoch, bool /*checkpoint_follows: the rollout ends every epoch*/) {
  const auto epoch_start = Clock::now();
  EpochTimings timings;
  set_exploration_noise(epoch);  // 1
  collect_rollout(epoch);        // 2
  timings.collect_seconds = seconds_since(epoch_start);
  const auto update_start = Clock::now();
  const double update_cpu_start = process_cpu_seconds();

  last_step_ = update_policy(epoch, timings);  // 3
  last_fits_ = fit_values(epoch, timings);     // 4
  update_normalizers(epoch);                   // 5
  timings.update_seconds = seconds_since(update_start);
  timings.update_cpu_seconds = process_cpu_seconds() - update_cpu_start;
  return epoch_result(timings);
}

// 1. Exploration noise of this epoch (docs/algorithms.md#exploration-noise); a learned
// log sigma is the update's to change (docs/algorithms.md#learned-log-sigma).
void OnPolicyFamily::set_exploration_noise(int epoch) {
  ActorCritic& ac = *actor_critic_;
  if (!ac.policy.has_learned_std()) {
    ac.policy.set_std(exploration_std(config_, epoch));
  }
  noise_rng_.seed(stream_seed(config_, SeedStream::action_noise, mpi_.rank(), epoch));
  shuffle_rng_.seed(stream_seed(config_, SeedStream::minibatch_shuffle, mpi_.rank(), epoch));
}

// 2. Rollout: this rank's local_steps_ steps, GAE at every path's end.
void OnPolicyFamily::collect_rollout(int epoch) {
  apply_budget_schedule(*algorithm_, *env_);  // Simmer's budgets of this epoch
  collector_.collect(*env_, stream_seed(config_, SeedStream::environment, mpi_.rank(), epoch), *actor_critic_,
                     noise_rng_, buffer_);
  check_rollout_finite(epoch);
}

// 3. Policy update with the pooled J_C (J_Ci) and L.
OnPolicyFamily::EpochPolicyStep OnPolicyFamily::update_policy(int epoch, EpochTimings& timings) {
  ActorCritic& ac = *actor_critic_;
  const bool several = !config_.constraints.empty();
  EpochPolicyStep step;
  step.episodes = pool_episode_statistics(buffer_, mpi_, several, budget_method(config_.alg) != BudgetMethod::none);
  for (int i = 0; i < buffer_.constraint_count(); ++i) {
    const double mean_cost = several ? step.episodes.constraint_costs[static_cast<std::size_t>(i)].mean
                                     : step.episodes.episode_cost.mean;
    step.constraints.push_back({mean_cost, constraint_limit(config_, i)});
  }
  ac.normalize_observations(buffer_.observations(), normalized_observations_);
  advantages_ = buffer_.advantages();
  cost_advantages_ = buffer_.constraint_cost_advantages();
  if (config_.use_standardized_advantages) {
    standardize_advantages(advantages_, cost_advantages_, mpi_);
  } else if (config_.center_advantages) {
    center_advantages(advantages_, cost_advantages_, mpi_);
  }
  const auto policy_start = Clock::now();
  PolicySurrogate surrogate(normalized_observations_, buffer_.actions(), buffer_.log_probs(), advantages_,
                            cost_advantages_);
  step.update = algorithm_->update(PolicyUpdateInputs{ac.policy, surrogate,
                                                      step.constraints.front().mean_episode_cost,
                                                      step.episodes.episode_length.mean, mpi_, step.constraints,
                                                      &shuffle_rng_});
  if (const auto loss = step.update.common(CommonDiagnostic::loss)) check_finite(epoch, "policy loss", *loss);
  check_parameters_finite(epoch);
  timings.policy_update_seconds = seconds_since(policy_start);
  return step;
}

// 4. Value fits (docs/algorithms.md#value-fits): V, and V_C if the algorithm uses it, on shared minibatches.
std::vector<ValueFitStats> OnPolicyFamily::fit_values(int epoch, EpochTimings& timings) {
  ActorCritic& ac = *actor_critic_;
  const auto value_fit_start = Clock::now();
  const ValueFitOptions fit_options{config_.train_v_iterations, config_.num_mini_batches, 16};
  std::vector<ValueFitJob> fit_jobs{{ac.value, buffer_.value_targets()}};
  if (algorithm_->uses_cost_value_function()) {
    for (int i = 0; i < buffer_.constraint_count(); ++i) {
      fit_jobs.push_back({ac.cost_value_net(i), buffer_.constraint_cost_value_targets().col(i)});
    }
  }
  const Eigen::MatrixXd* value_fit_inputs = &normalized_observations_;
  if (ac.value_time_limit > 0) {  // the time left as one more column (docs/algorithms.md#value-time-input)
    value_inputs_.resize(normalized_observations_.rows(), ac.value_input_size());
    ac.value_inputs(normalized_observations_, buffer_.episode_steps(), value_inputs_);
    value_fit_inputs = &value_inputs_;
  }
  std::vector<ValueFitStats> fits = fit_value_functions(fit_jobs, *value_fit_inputs, shuffle_rng_, mpi_, fit_options);
  check_finite(epoch, "value loss", fits.front().loss_before);
  check_finite(epoch, "value minibatch loss", fits.front().mean_minibatch_loss);
  if (algorithm_->uses_cost_value_function()) {
    // Constraint 1's V_C (the others are checked by check_parameters_finite).
    check_finite(epoch, "cost value loss", fits[1].loss_before);
    check_finite(epoch, "cost value minibatch loss", fits[1].mean_minibatch_loss);
  }
  timings.value_fit_seconds = seconds_since(value_fit_start);
  return fits;
}

// 5. Normalisers last (docs/algorithms.md#each-epoch, step 5), then the checks of the epoch's end.
void OnPolicyFamily::update_normalizers(int epoch) {
  ActorCritic& ac = *actor_critic_;
  if (ac.standardize_observations) ac.observation_normalizer.update(buffer_.observations(), mpi_);
  if (config_.use_reward_scaling &&
      (config_.reward_scale_warmup_epochs == 0 || epoch < config_.reward_scale_warmup_epochs)) {
    const double old_scale = ac.return_normalizer.std()[0] + Buffer::kStdEpsilon;
    returns_column_.col(0) = buffer_.discounted_returns();
    ac.return_normalizer.update(returns_column_, mpi_);
    // Q19: V learns G / (s_ret + 1e-5); keep its raw-unit predictions across the change of s_ret.
    if (config_.rescale_value_output) {
      ac.value.scale_output(old_scale / (ac.return_normalizer.std()[0] + Buffer::kStdEpsilon));
    }
  }
  check_parameters_finite(epoch);
  if (epoch % config_.check_freq == 0) check_ranks_agree(epoch);
}

// The epoch's costs summed over ranks (in one reduction) and the progress line's figures.
FamilyEpoch OnPolicyFamily::epoch_result(const EpochTimings& timings) {
  FamilyEpoch result;
  Eigen::VectorXd epoch_costs(1 + buffer_.constraint_count());
  epoch_costs << buffer_.epoch_cost(), buffer_.epoch_constraint_costs();
  mpi_.sum_in_place(epoch_costs.data(), static_cast<std::size_t>(epoch_costs.size()));
  result.epoch_cost = epoch_costs[0];
  result.epoch_constraint_costs = epoch_costs.tail(buffer_.constraint_count());
  result.constraints = last_step_.constraints;
  result.timings = timings;
  last_timings_ = timings;
  result.line.mean_return = last_step_.episodes.episode_return.mean;
  // Constraint 1's (the environment's without `constraints:`).
  result.line.mean_cost = last_step_.constraints.front().mean_episode_cost;
  if (algorithm_->uses_cost_value_function()) result.line.cost_limit = last_step_.constraints.front().limit;
  result.line.lagrange_multiplier = last_step_.update.lagrange_multiplier;
  result.line.kl = last_step_.update.common(CommonDiagnostic::kl).value_or(std::nan(""));
  return result;
}

std::vector<NamedScalar> OnPolicyFamily::progress_row(const EpochAccounts& accounts) {
  const bool trains_cost_values = algorithm_->uses_cost_value_function();
  EpochLogInputs log_inputs;
  log_inputs.epoch = accounts.epoch;
  log_inputs.total_env_steps = static_cast<long long>(accounts.epoch + 1) * config_.steps_per_epoch;
  log_inputs.steps_per_epoch = config_.steps_per_epoch;
  log_inputs.exploration_std = actor_critic_->policy.std();
  log_inputs.episodes = &last_step_.episodes;
  log_inputs.buffer = &buffer_;
  log_inputs.update = &last_step_.update;
  log_inputs.value_fit = &last_fits_.front();
  log_inputs.cost_value_fit = trains_cost_values ? &last_fits_[1] : nullptr;
  log_inputs.return_normalizer = &actor_critic_->return_normalizer;
  log_inputs.collect_seconds = last_timings_.collect_seconds;
  log_inputs.update_seconds = last_timings_.update_seconds;
  log_inputs.elapsed_seconds = accounts.elapsed_seconds;
  if (!config_.constraints.empty()) {
    log_inputs.constraints = last_step_.constraints;
    if (trains_cost_values) log_inputs.constraint_cost_value_fits = std::span(last_fits_).subspan(1);
  }
  log_inputs.training_cost = accounts.training_cost;
  return make_epoch_log_row(log_inputs, mpi_);
}

// Evaluation (docs/reproducing.md#evaluation) with the final statistics: the mean action, or
// sampled at the last epoch's sigma (set again here: a run resumed with no epoch left has
// not set it). The term names label evaluation.json's per-term costs.
EvaluationSummary OnPolicyFamily::evaluate(int epochs_completed) {
  if (config_.sampled_evaluation) set_last_epoch_std(config_, epochs_completed, actor_critic_->policy);
  restore_whole_budgets(*env_);  // a Simmer policy is judged at its limits, as by bsg eval
  ActorCriticActing acting(*actor_critic_);
  const ActionMode mode = evaluation_actions(config_);
  EvaluationSummary summary = evaluate_policy(*env_, acting, config_.eval_episodes, config_.seed, config_.max_ep_len,
                                              mpi_, collector_.cost_selector(), env_->spec().cost_term_names, mode);
  summary.action_std = mode == ActionMode::sampled ? actor_critic_->policy.std() : 0.0;
  return summary;
}

}  // namespace bsg::algos
