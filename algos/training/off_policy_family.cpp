#include "algos/training/off_policy_family.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/epoch_statistics.h"
#include "algos/training/off_policy_checkpoint.h"
#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/off_policy/off_policy_acting.h"
#include "algos/training/evaluation.h"
#include "common/checkpoint_file.h"
#include "common/run_config_checks.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::uint64_t stream_seed(const RunConfig& config, SeedStream stream, int rank, std::uint64_t index) {
  return derive_seed(static_cast<std::uint64_t>(config.seed), stream, static_cast<std::uint64_t>(rank), index);
}

const RunConfig& checked_off_policy(const RunConfig& config) {
  if (!is_off_policy(config.alg)) {
    throw std::invalid_argument("OffPolicyTrainer: " + std::string(to_string(config.alg)) + " is not off-policy");
  }
  return config;
}

int local_steps(const RunConfig& config, const MpiContext& mpi) {
  check_run_config_for_ranks(config, mpi.size());
  return config.steps_per_epoch / mpi.size();
}

}  // namespace

OffPolicyFamily::OffPolicyFamily(const RunConfig& config, const RunDirectory& directory, const MpiContext& mpi,
                                 std::vector<std::unique_ptr<envs::Env>> envs)
    : config_(checked_off_policy(config)),
      mpi_(mpi),
      collector_(config, std::move(envs), ignores_cost(config.alg) ? 0 : constraint_count(config)),
      constraint_count_(constraint_count(config)),
      critic_cost_count_(ignores_cost(config.alg) ? 0 : constraint_count_),
      local_steps_(local_steps(config, mpi)),
      buffer_(collector_.spec().observation_dim, collector_.spec().action_dim, critic_cost_count_,
              config.off_policy.buffer_size),
      buffer_log_(replay_buffer_log_path(directory.root, mpi.rank())),
      epoch_episodes_(constraint_count_) {
  const int observation_size = collector_.spec().observation_dim;
  const int action_size = collector_.spec().action_dim;
  Rng init_rng(stream_seed(config_, SeedStream::network_init, 0, 0));  // the same nets on every rank
  learner_ = make_off_policy_learner(config_, observation_size, action_size, critic_cost_count_, init_rng);
  if (has_lagrange_multiplier(config_.alg)) multipliers_.emplace(config_);
  lambdas_.assign(static_cast<std::size_t>(critic_cost_count_), 0.0);
  refresh_lambdas();
  action_.resize(action_size);
  log_layout_.critic_cost_count = critic_cost_count_;
  log_layout_.prefixed_cost_critics = constraint_count_ > 1;
  log_layout_.alpha = learner_->actor_kind() == ActorKind::squashed_gaussian;
  if (multipliers_) log_layout_.multiplier_names = multipliers_->multipliers().diagnostic_names();
  log_layout_.per_constraint = config_.constraints.empty() ? 0 : constraint_count_;
}

OffPolicyFamily::~OffPolicyFamily() = default;

TrainingProgress OffPolicyFamily::load_checkpoint(const std::filesystem::path& path) {
  const OffPolicyCheckpoint saved = load_off_policy_checkpoint(path, config_, *learner_);
  if (saved.progress.num_ranks != mpi_.size()) {
    throw CheckpointError(path.string() + ": written by a run with " + std::to_string(saved.progress.num_ranks) +
                          " ranks; an off-policy run resumes with the same rank count (each rank's replay buffer "
                          "is its own)");
  }
  schedule_.steps_since_update = saved.steps_since_update;
  schedule_.owed_updates = saved.owed_updates;
  if (multipliers_) {
    multipliers_->multipliers().restore_state(saved.multipliers);
    refresh_lambdas();
  }
  buffer_log_.restore(buffer_, saved.replay_transitions);
  return saved.progress;
}

void OffPolicyFamily::save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) {
  // A checkpoint cuts the episodes (the next epoch restarts the environments): steps still waiting
  // for their n-step sums go to the buffer as at a truncation (none after a cutting epoch).
  collector_.flush(buffer_);
  // Each rank's new transitions first, then rank 0's checkpoint.bin naming how many there are.
  buffer_log_.append(buffer_);
  mpi_.sum(0.0);
  if (mpi_.is_root()) {
    const OffPolicyCheckpoint state{progress, buffer_.total_added(), schedule_.steps_since_update,
                                    schedule_.owed_updates,
                                    multipliers_ ? multipliers_->multipliers().state() : std::vector<NamedScalar>{}};
    write_checkpoint_file(path, encode_off_policy_checkpoint(config_, state, *learner_));
  }
  mpi_.sum(0.0);
}

FamilyEpoch OffPolicyFamily::run_epoch(int epoch, bool checkpoint_follows) {
  start_epoch(epoch);  // 1
  // 2. Rounds of environment steps and, every update_every steps, rounds of gradient steps.
  const int rounds = local_steps_ / config_.off_policy.num_envs;
  const long long steps_per_round_all_ranks = static_cast<long long>(config_.off_policy.num_envs) * mpi_.size();
  for (int round = 0; round < rounds; ++round) {
    // Environment steps taken before this round, all ranks together.
    const long long steps_before =
        static_cast<long long>(epoch) * config_.steps_per_epoch + round * steps_per_round_all_ranks;
    collect_round(epoch, steps_before < config_.off_policy.start_steps, checkpoint_follows && round + 1 == rounds,
                  epoch_episodes_);
    record_episodes();
    schedule_.steps_since_update += config_.off_policy.num_envs;
    if (schedule_.steps_since_update >= config_.off_policy.update_every) {
      const bool learning =
          steps_before + steps_per_round_all_ranks >= config_.off_policy.start_steps && buffer_.size() > 0;
      const auto update_start = Clock::now();
      step_round_multipliers(learning);
      // Every rank takes the same number of steps (the schedule is the same on all), so the
      // gradient averages pair up.
      train(owed_gradient_steps(learning));
      update_seconds_ += seconds_since(update_start);
    }
  }
  constraints_ = update_multipliers(epoch_episodes_);  // 3
  check_networks_finite(epoch);                        // 4

  FamilyEpoch result;
  result.epoch_cost = mpi_.sum(epoch_episodes_.epoch_cost);
  result.epoch_constraint_costs = epoch_episodes_.epoch_constraint_costs;
  mpi_.sum_in_place(result.epoch_constraint_costs);
  result.constraints = constraints_;
  result.timings.collect_seconds = collect_seconds_;
  result.timings.policy_update_seconds = update_seconds_;
  result.timings.update_seconds = update_seconds_;
  const std::vector<double>& returns = epoch_episodes_.episodes.returns;
  result.line.mean_return =
      pool_statistics(Eigen::Map<const Eigen::VectorXd>(returns.data(), static_cast<Eigen::Index>(returns.size())), mpi_)
          .mean;
  result.line.mean_cost = constraints_.front().mean_episode_cost;
  if (!ignores_cost(config_.alg)) result.line.cost_limit = constraints_.front().limit;
  if (multipliers_ && multipliers_->multipliers().count() == 1) {
    result.line.lagrange_multiplier = multipliers_->multipliers().value(0);
  }
  result.line.kl = std::nan("");
  result.paces_later_epochs = static_cast<long long>(epoch) * config_.steps_per_epoch >= config_.off_policy.start_steps;
  return result;
}

// 1. This epoch's streams; the environments start afresh only after a checkpoint (and at the
// start), so a run resumed from a checkpoint starts where the uninterrupted run started too.
void OffPolicyFamily::start_epoch(int epoch) {
  epoch_episodes_ = OffPolicyEpochEpisodes(constraint_count_);
  recorded_episodes_ = 0;
  tally_ = OffPolicyUpdateTally{};
  tally_.cost_critic_losses = Eigen::VectorXd::Zero(critic_cost_count_);
  tally_.cost_qs = Eigen::VectorXd::Zero(critic_cost_count_);
  collect_seconds_ = update_seconds_ = 0.0;
  noise_rng_.seed(stream_seed(config_, SeedStream::action_noise, mpi_.rank(), static_cast<std::uint64_t>(epoch)));
  sample_rng_.seed(stream_seed(config_, SeedStream::minibatch_shuffle, mpi_.rank(), static_cast<std::uint64_t>(epoch)));
  if (epoch == checkpoint_mark().epochs) {
    if (multipliers_) multipliers_->restart();
    collector_.restart([&](int j) {
      return stream_seed(config_, SeedStream::environment, mpi_.rank(),
                         static_cast<std::uint64_t>(epoch) * config_.off_policy.num_envs +
                             static_cast<std::uint64_t>(j));
    });
  }
}

// One step of every environment: random actions before start_steps, else the actor's exploring ones.
void OffPolicyFamily::collect_round(int epoch, bool random_action, bool cut, OffPolicyEpochEpisodes& episodes) {
  const auto collect_start = Clock::now();
  const std::span<const double> action(action_.data(), static_cast<std::size_t>(action_.size()));
  for (int j = 0; j < collector_.env_count(); ++j) {
    if (random_action) {
      for (Eigen::Index a = 0; a < action_.size(); ++a) action_(a) = uniform(noise_rng_, -1.0, 1.0);
    } else {
      learner_->act(collector_.observation(j), false, noise_rng_, action_);
    }
    const envs::StepResult step = collector_.step(j, action);
    for (double value : step.observation) check_finite(epoch, "observation from the environment", value);
    check_finite(epoch, "reward from the environment", step.reward);
    collector_.record(j, action, step, cut, buffer_, episodes);
  }
  collect_seconds_ += seconds_since(collect_start);
}

// update_every * updates_per_step gradient steps per round once learning, the fraction carried over.
int OffPolicyFamily::owed_gradient_steps(bool learning) {
  int updates = 0;
  if (learning) {
    schedule_.owed_updates += static_cast<double>(schedule_.steps_since_update) * config_.off_policy.updates_per_step;
    updates = static_cast<int>(std::floor(schedule_.owed_updates));
    schedule_.owed_updates -= updates;
  }
  schedule_.steps_since_update = 0;
  return updates;
}

// The episodes completed since the last call into the multipliers' window.
void OffPolicyFamily::record_episodes() {
  if (!multipliers_) return;
  multipliers_->record(epoch_episodes_.constraint_costs, recorded_episodes_);
  recorded_episodes_ = epoch_episodes_.episodes.returns.size();
}

// multiplier_schedule update_round: one step before the round's gradient steps, which use it.
void OffPolicyFamily::step_round_multipliers(bool learning) {
  if (multipliers_ && multipliers_->before_gradient_round(learning, mpi_)) refresh_lambdas();
}

// The actor steps' lambdas from the multipliers.
void OffPolicyFamily::refresh_lambdas() {
  if (!multipliers_) return;
  for (int i = 0; i < critic_cost_count_; ++i) {
    lambdas_[static_cast<std::size_t>(i)] = multipliers_->multipliers().value(i);
  }
}

void OffPolicyFamily::train(int updates) {
  for (int u = 0; u < updates; ++u) {
    buffer_.sample(config_.off_policy.batch_size, sample_rng_, slots_, batch_);
    learner_->update(batch_, lambdas_, sample_rng_, mpi_, step_stats_);
    const OffPolicyStepStats& stats = step_stats_;
    ++tally_.updates;
    tally_.reward_critic_loss += stats.reward_critic_loss;
    tally_.reward_q += stats.reward_q_mean;
    for (int i = 0; i < critic_cost_count_; ++i) {
      tally_.cost_critic_losses(i) += stats.cost_critic_losses[static_cast<std::size_t>(i)];
      tally_.cost_qs(i) += stats.cost_q_means[static_cast<std::size_t>(i)];
    }
    if (stats.actor_updated) {
      ++tally_.actor_updates;
      tally_.actor_loss += stats.actor_loss;
    }
  }
}

// 3. The multipliers (multiplier_schedule epoch): one step on this epoch's pooled mean episode costs
// against the limits.
std::vector<ConstraintEstimate> OffPolicyFamily::update_multipliers(const OffPolicyEpochEpisodes& episodes) {
  std::vector<ConstraintEstimate> constraints;
  for (int i = 0; i < constraint_count_; ++i) {
    const std::vector<double>& values = episodes.constraint_costs[static_cast<std::size_t>(i)];
    const PooledStatistics pooled = pool_statistics(
        Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())), mpi_);
    constraints.push_back({pooled.mean, constraint_limit(config_, i)});
  }
  episode_count_ = static_cast<long long>(mpi_.sum(static_cast<double>(episodes.episodes.returns.size())));
  if (multipliers_ && multipliers_->after_epoch(constraints, episode_count_)) refresh_lambdas();
  return constraints;
}

// 4. Non-finite networks stop the run before the epoch is saved.
void OffPolicyFamily::check_networks_finite(int epoch) {
  if (!learner_->actor().parameters().allFinite()) check_finite(epoch, "actor parameter", std::nan(""));
  for (int k = 0; k < learner_->reward_critic_count(); ++k) {
    if (!learner_->reward_critic(k).parameters().allFinite()) {
      check_finite(epoch, "reward critic parameter", std::nan(""));
    }
  }
}

std::vector<NamedScalar> OffPolicyFamily::progress_row(const EpochAccounts& accounts) {
  OffPolicyLogInputs inputs;
  inputs.epoch = accounts.epoch;
  inputs.steps_per_epoch = config_.steps_per_epoch;
  inputs.episodes = &epoch_episodes_.episodes;
  inputs.episode_count = episode_count_;
  inputs.updates = &tally_;
  inputs.alpha = log_layout_.alpha ? learner_->alpha() : 0.0;
  if (multipliers_) inputs.multipliers = multipliers_->multipliers().diagnostics();
  inputs.constraints = constraints_;
  inputs.collect_seconds = collect_seconds_;
  inputs.update_seconds = update_seconds_;
  inputs.epoch_seconds = accounts.epoch_seconds;
  inputs.elapsed_seconds = accounts.elapsed_seconds;
  inputs.training_cost = accounts.training_cost;
  return make_off_policy_log_row(log_layout_, inputs, mpi_);
}

// Deterministic evaluation (evaluation.h): floor(eval_episodes / R) episodes per rank of a = tanh(mu(s)),
// as OmniSafe and FSRL evaluate; then the same episodes (the same environment seeds) with the
// exploring policy, whose training episodes the multipliers constrained (docs/algorithms.md#the-off-policy-loop).
// The term names label evaluation.json's per-term costs.
EvaluationSummary OffPolicyFamily::evaluate(int /*epochs_completed: the actor acts without noise*/) {
  OffPolicyActing acting(*learner_);
  envs::Env& env = collector_.env(0);
  EvaluationSummary summary = evaluate_policy(env, acting, config_.eval_episodes, config_.seed, config_.max_ep_len,
                                              mpi_, collector_.cost_selector(), env.spec().cost_term_names,
                                              ActionMode::mean);
  const EvaluationSummary exploring = evaluate_policy(env, acting, config_.eval_episodes, config_.seed,
                                                      config_.max_ep_len, mpi_, collector_.cost_selector(), {},
                                                      ActionMode::sampled);
  if (mpi_.is_root()) {
    summary.exploring = ExploringEvaluation{static_cast<long long>(exploring.episodes.size()), exploring.mean_return,
                                            exploring.mean_cost, exploring.mean_length};
  }
  return summary;
}

}  // namespace bsg::algos
