// The floating-point type of the learner's batch arithmetic (config key
// `dtype`): the forward, backward and Jacobian-vector passes of the policy and
// value networks over a batch, hence the surrogate, its gradient, the
// Fisher-vector products, the line-search evaluations and the value fits.
// Parameters, optimiser moments and the conjugate-gradient vectors (a few
// thousand numbers each) stay double in both cases, so checkpoints have one
// format and a float32 run resumes bit for bit.
#pragma once

#include <array>
#include <string_view>

namespace bsg {

enum class Dtype { float32, float64 };
inline constexpr std::array<std::string_view, 2> kDtypeNames = {"float32", "float64"};

inline std::string_view to_string(Dtype dtype) { return kDtypeNames[static_cast<std::size_t>(dtype)]; }

}  // namespace bsg
