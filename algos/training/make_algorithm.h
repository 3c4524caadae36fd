// The factory of the on-policy algorithms: the RunConfig's `alg` picks its
// family's factory, make_trust_region_algorithm (TRPO, TRPO-L, CPO, PDO, PCPO,
// CRPO, RCPO; algos/trust_region/make_trust_region_algorithm.h) or
// make_first_order_algorithm (PPO, PPO-Lag, FOCOPS, CUP, P3O, IPO;
// algos/first_order/make_first_order_algorithm.h); every hyper-parameter the
// update needs is read from the same RunConfig. Throws std::invalid_argument
// for an off-policy algorithm.
#pragma once

#include <memory>

#include "algos/core/algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

std::unique_ptr<OnPolicyAlgorithm> make_algorithm(const RunConfig& config);

}  // namespace bsg::algos
