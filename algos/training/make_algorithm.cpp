#include "algos/training/make_algorithm.h"

#include <cstddef>
#include <stdexcept>
#include <string>

#include "algos/first_order/make_first_order_algorithm.h"
#include "algos/training/simmer_algorithm.h"
#include "algos/trust_region/make_trust_region_algorithm.h"

namespace bsg::algos {

std::unique_ptr<OnPolicyAlgorithm> make_algorithm(const RunConfig& config) {
  if (static_cast<std::size_t>(config.alg) >= kAlgorithms.size()) {
    throw std::invalid_argument("make_algorithm: unknown alg value " + std::to_string(static_cast<int>(config.alg)));
  }
  // Simmer: the base update under its budget controllers (simmer_algorithm.h).
  if (schedules_saute_budgets(config.alg)) {
    return std::make_unique<SimmerAlgorithm>(config, algorithm_info(config.alg).family == AlgorithmFamily::trust_region
                                                         ? make_trust_region_algorithm(config)
                                                         : make_first_order_algorithm(config));
  }
  switch (algorithm_info(config.alg).family) {
    case AlgorithmFamily::trust_region: return make_trust_region_algorithm(config);
    case AlgorithmFamily::first_order: return make_first_order_algorithm(config);
    case AlgorithmFamily::off_policy:
      throw std::invalid_argument("make_algorithm: " + std::string(to_string(config.alg)) +
                                  " is an off-policy learner; it trains with OffPolicyTrainer, not the on-policy loop");
    case AlgorithmFamily::offline:
      throw std::invalid_argument("make_algorithm: " + std::string(to_string(config.alg)) +
                                  " is an offline algorithm; it trains with OfflineTrainer, not the on-policy loop");
    case AlgorithmFamily::multi_agent:
      throw std::invalid_argument("make_algorithm: " + std::string(to_string(config.alg)) +
                                  " is a multi-agent learner; it trains with MultiAgentTrainer, not the on-policy loop");
  }
  throw std::invalid_argument("make_algorithm: unknown family of " + std::string(to_string(config.alg)));
}

}  // namespace bsg::algos
