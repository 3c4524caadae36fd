#include "common/random.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace bsg {

double uniform01(Rng& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;  // 53 high bits -> [0, 1)
}

double uniform(Rng& rng, double low, double high) {
  return low + (high - low) * uniform01(rng);
}

double standard_normal(Rng& rng) {
  const double u1 = 1.0 - uniform01(rng);  // (0, 1]: log is finite
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::uint64_t uniform_index(Rng& rng, std::uint64_t count) {
  if (count == 0) throw std::invalid_argument("uniform_index: count must be positive, got 0");
  // Rejection sampling on the largest multiple of `count` below 2^64.
  const std::uint64_t limit = Rng::max() - Rng::max() % count;
  std::uint64_t draw = rng();
  while (draw >= limit) draw = rng();
  return draw % count;
}

}  // namespace bsg
