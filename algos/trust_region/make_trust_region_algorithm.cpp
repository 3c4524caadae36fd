#include "algos/trust_region/make_trust_region_algorithm.h"

#include <stdexcept>
#include <string>

#include "algos/trust_region/cpo.h"
#include "algos/trust_region/crpo.h"
#include "algos/trust_region/lag_trpo.h"
#include "algos/trust_region/pcpo.h"
#include "algos/trust_region/pdo.h"
#include "algos/trust_region/rcpo.h"
#include "algos/trust_region/trpo.h"

namespace bsg::algos {

std::unique_ptr<OnPolicyAlgorithm> make_trust_region_algorithm(const RunConfig& config) {
  switch (config.alg) {
    case Algorithm::trpo:
    case Algorithm::trpo_saute:  // TRPO's update; the budget decorator is the run's (algos/training/budget_decorator.h)
    case Algorithm::trpo_early_terminated:
    case Algorithm::trpo_simmer: return std::make_unique<Trpo>(config);  // Simmer's controller: make_algorithm
    case Algorithm::lag_trpo: return std::make_unique<LagTrpo>(config);
    case Algorithm::cpo: return std::make_unique<Cpo>(config);
    case Algorithm::pdo: return std::make_unique<Pdo>(config);
    case Algorithm::pcpo: return std::make_unique<Pcpo>(config);
    case Algorithm::crpo: return std::make_unique<Crpo>(config);
    case Algorithm::rcpo: return std::make_unique<Rcpo>(config);
    default: break;
  }
  throw std::invalid_argument("make_trust_region_algorithm: " + std::string(to_string(config.alg)) +
                              " is not a trust-region algorithm");
}

}  // namespace bsg::algos
