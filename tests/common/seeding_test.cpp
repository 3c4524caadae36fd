// Seeding: SplitMix64 against its published reference sequence, and derived
// seeds that are reproducible, distinct and pinned (changing the derivation
// would silently change every run's randomness).
#include "common/seeding.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>

namespace bsg {
namespace {

TEST(SplitMix64, MatchesReferenceSequenceForSeed1234567) {
  // Output of Vigna's reference splitmix64.c started at x = 1234567.
  SplitMix64 generator(1234567);
  EXPECT_EQ(generator.next(), 6457827717110365317ULL);
  EXPECT_EQ(generator.next(), 3203168211198807973ULL);
  EXPECT_EQ(generator.next(), 9817491932198370423ULL);
  EXPECT_EQ(generator.next(), 4593380528125082431ULL);
  EXPECT_EQ(generator.next(), 16408922859458223821ULL);
}

TEST(DeriveSeed, IsPinnedToTheDocumentedDerivation) {
  // Values from an independent Python implementation of seeding.cpp's comment:
  // h = mix(seed + G); h = mix(h + G (w + 1)) for w in (stream, rank, index).
  EXPECT_EQ(derive_seed(0, SeedStream::environment, 0, 0), 6723298101781840259ULL);
  EXPECT_EQ(derive_seed(42, SeedStream::network_init, 3, 0), 5103638684976656576ULL);
  EXPECT_EQ(environment_seed(4294967295ULL, 63, 7), 2477715625447860051ULL);
}

TEST(DeriveSeed, IsReproducible) {
  for (std::uint64_t rank = 0; rank < 8; ++rank) {
    EXPECT_EQ(derive_seed(17, SeedStream::action_noise, rank, 2),
              derive_seed(17, SeedStream::action_noise, rank, 2));
  }
}

TEST(DeriveSeed, GivesDistinctSeedsAcrossRunSeedsStreamsRanksAndEnvironments) {
  std::set<std::uint64_t> seen;
  std::size_t count = 0;
  for (std::uint64_t run_seed = 0; run_seed < 4; ++run_seed) {
    for (std::uint64_t stream = 1; stream <= 5; ++stream) {
      for (std::uint64_t rank = 0; rank < 64; ++rank) {
        for (std::uint64_t index = 0; index < 8; ++index) {
          seen.insert(derive_seed(run_seed, static_cast<SeedStream>(stream), rank, index));
          ++count;
        }
      }
    }
  }
  EXPECT_EQ(seen.size(), count);
}

TEST(DeriveSeed, DoesNotConfuseRankAndIndex) {
  // A naive "seed + rank + index" would map (1, 0) and (0, 1) to one seed.
  EXPECT_NE(environment_seed(5, 1, 0), environment_seed(5, 0, 1));
  EXPECT_NE(environment_seed(5, 0, 0), environment_seed(6, 0, 0));
}

TEST(OriginalRankSeed, IsSeedPlusTenThousandTimesRank) {
  // docs/algorithms.md#set-up, step 4: seed_rank = seed + 10000 * rank.
  EXPECT_EQ(original_rank_seed(7, 0), 7);
  EXPECT_EQ(original_rank_seed(7, 3), 30007);
  EXPECT_EQ(original_rank_seed(65535, 63), 695535);
}

}  // namespace
}  // namespace bsg
