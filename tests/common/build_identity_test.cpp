// The build record of a run directory (common/build_identity.h): this build's
// vector instructions follow the compiler's own macros, the text round-trips,
// a foreign or damaged record is refused, and a difference is named.
#include "common/build_identity.h"

#include <gtest/gtest.h>

#include <string>

namespace {

// The oracle: the instruction-set macros of the compiler, read here in a
// translation unit built with the same code generation options.
std::string expected_vector_instructions() {
  std::string widest;
#if defined(__AVX512F__) && !defined(EIGEN_DONT_VECTORIZE)
  widest = "AVX512";
#elif defined(__AVX2__)
  widest = "AVX2";
#elif defined(__AVX__)
  widest = "AVX";
#elif defined(__SSE4_2__)
  widest = "SSE4.2";
#elif defined(__SSE4_1__)
  widest = "SSE4.1";
#elif defined(__SSSE3__)
  widest = "SSSE3";
#elif defined(__SSE3__)
  widest = "SSE3";
#else
  widest = "SSE2";  // every x86-64 CPU
#endif
#if defined(__FMA__)
  widest += " FMA";
#endif
  return widest;
}

TEST(BuildIdentity, ThisBuildNamesTheInstructionSetsItWasCompiledFor) {
  const bsg::BuildIdentity build = bsg::this_build();
  EXPECT_EQ(build.vector_instructions, expected_vector_instructions());
#if defined(__GNUC__) && !defined(__clang__)
  EXPECT_EQ(build.compiler, "GCC " + std::to_string(__GNUC__) + "." + std::to_string(__GNUC_MINOR__) + "." +
                                std::to_string(__GNUC_PATCHLEVEL__));
#endif
  EXPECT_FALSE(build.eigen.empty());
}

TEST(BuildIdentity, TextRoundTrips) {
  const bsg::BuildIdentity build{"GCC 12.2.0", "3.4.0", "AVX2 FMA"};
  EXPECT_EQ(bsg::to_text(build), "compiler: GCC 12.2.0\neigen: 3.4.0\nvector_instructions: AVX2 FMA\n");
  EXPECT_EQ(bsg::parse_build_identity(bsg::to_text(build)), build);
}

TEST(BuildIdentity, AMissingOrUnknownLineIsNoRecord) {
  EXPECT_FALSE(bsg::parse_build_identity("compiler: GCC 12.2.0\neigen: 3.4.0\n").has_value());
  EXPECT_FALSE(bsg::parse_build_identity("compiler: GCC 12.2.0\neigen: 3.4.0\nvector_instructions: AVX\nflags: x\n")
                   .has_value());
  EXPECT_FALSE(bsg::parse_build_identity("").has_value());
}

TEST(BuildIdentity, TheDifferenceNamesEveryFieldThatChanged) {
  const bsg::BuildIdentity recorded{"GCC 12.2.0", "3.4.0", "AVX2 FMA"};
  EXPECT_EQ(bsg::describe_difference(recorded, recorded), "");
  bsg::BuildIdentity current = recorded;
  current.vector_instructions = "SSE4.2";
  EXPECT_EQ(bsg::describe_difference(recorded, current), "vector instructions AVX2 FMA -> SSE4.2");
  current.compiler = "GCC 13.1.0";
  EXPECT_EQ(bsg::describe_difference(recorded, current),
            "compiler GCC 12.2.0 -> GCC 13.1.0, vector instructions AVX2 FMA -> SSE4.2");
}

}  // namespace
