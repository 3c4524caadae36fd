#include "common/seeding.h"

#include <initializer_list>

namespace bsg {

namespace {
constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;
}  // namespace

std::uint64_t splitmix64_mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t SplitMix64::next() {
  state_ += kGoldenGamma;
  return splitmix64_mix(state_);
}

std::uint64_t derive_seed(std::uint64_t run_seed, SeedStream stream, std::uint64_t rank,
                          std::uint64_t index) {
  // Absorb one word at a time: h <- mix(h + gamma * (word + 1)). Each step is
  // a bijection of h for a fixed word, so different paths collide only by
  // 64-bit coincidence; the +1 keeps a zero word from being a no-op.
  std::uint64_t h = splitmix64_mix(run_seed + kGoldenGamma);
  for (std::uint64_t word : {static_cast<std::uint64_t>(stream), rank, index}) {
    h = splitmix64_mix(h + kGoldenGamma * (word + 1));
  }
  return h;
}

std::uint64_t environment_seed(std::uint64_t run_seed, std::uint64_t rank,
                               std::uint64_t env_index) {
  return derive_seed(run_seed, SeedStream::environment, rank, env_index);
}

std::int64_t original_rank_seed(std::int64_t run_seed, int rank) {
  return run_seed + 10000 * static_cast<std::int64_t>(rank);
}

}  // namespace bsg
