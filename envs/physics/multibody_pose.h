// Reading and teleporting a btMultiBody's base the way PyBullet does
// (PyBullet's resetBasePositionAndOrientation, docs/environments.md#motors-forces-and-contacts): the base pose is the COM pose,
// orientations are base-to-world, and the colliders follow immediately so that
// ray casts and the next collision detection see the new pose.
#pragma once

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

class btMultiBody;

namespace bsg::envs {

// Base-to-world rotation (btMultiBody stores world-to-base).
btQuaternion base_orientation(const btMultiBody& body);

// Moves the base COM and orientation; velocities are left unchanged.
void teleport_base(btMultiBody& body, const btVector3& com_position,
                   const btQuaternion& base_to_world);

// Recomputes link frames and moves every collider to them.
void refresh_colliders(btMultiBody& body);

}  // namespace bsg::envs
