#include "algos/offline/make_offline_algorithm.h"

#include <stdexcept>
#include <string>

#include "algos/offline/behaviour_cloning.h"

namespace bsg::algos {
namespace {

[[noreturn]] void not_offline(const RunConfig& config) {
  throw std::invalid_argument("offline algorithm: " + std::string(to_string(config.alg)) + " is not offline");
}

}  // namespace

TrainingRows offline_training_rows(const RunConfig& config, const OfflineDataset& dataset) {
  switch (config.alg) {
    case Algorithm::bc_all: return all_rows(dataset);
    case Algorithm::bc_safe: return rows_within_cost_limit(dataset, config.cost_limit);
    default: not_offline(config);
  }
}

std::unique_ptr<OfflineAlgorithm> make_offline_algorithm(const RunConfig& config, int observation_size,
                                                         int action_size, const ObservationScaling& scaling,
                                                         Rng& init_rng) {
  const MlpOptions network{.zero_bias_init = config.zero_bias_init, .dtype = config.dtype,
                           .activation = config.activation};
  switch (config.alg) {
    case Algorithm::bc_all:
    case Algorithm::bc_safe:
      return std::make_unique<BehaviourCloning>(std::string(algorithm_info(config.alg).label), observation_size,
                                                action_size, scaling, config.hidden_sizes, network, config.first_order.actor_lr,
                                                init_rng);
    default: not_offline(config);
  }
}

}  // namespace bsg::algos
