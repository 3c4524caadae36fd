#include "common/run_config.h"

#include <cstddef>

namespace bsg {

namespace {
template <std::size_t N, typename Enum>
std::string_view name_of(const std::array<std::string_view, N>& names, Enum value) {
  const auto index = static_cast<std::size_t>(value);
  return index < N ? names[index] : std::string_view("<invalid>");
}
}  // namespace

std::string_view to_string(Algorithm alg) { return name_of(kAlgorithmNames, alg); }
std::string_view to_string(LambdaOptimizer optimizer) {
  return name_of(kLambdaOptimizerNames, optimizer);
}
std::string_view to_string(CpoRSign sign) { return name_of(kCpoRSignNames, sign); }
std::string_view to_string(PcpoProjection projection) {
  return name_of(kPcpoProjectionNames, projection);
}
std::string_view to_string(Learner learner) { return name_of(kLearnerNames, learner); }

}  // namespace bsg
