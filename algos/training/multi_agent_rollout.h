// One epoch of a multi-agent learner's data on one rank (docs/multi_agent.md#learners): every agent
// acts with its slot's actor at each step, the critics of its slot value the global state, and each
// agent's step goes into its own Buffer (algos/core/buffer.h), whose finish_path computes that
// agent's GAE for reward and cost with its V(s) and V_C(s) (SafePO's SeparatedReplayBuffer: one
// buffer per agent). The team shares its episodes: at a termination every agent's path ends
// without bootstrap; at a time-out (truncation or max_ep_len; timeout_bootstrap) and at the epoch
// cut each agent bootstraps with its critics at the next global state. Every epoch starts with a
// reset seeded for the epoch; later episodes continue the environment's stream.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "algos/core/buffer.h"
#include "algos/multi_agent/multi_agent_networks.h"
#include "common/mlp.h"
#include "common/random.h"
#include "envs/multi_agent_env.h"

namespace bsg::algos {

struct MultiAgentRolloutOptions {
  int local_steps = 0;  // N, this rank's team steps per epoch
  int max_ep_len = 0;
  bool timeout_bootstrap = true;
};

class MultiAgentRollout {
 public:
  MultiAgentRollout(const envs::MultiAgentSpec& spec, const MultiAgentRolloutOptions& options,
                    const BufferOptions& buffer_options);

  // Fills every agent's buffer and the states of this epoch.
  void collect(envs::MultiAgentEnv& env, std::uint64_t epoch_env_seed, const MultiAgentNetworks& networks, Rng& noise);

  int agent_count() const { return static_cast<int>(buffers_.size()); }
  const Buffer& buffer(int agent) const { return buffers_.at(static_cast<std::size_t>(agent)); }
  const Eigen::MatrixXd& states() const { return states_; }  // N x state_dim, raw s_t
  // The agents' mean cost summed over the epoch's steps (the team's training cost per agent).
  double epoch_cost() const;

 private:
  // V and V_C of every agent at the environment's current global state.
  void predict_values(const MultiAgentNetworks& networks);

  MultiAgentRolloutOptions options_;
  std::vector<Buffer> buffers_;
  Eigen::MatrixXd states_;
  std::vector<Eigen::VectorXd> observations_;  // o_t per agent, raw
  std::vector<Eigen::VectorXd> actions_;
  std::vector<Eigen::VectorXd> policy_inputs_;
  Eigen::VectorXd state_;
  Eigen::VectorXd critic_input_;
  Eigen::VectorXd values_, cost_values_;
  MlpSampleWorkspace workspace_;
};

}  // namespace bsg::algos
