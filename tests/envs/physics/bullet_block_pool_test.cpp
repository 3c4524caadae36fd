// The block pool behind Bullet's allocations (envs/physics/bullet_block_pool.h): a
// freed block is reused for the next request of its size class, blocks are
// 16-byte aligned and hold what was asked, blocks outlive the thread that
// freed them into its lists, large and foreign blocks go back to the C
// library. Bullet's own use of it is checked by step_allocation_test.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "envs/physics/bullet_block_pool.h"

namespace bsg::envs {
namespace {

bool aligned16(const void* block) { return reinterpret_cast<std::uintptr_t>(block) % 16 == 0; }

TEST(BulletBlockPool, FreedBlockIsReusedForTheSameSizeClass) {
  void* first = bullet_pool_allocate(100);
  ASSERT_NE(first, nullptr);
  bullet_pool_free(first);
  // 100 and 120 bytes both round up to the 128-byte class.
  void* second = bullet_pool_allocate(120);
  EXPECT_EQ(second, first);
  bullet_pool_free(second);
}

TEST(BulletBlockPool, BlocksAreAlignedWritableAndDistinct) {
  std::vector<void*> blocks;
  for (std::size_t size : {1u, 16u, 33u, 64u, 1000u, 4096u, 70000u, 3000000u}) {
    void* block = bullet_pool_allocate(size);
    ASSERT_NE(block, nullptr) << size;
    EXPECT_TRUE(aligned16(block)) << size;
    std::memset(block, 0xab, size);  // the sanitizer build checks the bounds
    blocks.push_back(block);
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::size_t j = i + 1; j < blocks.size(); ++j) EXPECT_NE(blocks[i], blocks[j]);
  }
  for (void* block : blocks) bullet_pool_free(block);
}

TEST(BulletBlockPool, LargeBlocksAreNotPooled) {
  // Above 1 MiB blocks go straight back to the C library; the pool never
  // hands a freed large block out again for a small request.
  void* large = bullet_pool_allocate(2 << 20);
  ASSERT_NE(large, nullptr);
  bullet_pool_free(large);
  void* small = bullet_pool_allocate(64);
  EXPECT_NE(small, large);
  bullet_pool_free(small);
}

TEST(BulletBlockPool, BlockFreedOnAnotherThreadStaysUsable) {
  void* block = bullet_pool_allocate(200);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, 200);
  // Freed on a thread that then ends: the block goes to that thread's lists,
  // which release it to the C library at thread exit.
  std::thread([block] { bullet_pool_free(block); }).join();
  // A block allocated on a thread and freed after its lists are gone.
  void* orphan = nullptr;
  std::thread([&orphan] { orphan = bullet_pool_allocate(300); }).join();
  ASSERT_NE(orphan, nullptr);
  std::memset(orphan, 2, 300);
  bullet_pool_free(orphan);
}

TEST(BulletBlockPool, NullIsIgnored) { bullet_pool_free(nullptr); }

TEST(BulletBlockPool, BlockFromTheCLibraryIsHandedBack) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "reads the C library's chunk header, which ASan poisons";
#else
  // What Bullet obtained before the pool was installed comes back through
  // the pool's free; it must go to free(), not into a list.
  void* foreign = std::malloc(48);
  ASSERT_NE(foreign, nullptr);
  bullet_pool_free(foreign);
  void* next = bullet_pool_allocate(48);
  EXPECT_NE(next, foreign);
  bullet_pool_free(next);
#endif
}

}  // namespace
}  // namespace bsg::envs
