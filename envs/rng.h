// The environment's random stream: one per environment, seeded at reset.
// Draws are defined here (not by <random>'s distributions, whose algorithms
// vary between standard libraries) so a seed means the same layout everywhere.
#pragma once

#include <cstdint>
#include <random>

namespace bsg::envs {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0) : engine_(seed) {}
  void seed(std::uint64_t seed) { engine_.seed(seed); }

  // U(0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // U(low, high).
  double uniform(double low, double high) { return low + (high - low) * uniform01(); }

  // The engine's whole state, for checkpoints.
  const std::mt19937_64& engine() const { return engine_; }
  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace bsg::envs
