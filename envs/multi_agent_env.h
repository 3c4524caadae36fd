// The multi-agent face (docs/multi_agent.md): a `MultiAgentEnv` whose agents
// act together at every step, each with its own observation, action, reward
// and cost, plus a global state for centralised critics and one termination
// and truncation for the team (the convention of MAPPO-L and MACPO, Gu et al.
// 2021, and of PettingZoo's Parallel API). Made by id from its own registry,
// apart from the single-agent ids of env.h, or from a MultiAgentDescription.
// Includes no Bullet header.
//
// Threading and buffers as env.h: one per thread; the observation and state
// spans are views into buffers the environment owns, valid until its next
// reset()/step().
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/description/env_parameters.h"
#include "envs/description/env_types.h"
#include "envs/description/multi_agent_description.h"

namespace bsg::envs {

struct MultiAgentSpec {
  std::string id;         // e.g. "SafetyBallCircle2-v0"
  std::string agent;      // the robot: "Ball", "Car", "Ant"
  std::string task;       // "Circle", "Run"
  std::string partition;  // "body", "2x4", "4x2"
  int bodies = 0;         // robots in the arena
  std::vector<std::string> agent_names;  // "agent_0", "agent_1", ...
  std::vector<int> observation_dims;     // per agent
  std::vector<int> action_dims;          // per agent; their sum drives every robot
  int state_dim = 0;                     // global_state()
  int max_episode_steps = 0;             // the team's truncation
  double cost_limit = 0;                 // d of the robot's task, per agent and episode
  double action_low = -1;
  double action_high = 1;
  double observation_bound = 1000;
  bool team_reward = false;  // every agent gets the team's reward
  bool team_cost = false;    // every agent gets the team's cost
  // Each agent's cost terms, in the order of MultiAgentStepResult::cost_terms.
  std::vector<std::string> cost_term_names;

  int agent_count() const { return static_cast<int>(agent_names.size()); }
};

struct MultiAgentStepResult {
  std::span<const std::span<const double>> observations;  // one per agent
  std::span<const double> rewards;  // one per agent
  std::span<const double> costs;    // one per agent, each 0 or 1 (own) or their sum (team)
  std::span<const std::span<const CostTerm>> cost_terms;  // one list per agent
  bool terminated = false;  // the team's episode ended (a robot died)
  bool truncated = false;   // max_episode_steps reached without termination
};

class MultiAgentEnv {
 public:
  virtual ~MultiAgentEnv() = default;

  virtual const MultiAgentSpec& spec() const = 0;

  // Reseeds the environment's RNG and resets; observations one per agent.
  virtual std::span<const std::span<const double>> reset(std::uint64_t seed) = 0;
  // Resets and keeps drawing from the current RNG stream.
  virtual std::span<const std::span<const double>> reset() = 0;
  // Resets to one given layout per robot (spec().bodies of them) instead of
  // sampling; throws std::invalid_argument naming the layout at fault.
  virtual std::span<const std::span<const double>> reset_to(std::span<const Layout> layouts) = 0;

  // One step of every agent: one action per agent, agent order. Throws
  // std::invalid_argument for a wrong count, size or a non-finite entry, and
  // std::logic_error before the first reset.
  virtual MultiAgentStepResult step(std::span<const std::span<const double>> actions) = 0;

  // The global state of the last reset or step (centralised critics).
  virtual std::span<const double> global_state() const = 0;
  // Each robot's state (env_types.h), robot order; for tests, allocates.
  virtual std::vector<EnvState> body_states() const = 0;
};

// Makes a registered multi-agent environment; throws std::invalid_argument
// with one line listing the multi-agent ids if `id` is unknown.
std::unique_ptr<MultiAgentEnv> make_multi_agent(const std::string& id, const EnvOptions& options = {});
// Builds any multi-agent description; throws std::invalid_argument with one
// line naming the key at fault.
std::unique_ptr<MultiAgentEnv> make_multi_agent(const MultiAgentDescription& description,
                                                const EnvOptions& options = {});
// The description registered as `id` with `overrides` applied and checked.
MultiAgentDescription describe_multi_agent(const std::string& id, const EnvOverrides& overrides = {});
// Every registered multi-agent id, sorted.
std::vector<std::string> multi_agent_ids();

}  // namespace bsg::envs
