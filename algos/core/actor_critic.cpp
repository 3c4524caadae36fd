#include "algos/core/actor_critic.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "algos/core/network_checkpoint.h"
#include "common/adam.h"

namespace bsg::algos {
namespace {

MlpOptions init_options(const RunConfig& config) {
  return MlpOptions{.zero_bias_init = config.zero_bias_init, .dtype = config.dtype, .activation = config.activation};
}

AdamOptions value_adam_options(const RunConfig& config) {
  AdamOptions options;
  options.learning_rate = config.vf_lr;
  return options;
}

RunningMeanStdOptions observation_normalizer_options(const RunConfig& config) {
  RunningMeanStdOptions options;
  options.exact_parallel_variance = config.exact_parallel_variance;
  options.clip = config.obs_clip;
  return options;
}

RunningMeanStdOptions return_normalizer_options(const RunConfig& config) {
  RunningMeanStdOptions options;
  options.exact_parallel_variance = config.exact_parallel_variance;
  return options;
}

int value_input_size_of(int observation_size, const RunConfig& config) {
  return observation_size + (config.value_time_input ? 1 : 0);
}

// (T - t)/T: 1 at a reset, 1/T on the last step before a time-out, 0 at the
// time-out's bootstrap observation.
double time_left_fraction(int episode_step, int time_limit) {
  return static_cast<double>(time_limit - episode_step) / static_cast<double>(time_limit);
}

void broadcast_value_function(ValueFunction& value, const MpiContext& mpi) {
  mpi.broadcast_from_root(value.net().mutable_parameters());
}

void broadcast_normalizer(RunningMeanStd& normalizer, const MpiContext& mpi) { normalizer.broadcast_from_root(mpi); }

}  // namespace

ActorCritic::ActorCritic(int observation_size, int action_size, const RunConfig& config, Rng& init_rng)
    : policy(observation_size, action_size, config.hidden_sizes, init_rng, init_options(config)),
      value(value_input_size_of(observation_size, config), config.hidden_sizes, init_rng, init_options(config),
            value_adam_options(config)),
      cost_value(value_input_size_of(observation_size, config), config.hidden_sizes, init_rng, init_options(config),
                 value_adam_options(config)),
      observation_normalizer(observation_size, observation_normalizer_options(config)),
      return_normalizer(1, return_normalizer_options(config)),
      standardize_observations(config.use_standardized_obs),
      value_time_limit(config.value_time_input ? config.max_ep_len : 0) {
  if (config.value_time_input && config.max_ep_len <= 0) {
    throw std::invalid_argument("value_time_input needs a positive max_ep_len, got " +
                                std::to_string(config.max_ep_len));
  }
  const int constraints = std::max<int>(1, static_cast<int>(config.constraints.size()));
  extra_cost_values.reserve(static_cast<std::size_t>(constraints - 1));
  for (int i = 1; i < constraints; ++i) {
    extra_cost_values.emplace_back(value_input_size_of(observation_size, config), config.hidden_sizes, init_rng,
                                   init_options(config), value_adam_options(config));
  }
  // docs/algorithms.md#learned-log-sigma
  if (config.first_order.learn_log_std) policy.learn_log_std(config.first_order.learned_std_init);
}

void ActorCritic::value_input(const Eigen::Ref<const Eigen::VectorXd>& normalized, int episode_step,
                              Eigen::Ref<Eigen::VectorXd> input) const {
  const Eigen::Index d = normalized.size();
  input.head(d) = normalized;
  if (value_time_limit > 0) input[d] = time_left_fraction(episode_step, value_time_limit);
}

void ActorCritic::value_inputs(const Eigen::Ref<const Eigen::MatrixXd>& normalized,
                               const Eigen::Ref<const Eigen::VectorXi>& episode_steps,
                               Eigen::Ref<Eigen::MatrixXd> inputs) const {
  const Eigen::Index d = normalized.cols();
  inputs.leftCols(d) = normalized;
  if (value_time_limit > 0) {
    for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
      inputs(i, d) = time_left_fraction(episode_steps[i], value_time_limit);
    }
  }
}

void ActorCritic::normalize_observation(const Eigen::Ref<const Eigen::VectorXd>& raw,
                                        Eigen::Ref<Eigen::VectorXd> normalized) const {
  if (standardize_observations) {
    observation_normalizer.normalize(raw, normalized);
  } else {
    normalized = raw;
  }
}

void ActorCritic::normalize_observations(const Eigen::Ref<const Eigen::MatrixXd>& raw,
                                         Eigen::Ref<Eigen::MatrixXd> normalized) const {
  if (standardize_observations) {
    observation_normalizer.normalize_batch(raw, normalized);
  } else {
    normalized = raw;
  }
}

void ActorCritic::broadcast_from_root(const MpiContext& mpi) {
  mpi.broadcast_from_root(policy.mean_net().mutable_parameters());
  broadcast_value_function(value, mpi);
  broadcast_value_function(cost_value, mpi);
  for (ValueFunction& extra : extra_cost_values) broadcast_value_function(extra, mpi);
  broadcast_normalizer(observation_normalizer, mpi);
  broadcast_normalizer(return_normalizer, mpi);
}

double ActorCritic::parameter_sum() const {
  double sum = policy.mean_net().parameters().sum() + value.net().parameters().sum() +
               cost_value.net().parameters().sum();
  for (const ValueFunction& extra : extra_cost_values) sum += extra.net().parameters().sum();
  return sum;
}

const char* ActorCritic::first_non_finite() const {
  if (!policy.mean_net().parameters().allFinite()) return "policy parameters";
  if (!policy.log_stds().allFinite()) return "policy log sigma";
  if (!value.net().parameters().allFinite()) return "value-net parameters";
  if (!cost_value.net().parameters().allFinite()) return "cost value-net parameters";
  if (!value.optimizer().first_moment().allFinite() || !value.optimizer().second_moment().allFinite()) {
    return "value-net Adam moments";
  }
  if (!cost_value.optimizer().first_moment().allFinite() || !cost_value.optimizer().second_moment().allFinite()) {
    return "cost value-net Adam moments";
  }
  for (const ValueFunction& extra : extra_cost_values) {
    if (!extra.net().parameters().allFinite()) return "cost value-net parameters (constraints 2..m)";
    if (!extra.optimizer().first_moment().allFinite() || !extra.optimizer().second_moment().allFinite()) {
      return "cost value-net Adam moments (constraints 2..m)";
    }
  }
  if (!observation_normalizer.mean().allFinite() || !observation_normalizer.std().allFinite()) {
    return "observation normaliser";
  }
  if (!return_normalizer.mean().allFinite() || !return_normalizer.std().allFinite()) return "return normaliser";
  return "";
}

void ActorCritic::save(BinaryWriter& writer) const {
  writer.write_section("policy");
  writer.write_vector(policy.mean_net().parameters());
  writer.write_section("value net");
  save_value_function(value, writer);
  writer.write_section("cost value net");
  save_value_function(cost_value, writer);
  writer.write_section("observation normaliser");
  save_normalizer(observation_normalizer, writer);
  writer.write_section("return normaliser");
  save_normalizer(return_normalizer, writer);
  // Only with several constraints, so that a one-constraint checkpoint is unchanged.
  for (std::size_t i = 0; i < extra_cost_values.size(); ++i) {
    writer.write_section("cost value net " + std::to_string(i + 2));
    save_value_function(extra_cost_values[i], writer);
  }
  // Only with a learned log sigma, so that a checkpoint of the annealed sigma is unchanged.
  if (policy.has_learned_std()) {
    writer.write_section("policy log sigma");
    writer.write_vector(policy.log_stds());
  }
}

void ActorCritic::load(BinaryReader& reader) {
  reader.expect_section("policy");
  policy.mean_net().set_parameters(reader.read_vector("policy parameters", policy.mean_net().num_parameters()));
  reader.expect_section("value net");
  load_value_function(value, reader, "value-net");
  reader.expect_section("cost value net");
  load_value_function(cost_value, reader, "cost value-net");
  reader.expect_section("observation normaliser");
  load_normalizer(observation_normalizer, reader, "observation normaliser");
  reader.expect_section("return normaliser");
  load_normalizer(return_normalizer, reader, "return normaliser");
  for (std::size_t i = 0; i < extra_cost_values.size(); ++i) {
    const std::string name = "cost value net " + std::to_string(i + 2);
    reader.expect_section(name);
    load_value_function(extra_cost_values[i], reader, name);
  }
  if (policy.has_learned_std()) {
    reader.expect_section("policy log sigma");
    policy.set_log_stds(reader.read_vector("policy log sigma", policy.action_size()));
  }
}

}  // namespace bsg::algos
