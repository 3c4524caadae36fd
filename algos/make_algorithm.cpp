#include "algos/make_algorithm.h"

#include <stdexcept>
#include <string>

#include "algos/cpo.h"
#include "algos/lag_trpo.h"
#include "algos/pcpo.h"
#include "algos/pdo.h"
#include "algos/trpo.h"

namespace bsg {

std::unique_ptr<TrustRegionAlgorithm> make_algorithm(const RunConfig& config) {
  switch (config.alg) {
    case Algorithm::trpo: return std::make_unique<Trpo>(config);
    case Algorithm::lag_trpo: return std::make_unique<LagTrpo>(config);
    case Algorithm::cpo: return std::make_unique<Cpo>(config);
    case Algorithm::pdo: return std::make_unique<Pdo>(config);
    case Algorithm::pcpo: return std::make_unique<Pcpo>(config);
  }
  throw std::invalid_argument("make_algorithm: unknown alg value " + std::to_string(static_cast<int>(config.alg)));
}

}  // namespace bsg
