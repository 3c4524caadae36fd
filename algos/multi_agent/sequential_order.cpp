#include "algos/multi_agent/sequential_order.h"

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "algos/core/shuffle.h"
#include "common/seeding.h"

namespace bsg::algos {

std::vector<int> sequential_agent_order(int agent_count, Rng& rng) {
  if (agent_count < 1) {
    throw std::invalid_argument("sequential_agent_order: agent_count must be >= 1, got " +
                                std::to_string(agent_count));
  }
  std::vector<Eigen::Index> permutation(static_cast<std::size_t>(agent_count));
  shuffle_permutation(permutation, rng);
  return std::vector<int>(permutation.begin(), permutation.end());
}

std::vector<int> sequential_agent_order(int agent_count, std::uint64_t run_seed, std::uint64_t update_index) {
  Rng rng(derive_seed(run_seed, SeedStream::agent_order, 0, update_index));  // rank 0 on every rank
  return sequential_agent_order(agent_count, rng);
}

void check_agent_order(std::span<const int> order, int agent_count) {
  if (static_cast<int>(order.size()) != agent_count) {
    throw std::invalid_argument("sequential update: the order names " + std::to_string(order.size()) +
                                " agents, expected " + std::to_string(agent_count));
  }
  std::vector<bool> seen(static_cast<std::size_t>(agent_count), false);
  for (const int agent : order) {
    if (agent < 0 || agent >= agent_count || seen[static_cast<std::size_t>(agent)]) {
      throw std::invalid_argument("sequential update: the order is not a permutation of 0.." +
                                  std::to_string(agent_count - 1) + " (agent " + std::to_string(agent) +
                                  " out of range or repeated)");
    }
    seen[static_cast<std::size_t>(agent)] = true;
  }
}

}  // namespace bsg::algos
