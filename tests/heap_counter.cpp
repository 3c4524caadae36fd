#include "heap_counter.h"

#include <atomic>
#include <cstddef>

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define BSG_COUNT_HEAP 1
namespace {
std::atomic<long> counted_calls{0};
}
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* __libc_realloc(void* pointer, std::size_t size);
extern "C" void* malloc(std::size_t size) {
  counted_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t count, std::size_t size) {
  counted_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
extern "C" void* realloc(void* pointer, std::size_t size) {
  counted_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
#endif

namespace bsg::testing {

bool heap_calls_countable() {
#ifdef BSG_COUNT_HEAP
  return true;
#else
  return false;
#endif
}

long heap_calls() {
#ifdef BSG_COUNT_HEAP
  return counted_calls.load();
#else
  return 0;
#endif
}

}  // namespace bsg::testing
