// Seeds derived from a run's base seed. Each random stream of a run (network
// initialisation, action noise, minibatch shuffles, each environment) gets its
// own 64-bit seed by hashing (run seed, stream, rank, index) with the
// SplitMix64 output function, so that streams are independent of each other
// and of the rank count, and the same inputs always give the same seed.
// The original code instead seeds everything on rank r with seed + 10000 r
// (docs/algorithms.md#set-up, step 4); original_rank_seed() reproduces that.
#pragma once

#include <cstdint>

namespace bsg {

// The SplitMix64 generator (Steele, Lea, Flood 2014; Vigna's reference C):
// state += 0x9e3779b97f4a7c15, then the output mix of the new state.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t state) : state_(state) {}
  std::uint64_t next();

 private:
  std::uint64_t state_;
};

// SplitMix64's output mix: a bijection on 64-bit words with good avalanche.
std::uint64_t splitmix64_mix(std::uint64_t z);

// What a derived seed is for. Values are part of the seed derivation: never
// renumber them, only append.
enum class SeedStream : std::uint64_t {
  network_init = 1,
  action_noise = 2,
  minibatch_shuffle = 3,
  environment = 4,
  evaluation_environment = 5,
  evaluation_action_noise = 6,  // the sampled evaluation's eps (sampled_evaluation)
  agent_order = 7,  // the order of a sequential multi-agent update (HAPPO, MACPO), the same on every rank
};

// Seed of stream `stream` on MPI rank `rank`, element `index` (e.g. the
// index of an environment within the rank's vector of environments).
std::uint64_t derive_seed(std::uint64_t run_seed, SeedStream stream, std::uint64_t rank,
                          std::uint64_t index = 0);

// Shorthand: the seed of environment `env_index` on `rank`.
std::uint64_t environment_seed(std::uint64_t run_seed, std::uint64_t rank,
                               std::uint64_t env_index);

// The original's per-rank seed, seed + 10000 * rank (docs/algorithms.md#set-up, step 4, #across-mpi-ranks).
std::int64_t original_rank_seed(std::int64_t run_seed, int rank);

}  // namespace bsg
