// Conversions between the public, Bullet-free Layout/EnvState types of env.h
// and Bullet vectors, and the validation every task applies to an injected
// Layout (a field the task does not use must be empty, so that a layout meant
// for another task is rejected instead of silently ignored).
#pragma once

#include <initializer_list>
#include <string_view>

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

#include "envs/description/env_types.h"

namespace bsg::envs {

inline btVector3 to_bt(const Vec3& v) { return {v[0], v[1], v[2]}; }
inline btQuaternion to_bt(const Quat& q) { return {q[0], q[1], q[2], q[3]}; }
inline Vec3 to_vec3(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
inline Quat to_quat(const btQuaternion& q) { return {q.x(), q.y(), q.z(), q.w()}; }

// Throws std::invalid_argument if a task-specific field of `layout` that is
// not in `used` is set. Field names: goal, box, zones, d_prev, apples, bombs,
// phi_prev.
void require_unused_fields(const Layout& layout, std::string_view task_name,
                           std::initializer_list<std::string_view> used);

// Throws std::invalid_argument unless `count` positions were given.
void require_count(std::string_view task_name, std::string_view field, size_t given,
                   size_t expected);

// Throws std::invalid_argument if the agent orientation is not a unit quaternion
// or a position entry is not finite.
void require_valid_pose(const Layout& layout);

}  // namespace bsg::envs
