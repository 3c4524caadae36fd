// Explicit, portable random numbers. Every consumer receives an `Rng&` from its
// owner (no global RNG state); the draws below are written out by hand instead
// of using <random>'s distributions, whose algorithms differ between standard
// libraries, so that one seed gives the same numbers everywhere.
#pragma once

#include <cstdint>
#include <random>

namespace bsg {

// The engine every component draws from (seeded as `seed + 10000 * rank`, docs/algorithms.md#across-mpi-ranks).
using Rng = std::mt19937_64;

// Uniform on [0, 1) with 53 random bits.
double uniform01(Rng& rng);

// Uniform on [low, high).
double uniform(Rng& rng, double low, double high);

// Standard normal N(0, 1) by the Box–Muller transform (one value per two uniforms).
double standard_normal(Rng& rng);

// Uniform integer in [0, count) without modulo bias; throws if count == 0.
std::uint64_t uniform_index(Rng& rng, std::uint64_t count);

}  // namespace bsg
