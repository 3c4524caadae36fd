// The Ball (docs/environments.md#ball, class `Ball` of the original): a 0.5-m sphere of 0.3 kg
// pushed by a horizontal world-frame force at its centre. It never dies and has
// no joints.
//
// Parameters (docs/environments.md#agents, #ball; none depends on the task):
//   force per unit action  3.5 N (actions clipped to [-1, 1])
//   initial position       (0, 0, 0.5), identity orientation
//   collision radius       0.5 m; Run speed limit 2.5 m/s
#pragma once

#include <array>
#include <memory>

#include "envs/agents/agent.h"

class btMultiBody;

namespace bsg::envs {

class BallAgent final : public Agent {
 public:
  static constexpr double kRadius = 0.5;
  static constexpr double kMass = 0.3;
  static constexpr double kForcePerAction = 3.5;  // [N]

  BallAgent(World& world, const AgentOptions& options);

  const AgentTraits& traits() const override { return traits_; }
  void reset(Rng& rng) override;
  void set_base_pose(const btVector3& com_position, const btQuaternion& orientation) override;
  void set_joint_positions(std::span<const double> joint_positions) override;
  int movable_joint_count() const override { return 0; }
  void apply_action(std::span<const double> action) override;
  void write_observation(std::span<double> out) const override;
  double specific_reward() const override { return specific_reward_; }
  bool alive() const override { return true; }
  btVector3 position() const override;
  btQuaternion orientation() const override;
  btVector3 linear_velocity() const override;
  btVector3 angular_velocity() const override;
  void joint_state(std::span<double> positions, std::span<double> velocities) const override;
  std::span<const btCollisionObject* const> colliders() const override { return colliders_; }

 private:
  AgentTraits traits_;
  btMultiBody* body_ = nullptr;
  std::array<const btCollisionObject*, 1> colliders_{};
  double specific_reward_ = 0;
};

std::unique_ptr<Agent> make_ball_agent(World& world, const AgentOptions& options);

}  // namespace bsg::envs
