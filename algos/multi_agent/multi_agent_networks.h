// The networks of a multi-agent learner (docs/multi_agent.md#learners): for every policy slot a
// Gaussian actor on the agent's own observation and centralised critics V(s) and, for a
// constrained learner, V_C(s) on the environment's global state (MAPPO's centralised training
// with decentralised execution; SafePO's MultiAgentActor and MultiAgentCritic). Without sharing
// there is one slot per agent (SafePO's mappo.py and mappolag.py); with share_policy one slot
// serves every agent, whose inputs then end in the agent's one-hot id (agent_id_input.h).
// Observation and state normalisers (use_standardized_obs): one per slot for the observations
// (over all of its agents' rows), one for the global state.
//
// Initialisation: per slot in order, actor, V, V_C from `init_rng`; the actor's log sigma is
// learned from learned_std_init. Later sequential updates (HAPPO, MACPO) step the slots one agent
// at a time: each slot is its own object, reachable by index.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "algos/core/gaussian_policy.h"
#include "algos/core/value_function.h"
#include "common/binary_io.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"
#include "common/running_mean_std.h"

namespace bsg::algos {

struct MultiAgentSizes {
  std::vector<int> observation_dims;  // per agent
  std::vector<int> action_dims;       // per agent
  int state_dim = 0;                  // the global state's
};

// One actor and its critics, serving one agent or all of them.
struct AgentSlot {
  GaussianPolicy policy;
  RunningMeanStd observation_normalizer;
  ValueFunction value;                      // V(s)
  std::optional<ValueFunction> cost_value;  // V_C(s), constrained learners only
  std::vector<int> agents;                  // the agents it serves, in order
};

class MultiAgentNetworks {
 public:
  // Throws std::invalid_argument naming what does not fit: no agents, sizes of different counts, or
  // share_policy with unequal observation or action sizes.
  MultiAgentNetworks(const MultiAgentSizes& sizes, const RunConfig& config, bool cost_critics, Rng& init_rng);

  int agent_count() const { return static_cast<int>(slot_of_agent_.size()); }
  int slot_count() const { return static_cast<int>(slots_.size()); }
  bool shared() const { return id_width_ > 0; }
  int slot_of(int agent) const { return slot_of_agent_.at(static_cast<std::size_t>(agent)); }
  AgentSlot& slot(int index) { return slots_.at(static_cast<std::size_t>(index)); }
  const AgentSlot& slot(int index) const { return slots_.at(static_cast<std::size_t>(index)); }
  AgentSlot& slot_of_agent(int agent) { return slot(slot_of(agent)); }
  const AgentSlot& slot_of_agent(int agent) const { return slot(slot_of(agent)); }
  RunningMeanStd& state_normalizer() { return state_normalizer_; }
  bool has_cost_critics() const { return slots_.front().cost_value.has_value(); }

  int policy_input_size(int agent) const;
  int critic_input_size() const { return state_dim_ + id_width_; }

  // The actor's input of `agent`: its normalised observation, then its id if shared.
  void policy_input(int agent, const Eigen::Ref<const Eigen::VectorXd>& observation,
                    Eigen::Ref<Eigen::VectorXd> input) const;
  void policy_inputs(int agent, const Eigen::Ref<const Eigen::MatrixXd>& observations, Eigen::MatrixXd& inputs) const;
  // The critics' input for `agent`: the normalised global state, then its id if shared.
  void critic_input(int agent, const Eigen::Ref<const Eigen::VectorXd>& state, Eigen::Ref<Eigen::VectorXd> input) const;
  void critic_inputs(int agent, const Eigen::Ref<const Eigen::MatrixXd>& states, Eigen::MatrixXd& inputs) const;

  // Every parameter and normaliser from rank 0 (a new run starts alike on every rank).
  void broadcast_from_root(const MpiContext& mpi);
  double parameter_sum() const;
  // The first non-finite network parameter's owner ("" if none).
  const char* first_non_finite() const;

  // Every slot's actor (mean net and log sigma), critics with their Adam states, normalisers.
  void save(BinaryWriter& writer) const;
  void load(BinaryReader& reader);

 private:
  std::vector<AgentSlot> slots_;
  std::vector<int> slot_of_agent_;
  RunningMeanStd state_normalizer_;
  bool standardize_;
  int state_dim_;
  int id_width_;
};

}  // namespace bsg::algos
