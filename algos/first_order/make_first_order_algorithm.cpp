#include "algos/first_order/make_first_order_algorithm.h"

#include <stdexcept>
#include <string>

#include "algos/first_order/cup.h"
#include "algos/first_order/focops.h"
#include "algos/first_order/ipo.h"
#include "algos/first_order/p3o.h"
#include "algos/first_order/ppo.h"

namespace bsg::algos {

std::unique_ptr<OnPolicyAlgorithm> make_first_order_algorithm(const RunConfig& config) {
  switch (config.alg) {
    case Algorithm::ppo:
    case Algorithm::ppo_lag:
    case Algorithm::ppo_saute:  // PPO's update; the budget decorator is the run's (algos/training/budget_decorator.h)
    case Algorithm::ppo_early_terminated:
    case Algorithm::ppo_simmer: return std::make_unique<Ppo>(config);  // Simmer's controller: make_algorithm
    case Algorithm::focops: return std::make_unique<Focops>(config);
    case Algorithm::cup: return std::make_unique<Cup>(config);
    case Algorithm::p3o: return std::make_unique<P3o>(config);
    case Algorithm::ipo: return std::make_unique<Ipo>(config);
    default: break;
  }
  throw std::invalid_argument("make_first_order_algorithm: " + std::string(to_string(config.alg)) +
                              " is not a first-order algorithm");
}

}  // namespace bsg::algos
