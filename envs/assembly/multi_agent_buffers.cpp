#include "envs/assembly/multi_agent_buffers.h"

#include <cmath>
#include <stdexcept>

namespace bsg::envs {

MultiAgentBuffers::MultiAgentBuffers(const MultiAgentSpec& spec)
    : state_(static_cast<size_t>(spec.state_dim), 0.0),
      rewards_(static_cast<size_t>(spec.agent_count()), 0.0),
      costs_(static_cast<size_t>(spec.agent_count()), 0.0) {
  const auto agents = static_cast<size_t>(spec.agent_count());
  size_t total = 0;
  for (const int dim : spec.observation_dims) total += static_cast<size_t>(dim);
  observation_values_.assign(total, 0.0);
  const size_t terms_per_agent = spec.cost_term_names.size();
  term_values_.reserve(agents * terms_per_agent);
  for (size_t i = 0; i < agents; ++i) {
    for (const std::string& name : spec.cost_term_names) term_values_.push_back(CostTerm{name, 0});
  }
  size_t offset = 0;
  for (size_t i = 0; i < agents; ++i) {
    const auto dim = static_cast<size_t>(spec.observation_dims[i]);
    writable_observations_.emplace_back(observation_values_.data() + offset, dim);
    observations_.emplace_back(observation_values_.data() + offset, dim);
    offset += dim;
    writable_terms_.emplace_back(term_values_.data() + i * terms_per_agent, terms_per_agent);
    terms_.emplace_back(term_values_.data() + i * terms_per_agent, terms_per_agent);
  }
}

MultiAgentStepResult MultiAgentBuffers::result(bool terminated, bool truncated) const {
  MultiAgentStepResult result;
  result.observations = observations_;
  result.rewards = rewards_;
  result.costs = costs_;
  result.cost_terms = terms_;
  result.terminated = terminated;
  result.truncated = truncated;
  return result;
}

void check_multi_agent_actions(const MultiAgentSpec& spec, bool has_reset,
                               std::span<const std::span<const double>> actions) {
  if (!has_reset) throw std::logic_error(spec.id + ": step() called before reset()");
  if (actions.size() != static_cast<size_t>(spec.agent_count())) {
    throw std::invalid_argument(spec.id + ": " + std::to_string(actions.size()) +
                                " actions, expected one per agent (" +
                                std::to_string(spec.agent_count()) + ")");
  }
  for (size_t agent = 0; agent < actions.size(); ++agent) {
    const std::span<const double> action = actions[agent];
    if (action.size() != static_cast<size_t>(spec.action_dims[agent])) {
      throw std::invalid_argument(spec.id + ": " + spec.agent_names[agent] + "'s action has " +
                                  std::to_string(action.size()) + " entries, expected " +
                                  std::to_string(spec.action_dims[agent]));
    }
    for (size_t i = 0; i < action.size(); ++i) {
      if (!std::isfinite(action[i])) {
        throw std::invalid_argument(spec.id + ": " + spec.agent_names[agent] + "'s action entry " +
                                    std::to_string(i) + " is not finite (" +
                                    std::to_string(action[i]) + ")");
      }
    }
  }
}

}  // namespace bsg::envs
