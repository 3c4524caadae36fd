#include "algos/training/off_policy_trainer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <new>
#include <ostream>

#include "algos/core/epoch_statistics.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/training/epoch_log.h"
#include "algos/training/evaluation_files.h"
#include "algos/training/off_policy_checkpoint.h"
#include "algos/training/off_policy_evaluation.h"
#include "algos/training/progress_csv_fields.h"
#include "algos/training/progress_line.h"
#include "algos/training/run_environment.h"
#include "common/atomic_file.h"
#include "common/build_identity.h"
#include "common/run_config_checks.h"
#include "common/run_config_yaml.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::uint64_t stream_seed(const RunConfig& config, SeedStream stream, int rank, std::uint64_t index) {
  return derive_seed(static_cast<std::uint64_t>(config.seed), stream, static_cast<std::uint64_t>(rank), index);
}

std::vector<std::unique_ptr<envs::Env>> make_run_envs(const RunConfig& config) {
  std::vector<std::unique_ptr<envs::Env>> envs;
  for (int j = 0; j < config.num_envs; ++j) envs.push_back(make_run_env(config));
  return envs;
}

const envs::EnvSpec& checked_spec(const std::vector<std::unique_ptr<envs::Env>>& envs, int num_envs) {
  if (static_cast<int>(envs.size()) != num_envs || envs.empty()) {
    throw std::invalid_argument("OffPolicyTrainer: " + std::to_string(envs.size()) + " environments for num_envs = " +
                                std::to_string(num_envs));
  }
  for (const auto& env : envs) {
    if (env == nullptr) throw std::invalid_argument("OffPolicyTrainer: no environment");
  }
  const envs::EnvSpec& spec = envs.front()->spec();
  if (spec.observation_dim <= 0 || spec.action_dim <= 0) {
    throw std::runtime_error("environment " + spec.id + " reports an empty observation or action space");
  }
  return spec;
}

StepCostSelector bound_cost_selector(const RunConfig& config, const envs::EnvSpec& spec) {
  StepCostSelector selector(config);
  if (selector.needs_terms()) selector.bind(spec.cost_term_names, spec.id);
  return selector;
}

std::span<const double> span_of(const Eigen::VectorXd& vector) {
  return {vector.data(), static_cast<std::size_t>(vector.size())};
}

}  // namespace

// What one epoch gathers on this rank.
struct OffPolicyTrainer::EpochAccounts {
  std::vector<double> returns, costs, lengths;
  std::vector<std::vector<double>> constraint_costs;  // per constraint, per completed episode
  double epoch_cost = 0.0;                            // the environment's cost over every step
  Eigen::VectorXd epoch_constraint_costs;
  long long updates = 0;
  long long actor_updates = 0;
  double reward_critic_loss = 0.0, reward_q = 0.0, actor_loss = 0.0, alpha = 0.0;
  Eigen::VectorXd cost_critic_losses, cost_qs;
  double collect_seconds = 0.0, update_seconds = 0.0;
  Clock::time_point start;
};

OffPolicyTrainer::OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                   TrainerOptions options)
    : OffPolicyTrainer(config, std::move(directory), mpi, options, make_run_envs(config)) {}

OffPolicyTrainer::OffPolicyTrainer(const RunConfig& config, RunDirectory directory, const MpiContext& mpi,
                                   TrainerOptions options, std::vector<std::unique_ptr<envs::Env>> envs)
    : config_(config),
      directory_(std::move(directory)),
      mpi_(mpi),
      options_(options),
      envs_(std::move(envs)),
      observation_size_(checked_spec(envs_, config.num_envs).observation_dim),
      action_size_(envs_.front()->spec().action_dim),
      constraint_count_(constraint_count(config)),
      critic_cost_count_(ignores_cost(config.alg) ? 0 : constraint_count_),
      local_steps_((check_run_config_for_ranks(config, mpi.size()), config.steps_per_epoch / mpi.size())),
      cost_selector_(bound_cost_selector(config, envs_.front()->spec())),
      buffer_(observation_size_, action_size_, critic_cost_count_, config.buffer_size),
      buffer_log_(replay_buffer_log_path(directory_.root, mpi.rank())) {
  if (!is_off_policy(config.alg)) {
    throw std::invalid_argument("OffPolicyTrainer: " + std::string(to_string(config.alg)) + " is not off-policy");
  }
  Rng init_rng(stream_seed(config_, SeedStream::network_init, 0, 0));  // the same nets on every rank
  learner_ = make_off_policy_learner(config_, observation_size_, action_size_, critic_cost_count_, init_rng);
  if (has_lagrange_multiplier(config_.alg)) multipliers_.emplace(config_);
  for (int j = 0; j < config_.num_envs; ++j) {
    accumulators_.emplace_back(config_.n_step, config_.gamma, observation_size_, action_size_, critic_cost_count_);
  }
  observations_.assign(static_cast<std::size_t>(config_.num_envs), Eigen::VectorXd(observation_size_));
  episode_returns_.assign(static_cast<std::size_t>(config_.num_envs), 0.0);
  episode_costs_.assign(static_cast<std::size_t>(config_.num_envs), 0.0);
  episode_lengths_.assign(static_cast<std::size_t>(config_.num_envs), 0);
  episode_constraint_costs_.assign(static_cast<std::size_t>(config_.num_envs), Eigen::VectorXd::Zero(constraint_count_));
  action_.resize(action_size_);
  step_costs_.resize(constraint_count_);
  progress_.num_ranks = mpi_.size();
  progress_.training_cost = TrainingCost::for_constraints(constraint_count_);
  if (options_.resume) {
    const OffPolicyCheckpoint saved = load_off_policy_checkpoint(directory_.checkpoint(), config_, *learner_);
    if (saved.progress.num_ranks != mpi_.size()) {
      throw CheckpointError(directory_.checkpoint().string() + ": written by a run with " +
                            std::to_string(saved.progress.num_ranks) + " ranks; an off-policy run resumes with the "
                            "same rank count (each rank's replay buffer is its own)");
    }
    progress_.epochs_completed = saved.progress.epochs_completed;
    progress_.elapsed_seconds = saved.progress.elapsed_seconds;
    progress_.training_cost = saved.progress.training_cost;
    schedule_.steps_since_update = saved.steps_since_update;
    schedule_.owed_updates = saved.owed_updates;
    if (multipliers_) multipliers_->restore_state(saved.multipliers);
    buffer_log_.restore(buffer_, saved.replay_transitions);
    checkpoint_epochs_ = saved.progress.epochs_completed;
    if (mpi_.is_root()) {
      remove_stale_temporaries(directory_.root);
      progress_csv_.emplace(ProgressCsv::resume(
          directory_.progress(), ProgressResume{saved.progress.epochs_completed, saved.progress.progress_log,
                                                config_.steps_per_epoch,
                                                options_.log != nullptr ? options_.log : &std::cerr}));
    }
  } else {
    if (mpi_.is_root()) {
      prepare_new_run_directory(directory_);
      write_run_config(config_, directory_.config());
      write_file_atomically(directory_.build(), to_text(this_build()));
      progress_csv_.emplace(ProgressCsv::create(directory_.progress()));
    }
    mpi_.sum(0.0);  // the directory exists before any rank writes its buffer into it
    save_checkpoint();  // the initial model
  }
  lambdas_.assign(static_cast<std::size_t>(critic_cost_count_), 0.0);
  if (multipliers_) {
    for (int i = 0; i < critic_cost_count_; ++i) lambdas_[static_cast<std::size_t>(i)] = multipliers_->value(i);
  }
}

OffPolicyTrainer::~OffPolicyTrainer() = default;

TrainingSafety OffPolicyTrainer::training_safety() const {
  return TrainingSafety{effective_constraints(config_), progress_.training_cost,
                        static_cast<long long>(progress_.epochs_completed) * config_.steps_per_epoch};
}

void OffPolicyTrainer::save_checkpoint() {
  // A checkpoint cuts the episodes (the next epoch resets the environments): steps still waiting
  // for their n-step sums go to the buffer as at a truncation (none after a cutting epoch).
  for (int j = 0; j < config_.num_envs; ++j) {
    const std::size_t jj = static_cast<std::size_t>(j);
    accumulators_[jj].flush(span_of(observations_[jj]), buffer_);
  }
  // Each rank's new transitions first, then rank 0's checkpoint.bin naming how many there are.
  buffer_log_.append(buffer_);
  mpi_.sum(0.0);
  if (mpi_.is_root()) {
    progress_.progress_log = progress_csv_->contents();
    OffPolicyCheckpoint state{progress_, buffer_.total_added(), schedule_.steps_since_update, schedule_.owed_updates,
                              multipliers_ ? multipliers_->state() : std::vector<NamedScalar>{}};
    write_checkpoint_file(directory_.checkpoint(), encode_off_policy_checkpoint(config_, state, *learner_));
  }
  mpi_.sum(0.0);
  checkpoint_epochs_ = progress_.epochs_completed;
}

void OffPolicyTrainer::check_finite(int epoch, const char* quantity, double value) const {
  if (!std::isfinite(value)) {
    throw non_finite_error(epoch, quantity, value, directory_.checkpoint(), checkpoint_epochs_);
  }
}

void OffPolicyTrainer::collect_step(int epoch, int env_index, bool random_action, bool cut,
                                    EpochAccounts& accounts) {
  const std::size_t j = static_cast<std::size_t>(env_index);
  envs::Env& env = *envs_[j];
  if (random_action) {
    for (Eigen::Index a = 0; a < action_size_; ++a) action_(a) = uniform(noise_rng_, -1.0, 1.0);
  } else {
    learner_->act(span_of(observations_[j]), false, noise_rng_, action_);
  }
  const envs::StepResult step = env.step(span_of(action_));
  for (double value : step.observation) check_finite(epoch, "observation from the environment", value);
  check_finite(epoch, "reward from the environment", step.reward);
  cost_selector_.select(step, step_costs_);
  episode_returns_[j] += step.reward;
  episode_costs_[j] += step.cost;
  episode_constraint_costs_[j] += step_costs_;
  ++episode_lengths_[j];
  accounts.epoch_cost += step.cost;
  accounts.epoch_constraint_costs += step_costs_;
  const bool time_out = step.truncated || episode_lengths_[j] >= config_.max_ep_len;
  const bool episode_over = step.terminated || time_out;
  // A termination ends the return; a time-out and the epoch's cut bootstrap from s'.
  const std::span<const double> critic_costs(step_costs_.data(), static_cast<std::size_t>(critic_cost_count_));
  accumulators_[j].add(span_of(observations_[j]), span_of(action_), step.reward, critic_costs, step.observation,
                       step.terminated, episode_over || cut, buffer_);
  if (episode_over) {
    accounts.returns.push_back(episode_returns_[j]);
    accounts.costs.push_back(episode_costs_[j]);
    accounts.lengths.push_back(episode_lengths_[j]);
    for (int i = 0; i < constraint_count_; ++i) {
      accounts.constraint_costs[static_cast<std::size_t>(i)].push_back(episode_constraint_costs_[j](i));
    }
    episode_returns_[j] = episode_costs_[j] = 0.0;
    episode_lengths_[j] = 0;
    episode_constraint_costs_[j].setZero();
    if (!cut) {
      const std::span<const double> first = env.reset();  // continues the environment's stream
      observations_[j] = Eigen::Map<const Eigen::VectorXd>(first.data(), observation_size_);
    }
  } else {
    observations_[j] = Eigen::Map<const Eigen::VectorXd>(step.observation.data(), observation_size_);
  }
}

void OffPolicyTrainer::train(int updates, EpochAccounts& accounts) {
  for (int u = 0; u < updates; ++u) {
    buffer_.sample(config_.batch_size, sample_rng_, slots_, batch_);
    learner_->update(batch_, lambdas_, sample_rng_, mpi_, step_stats_);
    const OffPolicyStepStats& stats = step_stats_;
    ++accounts.updates;
    accounts.reward_critic_loss += stats.reward_critic_loss;
    accounts.reward_q += stats.reward_q_mean;
    for (int i = 0; i < critic_cost_count_; ++i) {
      accounts.cost_critic_losses(i) += stats.cost_critic_losses[static_cast<std::size_t>(i)];
      accounts.cost_qs(i) += stats.cost_q_means[static_cast<std::size_t>(i)];
    }
    if (stats.actor_updated) {
      ++accounts.actor_updates;
      accounts.actor_loss += stats.actor_loss;
    }
    accounts.alpha = stats.alpha;
  }
}

void OffPolicyTrainer::run_epoch(int epoch) {
  EpochAccounts accounts;
  accounts.start = Clock::now();
  accounts.constraint_costs.assign(static_cast<std::size_t>(constraint_count_), {});
  accounts.epoch_constraint_costs = Eigen::VectorXd::Zero(constraint_count_);
  accounts.cost_critic_losses = Eigen::VectorXd::Zero(critic_cost_count_);
  accounts.cost_qs = Eigen::VectorXd::Zero(critic_cost_count_);
  accounts.alpha = learner_->actor_kind() == ActorKind::squashed_gaussian ? learner_->alpha() : 0.0;
  noise_rng_.seed(stream_seed(config_, SeedStream::action_noise, mpi_.rank(), static_cast<std::uint64_t>(epoch)));
  sample_rng_.seed(stream_seed(config_, SeedStream::minibatch_shuffle, mpi_.rank(), static_cast<std::uint64_t>(epoch)));
  // Episodes run on across epochs; the environments start afresh only after a checkpoint (and at
  // the start), so a run resumed from a checkpoint starts where the uninterrupted run started too.
  if (epoch == checkpoint_epochs_) {
    for (int j = 0; j < config_.num_envs; ++j) {
      const std::size_t jj = static_cast<std::size_t>(j);
      const std::uint64_t seed = stream_seed(config_, SeedStream::environment, mpi_.rank(),
                                             static_cast<std::uint64_t>(epoch) * config_.num_envs + j);
      const std::span<const double> first = envs_[jj]->reset(seed);
      observations_[jj] = Eigen::Map<const Eigen::VectorXd>(first.data(), observation_size_);
      episode_returns_[jj] = episode_costs_[jj] = 0.0;
      episode_lengths_[jj] = 0;
      episode_constraint_costs_[jj].setZero();
      accumulators_[jj].clear();
    }
  }
  // An epoch that ends with a checkpoint cuts its episodes in its last round (bootstrapped, not counted).
  const bool saves = (epoch + 1) % config_.save_freq == 0 || epoch + 1 == config_.epochs ||
                     (options_.stop_after_epochs > 0 && epoch + 1 >= options_.stop_after_epochs);
  const int rounds = local_steps_ / config_.num_envs;
  const long long steps_per_round_all_ranks = static_cast<long long>(config_.num_envs) * mpi_.size();
  for (int round = 0; round < rounds; ++round) {
    // Environment steps taken before this round, all ranks together.
    const long long steps_before = static_cast<long long>(epoch) * config_.steps_per_epoch + round * steps_per_round_all_ranks;
    const bool random_action = steps_before < config_.start_steps;
    const auto collect_start = Clock::now();
    for (int j = 0; j < config_.num_envs; ++j) collect_step(epoch, j, random_action, saves && round + 1 == rounds, accounts);
    accounts.collect_seconds += seconds_since(collect_start);
    schedule_.steps_since_update += config_.num_envs;
    if (schedule_.steps_since_update >= config_.update_every) {
      const bool learning = steps_before + steps_per_round_all_ranks >= config_.start_steps &&
                            buffer_.size() > 0;
      int updates = 0;
      if (learning) {
        // update_every * updates_per_step gradient steps per round, the fraction carried over.
        schedule_.owed_updates += static_cast<double>(schedule_.steps_since_update) * config_.updates_per_step;
        updates = static_cast<int>(std::floor(schedule_.owed_updates));
        schedule_.owed_updates -= updates;
      }
      schedule_.steps_since_update = 0;
      const auto update_start = Clock::now();
      // Every rank takes the same number of steps (the schedule is the same on all), so the
      // gradient averages pair up.
      train(updates, accounts);
      accounts.update_seconds += seconds_since(update_start);
    }
  }
  // The multipliers: one step on this epoch's pooled mean episode costs against the limits.
  std::vector<ConstraintEstimate> constraints;
  for (int i = 0; i < constraint_count_; ++i) {
    const std::vector<double>& values = accounts.constraint_costs[static_cast<std::size_t>(i)];
    const PooledStatistics pooled =
        pool_statistics(Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())), mpi_);
    constraints.push_back({pooled.mean, constraint_limit(config_, i)});
  }
  const long long episodes = static_cast<long long>(mpi_.sum(static_cast<double>(accounts.returns.size())));
  if (multipliers_ && episodes > 0) {
    const std::vector<double> updated = multipliers_->update(constraints);
    for (int i = 0; i < critic_cost_count_; ++i) lambdas_[static_cast<std::size_t>(i)] = updated[static_cast<std::size_t>(i)];
  }
  if (!learner_->actor().parameters().allFinite()) check_finite(epoch, "actor parameter", std::nan(""));
  for (int k = 0; k < learner_->reward_critic_count(); ++k) {
    if (!learner_->reward_critic(k).parameters().allFinite()) {
      check_finite(epoch, "reward critic parameter", std::nan(""));
    }
  }
  // Accounts of the whole epoch.
  progress_.training_cost.add_epoch(mpi_.sum(accounts.epoch_cost),
                                    [&] {
                                      Eigen::VectorXd summed = accounts.epoch_constraint_costs;
                                      mpi_.sum_in_place(summed);
                                      return summed;
                                    }(),
                                    constraints);
  const double epoch_seconds = seconds_since(accounts.start);
  progress_.epochs_completed = epoch + 1;
  progress_.elapsed_seconds += epoch_seconds;
  seconds_this_process_ += epoch_seconds;
  ++epochs_this_process_;
  if (options_.on_epoch_timed) {
    EpochTimings timings;
    timings.epoch = epoch;
    timings.collect_seconds = accounts.collect_seconds;
    timings.policy_update_seconds = accounts.update_seconds;
    timings.update_seconds = accounts.update_seconds;
    timings.total_seconds = epoch_seconds;
    options_.on_epoch_timed(timings);
  }

  // The progress.csv row.
  std::vector<NamedScalar> row;
  const auto pooled_columns = [&](const char* name, const std::vector<double>& values) {
    const PooledStatistics pooled =
        pool_statistics(Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())), mpi_);
    row.push_back({std::string(name) + "_mean", pooled.mean});
    row.push_back({std::string(name) + "_std", pooled.std});
    row.push_back({std::string(name) + "_min", pooled.min});
    row.push_back({std::string(name) + "_max", pooled.max});
    return pooled;
  };
  row.push_back({"epoch", static_cast<double>(epoch)});
  row.push_back({"total_env_steps", static_cast<double>(static_cast<long long>(epoch + 1) * config_.steps_per_epoch)});
  const PooledStatistics returns = pooled_columns("episode_return", accounts.returns);
  pooled_columns("episode_cost", accounts.costs);
  pooled_columns("episode_length", accounts.lengths);
  row.push_back({"episodes", static_cast<double>(episodes)});
  const double updates = static_cast<double>(std::max<long long>(accounts.updates, 1));
  const double actor_updates = static_cast<double>(std::max<long long>(accounts.actor_updates, 1));
  const double none = std::numeric_limits<double>::quiet_NaN();
  row.push_back({"updates", static_cast<double>(accounts.updates)});
  row.push_back({"reward_critic_loss", accounts.updates ? mpi_.average(accounts.reward_critic_loss / updates) : none});
  row.push_back({"q_reward_mean", accounts.updates ? mpi_.average(accounts.reward_q / updates) : none});
  for (int i = 0; i < critic_cost_count_; ++i) {
    const std::string prefix = constraint_count_ > 1 ? "constraint_" + std::to_string(i + 1) + "_" : "";
    row.push_back({prefix + "cost_critic_loss", accounts.updates ? mpi_.average(accounts.cost_critic_losses(i) / updates) : none});
    row.push_back({prefix + "q_cost_mean", accounts.updates ? mpi_.average(accounts.cost_qs(i) / updates) : none});
  }
  row.push_back({"actor_loss", accounts.actor_updates ? mpi_.average(accounts.actor_loss / actor_updates) : none});
  if (learner_->actor_kind() == ActorKind::squashed_gaussian) row.push_back({"alpha", learner_->alpha()});
  if (multipliers_) {
    for (const NamedScalar& entry : multipliers_->diagnostics()) {
      row.push_back({progress_column_name(entry.name), entry.value});
    }
  }
  if (!config_.constraints.empty()) {
    for (int i = 0; i < constraint_count_; ++i) {
      const std::string prefix = "constraint_" + std::to_string(i + 1) + "_";
      row.push_back({prefix + "cost", constraints[static_cast<std::size_t>(i)].mean_episode_cost});
      row.push_back({prefix + "limit", constraints[static_cast<std::size_t>(i)].limit});
    }
  }
  row.push_back({"time_collect_s", accounts.collect_seconds});
  row.push_back({"time_update_s", accounts.update_seconds});
  row.push_back({"time_s", progress_.elapsed_seconds});
  row.push_back({"fps", config_.steps_per_epoch / std::max(epoch_seconds, 1e-9)});
  const long long steps_so_far = static_cast<long long>(epoch + 1) * config_.steps_per_epoch;
  row.push_back({"cumulative_cost", progress_.training_cost.cumulative_cost});
  row.push_back({"cost_rate", TrainingCost::rate(progress_.training_cost.cumulative_cost, steps_so_far)});

  if (mpi_.is_root()) {
    progress_csv_->write_row(row);
    if (options_.log != nullptr) {
      ProgressLineInputs line;
      line.epoch = epoch;
      line.epochs = config_.epochs;
      line.mean_return = returns.mean;
      line.mean_cost = constraints.front().mean_episode_cost;
      if (!ignores_cost(config_.alg)) line.cost_limit = constraints.front().limit;
      if (multipliers_ && multipliers_->count() == 1) line.lagrange_multiplier = multipliers_->value(0);
      line.kl = none;
      line.epoch_seconds = epoch_seconds;
      line.eta_seconds = seconds_this_process_ / epochs_this_process_ * (config_.epochs - epoch - 1);
      *options_.log << format_progress_line(line) << std::endl;
    }
  }
  if (saves) save_checkpoint();
}

TrainingOutcome OffPolicyTrainer::run() {
  TrainingOutcome outcome;
  for (int epoch = progress_.epochs_completed; epoch < config_.epochs; ++epoch) {
    if (options_.stop_after_epochs > 0 && progress_.epochs_completed >= options_.stop_after_epochs) break;
    run_epoch_naming_errors(epoch, "", [&] { run_epoch(epoch); });
    if (options_.stop_requested && progress_.epochs_completed < config_.epochs && options_.stop_requested()) {
      if (checkpoint_epochs_ != progress_.epochs_completed) save_checkpoint();
      outcome.stop_requested = true;
      break;
    }
  }
  if (options_.stop_after_epochs > 0 && checkpoint_epochs_ != progress_.epochs_completed) save_checkpoint();
  outcome.epochs_completed = progress_.epochs_completed;
  outcome.finished = progress_.epochs_completed == config_.epochs;
  if (!outcome.finished) return outcome;

  // Deterministic evaluation: floor(eval_episodes / R) episodes per rank of a = tanh(mu(s)).
  EvaluationSummary summary = evaluate_off_policy(*envs_.front(), *learner_, config_.eval_episodes, config_.seed,
                                                  config_.max_ep_len, mpi_, cost_selector_);
  if (!mpi_.is_root()) return outcome;
  const TrainingSafety safety = training_safety();
  write_evaluation_files(directory_, summary, &safety);
  if (options_.log != nullptr) {
    *options_.log << "evaluation: " << summary.episodes.size() << " episodes  J (mean return) "
                  << format_csv_number(summary.mean_return) << "  H (mean cost) "
                  << format_csv_number(summary.mean_cost) << "  mean length " << format_csv_number(summary.mean_length)
                  << std::endl;
  }
  outcome.evaluation = std::move(summary);
  return outcome;
}

}  // namespace bsg::algos
