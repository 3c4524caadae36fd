#include "algos/training/trainer.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>
#include <limits>
#include <new>
#include <ostream>

#include "algos/core/advantage_normalization.h"
#include "algos/core/constraint_costs.h"
#include "algos/training/epoch_log.h"
#include "algos/core/epoch_statistics.h"
#include "algos/training/evaluation_files.h"
#include "algos/training/exploration_noise.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/progress_line.h"
#include "algos/training/run_environment.h"
#include "common/atomic_file.h"
#include "common/build_identity.h"
#include "common/file_reading.h"
#include "common/run_config_checks.h"
#include "common/run_config_yaml.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

NonFiniteError non_finite_error(int epoch, const char* quantity, double value,
                                const std::filesystem::path& checkpoint, int checkpoint_epochs) {
  return NonFiniteError(std::string("non-finite ") + quantity + " (" + std::to_string(value) + ") in epoch " +
                        std::to_string(epoch) + "; training stopped, the last good checkpoint " +
                        checkpoint.string() + " (after " + std::to_string(checkpoint_epochs) + " epochs) is kept");
}

void run_epoch_naming_errors(int epoch, std::string_view phases, const std::function<void()>& run_epoch) {
  try {
    run_epoch();
  } catch (const NonFiniteError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("epoch " + std::to_string(epoch) + ": out of memory (std::bad_alloc)" +
                             (phases.empty() ? std::string() : " during " + std::string(phases)));
  } catch (const std::exception& e) {
    throw std::runtime_error("epoch " + std::to_string(epoch) + ": " + e.what());
  }
}

OnPolicyTrainer::OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                 TrainerOptions options)
    : OnPolicyTrainer(config, std::move(directory), mpi, options,
                      make_run_env(config)) {}

OnPolicyTrainer::OnPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                 TrainerOptions options, std::unique_ptr<envs::Env> env)
    : config_(config),
      directory_(std::move(directory)),
      mpi_(mpi),
      options_(options),
      env_(checked_env(std::move(env))),
      actor_critic_(make_actor_critic(config, env_->spec())),
      algorithm_(make_algorithm(config)),
      local_steps_(local_steps(config, mpi)),
      buffer_(local_steps_, env_->spec().observation_dim, env_->spec().action_dim,
              buffer_options(config)),
      collector_(env_->spec().observation_dim, env_->spec().action_dim,
                 RolloutOptions{local_steps_, config.max_ep_len, config.use_reward_scaling,
                                config.timeout_bootstrap},
                 bound_cost_selector(config, *env_)),
      normalized_observations_(local_steps_, env_->spec().observation_dim),
      returns_column_(local_steps_, 1) {
  progress_.num_ranks = mpi_.size();
  progress_.training_cost = TrainingCost::for_constraints(constraint_count(config_));
  if (options_.resume) {
    const TrainingProgress saved =
        load_training_checkpoint(directory_.checkpoint(), config_, *actor_critic_, *algorithm_);
    if (saved.num_ranks != mpi_.size() && mpi_.is_root() && options_.log != nullptr) {
      *options_.log << "note: the checkpoint was written by a run with " << saved.num_ranks
                    << " ranks, this one has " << mpi_.size()
                    << "; training continues but will not reproduce the original rank count's numbers\n";
    }
    if (mpi_.is_root()) note_another_build();
    progress_.epochs_completed = saved.epochs_completed;
    progress_.elapsed_seconds = saved.elapsed_seconds;
    if (!saved.training_cost.constraint_cumulative_costs.empty()) progress_.training_cost = saved.training_cost;
    checkpoint_epochs_ = saved.epochs_completed;
    if (mpi_.is_root()) {
      // A write killed half-way (SIGKILL, a lost node) leaves its temporary behind; the target is intact.
      const std::vector<std::filesystem::path> stale = remove_stale_temporaries(directory_.root);
      if (!stale.empty() && options_.log != nullptr) {
        *options_.log << "removed " << stale.size() << " stale temporary file" << (stale.size() == 1 ? "" : "s")
                      << " left by interrupted writes in " << directory_.root.string() << " (first: "
                      << stale.front().filename().string() << ")\n";
      }
      progress_csv_.emplace(ProgressCsv::resume(
          directory_.progress(), ProgressResume{saved.epochs_completed, saved.progress_log, config_.steps_per_epoch,
                                                options_.log != nullptr ? options_.log : &std::cerr}));
    }
  } else {
    actor_critic_->broadcast_from_root(mpi_);  // docs/algorithms.md#set-up, step 5
    if (mpi_.is_root()) {
      prepare_new_run_directory(directory_);
      write_run_config(config_, directory_.config());
      write_file_atomically(directory_.build(), to_text(this_build()));
      progress_csv_.emplace(ProgressCsv::create(directory_.progress()));
      save_checkpoint();  // docs/algorithms.md#set-up, step 7: the initial model
    }
  }
}

OnPolicyTrainer::~OnPolicyTrainer() = default;

void OnPolicyTrainer::note_another_build() const {
  // Runs started before builds were recorded have no build.txt: nothing to compare.
  if (!std::filesystem::exists(directory_.build())) return;
  const std::optional<BuildIdentity> recorded = parse_build_identity(read_regular_file(directory_.build(), "build record"));
  std::ostream& out = options_.log != nullptr ? *options_.log : std::cerr;
  if (!recorded) {
    out << "note: " << directory_.build().string() << " is not a build record this version reads; "
        << "cannot tell whether this build computes the same numbers as the one that started the run\n";
    return;
  }
  const std::string difference = describe_difference(*recorded, this_build());
  if (!difference.empty()) {
    out << "note: the run was started by another build (" << difference
        << "); training continues but the remaining epochs will not be bit-identical to an uninterrupted run "
           "(docs/reproducibility.md)\n";
  }
}

TrainingSafety OnPolicyTrainer::training_safety() const {
  return TrainingSafety{effective_constraints(config_), progress_.training_cost,
                        static_cast<long long>(progress_.epochs_completed) * config_.steps_per_epoch};
}

void OnPolicyTrainer::save_checkpoint() {
  if (mpi_.is_root()) {
    progress_.progress_log = progress_csv_->contents();  // docs/reproducing.md#run-directory: rows restorable
    save_training_checkpoint(directory_.checkpoint(), config_, progress_, *actor_critic_, *algorithm_);
  }
  checkpoint_epochs_ = progress_.epochs_completed;
}

void OnPolicyTrainer::check_finite(int epoch, const char* quantity, double value) const {
  if (!std::isfinite(value)) {
    throw non_finite_error(epoch, quantity, value, directory_.checkpoint(), checkpoint_epochs_);
  }
}

void OnPolicyTrainer::check_rollout_finite(int epoch) const {
  if (!buffer_.observations().allFinite()) check_finite(epoch, "observation from the environment", std::nan(""));
  if (!buffer_.rewards().allFinite()) check_finite(epoch, "reward from the environment", std::nan(""));
  if (!buffer_.constraint_costs().allFinite()) check_finite(epoch, "cost from the environment", std::nan(""));
}

void OnPolicyTrainer::check_parameters_finite(int epoch) const {
  const char* quantity = actor_critic_->first_non_finite();
  if (*quantity != '\0') check_finite(epoch, quantity, std::nan(""));
  for (const NamedScalar& entry : algorithm_->state()) check_finite(epoch, entry.name.c_str(), entry.value);
}

void OnPolicyTrainer::check_ranks_agree(int epoch) const {
  const double sum = actor_critic_->parameter_sum();
  const double low = mpi_.min(sum);
  const double high = mpi_.max(sum);
  if (low != high) {
    throw std::runtime_error("the MPI ranks' parameters disagree after epoch " + std::to_string(epoch) +
                             " (parameter sums from " + format_csv_number(low) + " to " + format_csv_number(high) + ")");
  }
}

// One epoch (docs/algorithms.md#the-epoch-loop) as its six steps, in this order on every rank.
void OnPolicyTrainer::run_epoch(int epoch) {
  EpochClock clock;
  clock.epoch_start = Clock::now();
  clock.epoch_cpu_start = process_cpu_seconds();

  set_exploration_noise(epoch);  // 1
  collect_rollout(epoch);        // 2
  clock.collect_seconds = seconds_since(clock.epoch_start);
  const auto update_start = Clock::now();
  const double update_cpu_start = process_cpu_seconds();

  const EpochPolicyStep policy_step = update_policy(epoch, clock);  // 3
  const std::vector<ValueFitStats> fits = fit_values(epoch, clock);  // 4
  update_normalizers(epoch);                                         // 5
  clock.update_seconds = seconds_since(update_start);
  clock.update_cpu_seconds = process_cpu_seconds() - update_cpu_start;

  record_epoch(epoch, policy_step, fits, clock);  // 6
  const bool last = epoch == config_.epochs - 1;
  const bool stopping = options_.stop_after_epochs > 0 && progress_.epochs_completed >= options_.stop_after_epochs;
  if (epoch % config_.save_freq == 0 || last || stopping) save_checkpoint();
}

// 1. Exploration noise of this epoch (docs/algorithms.md#exploration-noise); a learned
// log sigma is the update's to change (docs/algorithms.md#learned-log-sigma).
void OnPolicyTrainer::set_exploration_noise(int epoch) {
  ActorCritic& ac = *actor_critic_;
  if (!ac.policy.has_learned_std()) {
    ac.policy.set_std(exploration_std(config_, epoch));
  }
  noise_rng_.seed(stream_seed(config_, SeedStream::action_noise, mpi_.rank(), epoch));
  shuffle_rng_.seed(stream_seed(config_, SeedStream::minibatch_shuffle, mpi_.rank(), epoch));
}

// 2. Rollout: this rank's local_steps_ steps, GAE at every path's end.
void OnPolicyTrainer::collect_rollout(int epoch) {
  collector_.collect(*env_, stream_seed(config_, SeedStream::environment, mpi_.rank(), epoch), *actor_critic_,
                     noise_rng_, buffer_);
  check_rollout_finite(epoch);
}

// 3. Policy update with the pooled J_C (J_Ci) and L.
OnPolicyTrainer::EpochPolicyStep OnPolicyTrainer::update_policy(int epoch, EpochClock& clock) {
  ActorCritic& ac = *actor_critic_;
  const bool several = !config_.constraints.empty();
  EpochPolicyStep step;
  step.episodes = pool_episode_statistics(buffer_, mpi_, several);
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
  clock.policy_update_seconds = seconds_since(policy_start);
  return step;
}

// 4. Value fits (docs/algorithms.md#value-fits): V, and V_C if the algorithm uses it, on shared minibatches.
std::vector<ValueFitStats> OnPolicyTrainer::fit_values(int epoch, EpochClock& clock) {
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
  clock.value_fit_seconds = seconds_since(value_fit_start);
  return fits;
}

// 5. Normalisers last (docs/algorithms.md#each-epoch, step 5), then the checks of the epoch's end.
void OnPolicyTrainer::update_normalizers(int epoch) {
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

// 6. The epoch's accounts: the timings hook, the training cost, the progress.csv row and line.
void OnPolicyTrainer::record_epoch(int epoch, const EpochPolicyStep& policy_step,
                                   const std::vector<ValueFitStats>& fits, const EpochClock& clock) {
  const double epoch_seconds = seconds_since(clock.epoch_start);
  if (options_.on_epoch_timed) {
    options_.on_epoch_timed(EpochTimings{epoch, clock.collect_seconds, clock.policy_update_seconds,
                                         clock.value_fit_seconds, clock.update_seconds, epoch_seconds,
                                         clock.update_cpu_seconds, process_cpu_seconds() - clock.epoch_cpu_start});
  }
  progress_.epochs_completed = epoch + 1;
  progress_.elapsed_seconds += epoch_seconds;
  // Safety during training: this epoch's cost summed over ranks, in one reduction.
  Eigen::VectorXd epoch_costs(1 + buffer_.constraint_count());
  epoch_costs << buffer_.epoch_cost(), buffer_.epoch_constraint_costs();
  mpi_.sum_in_place(epoch_costs.data(), static_cast<std::size_t>(epoch_costs.size()));
  progress_.training_cost.add_epoch(epoch_costs[0], epoch_costs.tail(buffer_.constraint_count()),
                                    policy_step.constraints);
  seconds_this_process_ += epoch_seconds;
  ++epochs_this_process_;

  const bool trains_cost_values = algorithm_->uses_cost_value_function();
  EpochLogInputs log_inputs;
  log_inputs.epoch = epoch;
  log_inputs.total_env_steps = static_cast<long long>(epoch + 1) * config_.steps_per_epoch;
  log_inputs.steps_per_epoch = config_.steps_per_epoch;
  log_inputs.exploration_std = actor_critic_->policy.std();
  log_inputs.episodes = &policy_step.episodes;
  log_inputs.buffer = &buffer_;
  log_inputs.update = &policy_step.update;
  log_inputs.value_fit = &fits.front();
  log_inputs.cost_value_fit = trains_cost_values ? &fits[1] : nullptr;
  log_inputs.return_normalizer = &actor_critic_->return_normalizer;
  log_inputs.collect_seconds = clock.collect_seconds;
  log_inputs.update_seconds = clock.update_seconds;
  log_inputs.elapsed_seconds = progress_.elapsed_seconds;
  if (!config_.constraints.empty()) {
    log_inputs.constraints = policy_step.constraints;
    if (trains_cost_values) log_inputs.constraint_cost_value_fits = std::span(fits).subspan(1);
  }
  log_inputs.training_cost = &progress_.training_cost;
  const std::vector<NamedScalar> row = make_epoch_log_row(log_inputs, mpi_);

  if (!mpi_.is_root()) return;
  progress_csv_->write_row(row);
  if (options_.log == nullptr) return;
  ProgressLineInputs line;
  line.epoch = epoch;
  line.epochs = config_.epochs;
  line.mean_return = policy_step.episodes.episode_return.mean;
  // Constraint 1's (the environment's without `constraints:`).
  line.mean_cost = policy_step.constraints.front().mean_episode_cost;
  if (trains_cost_values) line.cost_limit = policy_step.constraints.front().limit;
  line.lagrange_multiplier = policy_step.update.lagrange_multiplier;
  line.kl = policy_step.update.common(CommonDiagnostic::kl).value_or(std::nan(""));
  line.epoch_seconds = epoch_seconds;
  line.eta_seconds = seconds_this_process_ / epochs_this_process_ * (config_.epochs - epoch - 1);
  *options_.log << format_progress_line(line) << std::endl;
}

TrainingOutcome OnPolicyTrainer::run() {
  TrainingOutcome outcome;
  for (int epoch = progress_.epochs_completed; epoch < config_.epochs; ++epoch) {
    if (options_.stop_after_epochs > 0 && progress_.epochs_completed >= options_.stop_after_epochs) break;
    run_epoch_naming_errors(epoch, "the epoch's rollout, update or value fits", [&] { run_epoch(epoch); });
    if (options_.stop_requested && progress_.epochs_completed < config_.epochs && options_.stop_requested()) {
      if (checkpoint_epochs_ != progress_.epochs_completed) save_checkpoint();
      outcome.stop_requested = true;
      break;
    }
  }
  outcome.epochs_completed = progress_.epochs_completed;
  outcome.finished = progress_.epochs_completed == config_.epochs;
  if (!outcome.finished) return outcome;
  if (config_.eval_episodes / mpi_.size() == 0) {
    // No evaluation episodes: the run is still finished, and evaluation.json
    // says so (0 episodes, null J and H), because sweeps, `bsg sweep --status`
    // and resume take that file as the mark of a finished run.
    if (mpi_.is_root()) {
      constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
      const TrainingSafety safety = training_safety();
      write_evaluation_files(directory_,
                             EvaluationSummary{{}, kNone, kNone, kNone, std::vector<double>(safety.constraints.size(), kNone)},
                             &safety);
      if (options_.log != nullptr) {
        *options_.log << "evaluation skipped (eval_episodes = " << config_.eval_episodes << " for " << mpi_.size()
                      << (mpi_.size() == 1 ? " rank" : " ranks") << "): evaluation.json records 0 episodes"
                      << std::endl;
      }
    }
    return outcome;
  }

  // Evaluation (docs/reproducing.md#evaluation) with the final statistics: the mean action, or
  // sampled at the last epoch's sigma (set again here: a run resumed with no epoch left has
  // not set it). The term names label evaluation.json's per-term costs.
  if (config_.sampled_evaluation) set_last_epoch_std(config_, progress_.epochs_completed, actor_critic_->policy);
  EvaluationSummary summary = evaluate_policy(*env_, *actor_critic_, config_.eval_episodes, config_.seed,
                                              config_.max_ep_len, mpi_, collector_.cost_selector(),
                                              env_->spec().cost_term_names, evaluation_actions(config_));
  if (mpi_.is_root()) {
    const TrainingSafety safety = training_safety();
    write_evaluation_files(directory_, summary, &safety);
    if (options_.log != nullptr) {
      *options_.log << "evaluation: " << summary.episodes.size() << " episodes  J (mean return) "
                    << format_csv_number(summary.mean_return) << "  H (mean cost) "
                    << format_csv_number(summary.mean_cost) << "  mean length "
                    << format_csv_number(summary.mean_length) << std::endl;
    }
    outcome.evaluation = std::move(summary);
  }
  return outcome;
}

}  // namespace bsg::algos
