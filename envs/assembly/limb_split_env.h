// One Ant split into agents by limb groups, MaMuJoCo's way (Peng et al. 2021;
// docs/multi_agent.md#the-split-ant): partition 2x4 gives the front and the back
// legs an agent each, 4x2 every leg. The robot is the single-agent environment
// of the same description, stepped with the agents' actions concatenated in
// agent order (= the Ant's joint order), so the split reproduces it bit for bit.
//
// Agent k observes the shared body state (the Ant's first 13 entries: 0.1·p,
// 0.3·v, quaternion, 0.15·ω), then its own legs' joints (ρ/2, 0.05·q̇ of hip and
// ankle, leg by leg), then its own feet contacts, then the task's entries.
// Every agent gets the robot's reward and cost (the team's). The global state is
// the single-agent observation.
#pragma once

#include <memory>
#include <vector>

#include "envs/assembly/multi_agent_buffers.h"
#include "envs/env.h"
#include "envs/multi_agent_env.h"

namespace bsg::envs {

class LimbSplitEnv final : public MultiAgentEnv {
 public:
  // `robot` is the single-agent Ant environment built from description.env.
  LimbSplitEnv(const MultiAgentDescription& description, std::unique_ptr<Env> robot);

  const MultiAgentSpec& spec() const override { return spec_; }
  std::span<const std::span<const double>> reset(std::uint64_t seed) override;
  std::span<const std::span<const double>> reset() override;
  std::span<const std::span<const double>> reset_to(std::span<const Layout> layouts) override;
  MultiAgentStepResult step(std::span<const std::span<const double>> actions) override;
  std::span<const double> global_state() const override { return buffers_.global_state(); }
  std::vector<EnvState> body_states() const override { return {robot_->state()}; }

  // The single-agent environment inside, for drawing (scene.h).
  const Env& robot() const { return *robot_; }

 private:
  // Writes every agent's observation and the state from the robot's observation.
  std::span<const std::span<const double>> observe(std::span<const double> robot_observation);

  std::unique_ptr<Env> robot_;
  std::vector<std::vector<int>> leg_groups_;
  MultiAgentSpec spec_;
  MultiAgentBuffers buffers_;
  std::vector<double> joint_action_;
  bool has_reset_ = false;
};

}  // namespace bsg::envs
