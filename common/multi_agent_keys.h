// MultiAgentKeys: the keys of the multi-agent family alone (mappo, mappo-lag, happo, macpo;
// algos/multi_agent, docs/multi_agent.md#learners). RunConfig holds them as `multi_agent`; their
// rows are in multi_agent_keys.cpp. The family also reads keys it shares with others (actor_lr,
// update_iters, policy_minibatch_size, max_grad_norm, clip but not for macpo; learned_std_init; lam,
// lam_c, vf_lr, train_v_iterations, num_mini_batches; the multipliers' of mappo-lag; the trust-region
// keys of CPO's step for macpo).
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml): share_policy = false (SafePO's mappo.py and mappolag.py keep
// one actor and one pair of critics per agent; happo and macpo refuse true).
#pragma once

namespace bsg {

struct MultiAgentKeys {
  // One actor and one pair of critics for all agents, each input with the agent's one-hot id
  // appended (needs equal observation sizes); false: one of each per agent.
  bool share_policy = false;

  bool operator==(const MultiAgentKeys&) const = default;
};

}  // namespace bsg
