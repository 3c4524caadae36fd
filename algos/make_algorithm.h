// The factory of the five algorithms: the RunConfig's `alg` picks TRPO,
// TRPO-L, CPO, PDO or PCPO; every hyper-parameter the update needs is read
// from the same RunConfig.
#pragma once

#include <memory>

#include "algos/algorithm.h"
#include "common/run_config.h"

namespace bsg {

std::unique_ptr<TrustRegionAlgorithm> make_algorithm(const RunConfig& config);

}  // namespace bsg
