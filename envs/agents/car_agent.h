// The Car (docs/environments.md#car, class `RaceCar` of the original): the MIT racecar of
// `racecar_differential.urdf` loaded with global scaling 3, built here link by
// link as PyBullet's URDF importer builds it (no importer). The rear wheels are
// driven through differential 1 (ring = link 8), the front wheels are coupled
// to differential 2 (ring = link 15) by gear constraints; the action sets the
// two ring velocity motors and the two steering position motors. The car never
// dies and its actions are not clipped (docs/environments.md#kept-quirks, item 4).
//
// Parameters (docs/environments.md#agents, #car):
//   wheel speed per unit action  40 rad/s (power upgrade, Reach/Gather: 80)
//   ring motor force             20 (power upgrade: 40); max impulse F/60 per internal step
//   steering per unit action     0.5 rad, position motor kp 0.1, kd 1, force 100000,
//                                target clamped to the hinge limits [-1, 1] (docs/environments.md#car)
//   gear constraints             8, max force 10000 → max impulse 10000·h (h = internal step)
//   initial pose                 COM (0, 0, 0.2), yaw π (facing world −x)
//   collision radius             0.35 m; Run speed limit 1.5 m/s
//   sensors                      rotate with the car, offset (0.2, 0, 0.3) in the base frame
//
// Link indices are PyBullet's (the table in car_agent.cpp, docs/environments.md#car); the
// movable joints, in the agent's own order, are 0, 1, 2, 3, 8, 9, 10, 11, 13,
// 15, 16, 17, 18, 19.
//
// AgentOptions::physics:
//   kFaithful  the 20 links above, and a disabled motor on each of the 14 movable joints;
//   kLean      the chassis and the four links fixed to it (laser, zed_camera_link,
//              camera_link, zed_camera_right_link) welded into one base, whose COM
//              frame is the merged body's principal frame (shifted and turned a
//              little from the chassis's); 16 links. The rear wheels stay links of
//              their own: their friction (0.7) is not their side gears' (1.0), and a
//              link carries one collider. The 14 motors stay (the 10 never switched
//              on make no solver row; see add_constraints()). Same shapes, contacts, limits,
//              gears, solver. The agent reports the chassis's COM pose and velocity.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <LinearMath/btAlignedObjectArray.h>
#include <LinearMath/btQuaternion.h>
#include <LinearMath/btTransform.h>

#include "envs/agents/agent.h"

class btCollisionShape;
class btMultiBody;
class btMultiBodyJointMotor;

namespace bsg::envs {

class CarAgent final : public Agent {
 public:
  static constexpr int kLinkCount = 20;
  static constexpr int kMovableJointCount = 14;
  // PyBullet link index of every movable joint, in the agent's joint order
  // (also the order of the agent-reset draws, docs/environments.md#car).
  static constexpr std::array<int, kMovableJointCount> kMovableLinks = {0,  1,  2,  3,  8,  9,  10,
                                                                        11, 13, 15, 16, 17, 18, 19};

  CarAgent(World& world, const AgentOptions& options);

  const AgentTraits& traits() const override { return traits_; }
  void reset(Rng& rng) override;
  void set_base_pose(const btVector3& com_position, const btQuaternion& orientation) override;
  void set_joint_positions(std::span<const double> joint_positions) override;
  int movable_joint_count() const override { return kMovableJointCount; }
  void apply_action(std::span<const double> action) override;
  void write_observation(std::span<double> out) const override;
  double specific_reward() const override { return 0.0; }  // docs/environments.md#car
  bool alive() const override { return true; }             // docs/environments.md#car
  btVector3 position() const override;
  btQuaternion orientation() const override;
  btVector3 linear_velocity() const override;
  btVector3 angular_velocity() const override;
  void joint_state(std::span<double> positions, std::span<double> velocities) const override;
  std::span<const btCollisionObject* const> colliders() const override { return colliders_; }

  // World pose of PyBullet link `link`'s COM frame as of the last forward
  // kinematics (PyBullet's getLinkState), for model checks; in the lean model a
  // welded link's frame is carried by the base.
  btTransform link_com_transform(int link) const;
  // The multibody, for model checks (lean vs faithful mass properties).
  const btMultiBody& multibody() const { return *body_; }
  // Motor targets set by the last apply_action (after the hinge clamp).
  double wheel_target_rad_per_s() const { return wheel_target_rad_per_s_; }
  double steering_target_rad() const { return steering_target_rad_; }

 private:
  // Where a PyBullet link's COM frame lives: a body link (−1 = base) and the
  // frame's pose in that link's COM frame (identity unless welded).
  struct LinkPlace {
    int body_link = -1;
    btTransform offset = btTransform::getIdentity();
  };

  using BodyLinks = std::array<int, kLinkCount>;  // each PyBullet link's body link (−1: welded into the base)
  // The shapes and inertias both models start from.
  struct CarShapes {
    btTransform chassis_inertial = btTransform::getIdentity();  // the chassis's COM frame in its link frame
    btCollisionShape* hull = nullptr;
    btCollisionShape* chassis = nullptr;  // the hull at −COM
    btVector3 chassis_inertia{0, 0, 0};
    std::array<btCollisionShape*, kLinkCount> links{};
    std::array<btVector3, kLinkCount> inertias{};
  };
  // The multibody's base: mass, diagonal inertia, COM frame in the chassis link frame, shape.
  struct CarBase {
    double mass = 0;
    btVector3 inertia{0, 0, 0};
    btTransform inertial = btTransform::getIdentity();
    btCollisionShape* shape = nullptr;
  };

  void build_faithful(World& world);
  void build_lean(World& world);
  CarShapes make_shapes(World& world);
  CarBase weld_into_base(World& world, const CarShapes& shapes, const BodyLinks& body_link);
  void assemble(World& world, const CarShapes& shapes, const CarBase& base, const BodyLinks& body_link,
                int body_link_count);
  void set_up_joints(btMultiBody& mb, const CarShapes& shapes, const CarBase& base, const BodyLinks& body_link);
  void add_colliders(World& world, btMultiBody& mb, const CarShapes& shapes, const CarBase& base,
                     const BodyLinks& body_link);
  void add_constraints(World& world, const BodyLinks& body_link);
  void refresh_colliders();
  // World pose of the chassis's COM frame (the base's, unless the base is welded).
  btTransform chassis_com_transform() const;

  AgentTraits traits_;
  double speed_per_action_rad_per_s_;
  double ring_motor_max_impulse_;  // F·T_param per internal step (docs/environments.md#motors-forces-and-contacts)
  double steering_max_impulse_;
  bool clip_actions_;
  btMultiBody* body_ = nullptr;
  // Lean: the chassis's COM frame in the welded base's COM frame.
  bool welded_base_ = false;
  btTransform chassis_in_base_ = btTransform::getIdentity();
  std::array<LinkPlace, kLinkCount> link_places_{};
  // Body link of each movable joint, in kMovableLinks order.
  std::array<int, kMovableJointCount> movable_links_{};
  // One motor per movable joint in kMovableLinks order, all created disabled
  // (PyBullet creates a motor for every revolute joint, docs/environments.md#motors-forces-and-contacts).
  std::array<btMultiBodyJointMotor*, kMovableJointCount> motors_{};
  // Faithful: base collider first, then links 0..19 (links without geometry
  // carry an empty compound, as in PyBullet). Lean: the compound base, then
  // the 16 links.
  std::vector<const btCollisionObject*> colliders_;
  btAlignedObjectArray<btQuaternion> scratch_rotations_;
  btAlignedObjectArray<btVector3> scratch_vectors_;
  double wheel_target_rad_per_s_ = 0;
  double steering_target_rad_ = 0;
};

std::unique_ptr<Agent> make_car_agent(World& world, const AgentOptions& options);

}  // namespace bsg::envs
