#include "common/build_identity.h"

#include <Eigen/Core>
#include <sstream>
#include <vector>

namespace bsg {

namespace {

std::string compiler_name() {
#if defined(__clang__)
  return "Clang " __clang_version__;
#elif defined(__GNUC__)
  return "GCC " + std::to_string(__GNUC__) + "." + std::to_string(__GNUC_MINOR__) + "." +
         std::to_string(__GNUC_PATCHLEVEL__);
#else
  return "unknown compiler";
#endif
}

// Eigen's own macros, set from the code generation options: the widest packet
// it uses decides the kernels; FMA decides whether its products are fused.
std::string eigen_vector_instructions() {
  std::vector<std::string> sets;
#if defined(EIGEN_VECTORIZE_AVX512)
  sets.push_back("AVX512");
#elif defined(EIGEN_VECTORIZE_AVX2)
  sets.push_back("AVX2");
#elif defined(EIGEN_VECTORIZE_AVX)
  sets.push_back("AVX");
#elif defined(EIGEN_VECTORIZE_SSE4_2)
  sets.push_back("SSE4.2");
#elif defined(EIGEN_VECTORIZE_SSE4_1)
  sets.push_back("SSE4.1");
#elif defined(EIGEN_VECTORIZE_SSSE3)
  sets.push_back("SSSE3");
#elif defined(EIGEN_VECTORIZE_SSE3)
  sets.push_back("SSE3");
#elif defined(EIGEN_VECTORIZE_SSE2)
  sets.push_back("SSE2");
#else
  sets.push_back("none");
#endif
#if defined(EIGEN_VECTORIZE_FMA)
  sets.push_back("FMA");
#endif
  std::string text;
  for (const std::string& set : sets) text += (text.empty() ? "" : " ") + set;
  return text;
}

constexpr std::string_view kCompiler = "compiler: ";
constexpr std::string_view kEigen = "eigen: ";
constexpr std::string_view kVector = "vector_instructions: ";

}  // namespace

BuildIdentity this_build() {
  return {compiler_name(),
          std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
              std::to_string(EIGEN_MINOR_VERSION),
          eigen_vector_instructions()};
}

std::string to_text(const BuildIdentity& identity) {
  return std::string(kCompiler) + identity.compiler + "\n" + std::string(kEigen) + identity.eigen + "\n" +
         std::string(kVector) + identity.vector_instructions + "\n";
}

std::optional<BuildIdentity> parse_build_identity(std::string_view text) {
  BuildIdentity identity;
  bool has_compiler = false, has_eigen = false, has_vector = false;
  std::istringstream lines{std::string(text)};
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    if (line.starts_with(kCompiler)) {
      identity.compiler = line.substr(kCompiler.size());
      has_compiler = true;
    } else if (line.starts_with(kEigen)) {
      identity.eigen = line.substr(kEigen.size());
      has_eigen = true;
    } else if (line.starts_with(kVector)) {
      identity.vector_instructions = line.substr(kVector.size());
      has_vector = true;
    } else {
      return std::nullopt;
    }
  }
  if (!has_compiler || !has_eigen || !has_vector) return std::nullopt;
  return identity;
}

std::string describe_difference(const BuildIdentity& recorded, const BuildIdentity& current) {
  std::string text;
  const auto add = [&text](std::string_view what, const std::string& from, const std::string& to) {
    if (from == to) return;
    text += (text.empty() ? "" : ", ") + std::string(what) + " " + from + " -> " + to;
  };
  add("compiler", recorded.compiler, current.compiler);
  add("Eigen", recorded.eigen, current.eigen);
  add("vector instructions", recorded.vector_instructions, current.vector_instructions);
  return text;
}

}  // namespace bsg
