// The order of one sequential multi-agent update (HAPPO, Kuba et al. 2022; MACPO, Gu et al.
// 2021): the agents are updated one after another in a uniformly random permutation,
// drawn afresh for every update. SafePO draws it with torch.randperm(num_agents) in Runner.train
// (safepo/multi_agent/happo.py and macpo.py); here it is a Fisher-Yates shuffle
// (algos/core/shuffle.h) of bsg's own seed stream, so the orders differ from SafePO's.
//
// Every rank must update the agents in the same order (each agent's step averages over ranks),
// so the stream has no rank: the seed of update k is derive_seed(run seed, agent_order, 0, k).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/random.h"

namespace bsg::algos {

// A uniformly random permutation of 0 .. agent_count - 1 drawn from `rng`. Throws
// std::invalid_argument if agent_count < 1.
std::vector<int> sequential_agent_order(int agent_count, Rng& rng);

// The order of update `update_index` (the epoch) of a run seeded `run_seed`.
std::vector<int> sequential_agent_order(int agent_count, std::uint64_t run_seed, std::uint64_t update_index);

// Throws std::invalid_argument naming the problem unless `order` is a permutation of 0 .. agent_count - 1.
void check_agent_order(std::span<const int> order, int agent_count);

}  // namespace bsg::algos
