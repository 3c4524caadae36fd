// The factory of the first-order family: the RunConfig's `alg` picks PPO,
// PPO-Lag (CPPO-PID with the PID multiplier), FOCOPS, CUP, P3O or IPO; each reads its
// keys from the same RunConfig (config.first_order, config.multiplier). A
// first-order variant adds its case here; make_algorithm
// (algos/training/make_algorithm.h) dispatches to this factory by family.
#pragma once

#include <memory>

#include "algos/core/algorithm.h"
#include "common/run_config.h"

namespace bsg::algos {

// Throws std::invalid_argument naming the algorithm if config.alg is not of the first-order family.
std::unique_ptr<OnPolicyAlgorithm> make_first_order_algorithm(const RunConfig& config);

}  // namespace bsg::algos
