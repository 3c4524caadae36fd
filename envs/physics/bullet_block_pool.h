// Bullet's heap memory through per-thread free lists of size-classed blocks.
//
// Bullet allocates while it steps whenever a pair of bodies starts or stops
// overlapping in the broadphase: the pair's collision algorithm, a compound's
// child-pair cache and arrays (btAlignedAlloc). With the pool those requests
// reuse blocks freed earlier, so once an environment has warmed up its step
// path makes no heap allocation (issue 3). Results do not depend on where
// memory lives.
//
// Bullet's allocator hook is process-wide by Bullet's design; it is installed
// once, before a World builds anything, and never removed. Blocks freed on a
// thread go to that thread's lists; a thread's cached blocks are released
// when it ends. Blocks Bullet obtained before the pool was installed are
// recognised on free and handed back to the C library.
#pragma once

#include <cstddef>

namespace bsg::envs {

// Installs the pool as Bullet's allocator (idempotent, thread-safe; does
// nothing under AddressSanitizer).
void install_bullet_block_pool();

// Bullet's allocation hooks, exposed for tests.
void* bullet_pool_allocate(std::size_t size);
void bullet_pool_free(void* block);

}  // namespace bsg::envs
