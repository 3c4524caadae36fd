// Mass properties of rigid parts welded into one body (lean models, env.h):
// total mass, centre of mass, and the inertia tensor about that centre by the
// parallel-axis theorem, I = Σ_i R_i·diag(I_i)·R_iᵀ + m_i·(|d_i|²·E − d_i·d_iᵀ),
// d_i = c_i − c.
#pragma once

#include <span>

#include <LinearMath/btMatrix3x3.h>
#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

namespace bsg::envs {

// One part, expressed in a frame common to all parts.
struct RigidPart {
  double mass = 0;
  btVector3 principal_inertia{0, 0, 0};  // about its COM, in its own inertial frame
  btVector3 com{0, 0, 0};                // COM position in the common frame
  btQuaternion rotation = btQuaternion::getIdentity();  // own inertial frame → common frame
};

struct MergedBody {
  double mass = 0;
  btVector3 com{0, 0, 0};  // in the common frame
  btMatrix3x3 inertia;     // about com, axes of the common frame
};

// Throws std::invalid_argument if the parts' total mass is not positive.
MergedBody merge_rigid_parts(std::span<const RigidPart> parts);

}  // namespace bsg::envs
