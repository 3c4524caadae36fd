#include "envs/physics/bullet_block_pool.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <mutex>

#include <LinearMath/btAlignedAllocator.h>

namespace bsg::envs {
namespace {

// Classes hold blocks of 2^kSmallestShift … 2^kLargestShift bytes; larger
// requests go to malloc/free directly (Bullet makes them only when it sizes
// its worlds, not per step).
constexpr int kSmallestShift = 5;
constexpr int kLargestShift = 20;
constexpr int kClasses = kLargestShift - kSmallestShift + 1;
constexpr std::uint64_t kDirect = ~std::uint64_t{0};
// Each thread's lists start with blocks of every class up to
// 2^kPrefilledLargestShift bytes (about 2.3 MiB in all), so that the
// high-water marks an environment reaches after its first episode (more
// simultaneous contact pairs than before: collision algorithms, pair caches,
// manifolds; Bullet's solver arrays growing) are served from the pool. The
// counts cover what 40 episodes of random play in each of the 16
// environments needed after the first, with room to spare.
constexpr int kPrefilledLargestShift = 16;
constexpr int prefilled_blocks(int shift) { return shift <= 8 ? 128 : shift <= 12 ? 32 : 16; }

// A header in front of every block we hand out, 16 bytes so the block keeps
// malloc's 16-byte alignment. The tag sits right before the block: in a block
// from plain malloc those 8 bytes are the C library's chunk size field, which
// never equals the tag.
struct Header {
  std::uint64_t size_class;
  std::uint64_t tag;
};
static_assert(sizeof(Header) == 16);
constexpr std::uint64_t kTag = 0x6273672d706f6f6cULL;  // "bsg-pool"

struct FreeBlock {
  FreeBlock* next;
};

void* carve(std::uint64_t size_class, std::size_t size) {
  const std::size_t bytes =
      size_class == kDirect ? size : std::size_t{1} << (size_class + kSmallestShift);
  auto* header = static_cast<Header*>(std::malloc(sizeof(Header) + bytes));
  if (header == nullptr) return nullptr;
  header->size_class = size_class;
  header->tag = kTag;
  return header + 1;
}

// The calling thread's free lists. Blocks freed after the thread's lists are
// gone (thread exit, static destruction) go straight back to the C library.
enum class ListsState : unsigned char { kUnborn, kAlive, kGone };
thread_local ListsState lists_state = ListsState::kUnborn;  // trivial: valid after ~ThreadLists

class ThreadLists {
 public:
  ThreadLists() {
    lists_state = ListsState::kAlive;
    for (int shift = kSmallestShift; shift <= kPrefilledLargestShift; ++shift) {
      const auto size_class = static_cast<std::uint64_t>(shift - kSmallestShift);
      for (int i = 0; i < prefilled_blocks(shift); ++i) {
        auto* block = static_cast<FreeBlock*>(carve(size_class, 0));
        if (block == nullptr) return;  // out of memory: later requests go to malloc
        block->next = heads_[size_class];
        heads_[size_class] = block;
      }
    }
  }
  ~ThreadLists() {
    lists_state = ListsState::kGone;
    for (FreeBlock* head : heads_) {
      while (head != nullptr) {
        FreeBlock* next = head->next;
        std::free(reinterpret_cast<Header*>(head) - 1);
        head = next;
      }
    }
  }
  FreeBlock*& head(std::uint64_t size_class) { return heads_[size_class]; }

 private:
  std::array<FreeBlock*, kClasses> heads_{};
};

// Null once the calling thread's lists have been destroyed.
ThreadLists* thread_lists() {
  if (lists_state == ListsState::kGone) return nullptr;
  thread_local ThreadLists lists;
  return &lists;
}

std::uint64_t size_class_of(std::size_t size) {
  const std::size_t rounded = std::bit_ceil(std::max<std::size_t>(size, 1));
  const int shift = std::max(kSmallestShift, std::countr_zero(rounded));
  return shift > kLargestShift ? kDirect : static_cast<std::uint64_t>(shift - kSmallestShift);
}

}  // namespace

void* bullet_pool_allocate(std::size_t size) {
  const std::uint64_t size_class = size_class_of(size);
  if (size_class != kDirect) {
    if (ThreadLists* lists = thread_lists()) {
      FreeBlock*& head = lists->head(size_class);
      if (head != nullptr) {
        FreeBlock* block = head;
        head = block->next;
        return block;
      }
    }
  }
  return carve(size_class, size);
}

void bullet_pool_free(void* block) {
  if (block == nullptr) return;
  Header* header = static_cast<Header*>(block) - 1;
  if (header->tag != kTag) {  // allocated before the pool was installed
    std::free(block);
    return;
  }
  if (header->size_class != kDirect) {
    if (ThreadLists* lists = thread_lists()) {
      FreeBlock*& head = lists->head(header->size_class);
      auto* free_block = static_cast<FreeBlock*>(block);
      free_block->next = head;
      head = free_block;
      return;
    }
  }
  header->tag = 0;
  std::free(header);
}

void install_bullet_block_pool() {
#if defined(__SANITIZE_ADDRESS__)
  // Under AddressSanitizer Bullet keeps the C library's allocator, so that
  // ASan watches every Bullet block (and the foreign-block check below, which
  // reads the 8 bytes before a block, never runs on ASan's redzones).
  return;
#endif
  static std::once_flag installed;
  std::call_once(installed, [] { btAlignedAllocSetCustom(bullet_pool_allocate, bullet_pool_free); });
}

}  // namespace bsg::envs
