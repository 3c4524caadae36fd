// The Fisher–Yates permutation of minibatch passes (the value fits, docs/algorithms.md#value-fits,
// and the first-order policy updates, docs/algorithms.md#first-order-updates), drawn from a rank's RNG.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "common/random.h"

namespace bsg::algos {

// permutation <- a uniformly shuffled 0 .. permutation.size() - 1 (its size is kept).
void shuffle_permutation(std::vector<Eigen::Index>& permutation, Rng& rng);

}  // namespace bsg::algos
