// Access to the golden trajectories of the original suite (tests/data/golden/,
// recorded from the original; its README says what every field means and which
// tolerances the original's own sensitivity allows).
#pragma once

#include <algorithm>
#include <cmath>
#include <fstream>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>
#include <nlohmann/json.hpp>

#include "envs/agents/agent.h"
#include "envs/physics/world.h"

namespace bsg::testing {

inline nlohmann::json load_golden(const std::string& env_id) {
  const std::string path = std::string(BSG_TEST_DATA_DIR) + "/golden/" + env_id + ".json";
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot open golden file " + path);
  return nlohmann::json::parse(file);
}

inline btVector3 golden_vec3(const nlohmann::json& value) {
  return {value.at(0).get<double>(), value.at(1).get<double>(), value.at(2).get<double>()};
}

// Golden quaternions are [x, y, z, w].
inline btQuaternion golden_quat(const nlohmann::json& value) {
  return {value.at(0).get<double>(), value.at(1).get<double>(), value.at(2).get<double>(),
          value.at(3).get<double>()};
}

inline std::vector<double> golden_vector(const nlohmann::json& value) {
  return value.get<std::vector<double>>();
}

// Largest absolute entry-wise difference; throws on a size mismatch.
inline double max_abs_diff(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) {
    throw std::runtime_error("size mismatch: " + std::to_string(a.size()) + " vs " +
                             std::to_string(b.size()));
  }
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

inline double max_abs_diff(const btVector3& a, const btVector3& b) {
  return std::max({std::abs(a.x() - b.x()), std::abs(a.y() - b.y()), std::abs(a.z() - b.z())});
}

// Largest entry-wise difference of two quaternions [x, y, z, w] (btQuaternion
// or std::array), where q and −q count as the same rotation (PyBullet may
// return either sign).
template <class Quaternion>
double quat_diff(const Quaternion& a, const Quaternion& b) {
  double same = 0, flipped = 0;
  for (int i = 0; i < 4; ++i) {
    same = std::max(same, std::abs(a[i] - b[i]));
    flipped = std::max(flipped, std::abs(a[i] + b[i]));
  }
  return std::min(same, flipped);
}

// The world layout a golden file's meta names ("Plane200", "Octagon", "SmallRoom").
inline envs::WorldLayout golden_world_layout(const std::string& name) {
  if (name == "Plane200") return envs::WorldLayout::kPlane200;
  if (name == "Octagon") return envs::WorldLayout::kOctagon;
  if (name == "SmallRoom") return envs::WorldLayout::kSmallRoom;
  throw std::invalid_argument("unknown world in golden file: " + name);
}

// The entries at `links` of a golden joint array (`joint_q`, `joint_qd`),
// which lists every PyBullet joint in PyBullet order.
template <class Links>
std::vector<double> golden_joints_at(const nlohmann::json& all_joints, const Links& links) {
  std::vector<double> values;
  for (int link : links) values.push_back(all_joints.at(link).get<double>());
  return values;
}

// Placement as recorded (golden README "How a C++ test should use a file",
// step 2): the base COM pose of `placed` and the angles of the joints at
// `movable_links`; velocities are zero in a new agent.
template <class Links>
void place_as_recorded(envs::Agent& agent, const nlohmann::json& placed,
                       const Links& movable_links) {
  agent.set_base_pose(golden_vec3(placed.at("pos")), golden_quat(placed.at("orn")));
  agent.set_joint_positions(golden_joints_at(placed.at("joint_q"), movable_links));
}

// How far a link's COM pose is from a golden link record (`com_pos`, `com_orn`).
struct LinkPoseError {
  double position = 0;     // largest coordinate difference [m]
  double orientation = 0;  // quat_diff
};

inline LinkPoseError link_pose_error(const btTransform& pose, const nlohmann::json& golden_link) {
  return {max_abs_diff(pose.getOrigin(), golden_vec3(golden_link.at("com_pos"))),
          quat_diff(pose.getRotation(), golden_quat(golden_link.at("com_orn")))};
}

}  // namespace bsg::testing
