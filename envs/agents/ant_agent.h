// The Ant (docs/environments.md#ant): the MJCF ant as PyBullet builds it, assembled directly
// with btMultiBody. A torso sphere plus 20 links in PyBullet's joint order
// (fixed joints included), 8 torque-driven revolute joints, feet-contact
// bookkeeping and the joint-limit and electricity terms of its reward.
//
// Parameters (AgentOptions):
//   power_upgrade  false: 250 N·m per unit action (Circle, Run);
//                  true: 1000 N·m per unit action (Reach, Gather; "max_force 2.5→10", docs/environments.md#agents)
//   physics        kFaithful: the 20 links above, and the 8 disabled joint motors;
//                  kLean: the same bodies welded along the fixed joints, 8 links
//                  (thigh on its hip joint, foot on its ankle joint) under one base
//                  (torso + 4 leg stubs, one compound collider), no disabled motors.
//                  Same shapes, friction, limits and solver.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include <LinearMath/btAlignedObjectArray.h>
#include <LinearMath/btQuaternion.h>
#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include "envs/agents/agent.h"

class btCollisionShape;
class btMultiBody;
class btMultiBodyLinkCollider;

namespace bsg::envs {

class AntAgent final : public Agent {
 public:
  static constexpr int kActionDim = 8;
  static constexpr int kObservationDim = 33;
  // The observation's layout (write_observation): the body's 13 entries first
  // (0.1·p, 0.3·v, quaternion, 0.15·ω), then (ρ_k/2, 0.05·q̇_k) per joint k,
  // then the 4 feet contacts; leg l drives joints 2l and 2l+1 and stands on foot l.
  static constexpr int kBodyObservationDim = 13;
  static constexpr int kFeetObservationOffset = 29;
  // PyBullet's links of the MJCF ant: 5 per leg (leg stub, hip joint link,
  // thigh, ankle joint link, foot), legs in the order front_left,
  // front_right, left_back, right_back (docs/environments.md#ant).
  static constexpr int kLinkCount = 20;
  static constexpr int kFootCount = 4;
  // PyBullet link index of the k-th actuated joint (hip_1, ankle_1, …, ankle_4)
  // in the faithful model.
  static constexpr std::array<int, kActionDim> kMovableLinks = {1, 3, 6, 8, 11, 13, 16, 18};
  static constexpr std::array<int, kFootCount> kFootLinks = {4, 9, 14, 19};

  AntAgent(World& world, const AgentOptions& options);

  const AgentTraits& traits() const override { return traits_; }
  void reset(Rng& rng) override;
  void set_base_pose(const btVector3& com_position, const btQuaternion& orientation) override;
  void set_joint_positions(std::span<const double> joint_positions) override;
  int movable_joint_count() const override { return kActionDim; }
  void apply_action(std::span<const double> action) override;
  void after_step() override;
  void write_observation(std::span<double> out) const override;
  double specific_reward() const override { return specific_reward_; }
  bool alive() const override;
  btVector3 position() const override;
  btQuaternion orientation() const override;
  btVector3 linear_velocity() const override;
  btVector3 angular_velocity() const override;
  void joint_state(std::span<double> positions, std::span<double> velocities) const override;
  std::span<const btCollisionObject* const> colliders() const override { return colliders_; }

  // Post-step bookkeeping of the last after_step() (docs/environments.md#ant).
  const std::array<double, kFootCount>& feet_contact() const { return feet_contact_; }
  double joints_at_limit_reward() const { return joints_at_limit_reward_; }  // J
  double electricity_reward() const { return electricity_reward_; }          // E

  // Model inspection for tests.
  double total_mass_kg() const;
  // World pose of the COM (inertial) frame of PyBullet link `link` in [0, 20),
  // from the current joint angles (fresh forward kinematics). In the lean model
  // a massless joint link's COM frame is its pivot, as in the faithful one.
  btTransform link_com_transform(int link) const;
  // Joint torque [N·m] per unit of action: 250, or 1000 with the power upgrade.
  double torque_per_unit_action() const { return torque_per_unit_action_; }
  // The multibody, for model checks (lean vs faithful mass properties).
  const btMultiBody& multibody() const { return *body_; }

 private:
  // One capsule geom (docs/environments.md#ant) and the link it makes in the faithful model.
  struct CapsuleLink {
    btCollisionShape* spheres = nullptr;  // the two-sphere shape, from 0 to the end point
    btCollisionShape* shape = nullptr;    // compound: the spheres at −com_offset
    double mass = 0;
    btVector3 inertia{0, 0, 0};
    btVector3 com_offset{0, 0, 0};  // from the body frame's origin to the inertial frame
  };
  struct LegCapsules {
    CapsuleLink stub, thigh, foot;
  };
  // Where a PyBullet link's COM frame lives: a body link (−1 = base) and an
  // offset in that link's COM frame (same orientation in both models).
  struct LinkPlace {
    int body_link = -1;
    btVector3 offset{0, 0, 0};
  };

  CapsuleLink make_capsule(const btVector3& to);
  void build_faithful();
  void build_lean();
  btMultiBodyLinkCollider* add_collider(int link, btCollisionShape* shape);
  void add_joint_limits();

  // Puts the colliders where the current pose says (PyBullet does this in
  // resetBasePositionAndOrientation / resetJointState).
  void refresh_colliders();

  World& world_;
  PhysicsModel physics_;
  AgentTraits traits_;
  double torque_per_unit_action_;
  btCollisionShape* torso_shape_ = nullptr;
  double torso_mass_ = 0;
  btVector3 torso_inertia_{0, 0, 0};
  std::array<LegCapsules, 4> legs_{};
  btMultiBody* body_ = nullptr;
  // Body link of each actuated joint, in action order.
  std::array<int, kActionDim> movable_links_{};
  std::array<LinkPlace, kLinkCount> link_places_{};
  // Faithful: base + 12 capsule links; lean: compound base + 4 thighs + 4 feet.
  std::vector<const btCollisionObject*> colliders_;
  std::array<const btMultiBodyLinkCollider*, kFootCount> feet_{};
  btAlignedObjectArray<btQuaternion> scratch_rotations_;
  btAlignedObjectArray<btVector3> scratch_vectors_;

  // Last raw (unclipped) action and the bookkeeping it produced.
  std::array<double, kActionDim> last_action_{};
  std::array<double, kFootCount> feet_contact_{};
  double joints_at_limit_reward_ = 0;
  double electricity_reward_ = 0;
  double specific_reward_ = 0;
};

std::unique_ptr<Agent> make_ant_agent(World& world, const AgentOptions& options);

}  // namespace bsg::envs
