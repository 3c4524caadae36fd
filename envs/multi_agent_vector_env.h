// N copies of one multi-agent environment (envs/multi_agent_env.h) stepped
// together on the pool of threads VectorEnv uses (envs/worker_pool.h), with
// the results in batched buffers shaped for learners that run one policy per
// agent over a batch of environments (SafePO's ShareVecEnv for MAPPO-L and
// MACPO: observations [env][agent][obs], the global state [env][state],
// rewards and costs [env][agent], one team end per environment).
//
// Layout. An agent's observations, final observations and actions are one
// array of its own, N x observation_dims[agent] (N x action_dims[agent]) row
// major, because agents may differ in size; nothing is padded. Rewards and
// costs are N x agents, cost terms N x agents x cost_term_names.size(), the
// global state N x state_dim, the team's flags N.
//
// Parameters:
//   id or description  a registered multi-agent id or any MultiAgentDescription
//                      (its robot's max_episode_steps sets the team's truncation)
//   num_envs           N >= 1
//   num_threads        worker threads including the caller; 0 (default): the
//                      machine's hardware threads, at most N
//   options            EnvOptions passed to every environment
//
// Auto-reset: an environment whose team episode ended (terminated or
// truncated) is reset in the step that ended it, continuing its own random
// stream (MultiAgentEnv::reset()), as VectorEnv's default and SafePO's
// ShareVecEnv do; observations() and states() then hold the new episode's
// first ones, while final_observations() and final_states() hold what the step
// itself produced (for every environment, ended or not).
//
// Seeding: reset(seed) resets environment i with seed + i, so environment i of
// a new MultiAgentVectorEnv plays exactly what a new MultiAgentEnv reset with
// seed + i plays under the same actions; restart(seed) gives the same episodes
// from environments that have played before (it rebuilds them). Each
// environment is touched by one thread at a time and environments share
// nothing, so results are bit-identical whatever num_threads is.
//
// Threading: the MultiAgentVectorEnv itself is not thread-safe; call it from
// one thread. Spans are views into its buffers, valid until the next call.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/multi_agent_env.h"

namespace bsg::envs {

class WorkerPool;

class MultiAgentVectorEnv {
 public:
  // Throws std::invalid_argument for an unknown id (listing the multi-agent
  // ids), a bad description, num_envs < 1 or num_threads < 0.
  MultiAgentVectorEnv(const std::string& id, int num_envs, int num_threads = 0,
                      const EnvOptions& options = {});
  MultiAgentVectorEnv(const MultiAgentDescription& description, int num_envs,
                      int num_threads = 0, const EnvOptions& options = {});
  ~MultiAgentVectorEnv();
  MultiAgentVectorEnv(const MultiAgentVectorEnv&) = delete;
  MultiAgentVectorEnv& operator=(const MultiAgentVectorEnv&) = delete;

  const MultiAgentSpec& spec() const { return spec_; }
  int num_envs() const { return num_envs_; }
  int num_threads() const { return num_threads_; }
  int agent_count() const { return agents_; }

  // Resets environment i with seed + i.
  void reset(std::uint64_t seed);
  // Resets every environment, continuing its random stream.
  void reset();
  // As reset(seed), after rebuilding every environment reset since it was
  // built: the episodes of a new MultiAgentVectorEnv reset with `seed`.
  void restart(std::uint64_t seed);

  // Steps every environment: actions[agent] is that agent's N x
  // action_dims[agent] array, row i for environment i. Throws
  // std::invalid_argument for a wrong number of arrays, a wrong size or a
  // non-finite entry, naming the agent (and environment), before anything is
  // stepped; std::logic_error before the first reset.
  void step(std::span<const std::span<const double>> actions);

  // Buffers of the last reset()/step().
  std::span<const double> observations(int agent) const;        // N x observation_dims[agent]
  std::span<const double> final_observations(int agent) const;  // N x observation_dims[agent]
  std::span<const double> states() const { return states_; }    // N x state_dim
  std::span<const double> final_states() const { return final_states_; }  // N x state_dim
  std::span<const double> rewards() const { return rewards_; }  // N x agents
  std::span<const double> costs() const { return costs_; }      // N x agents
  // N x agents x spec().cost_term_names.size().
  std::span<const double> cost_terms() const { return cost_terms_; }
  std::span<const std::uint8_t> terminated() const { return terminated_; }  // N, the team's
  std::span<const std::uint8_t> truncated() const { return truncated_; }    // N, the team's

 private:
  void check_actions(std::span<const std::span<const double>> actions);
  void reset_one(int index, const std::uint64_t* seed);
  void step_one(int index);
  // Copies environment index's observations and state into the row of
  // `observations` (one buffer per agent) and `states`.
  void write_row(int index, std::span<const std::span<const double>> agent_observations,
                 std::span<const double> state, std::vector<std::vector<double>>& observations,
                 std::vector<double>& states);

  MultiAgentDescription description_;
  EnvOptions options_;
  std::vector<std::unique_ptr<MultiAgentEnv>> envs_;
  MultiAgentSpec spec_;
  int num_envs_;
  int num_threads_;
  int agents_;
  bool has_reset_ = false;
  std::vector<std::uint8_t> used_;  // reset since built: restart() rebuilds it

  std::vector<std::vector<double>> observations_;  // one buffer per agent
  std::vector<std::vector<double>> final_observations_;
  std::vector<double> states_;
  std::vector<double> final_states_;
  std::vector<double> rewards_;
  std::vector<double> costs_;
  std::vector<double> cost_terms_;
  std::vector<std::uint8_t> terminated_;
  std::vector<std::uint8_t> truncated_;
  // Environment i's actions, one span per agent into the caller's arrays (step() only).
  std::vector<std::vector<std::span<const double>>> env_actions_;

  std::unique_ptr<WorkerPool> workers_;
};

}  // namespace bsg::envs
