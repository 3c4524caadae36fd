#include "envs/physics/deterministic_pair_cache.h"

#include <algorithm>

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>

namespace bsg::envs {

// Room for far more pairs than any of the 16 worlds holds (an Ant touching a
// wall: about 20), so that a new high-water mark of pairs in the middle of an
// episode does not allocate.
DeterministicPairCache::DeterministicPairCache() { order_.reserve(256); }

void DeterministicPairCache::processAllOverlappingPairs(btOverlapCallback* callback,
                                                        btDispatcher* dispatcher,
                                                        const btDispatcherInfo& dispatch_info) {
  if (!dispatch_info.m_deterministicOverlappingPairs) {
    btHashedOverlappingPairCache::processAllOverlappingPairs(callback, dispatcher);
    return;
  }
  btBroadphasePairArray& pairs = getOverlappingPairArray();
  order_.resize(static_cast<size_t>(pairs.size()));  // grows only while pairs do
  for (int i = 0; i < pairs.size(); ++i) {
    const btBroadphasePair& pair = pairs[i];
    order_[static_cast<size_t>(i)] = {pair.m_pProxy0 ? pair.m_pProxy0->m_uniqueId : -1,
                                      pair.m_pProxy1 ? pair.m_pProxy1->m_uniqueId : -1, i};
  }
  // Bullet's order: descending by (first uid, second uid). A pair of proxies
  // is in the cache once, so the keys are distinct and any sort gives the same
  // sequence as Bullet's quickSort.
  std::sort(order_.begin(), order_.end(), [](const PairOrder& a, const PairOrder& b) {
    return a.first_uid > b.first_uid ||
           (a.first_uid == b.first_uid && a.second_uid > b.second_uid);
  });
  // As in Bullet, a pair the callback asks to remove is removed and the same
  // position of the order is visited again (the dispatcher's callback never
  // asks; the loop is kept for any other callback).
  for (size_t i = 0; i < order_.size();) {
    btBroadphasePair* pair = &pairs[order_[i].pair_index];
    if (callback->processOverlap(*pair)) {
      removeOverlappingPair(pair->m_pProxy0, pair->m_pProxy1, dispatcher);
    } else {
      ++i;
    }
  }
}

}  // namespace bsg::envs
