// The factory of the nine algorithms: the RunConfig's `alg` picks TRPO,
// TRPO-L, CPO, PDO or PCPO (algos/trust_region/) or PPO, PPO-Lag (CPPO-PID with
// the PID multiplier), FOCOPS or CUP (algos/first_order/); every
// hyper-parameter the update needs is read from the same RunConfig.
#pragma once

#include <memory>

#include "algos/core/algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

std::unique_ptr<OnPolicyAlgorithm> make_algorithm(const RunConfig& config);

}  // namespace bsg::algos
