#include "envs/physics/rigid_body_merge.h"

#include <stdexcept>

namespace bsg::envs {

MergedBody merge_rigid_parts(std::span<const RigidPart> parts) {
  MergedBody merged;
  btVector3 moment(0, 0, 0);  // Σ m_i·c_i
  for (const RigidPart& part : parts) {
    merged.mass += part.mass;
    moment += part.mass * part.com;
  }
  if (!(merged.mass > 0)) {
    throw std::invalid_argument("merge_rigid_parts: total mass must be positive");
  }
  merged.com = moment / merged.mass;
  btMatrix3x3 inertia(0, 0, 0, 0, 0, 0, 0, 0, 0);
  for (const RigidPart& part : parts) {
    const btMatrix3x3 rotation(part.rotation);
    const btMatrix3x3 own = rotation.scaled(part.principal_inertia) * rotation.transpose();
    const btVector3 d = part.com - merged.com;
    const double d2 = d.length2();
    // m·(|d|²·E − d·dᵀ): the parallel-axis term.
    const btMatrix3x3 shift(d2 - d.x() * d.x(), -d.x() * d.y(), -d.x() * d.z(),
                            -d.y() * d.x(), d2 - d.y() * d.y(), -d.y() * d.z(),
                            -d.z() * d.x(), -d.z() * d.y(), d2 - d.z() * d.z());
    inertia += own + shift * part.mass;
  }
  merged.inertia = inertia;
  return merged;
}

}  // namespace bsg::envs
