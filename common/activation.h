// The hidden-layer activation of the MLPs (config key `activation`,
// docs/algorithms.md#networks): tanh, the original's and every on-policy
// learner's, or relu, the choice of OmniSafe's and FSRL's off-policy networks.
// Output layers are always the identity.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace bsg {

enum class Activation { tanh, relu };
inline constexpr std::array<std::string_view, 2> kActivationNames = {"tanh", "relu"};

inline std::string_view to_string(Activation activation) {
  return kActivationNames[static_cast<std::size_t>(activation)];
}

}  // namespace bsg
