#include "algos/training/multi_agent_family.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/advantage_normalization.h"
#include "algos/core/policy_surrogate.h"
#include "algos/first_order/make_first_order_algorithm.h"
#include "algos/first_order/ppo.h"
#include "algos/multi_agent/sequential_policy_step.h"
#include "algos/multi_agent/sequential_order.h"
#include "algos/training/epoch_log.h"
#include "algos/training/evaluation.h"
#include "algos/training/progress_csv_fields.h"
#include "algos/training/run_header.h"
#include "common/checkpoint_file.h"
#include "common/run_config_checks.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::uint64_t stream_seed(const RunConfig& config, SeedStream stream, int rank, int index) {
  return derive_seed(static_cast<std::uint64_t>(config.seed), stream, static_cast<std::uint64_t>(rank),
                     static_cast<std::uint64_t>(index));
}

const RunConfig& checked_config(const RunConfig& config, const MpiContext& mpi) {
  if (!is_multi_agent(config.alg)) {
    throw std::invalid_argument("MultiAgentFamily: " + std::string(to_string(config.alg)) + " is not a multi-agent learner");
  }
  if (is_sequential_multi_agent(config.alg) && config.multi_agent.share_policy) {
    throw std::invalid_argument("MultiAgentFamily: " + std::string(to_string(config.alg)) +
                                " updates each agent's own policy in turn; share_policy must be false");
  }
  check_run_config_for_ranks(config, mpi.size());
  return config;
}

std::unique_ptr<envs::MultiAgentEnv> checked_env(std::unique_ptr<envs::MultiAgentEnv> env) {
  if (env == nullptr) throw std::invalid_argument("MultiAgentFamily: no environment");
  return env;
}

MultiAgentSizes sizes_of(const envs::MultiAgentSpec& spec) {
  return MultiAgentSizes{spec.observation_dims, spec.action_dims, spec.state_dim};
}

std::unique_ptr<MultiAgentNetworks> make_networks(const RunConfig& config, const envs::MultiAgentSpec& spec) {
  Rng init_rng(stream_seed(config, SeedStream::network_init, 0, 0));
  return std::make_unique<MultiAgentNetworks>(sizes_of(spec), config, !ignores_cost(config.alg), init_rng);
}

// The rows of `agents` stacked: each agent's block of `rows_of(agent)`.
template <typename RowsOf>
Eigen::MatrixXd stacked(const std::vector<int>& agents, RowsOf rows_of) {
  std::vector<Eigen::MatrixXd> blocks;
  Eigen::Index rows = 0;
  for (int agent : agents) {
    blocks.push_back(rows_of(agent));
    rows += blocks.back().rows();
  }
  Eigen::MatrixXd all(rows, blocks.front().cols());
  Eigen::Index at = 0;
  for (const Eigen::MatrixXd& block : blocks) {
    all.middleRows(at, block.rows()) = block;
    at += block.rows();
  }
  return all;
}

// The slots' mean of a rank-averaged diagnostic.
double slot_mean(const std::vector<PolicyUpdateResult>& updates, CommonDiagnostic which, const MpiContext& mpi) {
  double sum = 0.0;
  for (const PolicyUpdateResult& update : updates) sum += update.common(which).value_or(std::nan(""));
  return mpi.average(sum / static_cast<double>(updates.size()));
}

}  // namespace

TeamEpisodes team_episodes(const MultiAgentRollout& rollout) {
  const int n = rollout.agent_count();
  const std::size_t count = rollout.buffer(0).episodes().size();
  TeamEpisodes team{Eigen::VectorXd::Zero(static_cast<Eigen::Index>(count)),
                    Eigen::VectorXd::Zero(static_cast<Eigen::Index>(count)),
                    Eigen::VectorXd::Zero(static_cast<Eigen::Index>(count))};
  for (int i = 0; i < n; ++i) {
    const std::vector<EpisodeStats>& episodes = rollout.buffer(i).episodes();
    if (episodes.size() != count) {
      throw std::invalid_argument("team_episodes: agent_" + std::to_string(i) + " finished " +
                                  std::to_string(episodes.size()) + " episodes, agent_0 " + std::to_string(count));
    }
    for (std::size_t e = 0; e < count; ++e) {
      const auto row = static_cast<Eigen::Index>(e);
      team.returns[row] += episodes[e].episode_return / n;
      team.costs[row] += episodes[e].episode_cost / n;
      team.lengths[row] = episodes[e].episode_length;
    }
  }
  return team;
}

RunConfig slot_update_config(const RunConfig& config) {
  RunConfig slot = config;
  slot.alg = ignores_cost(config.alg) ? Algorithm::ppo : Algorithm::ppo_lag;
  slot.first_order.learn_log_std = true;
  slot.first_order.kl_early_stop = false;
  slot.use_cost_value_function = !ignores_cost(config.alg);
  return slot;
}

MultiAgentFamily::MultiAgentFamily(const RunConfig& config, const MpiContext& mpi,
                                   std::unique_ptr<envs::MultiAgentEnv> env)
    : config_(checked_config(config, mpi)),
      mpi_(mpi),
      env_(checked_env(std::move(env))),
      networks_(make_networks(config_, env_->spec())),
      rollout_(env_->spec(),
               MultiAgentRolloutOptions{config_.steps_per_epoch / mpi.size(), config_.max_ep_len, config_.timeout_bootstrap},
               BufferOptions{config_.gamma, config_.lam, config_.lam_c, 1, false}) {
  // MACPO's CPO steps keep no state between epochs; every other learner's slot keeps its PPO's Adam.
  if (config_.alg == Algorithm::macpo) return;
  for (int s = 0; s < networks_->slot_count(); ++s) algorithms_.push_back(make_first_order_algorithm(slot_update_config(config_)));
}

MultiAgentFamily::~MultiAgentFamily() = default;

TrainingProgress load_multi_agent_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                             MultiAgentNetworks& networks,
                                             std::vector<std::unique_ptr<OnPolicyAlgorithm>>& algorithms) {
  const CheckpointContents contents = read_checkpoint_contents(path);
  BinaryReader reader(contents.payload, path.string());
  TrainingProgress progress = read_run_header(reader, RunHeaderLayout::multi_agent, config, contents.format_version);
  progress.training_cost = load_training_cost(reader, 1);
  networks.load(reader);
  for (std::size_t s = 0; s < algorithms.size(); ++s) {
    reader.expect_section("slot update " + std::to_string(s));
    const std::uint64_t count = reader.read_u64("slot update state size");
    if (count > reader.remaining()) reader.fail("corrupt slot update state size " + std::to_string(count));
    std::vector<NamedScalar> state;
    for (std::uint64_t i = 0; i < count; ++i) {
      NamedScalar entry;
      entry.name = reader.read_string("slot update state name");
      entry.value = reader.read_f64("slot update state value");
      state.push_back(std::move(entry));
    }
    try {
      algorithms[s]->restore_state(state);
    } catch (const std::invalid_argument& e) {
      reader.fail(std::string("slot update state: ") + e.what());
    }
  }
  reader.expect_end();
  return progress;
}

TrainingProgress MultiAgentFamily::load_checkpoint(const std::filesystem::path& path) {
  return load_multi_agent_checkpoint(path, config_, *networks_, algorithms_);
}

void MultiAgentFamily::save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) {
  if (!mpi_.is_root()) return;
  BinaryWriter writer;
  write_run_header(writer, RunHeaderLayout::multi_agent, config_, progress);
  save_training_cost(progress.training_cost, writer);
  networks_->save(writer);
  for (std::size_t s = 0; s < algorithms_.size(); ++s) {
    writer.write_section("slot update " + std::to_string(s));
    const std::vector<NamedScalar> state = algorithms_[s]->state();
    writer.write_u64(state.size());
    for (const NamedScalar& entry : state) {
      writer.write_string(entry.name);
      writer.write_f64(entry.value);
    }
  }
  write_checkpoint_file(path, writer.bytes());
}

void MultiAgentFamily::pool_episodes(EpochRecord& record) const {
  const TeamEpisodes team = team_episodes(rollout_);
  record.team_return = pool_statistics(team.returns, mpi_);
  record.team_cost = pool_statistics(team.costs, mpi_);
  record.team_length = pool_statistics(team.lengths, mpi_);
  record.agent_returns.clear();
  record.agent_costs.clear();
  for (int i = 0; i < rollout_.agent_count(); ++i) {
    const std::vector<EpisodeStats>& episodes = rollout_.buffer(i).episodes();
    Eigen::VectorXd returns(static_cast<Eigen::Index>(episodes.size()));
    Eigen::VectorXd costs(returns.size());
    for (std::size_t e = 0; e < episodes.size(); ++e) {
      returns[static_cast<Eigen::Index>(e)] = episodes[e].episode_return;
      costs[static_cast<Eigen::Index>(e)] = episodes[e].episode_cost;
    }
    record.agent_returns.push_back(pool_statistics(returns, mpi_).mean);
    record.agent_costs.push_back(pool_statistics(costs, mpi_).mean);
  }
}

// Step 3 for one slot: its agents' rows stacked, advantages standardised over them, PPO's update.
void MultiAgentFamily::update_slot(int s, const ConstraintEstimate& constraint, double mean_length,
                                   EpochRecord& record) {
  AgentSlot& slot = networks_->slot(s);
  const Eigen::MatrixXd inputs = stacked(slot.agents, [&](int agent) {
    Eigen::MatrixXd rows;
    networks_->policy_inputs(agent, rollout_.buffer(agent).observations(), rows);
    return rows;
  });
  const Eigen::MatrixXd actions = stacked(slot.agents, [&](int agent) { return rollout_.buffer(agent).actions(); });
  const Eigen::VectorXd log_probs =
      stacked(slot.agents, [&](int agent) { return Eigen::MatrixXd(rollout_.buffer(agent).log_probs()); });
  Eigen::VectorXd advantages =
      stacked(slot.agents, [&](int agent) { return Eigen::MatrixXd(rollout_.buffer(agent).advantages()); });
  Eigen::MatrixXd cost_advantages =
      stacked(slot.agents, [&](int agent) { return rollout_.buffer(agent).constraint_cost_advantages(); });
  standardize_advantages(advantages, cost_advantages, mpi_);  // SafePO's trainers standardise both
  PolicySurrogate surrogate(inputs, actions, log_probs, advantages, cost_advantages);
  const std::vector<ConstraintEstimate> constraints{constraint};
  record.updates.push_back(algorithms_[static_cast<std::size_t>(s)]->update(PolicyUpdateInputs{
      slot.policy, surrogate, constraint.mean_episode_cost, mean_length, mpi_, constraints, &shuffle_rng_}));
}

// Step 3 of HAPPO and MACPO: one sequential round over the agents, each on its own buffer's rows.
void MultiAgentFamily::update_agents_in_turn(int epoch, EpochRecord& record) {
  const int n = networks_->agent_count();
  std::vector<AgentBatch> batches;
  std::vector<GaussianPolicy*> policies;
  for (int i = 0; i < n; ++i) {
    const Buffer& buffer = rollout_.buffer(i);
    AgentBatch batch;
    networks_->policy_inputs(i, buffer.observations(), batch.observations);
    batch.actions = buffer.actions();
    batch.old_log_probs = buffer.log_probs();
    batch.advantages = buffer.advantages();
    const Eigen::MatrixXd cost_advantages = buffer.constraint_cost_advantages();
    if (cost_advantages.cols() > 0) batch.cost_advantages = cost_advantages.col(0);
    batches.push_back(std::move(batch));
    policies.push_back(&networks_->slot_of_agent(i).policy);
  }
  const std::vector<int> order =
      sequential_agent_order(n, static_cast<std::uint64_t>(config_.seed), static_cast<std::uint64_t>(epoch));
  std::vector<Ppo*> ppos;  // HAPPO's; MACPO keeps none
  for (const auto& algorithm : algorithms_) ppos.push_back(dynamic_cast<Ppo*>(algorithm.get()));
  SequentialPolicyStep step = sequential_policy_step(config_, std::move(batches), policies, ppos,
                                                     record.team_cost.mean, order, mpi_, shuffle_rng_);
  record.round = std::move(step.round);
  record.constraint_violations = std::move(step.constraint_violations);
  for (const AgentRoundStatistics& agent : record.round) {
    record.updates.push_back(PolicyUpdateResult{agent.diagnostics, {}});
  }
}

// Step 4: V (and V_C) of the slot on the stacked critic inputs.
void MultiAgentFamily::fit_critics(int s, EpochRecord& record) {
  AgentSlot& slot = networks_->slot(s);
  const Eigen::MatrixXd critic_inputs = stacked(slot.agents, [&](int agent) {
    Eigen::MatrixXd rows;
    networks_->critic_inputs(agent, rollout_.states(), rows);
    return rows;
  });
  const Eigen::VectorXd value_targets =
      stacked(slot.agents, [&](int agent) { return Eigen::MatrixXd(rollout_.buffer(agent).value_targets()); });
  const Eigen::VectorXd cost_targets =
      stacked(slot.agents, [&](int agent) { return Eigen::MatrixXd(rollout_.buffer(agent).cost_value_targets()); });
  std::vector<ValueFitJob> jobs{{slot.value, value_targets}};
  if (slot.cost_value) jobs.push_back({*slot.cost_value, cost_targets});
  record.fits.push_back(fit_value_functions(jobs, critic_inputs, shuffle_rng_, mpi_,
                                            ValueFitOptions{config_.train_v_iterations, config_.num_mini_batches, 16}));
}

void MultiAgentFamily::update_normalizers() {
  if (!config_.use_standardized_obs) return;
  for (int s = 0; s < networks_->slot_count(); ++s) {
    AgentSlot& slot = networks_->slot(s);
    slot.observation_normalizer.update(
        stacked(slot.agents, [&](int agent) { return rollout_.buffer(agent).observations(); }), mpi_);
  }
  networks_->state_normalizer().update(rollout_.states(), mpi_);
}

void MultiAgentFamily::check_parameters_finite(int epoch) const {
  const char* quantity = networks_->first_non_finite();
  if (*quantity != '\0') check_finite(epoch, quantity, std::nan(""));
  for (const auto& algorithm : algorithms_) {
    for (const NamedScalar& entry : algorithm->state()) check_finite(epoch, entry.name.c_str(), entry.value);
  }
}

FamilyEpoch MultiAgentFamily::run_epoch(int epoch, bool /*checkpoint_follows: the rollout ends every epoch*/) {
  const auto epoch_start = Clock::now();
  noise_rng_.seed(stream_seed(config_, SeedStream::action_noise, mpi_.rank(), epoch));
  shuffle_rng_.seed(stream_seed(config_, SeedStream::minibatch_shuffle, mpi_.rank(), epoch));
  rollout_.collect(*env_, stream_seed(config_, SeedStream::environment, mpi_.rank(), epoch), *networks_, noise_rng_);
  for (int i = 0; i < rollout_.agent_count(); ++i) {
    const Buffer& buffer = rollout_.buffer(i);
    if (!buffer.observations().allFinite()) check_finite(epoch, "observation from the environment", std::nan(""));
    if (!buffer.rewards().allFinite()) check_finite(epoch, "reward from the environment", std::nan(""));
    if (!buffer.costs().allFinite()) check_finite(epoch, "cost from the environment", std::nan(""));
  }
  EpochRecord record;
  record.collect_seconds = seconds_since(epoch_start);
  const auto update_start = Clock::now();

  pool_episodes(record);
  const ConstraintEstimate constraint{record.team_cost.mean, config_.cost_limit};
  if (is_sequential_multi_agent(config_.alg)) {
    update_agents_in_turn(epoch, record);
    for (int s = 0; s < networks_->slot_count(); ++s) fit_critics(s, record);
  } else {
    for (int s = 0; s < networks_->slot_count(); ++s) {
      update_slot(s, constraint, record.team_length.mean, record);
      fit_critics(s, record);
    }
  }
  for (const PolicyUpdateResult& update : record.updates) {
    if (const auto loss = update.common(CommonDiagnostic::loss)) check_finite(epoch, "policy loss", *loss);
  }
  for (const auto& fits : record.fits) check_finite(epoch, "value loss", fits.front().loss_before);
  update_normalizers();
  check_parameters_finite(epoch);
  if (epoch % config_.check_freq == 0) {
    const double sum = networks_->parameter_sum();
    if (mpi_.min(sum) != mpi_.max(sum)) {
      throw std::runtime_error("the MPI ranks' parameters disagree after epoch " + std::to_string(epoch));
    }
  }
  record.update_seconds = seconds_since(update_start);
  last_ = std::move(record);

  FamilyEpoch result;
  double epoch_cost = rollout_.epoch_cost();
  mpi_.sum_in_place(&epoch_cost, 1);
  result.epoch_cost = epoch_cost;
  result.epoch_constraint_costs = Eigen::VectorXd::Constant(1, epoch_cost);
  result.constraints = {constraint};
  result.timings.collect_seconds = last_.collect_seconds;
  result.timings.update_seconds = last_.update_seconds;
  result.line.mean_return = last_.team_return.mean;
  result.line.mean_cost = last_.team_cost.mean;
  if (!ignores_cost(config_.alg)) result.line.cost_limit = config_.cost_limit;
  if (algorithm_info(config_.alg).lagrange_multiplier) {
    result.line.lagrange_multiplier = last_.updates.front().lagrange_multiplier;
  }
  result.line.kl = slot_mean(last_.updates, CommonDiagnostic::kl, mpi_);
  return result;
}

// The one list of the columns, in order: without accounts (the header) every value is 0.
std::vector<NamedScalar> MultiAgentFamily::log_entries(const EpochAccounts* accounts) const {
  std::vector<NamedScalar> row;
  const bool values = accounts != nullptr;
  const auto add = [&row, values](std::string name, double value) { row.push_back({std::move(name), values ? value : 0.0}); };
  const bool constrained = !ignores_cost(config_.alg);
  add("epoch", values ? accounts->epoch : 0);
  add("total_env_steps", values ? static_cast<double>(accounts->epoch + 1) * config_.steps_per_epoch : 0.0);
  add("episode_return_mean", last_.team_return.mean);
  add("episode_return_min", last_.team_return.min);
  add("episode_return_max", last_.team_return.max);
  add("episode_cost_mean", last_.team_cost.mean);
  add("episode_cost_min", last_.team_cost.min);
  add("episode_cost_max", last_.team_cost.max);
  add("episode_length_mean", last_.team_length.mean);
  add("episodes", static_cast<double>(last_.team_return.count));
  for (int i = 0; i < networks_->agent_count(); ++i) {
    const auto a = static_cast<std::size_t>(i);
    add("agent_" + std::to_string(i) + "_return_mean", values ? last_.agent_returns[a] : 0.0);
    add("agent_" + std::to_string(i) + "_cost_mean", values ? last_.agent_costs[a] : 0.0);
  }
  // Rank-local diagnostics averaged over ranks, then over slots.
  const auto fit_mean = [&](std::size_t job) {
    if (!values) return 0.0;
    double sum = 0.0;
    for (const auto& fits : last_.fits) sum += fits[job].loss_before;
    return mpi_.average(sum / static_cast<double>(last_.fits.size()));
  };
  add("policy_loss", values ? slot_mean(last_.updates, CommonDiagnostic::loss, mpi_) : 0.0);
  add("entropy", values ? slot_mean(last_.updates, CommonDiagnostic::entropy, mpi_) : 0.0);
  add("kl", values ? slot_mean(last_.updates, CommonDiagnostic::kl, mpi_) : 0.0);
  add("policy_ratio", values ? slot_mean(last_.updates, CommonDiagnostic::policy_ratio, mpi_) : 0.0);
  add("value_loss", fit_mean(0));
  if (constrained) add("cost_value_loss", fit_mean(1));
  if (algorithm_info(config_.alg).lagrange_multiplier) {
    add("lagrange_multiplier", values ? last_.updates.front().lagrange_multiplier.value_or(std::nan("")) : 0.0);
  }
  // The sequential round's per-agent statistics: position in the order (0 first), KL and step norm
  // averaged over ranks, the correction factor M the agent's step saw on this rank's rows.
  if (is_sequential_multi_agent(config_.alg)) {
    for (int i = 0; i < networks_->agent_count(); ++i) {
      const std::string prefix = "agent_" + std::to_string(i) + "_";
      const AgentRoundStatistics* agent = values ? &last_.round[static_cast<std::size_t>(i)] : nullptr;
      add(prefix + "position", agent ? agent->position : 0.0);
      add(prefix + "kl", agent ? mpi_.average(agent->kl) : 0.0);
      add(prefix + "step_norm", agent ? mpi_.average(agent->step_norm) : 0.0);
      add(prefix + "factor_mean", agent ? agent->factor.mean : 0.0);
      add(prefix + "factor_min", agent ? agent->factor.min : 0.0);
      add(prefix + "factor_max", agent ? agent->factor.max : 0.0);
      if (config_.alg == Algorithm::macpo) {
        add(prefix + "constraint_violation", agent ? last_.constraint_violations[static_cast<std::size_t>(i)] : 0.0);
      }
    }
  }
  add("time_collect_s", last_.collect_seconds);
  add("time_update_s", last_.update_seconds);
  add("time_s", values ? accounts->elapsed_seconds : 0.0);
  const long long steps = values ? static_cast<long long>(accounts->epoch + 1) * config_.steps_per_epoch : 0;
  const double cumulative = values && accounts->training_cost ? accounts->training_cost->cumulative_cost : 0.0;
  add("cumulative_cost", cumulative);
  add("cost_rate", values ? TrainingCost::rate(cumulative, steps) : 0.0);
  return row;
}

std::vector<NamedScalar> MultiAgentFamily::progress_row(const EpochAccounts& accounts) { return log_entries(&accounts); }

std::vector<std::string> MultiAgentFamily::progress_columns() const { return names_of(log_entries(nullptr)); }

EvaluationSummary MultiAgentFamily::evaluate(int /*epochs_completed*/) {
  return evaluate_mean_actions(config_.eval_episodes, config_.seed);
}

// The agents' mean actions on floor(total_episodes / R) episodes per rank, seeded as every family's
// evaluation; an episode's return and cost are the agents' mean, as in training.
EvaluationSummary MultiAgentFamily::evaluate_mean_actions(int total_episodes, std::int64_t run_seed) {
  if (total_episodes < 0) {
    throw std::invalid_argument("evaluation: the number of episodes must be >= 0, got " + std::to_string(total_episodes));
  }
  const int local_episodes = total_episodes / mpi_.size();
  const int n = networks_->agent_count();
  std::vector<EvaluationEpisode> local;
  std::vector<Eigen::VectorXd> observations, inputs, actions;
  for (int i = 0; i < n; ++i) {
    observations.emplace_back(env_->spec().observation_dims[static_cast<std::size_t>(i)]);
    inputs.emplace_back(networks_->policy_input_size(i));
    actions.emplace_back(env_->spec().action_dims[static_cast<std::size_t>(i)]);
  }
  std::vector<std::span<const double>> action_views;
  for (const Eigen::VectorXd& action : actions) action_views.emplace_back(action.data(), static_cast<std::size_t>(action.size()));
  MlpSampleWorkspace workspace;
  const auto observe = [&](std::span<const std::span<const double>> views) {
    for (int i = 0; i < n; ++i) {
      const std::span<const double> view = views[static_cast<std::size_t>(i)];
      observations[static_cast<std::size_t>(i)] = Eigen::Map<const Eigen::VectorXd>(view.data(), static_cast<Eigen::Index>(view.size()));
    }
  };
  for (int e = 0; e < local_episodes; ++e) {
    if (e == 0) {
      observe(env_->reset(derive_seed(static_cast<std::uint64_t>(run_seed), SeedStream::evaluation_environment,
                                      static_cast<std::uint64_t>(mpi_.rank()))));
    } else {
      observe(env_->reset());
    }
    EvaluationEpisode episode;
    episode.constraint_costs.assign(1, 0.0);
    episode.agent_returns.assign(static_cast<std::size_t>(n), 0.0);
    episode.agent_costs.assign(static_cast<std::size_t>(n), 0.0);
    for (int t = 0; t < config_.max_ep_len; ++t) {
      for (int i = 0; i < n; ++i) {
        const auto a = static_cast<std::size_t>(i);
        networks_->policy_input(i, observations[a], inputs[a]);
        networks_->slot_of_agent(i).policy.mean_action(inputs[a], actions[a], workspace);
      }
      const envs::MultiAgentStepResult step = env_->step(action_views);
      for (int i = 0; i < n; ++i) {
        const auto a = static_cast<std::size_t>(i);
        episode.episode_return += step.rewards[a] / n;
        episode.episode_cost += step.costs[a] / n;
        episode.agent_returns[a] += step.rewards[a];
        episode.agent_costs[a] += step.costs[a];
      }
      ++episode.episode_length;
      observe(step.observations);
      if (step.terminated || step.truncated) break;
    }
    episode.constraint_costs[0] = episode.episode_cost;
    local.push_back(std::move(episode));
  }
  return gather_evaluation(local, mpi_, 1, {}, static_cast<std::size_t>(n));
}

}  // namespace bsg::algos
