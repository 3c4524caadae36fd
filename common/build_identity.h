// What decides the numbers this build of bsg computes, as a record a run
// directory keeps (<run dir>/build.txt) so that a run resumed by another
// build can say that its remaining epochs will not be bit-identical to an
// uninterrupted run (docs/reproducibility.md). Measured: builds for the same
// instruction set agree to the bit whatever CPU they are tuned for; the
// instruction set Eigen vectorises for (SSE2 ... SSE4.2, AVX, AVX2 + FMA)
// chooses its kernels and so the rounding of the learner's sums.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace bsg {

struct BuildIdentity {
  std::string compiler;             // e.g. "GCC 12.2.0"
  std::string eigen;                // e.g. "3.4.0"
  std::string vector_instructions;  // what Eigen vectorises with, e.g. "AVX2 FMA"

  bool operator==(const BuildIdentity&) const = default;
};

// This build's identity (fixed when bsg_common was compiled, with the
// project's code generation options).
BuildIdentity this_build();

// "compiler: ...\neigen: ...\nvector_instructions: ...\n"
std::string to_text(const BuildIdentity& identity);

// The inverse of to_text; std::nullopt if a line is missing or unknown (a
// record from another version is treated as no record).
std::optional<BuildIdentity> parse_build_identity(std::string_view text);

// One line for a person: what differs between the two, e.g.
// "vector instructions AVX2 FMA -> SSE4.2"; empty when they are equal.
std::string describe_difference(const BuildIdentity& recorded, const BuildIdentity& current);

}  // namespace bsg
