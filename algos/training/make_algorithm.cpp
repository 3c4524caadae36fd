#include "algos/training/make_algorithm.h"

#include <stdexcept>
#include <string>

#include "algos/trust_region/cpo.h"
#include "algos/trust_region/crpo.h"
#include "algos/first_order/cup.h"
#include "algos/first_order/focops.h"
#include "algos/trust_region/lag_trpo.h"
#include "algos/trust_region/pcpo.h"
#include "algos/trust_region/pdo.h"
#include "algos/first_order/ppo.h"
#include "algos/trust_region/trpo.h"

namespace bsg::algos {

std::unique_ptr<OnPolicyAlgorithm> make_algorithm(const RunConfig& config) {
  switch (config.alg) {
    case Algorithm::trpo: return std::make_unique<Trpo>(config);
    case Algorithm::lag_trpo: return std::make_unique<LagTrpo>(config);
    case Algorithm::cpo: return std::make_unique<Cpo>(config);
    case Algorithm::pdo: return std::make_unique<Pdo>(config);
    case Algorithm::pcpo: return std::make_unique<Pcpo>(config);
    case Algorithm::crpo: return std::make_unique<Crpo>(config);
    case Algorithm::ppo:
    case Algorithm::ppo_lag: return std::make_unique<Ppo>(config);
    case Algorithm::focops: return std::make_unique<Focops>(config);
    case Algorithm::cup: return std::make_unique<Cup>(config);
    case Algorithm::sac:
    case Algorithm::td3:
    case Algorithm::ddpg:
    case Algorithm::sac_lag:
    case Algorithm::td3_lag:
    case Algorithm::ddpg_lag:
      throw std::invalid_argument("make_algorithm: " + std::string(to_string(config.alg)) +
                                  " is an off-policy learner; it trains with OffPolicyTrainer, not the on-policy loop");
    case Algorithm::bc_all:
    case Algorithm::bc_safe:
      throw std::invalid_argument("make_algorithm: " + std::string(to_string(config.alg)) +
                                  " is an offline algorithm; it trains with OfflineTrainer, not the on-policy loop");
  }
  throw std::invalid_argument("make_algorithm: unknown alg value " + std::to_string(static_cast<int>(config.alg)));
}

}  // namespace bsg::algos
