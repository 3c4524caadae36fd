// What both multi-agent environments share (docs/multi_agent.md): the
// preallocated per-agent buffers a step writes (observations, rewards, costs,
// cost terms, the global state) with the spans the face hands out, and the
// check of the agents' actions. Nothing here allocates on the step path.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "envs/multi_agent_env.h"

namespace bsg::envs {

class MultiAgentBuffers {
 public:
  // Sizes every buffer from the spec (observation_dims, state_dim,
  // cost_term_names); `spec` must outlive the buffers (its term names are viewed).
  explicit MultiAgentBuffers(const MultiAgentSpec& spec);
  MultiAgentBuffers(const MultiAgentBuffers&) = delete;
  MultiAgentBuffers& operator=(const MultiAgentBuffers&) = delete;

  std::span<double> observation(int agent) { return writable_observations_[agent]; }
  std::span<double> state() { return state_; }
  std::span<CostTerm> cost_terms(int agent) { return writable_terms_[agent]; }
  std::vector<double>& rewards() { return rewards_; }
  std::vector<double>& costs() { return costs_; }

  std::span<const std::span<const double>> observations() const { return observations_; }
  std::span<const double> global_state() const { return state_; }
  // The step's result over these buffers with the team's episode end.
  MultiAgentStepResult result(bool terminated, bool truncated) const;

 private:
  std::vector<double> observation_values_;
  std::vector<std::span<double>> writable_observations_;
  std::vector<std::span<const double>> observations_;
  std::vector<double> state_;
  std::vector<double> rewards_;
  std::vector<double> costs_;
  std::vector<CostTerm> term_values_;
  std::vector<std::span<CostTerm>> writable_terms_;
  std::vector<std::span<const CostTerm>> terms_;
};

// Throws std::logic_error before the first reset, std::invalid_argument
// naming the agent for a wrong number of actions, a wrong size or a
// non-finite entry.
void check_multi_agent_actions(const MultiAgentSpec& spec, bool has_reset,
                               std::span<const std::span<const double>> actions);

}  // namespace bsg::envs
