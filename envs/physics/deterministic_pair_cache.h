// Bullet's hashed pair cache with its deterministic pair order (PyBullet's
// m_deterministicOverlappingPairs, docs/environments.md#physics-settings) kept, but without the heap
// allocation Bullet's own version makes at every internal step: it sorts the
// pair indices in a local array. Here that array is a member, sized once.
#pragma once

#include <vector>

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>

namespace bsg::envs {

class DeterministicPairCache final : public btHashedOverlappingPairCache {
 public:
  DeterministicPairCache();
  using btHashedOverlappingPairCache::processAllOverlappingPairs;
  void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher,
                                  const btDispatcherInfo& dispatch_info) override;

 private:
  struct PairOrder {
    int first_uid;
    int second_uid;
    int pair_index;
  };
  std::vector<PairOrder> order_;
};

}  // namespace bsg::envs
