#include "envs/assembly/limb_split_env.h"

#include <algorithm>
#include <stdexcept>

#include "envs/agents/ant_agent.h"

namespace bsg::envs {
namespace {

constexpr int kBody = AntAgent::kBodyObservationDim;
constexpr int kFeet = AntAgent::kFeetObservationOffset;
constexpr int kEntriesPerLeg = 4;  // hip ρ/2, hip 0.05·q̇, ankle ρ/2, ankle 0.05·q̇
constexpr int kJointsPerLeg = 2;
static_assert(kFeet == kBody + kEntriesPerLeg * AntAgent::kFootCount);
static_assert(kFeet + AntAgent::kFootCount == AntAgent::kObservationDim);
static_assert(kJointsPerLeg * AntAgent::kFootCount == AntAgent::kActionDim);

MultiAgentSpec split_spec(const MultiAgentDescription& d, const EnvSpec& robot,
                          const std::vector<std::vector<int>>& groups) {
  MultiAgentSpec spec;
  spec.id = d.name;
  spec.agent = robot.agent;
  spec.task = robot.task;
  spec.partition = d.partition;
  spec.bodies = 1;
  const int task_dim = robot.observation_dim - AntAgent::kObservationDim;
  for (size_t k = 0; k < groups.size(); ++k) {
    const int legs = static_cast<int>(groups[k].size());
    spec.agent_names.push_back("agent_" + std::to_string(k));
    spec.observation_dims.push_back(kBody + legs * (kEntriesPerLeg + 1) + task_dim);
    spec.action_dims.push_back(legs * kJointsPerLeg);
  }
  spec.state_dim = robot.observation_dim;
  spec.max_episode_steps = robot.max_episode_steps;
  spec.cost_limit = robot.cost_limit;
  spec.action_low = robot.action_low;
  spec.action_high = robot.action_high;
  spec.observation_bound = robot.observation_bound;
  spec.team_reward = true;
  spec.team_cost = true;
  spec.cost_term_names = robot.cost_term_names;
  return spec;
}

}  // namespace

LimbSplitEnv::LimbSplitEnv(const MultiAgentDescription& description, std::unique_ptr<Env> robot)
    : robot_(std::move(robot)),
      leg_groups_(ant_leg_groups(description.partition)),
      spec_(split_spec(description, robot_->spec(), leg_groups_)),
      buffers_(spec_),
      joint_action_(static_cast<size_t>(AntAgent::kActionDim), 0.0) {
  if (robot_->spec().agent != "Ant" || leg_groups_.empty()) {
    throw std::invalid_argument(description.name + ": a limb split needs the Ant and partition 2x4 or 4x2");
  }
}

std::span<const std::span<const double>> LimbSplitEnv::observe(std::span<const double> robot_observation) {
  const std::span<const double> task = robot_observation.subspan(AntAgent::kObservationDim);
  for (size_t k = 0; k < leg_groups_.size(); ++k) {
    std::span<double> out = buffers_.observation(static_cast<int>(k));
    auto next = std::copy_n(robot_observation.begin(), kBody, out.begin());
    for (const int leg : leg_groups_[k]) {
      next = std::copy_n(robot_observation.begin() + kBody + kEntriesPerLeg * leg, kEntriesPerLeg, next);
    }
    for (const int leg : leg_groups_[k]) *next++ = robot_observation[kFeet + leg];
    std::copy(task.begin(), task.end(), next);
  }
  std::copy(robot_observation.begin(), robot_observation.end(), buffers_.state().begin());
  has_reset_ = true;
  return buffers_.observations();
}

std::span<const std::span<const double>> LimbSplitEnv::reset(std::uint64_t seed) {
  return observe(robot_->reset(seed));
}

std::span<const std::span<const double>> LimbSplitEnv::reset() { return observe(robot_->reset()); }

std::span<const std::span<const double>> LimbSplitEnv::reset_to(std::span<const Layout> layouts) {
  if (layouts.size() != 1) {
    throw std::invalid_argument(spec_.id + ": reset_to needs 1 layout (one robot), got " +
                                std::to_string(layouts.size()));
  }
  return observe(robot_->reset_to(layouts[0]));
}

MultiAgentStepResult LimbSplitEnv::step(std::span<const std::span<const double>> actions) {
  check_multi_agent_actions(spec_, has_reset_, actions);
  // Agent k's entries are its legs' joints (hip, ankle), legs in its group's order.
  for (size_t k = 0; k < leg_groups_.size(); ++k) {
    for (size_t j = 0; j < leg_groups_[k].size(); ++j) {
      const int leg = leg_groups_[k][j];
      for (int joint = 0; joint < kJointsPerLeg; ++joint) {
        joint_action_[kJointsPerLeg * leg + joint] = actions[k][kJointsPerLeg * j + joint];
      }
    }
  }
  const StepResult step = robot_->step(joint_action_);
  observe(step.observation);
  std::fill(buffers_.rewards().begin(), buffers_.rewards().end(), step.reward);
  std::fill(buffers_.costs().begin(), buffers_.costs().end(), step.cost);
  for (size_t k = 0; k < leg_groups_.size(); ++k) {
    std::span<CostTerm> terms = buffers_.cost_terms(static_cast<int>(k));
    for (size_t t = 0; t < terms.size(); ++t) terms[t].value = step.cost_terms[t].value;
  }
  return buffers_.result(step.terminated, step.truncated);
}

}  // namespace bsg::envs
