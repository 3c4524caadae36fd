// Counts heap allocations (malloc, calloc, realloc) made by the whole test
// program, for the tests that show a hot path allocates nothing. Counting
// works with glibc and not under AddressSanitizer, which owns malloc itself;
// heap_calls_countable() says which. Operator new, Eigen and Bullet's
// btAlignedAlloc all end in malloc, so they are counted too.
#pragma once

#include <utility>

namespace bsg::testing {

bool heap_calls_countable();
long heap_calls();

// Heap allocations made while `call` runs.
template <typename Call>
long allocations_of(Call&& call) {
  const long before = heap_calls();
  std::forward<Call>(call)();
  return heap_calls() - before;
}

}  // namespace bsg::testing
