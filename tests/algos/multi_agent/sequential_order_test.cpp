// The order of a sequential round (algos/multi_agent/sequential_order.h): a permutation of the
// agents, the same from the same seed and update, uniform over the permutations, and refused
// when it is not one.
#include "algos/multi_agent/sequential_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <vector>

namespace bsg::algos {
namespace {

TEST(SequentialAgentOrder, IsAPermutationOfEveryAgent) {
  for (int agents = 1; agents <= 7; ++agents) {
    for (std::uint64_t update = 0; update < 50; ++update) {
      std::vector<int> order = sequential_agent_order(agents, 11, update);
      std::sort(order.begin(), order.end());
      std::vector<int> expected(static_cast<std::size_t>(agents));
      std::iota(expected.begin(), expected.end(), 0);
      EXPECT_EQ(order, expected) << agents << " agents, update " << update;
    }
  }
}

TEST(SequentialAgentOrder, IsReproducibleFromTheSeedAndDrawnAfreshPerUpdate) {
  std::set<std::vector<int>> seen;
  for (std::uint64_t update = 0; update < 20; ++update) {
    const std::vector<int> order = sequential_agent_order(5, 3, update);
    EXPECT_EQ(order, sequential_agent_order(5, 3, update));
    seen.insert(order);
  }
  // 20 uniform draws of 120 permutations: all alike with probability 120^-19.
  EXPECT_GT(seen.size(), 10u);
  std::set<std::vector<int>> other_seed;
  for (std::uint64_t update = 0; update < 20; ++update) other_seed.insert(sequential_agent_order(5, 4, update));
  EXPECT_NE(seen, other_seed);
}

TEST(SequentialAgentOrder, IsUniformOverThePermutations) {
  // 6000 orders of 3 agents: each of the 6 permutations 1000 times on average, standard
  // deviation sqrt(6000 (1/6)(5/6)) = 28.9; the bounds are 5 standard deviations.
  std::map<std::vector<int>, int> counts;
  for (std::uint64_t update = 0; update < 6000; ++update) ++counts[sequential_agent_order(3, 17, update)];
  ASSERT_EQ(counts.size(), 6u);
  for (const auto& [order, count] : counts) {
    EXPECT_GT(count, 855);
    EXPECT_LT(count, 1145);
  }
}

TEST(SequentialAgentOrder, RefusesWhatIsNotAPermutation) {
  Rng rng(1);
  EXPECT_THROW(sequential_agent_order(0, rng), std::invalid_argument);
  const std::vector<int> repeated{0, 0, 2};
  const std::vector<int> out_of_range{0, 3, 1};
  const std::vector<int> too_short{1, 0};
  const std::vector<int> permutation{2, 0, 1};
  EXPECT_THROW(check_agent_order(repeated, 3), std::invalid_argument);
  EXPECT_THROW(check_agent_order(out_of_range, 3), std::invalid_argument);
  EXPECT_THROW(check_agent_order(too_short, 3), std::invalid_argument);
  EXPECT_NO_THROW(check_agent_order(permutation, 3));
  try {
    check_agent_order(repeated, 3);
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("not a permutation of 0..2"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace bsg::algos
