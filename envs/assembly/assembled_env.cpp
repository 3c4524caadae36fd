#include "envs/assembly/assembled_env.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "envs/tasks/layout_checks.h"

namespace bsg::envs {

double StepResult::cost_term(std::string_view name) const {
  std::string names;
  for (const CostTerm& term : cost_terms) {
    if (term.name == name) return term.value;
    names += (names.empty() ? "" : ", ") + std::string(term.name);
  }
  throw std::out_of_range("no cost term '" + std::string(name) + "'; this task reports: " + names);
}

AssembledEnv::AssembledEnv(EnvSpec spec, const EnvOptions& options, std::unique_ptr<World> world,
                           std::unique_ptr<Agent> agent, std::unique_ptr<Task> task)
    : spec_(std::move(spec)),
      options_(options),
      world_(std::move(world)),
      agent_(std::move(agent)),
      task_(std::move(task)) {
  spec_.action_dim = agent_->traits().action_dim;
  spec_.observation_dim = agent_->traits().observation_dim + task_->observation_dim();
  spec_.cost_term_names.clear();
  for (const CostTerm& term : task_->cost_terms()) spec_.cost_term_names.emplace_back(term.name);
  observation_.assign(static_cast<size_t>(spec_.observation_dim), 0.0);
}

std::span<const double> AssembledEnv::reset(std::uint64_t seed) {
  rng_.seed(seed);
  return reset_impl(nullptr);
}

std::span<const double> AssembledEnv::reset() { return reset_impl(nullptr); }

std::span<const double> AssembledEnv::reset_to(const Layout& layout) {
  require_valid_pose(layout);
  const int joints = agent_->movable_joint_count();
  if (!layout.joint_positions.empty() &&
      layout.joint_positions.size() != static_cast<size_t>(joints)) {
    throw std::invalid_argument(spec_.id + ": Layout.joint_positions needs " +
                                std::to_string(joints) + " entries (or none), got " +
                                std::to_string(layout.joint_positions.size()));
  }
  return reset_impl(&layout);
}

double AssembledEnv::clock_seconds() const {
  if (options_.box_clock == BoxClock::kEpisodePhase) return 0;
  return static_cast<double>(steps_since_construction_) * world_->env_step_seconds();
}

std::span<const double> AssembledEnv::reset_impl(const Layout* injected) {
  // docs/environments.md#reset, step 1: the original restores its first-reset snapshot: every
  // velocity zero, the agent back to its initial pose, no cached contacts.
  world_->forget_contacts();
  elapsed_steps_ = 0;
  // docs/environments.md#reset, step 3: agent reset (joint noise) first, then the task's placement.
  agent_->reset(rng_);
  Layout layout;
  if (injected != nullptr) {
    layout = *injected;
    if (!layout.joint_positions.empty()) agent_->set_joint_positions(layout.joint_positions);
  } else {
    task_->sample_layout(rng_, layout);
  }
  if (layout.joint_positions.empty() && agent_->movable_joint_count() > 0) {
    std::vector<double> velocities(static_cast<size_t>(agent_->movable_joint_count()));
    layout.joint_positions.resize(velocities.size());
    agent_->joint_state(layout.joint_positions, velocities);
  }
  task_->place(layout, clock_seconds());
  layout_ = std::move(layout);
  // docs/environments.md#reset, step 5: one engine step without a new action; no agent bookkeeping.
  world_->step();
  has_reset_ = true;
  write_observation();
  return observation_;
}

void AssembledEnv::check_action(std::span<const double> action) const {
  if (!has_reset_) throw std::logic_error(spec_.id + ": step() called before reset()");
  if (action.size() != static_cast<size_t>(spec_.action_dim)) {
    throw std::invalid_argument(spec_.id + ": action has " + std::to_string(action.size()) +
                                " entries, expected " + std::to_string(spec_.action_dim));
  }
  for (size_t i = 0; i < action.size(); ++i) {
    if (!std::isfinite(action[i])) {
      throw std::invalid_argument(spec_.id + ": action entry " + std::to_string(i) +
                                  " is not finite (" + std::to_string(action[i]) + ")");
    }
  }
}

StepResult AssembledEnv::step(std::span<const double> action) {
  check_action(action);
  // The order of docs/environments.md#one-step.
  ++elapsed_steps_;
  ++steps_since_construction_;
  agent_->apply_action(action);
  task_->before_physics(clock_seconds());
  world_->step();
  agent_->after_step();
  const TaskOutcome outcome = task_->evaluate(rng_);
  StepResult result;
  result.reward = outcome.reward;
  result.cost = outcome.cost;
  result.terminated = !agent_->alive() || outcome.ends_episode;
  result.truncated = !result.terminated && elapsed_steps_ >= spec_.max_episode_steps;
  result.cost_terms = task_->cost_terms();
  write_observation();
  result.observation = observation_;
  return result;
}

void AssembledEnv::write_observation() {
  const auto agent_dim = static_cast<size_t>(agent_->traits().observation_dim);
  std::span<double> out(observation_);
  agent_->write_observation(out.first(agent_dim));
  task_->write_observation(out.subspan(agent_dim));
}

EnvState snapshot_state(const Agent& agent, const Task& task, int elapsed_steps) {
  EnvState state;
  state.elapsed_steps = elapsed_steps;
  state.agent_position = to_vec3(agent.position());
  state.agent_orientation = to_quat(agent.orientation());
  state.agent_linear_velocity = to_vec3(agent.linear_velocity());
  state.agent_angular_velocity = to_vec3(agent.angular_velocity());
  const auto joints = static_cast<size_t>(agent.movable_joint_count());
  state.joint_positions.resize(joints);
  state.joint_velocities.resize(joints);
  agent.joint_state(state.joint_positions, state.joint_velocities);
  state.agent_reward = agent.specific_reward();
  state.alive = agent.alive();
  task.write_state(state);
  return state;
}

EnvState AssembledEnv::state() const { return snapshot_state(*agent_, *task_, elapsed_steps_); }

void AssembledEnv::teleport_agent(const Vec3& com_position) {
  agent_->set_base_pose(to_bt(com_position), agent_->orientation());
}

std::vector<Marking> AssembledEnv::markings() const {
  std::vector<Marking> markings;
  task_->add_markings(markings);
  return markings;
}

}  // namespace bsg::envs
