#include "algos/multi_agent/multi_agent_networks.h"

#include <stdexcept>
#include <string>

#include "algos/core/network_checkpoint.h"
#include "algos/multi_agent/agent_id_input.h"
#include "common/adam.h"

namespace bsg::algos {
namespace {

MlpOptions init_options(const RunConfig& config) {
  return MlpOptions{.zero_bias_init = config.zero_bias_init, .dtype = config.dtype, .activation = config.activation};
}

RunningMeanStdOptions normalizer_options(const RunConfig& config) {
  return RunningMeanStdOptions{.exact_parallel_variance = config.exact_parallel_variance, .clip = config.obs_clip};
}

const MultiAgentSizes& checked(const MultiAgentSizes& sizes, bool share) {
  const std::size_t n = sizes.observation_dims.size();
  if (n == 0 || sizes.action_dims.size() != n || sizes.state_dim <= 0) {
    throw std::invalid_argument("multi-agent networks: " + std::to_string(n) + " observation sizes, " +
                                std::to_string(sizes.action_dims.size()) + " action sizes and a state of " +
                                std::to_string(sizes.state_dim));
  }
  for (std::size_t i = 1; share && i < n; ++i) {
    if (sizes.observation_dims[i] != sizes.observation_dims[0] || sizes.action_dims[i] != sizes.action_dims[0]) {
      throw std::invalid_argument("share_policy: true needs equal observation and action sizes, but agent_" +
                                  std::to_string(i) + " has " + std::to_string(sizes.observation_dims[i]) + " and " +
                                  std::to_string(sizes.action_dims[i]) + ", agent_0 " +
                                  std::to_string(sizes.observation_dims[0]) + " and " +
                                  std::to_string(sizes.action_dims[0]) + " (set share_policy: false)");
    }
  }
  return sizes;
}

}  // namespace

MultiAgentNetworks::MultiAgentNetworks(const MultiAgentSizes& sizes, const RunConfig& config, bool cost_critics,
                                       Rng& init_rng)
    : state_normalizer_(checked(sizes, config.multi_agent.share_policy).state_dim, normalizer_options(config)),
      standardize_(config.use_standardized_obs),
      state_dim_(sizes.state_dim),
      id_width_(agent_id_width(config.multi_agent.share_policy, static_cast<int>(sizes.observation_dims.size()))) {
  const int n = static_cast<int>(sizes.observation_dims.size());
  const int slots = shared() ? 1 : n;
  AdamOptions critic_adam;
  critic_adam.learning_rate = config.vf_lr;
  slots_.reserve(static_cast<std::size_t>(slots));
  for (int s = 0; s < slots; ++s) {
    const int observation_dim = sizes.observation_dims[static_cast<std::size_t>(s)];
    GaussianPolicy policy(observation_dim + id_width_, sizes.action_dims[static_cast<std::size_t>(s)],
                          config.hidden_sizes, init_rng, init_options(config));
    policy.learn_log_std(config.first_order.learned_std_init);
    ValueFunction value(critic_input_size(), config.hidden_sizes, init_rng, init_options(config), critic_adam);
    std::optional<ValueFunction> cost_value;
    if (cost_critics) cost_value.emplace(critic_input_size(), config.hidden_sizes, init_rng, init_options(config), critic_adam);
    std::vector<int> agents;
    if (shared()) {
      for (int i = 0; i < n; ++i) agents.push_back(i);
    } else {
      agents.push_back(s);
    }
    slots_.push_back(AgentSlot{std::move(policy), RunningMeanStd(observation_dim, normalizer_options(config)),
                               std::move(value), std::move(cost_value), std::move(agents)});
  }
  for (int i = 0; i < n; ++i) slot_of_agent_.push_back(shared() ? 0 : i);
}

int MultiAgentNetworks::policy_input_size(int agent) const { return slot_of_agent(agent).policy.observation_size(); }

void MultiAgentNetworks::policy_input(int agent, const Eigen::Ref<const Eigen::VectorXd>& observation,
                                      Eigen::Ref<Eigen::VectorXd> input) const {
  const RunningMeanStd& normalizer = slot_of_agent(agent).observation_normalizer;
  Eigen::VectorXd normalized = observation;
  if (standardize_) normalizer.normalize(observation, normalized);
  write_agent_input(normalized, agent, id_width_, input);
}

void MultiAgentNetworks::policy_inputs(int agent, const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                       Eigen::MatrixXd& inputs) const {
  const RunningMeanStd& normalizer = slot_of_agent(agent).observation_normalizer;
  Eigen::MatrixXd normalized = observations;
  if (standardize_) normalizer.normalize_batch(observations, normalized);
  inputs.resize(observations.rows(), observations.cols() + id_width_);
  write_agent_inputs(normalized, agent, id_width_, inputs);
}

void MultiAgentNetworks::critic_input(int agent, const Eigen::Ref<const Eigen::VectorXd>& state,
                                      Eigen::Ref<Eigen::VectorXd> input) const {
  Eigen::VectorXd normalized = state;
  if (standardize_) state_normalizer_.normalize(state, normalized);
  write_agent_input(normalized, agent, id_width_, input);
}

void MultiAgentNetworks::critic_inputs(int agent, const Eigen::Ref<const Eigen::MatrixXd>& states,
                                       Eigen::MatrixXd& inputs) const {
  Eigen::MatrixXd normalized = states;
  if (standardize_) state_normalizer_.normalize_batch(states, normalized);
  inputs.resize(states.rows(), states.cols() + id_width_);
  write_agent_inputs(normalized, agent, id_width_, inputs);
}

void MultiAgentNetworks::broadcast_from_root(const MpiContext& mpi) {
  for (AgentSlot& slot : slots_) {
    mpi.broadcast_from_root(slot.policy.mean_net().mutable_parameters());
    Eigen::VectorXd log_stds = slot.policy.log_stds();
    mpi.broadcast_from_root(log_stds);
    slot.policy.set_log_stds(log_stds);
    mpi.broadcast_from_root(slot.value.net().mutable_parameters());
    if (slot.cost_value) mpi.broadcast_from_root(slot.cost_value->net().mutable_parameters());
    slot.observation_normalizer.broadcast_from_root(mpi);
  }
  state_normalizer_.broadcast_from_root(mpi);
}

double MultiAgentNetworks::parameter_sum() const {
  double sum = 0.0;
  for (const AgentSlot& slot : slots_) {
    sum += slot.policy.mean_net().parameters().sum() + slot.policy.log_stds().sum() + slot.value.net().parameters().sum();
    if (slot.cost_value) sum += slot.cost_value->net().parameters().sum();
  }
  return sum;
}

const char* MultiAgentNetworks::first_non_finite() const {
  for (const AgentSlot& slot : slots_) {
    if (!slot.policy.mean_net().parameters().allFinite()) return "policy parameter";
    if (!slot.policy.log_stds().allFinite()) return "policy log sigma";
    if (!slot.value.net().parameters().allFinite()) return "value-net parameter";
    if (slot.cost_value && !slot.cost_value->net().parameters().allFinite()) return "cost value-net parameter";
  }
  return "";
}

void MultiAgentNetworks::save(BinaryWriter& writer) const {
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    const AgentSlot& slot = slots_[s];
    writer.write_section("policy slot " + std::to_string(s));
    writer.write_vector(slot.policy.mean_net().parameters());
    writer.write_vector(slot.policy.log_stds());
    save_value_function(slot.value, writer);
    if (slot.cost_value) save_value_function(*slot.cost_value, writer);
    save_normalizer(slot.observation_normalizer, writer);
  }
  writer.write_section("state normaliser");
  save_normalizer(state_normalizer_, writer);
}

void MultiAgentNetworks::load(BinaryReader& reader) {
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    AgentSlot& slot = slots_[s];
    const std::string name = "policy slot " + std::to_string(s);
    reader.expect_section(name);
    slot.policy.mean_net().set_parameters(reader.read_vector(name + " parameters", slot.policy.mean_net().num_parameters()));
    slot.policy.set_log_stds(reader.read_vector(name + " log sigma", slot.policy.action_size()));
    load_value_function(slot.value, reader, name + " value-net");
    if (slot.cost_value) load_value_function(*slot.cost_value, reader, name + " cost value-net");
    load_normalizer(slot.observation_normalizer, reader, name + " observation normaliser");
  }
  reader.expect_section("state normaliser");
  load_normalizer(state_normalizer_, reader, "state normaliser");
}

}  // namespace bsg::algos
