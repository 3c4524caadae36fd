#include "envs/physics/multibody_pose.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>

namespace bsg::envs {

btQuaternion base_orientation(const btMultiBody& body) {
  return body.getWorldToBaseRot().inverse();
}

void teleport_base(btMultiBody& body, const btVector3& com_position,
                   const btQuaternion& base_to_world) {
  body.setBasePos(com_position);
  body.setWorldToBaseRot(base_to_world.inverse());
  refresh_colliders(body);
}

void refresh_colliders(btMultiBody& body) {
  // Called on resets and teleports only (it allocates scratch arrays).
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  body.forwardKinematics(world_to_local, local_origin);
  body.updateCollisionObjectWorldTransforms(world_to_local, local_origin);
}

}  // namespace bsg::envs
