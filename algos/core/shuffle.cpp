#include "algos/core/shuffle.h"

#include <cstdint>
#include <numeric>
#include <utility>

namespace bsg::algos {

void shuffle_permutation(std::vector<Eigen::Index>& permutation, Rng& rng) {
  // Fisher–Yates shuffle with the rank's RNG (not NumPy's permutation stream).
  std::iota(permutation.begin(), permutation.end(), Eigen::Index{0});
  for (Eigen::Index i = static_cast<Eigen::Index>(permutation.size()) - 1; i > 0; --i) {
    const auto j = static_cast<Eigen::Index>(uniform_index(rng, static_cast<std::uint64_t>(i + 1)));
    std::swap(permutation[static_cast<std::size_t>(i)], permutation[static_cast<std::size_t>(j)]);
  }
}

}  // namespace bsg::algos
