// The factory of the trust-region family: the RunConfig's `alg` picks TRPO,
// TRPO-L, CPO, PDO, PCPO, CRPO or RCPO; each reads its keys from the same RunConfig
// (config.trust_region, config.multiplier). A trust-region variant adds its
// case here (docs/architecture.md#adding-things); make_algorithm
// (algos/training/make_algorithm.h) dispatches to this factory by family.
#pragma once

#include <memory>

#include "algos/core/algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

// Throws std::invalid_argument naming the algorithm if config.alg is not of the trust-region family.
std::unique_ptr<OnPolicyAlgorithm> make_trust_region_algorithm(const RunConfig& config);

}  // namespace bsg::algos
