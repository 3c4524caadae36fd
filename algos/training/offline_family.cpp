#include "algos/training/offline_family.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "algos/offline/dataset_environment.h"
#include "algos/offline/dataset_file.h"
#include "algos/offline/make_offline_algorithm.h"
#include "algos/offline/normalized_score.h"
#include "algos/training/evaluation.h"
#include "algos/training/run_environment.h"
#include "algos/training/run_header.h"
#include "common/checkpoint_file.h"
#include "common/run_config_checks.h"
#include "common/seeding.h"

namespace bsg::algos {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

std::uint64_t stream_seed(const RunConfig& config, SeedStream stream, std::uint64_t index) {
  return derive_seed(static_cast<std::uint64_t>(config.seed), stream, 0, index);
}

const RunConfig& checked_offline(const RunConfig& config, const MpiContext& mpi) {
  if (!is_offline(config.alg)) {
    throw std::invalid_argument("OfflineTrainer: " + std::string(to_string(config.alg)) + " is not offline");
  }
  check_run_config_for_ranks(config, mpi.size());  // one rank, before the dataset is read
  return config;
}

// The dataset of `dataset:`, checked against the run and its environment.
OfflineDataset read_run_dataset(const RunConfig& config, const envs::Env& env) {
  if (config.offline.dataset.empty()) {
    throw std::invalid_argument("alg " + std::string(to_string(config.alg)) + " needs 'dataset:', the HDF5 file it learns from");
  }
  OfflineDataset dataset = read_dataset_file(config.offline.dataset);
  const std::string where = "dataset " + config.offline.dataset + ": ";
  const auto env_id = dataset.text_attributes.find("env_id");
  if (env_id != dataset.text_attributes.end() && env_id->second != config.env_id) {
    throw std::invalid_argument(where + "collected on " + env_id->second + ", but the run's env_id is " +
                                config.env_id + " (set env_id: " + env_id->second + ", or another dataset)");
  }
  if (dataset.text_attributes.count("env_description") != 0 &&
      dataset_env_description(dataset) != run_env_description(config)) {
    throw std::invalid_argument(where + "collected on another description of " + config.env_id +
                                " (its env_description attribute differs from the run's env: block; "
                                "`bsg dataset info` shows the file's)");
  }
  const envs::EnvSpec& spec = env.spec();
  if (dataset.observation_dim != spec.observation_dim || dataset.action_dim != spec.action_dim) {
    throw std::invalid_argument(where + "holds " + std::to_string(dataset.observation_dim) + " observations and " +
                                std::to_string(dataset.action_dim) + " actions per row, " + config.env_id + " has " +
                                std::to_string(spec.observation_dim) + " and " + std::to_string(spec.action_dim));
  }
  return dataset;
}

double reward_constant(const OfflineDataset& dataset, const char* key, double from_episodes) {
  const auto it = dataset.number_attributes.find(key);
  return it != dataset.number_attributes.end() ? it->second : from_episodes;
}

// The one list of the columns, in order: without a family (the header) every value is 0.
std::vector<NamedScalar> offline_log_entries(const RunConfig& config, const EpochAccounts* accounts, double loss,
                                             const std::optional<OfflineEpochEvaluation>& evaluation,
                                             double update_seconds) {
  std::vector<NamedScalar> row;
  const auto add = [&row](std::string name, double value) { row.push_back({std::move(name), value}); };
  const bool values = accounts != nullptr;
  const auto scored = [&](double OfflineEpochEvaluation::*member) {
    if (!values) return 0.0;
    return evaluation ? (*evaluation).*member : kNone;
  };
  add("epoch", values ? accounts->epoch : 0);
  add("updates", values ? static_cast<double>(accounts->epoch + 1) * config.offline.updates_per_epoch : 0.0);
  add("loss", values ? loss : 0.0);
  add("eval_return", scored(&OfflineEpochEvaluation::mean_return));
  add("eval_cost", scored(&OfflineEpochEvaluation::mean_cost));
  add("eval_length", scored(&OfflineEpochEvaluation::mean_length));
  add("normalized_reward", scored(&OfflineEpochEvaluation::normalized_reward));
  add("normalized_cost", scored(&OfflineEpochEvaluation::normalized_cost));
  add("time_update_s", values ? update_seconds : 0.0);
  add("time_s", values ? accounts->elapsed_seconds : 0.0);
  return row;
}

}  // namespace

OfflineFamily::OfflineFamily(const RunConfig& config, const MpiContext& mpi, std::unique_ptr<envs::Env> env)
    : config_(checked_offline(config, mpi)),
      mpi_(mpi),
      env_(std::move(env)),
      costs_(config),
      dataset_(read_run_dataset(config_, *env_)) {
  const ReturnRanges ranges = return_ranges(dataset_episodes(dataset_));
  min_episode_reward_ = reward_constant(dataset_, "min_episode_reward", ranges.min_episode_reward);
  max_episode_reward_ = reward_constant(dataset_, "max_episode_reward", ranges.max_episode_reward);
  if (!(max_episode_reward_ > min_episode_reward_)) {
    throw std::invalid_argument("dataset " + config_.offline.dataset + ": its episode rewards span no range (min " +
                                std::to_string(min_episode_reward_) + ", max " + std::to_string(max_episode_reward_) +
                                "), so DSRL's normalised reward is undefined");
  }
  batches_.emplace(dataset_, offline_training_rows(config_, dataset_), config_.off_policy.batch_size);
  Rng init_rng(stream_seed(config_, SeedStream::network_init, 0));
  algorithm_ = make_offline_algorithm(config_, dataset_.observation_dim, dataset_.action_dim, batches_->scaling(),
                                      init_rng, batches_->statistics());
}

OfflineFamily::~OfflineFamily() = default;

TrainingProgress load_offline_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                         OfflineAlgorithm& algorithm) {
  const CheckpointContents contents = read_checkpoint_contents(path);
  BinaryReader reader(contents.payload, path.string());
  TrainingProgress progress = read_run_header(reader, RunHeaderLayout::offline, config, contents.format_version);
  progress.training_cost = load_training_cost(reader, constraint_count(config));
  algorithm.load(reader);
  reader.expect_end();
  return progress;
}

TrainingProgress OfflineFamily::load_checkpoint(const std::filesystem::path& path) {
  return load_offline_checkpoint(path, config_, *algorithm_);
}

void OfflineFamily::save_checkpoint(const std::filesystem::path& path, const TrainingProgress& progress) {
  if (!mpi_.is_root()) return;  // one rank (check_run_config_for_ranks)
  BinaryWriter writer;
  write_run_header(writer, RunHeaderLayout::offline, config_, progress);
  save_training_cost(progress.training_cost, writer);
  algorithm_->save(writer);
  write_checkpoint_file(path, writer.bytes());
}

FamilyEpoch OfflineFamily::run_epoch(int epoch, bool /*checkpoint_follows: nothing to cut*/) {
  const auto update_start = Clock::now();
  sample_rng_.seed(stream_seed(config_, SeedStream::minibatch_shuffle, static_cast<std::uint64_t>(epoch)));
  double loss_sum = 0.0;
  for (int u = 0; u < config_.offline.updates_per_epoch; ++u) {
    batches_->sample(sample_rng_, batch_);
    loss_sum += algorithm_->update(batch_, sample_rng_);
  }
  loss_ = loss_sum / config_.offline.updates_per_epoch;
  check_finite(epoch, "behaviour-cloning loss", loss_);
  update_seconds_ = seconds_since(update_start);

  const bool evaluates = config_.eval_episodes > 0 &&
                         ((epoch + 1) % config_.offline.eval_every == 0 || epoch + 1 == config_.epochs);
  evaluation_.reset();
  if (evaluates) evaluation_ = evaluate_epoch();

  FamilyEpoch result;
  const int m = constraint_count(config_);
  result.epoch_cost = 0.0;  // no environment step while learning
  result.epoch_constraint_costs = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < m; ++i) result.constraints.push_back({kNone, constraint_limit(config_, i)});
  result.timings.policy_update_seconds = result.timings.update_seconds = update_seconds_;
  result.line.mean_return = evaluation_ ? evaluation_->mean_return : kNone;
  result.line.mean_cost = evaluation_ ? evaluation_->mean_cost : kNone;
  if (!ignores_cost(config_.alg)) result.line.cost_limit = config_.cost_limit;
  result.line.kl = kNone;
  return result;
}

OfflineEpochEvaluation OfflineFamily::evaluate_epoch() {
  const EvaluationSummary summary = evaluate(0);
  OfflineEpochEvaluation scored;
  scored.mean_return = summary.mean_return;
  scored.mean_cost = summary.mean_cost;
  scored.mean_length = summary.mean_length;
  const NormalizedScore score = normalized_score(summary.mean_return, summary.mean_cost, config_.cost_limit,
                                                 min_episode_reward_, max_episode_reward_);
  scored.normalized_reward = score.reward;
  scored.normalized_cost = score.cost;
  return scored;
}

std::vector<NamedScalar> OfflineFamily::progress_row(const EpochAccounts& accounts) {
  return offline_log_entries(config_, &accounts, loss_, evaluation_, update_seconds_);
}

std::vector<std::string> OfflineFamily::progress_columns() const {
  return names_of(offline_log_entries(config_, nullptr, 0.0, std::nullopt, 0.0));
}

// The policy's action (both modes act alike) on eval_episodes episodes seeded as every family's.
EvaluationSummary OfflineFamily::evaluate(int /*epochs_completed*/) {
  return evaluate_policy(*env_, algorithm_->acting(), config_.eval_episodes, config_.seed, config_.max_ep_len, mpi_,
                         costs_, env_->spec().cost_term_names, ActionMode::mean);
}

}  // namespace bsg::algos
