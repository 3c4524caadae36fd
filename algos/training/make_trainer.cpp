#include "algos/training/make_trainer.h"

#include <stdexcept>
#include <string>

#include "algos/training/off_policy_trainer.h"
#include "algos/training/multi_agent_trainer.h"
#include "algos/training/offline_trainer.h"
#include "algos/training/on_policy_trainer.h"

namespace bsg::algos {

std::unique_ptr<Trainer> make_trainer(const RunConfig& config, const RunDirectory& directory, const MpiContext& mpi,
                                      const TrainerOptions& options) {
  switch (algorithm_info(config.alg).family) {
    case AlgorithmFamily::trust_region:
    case AlgorithmFamily::first_order: return std::make_unique<OnPolicyTrainer>(config, directory, mpi, options);
    case AlgorithmFamily::off_policy: return std::make_unique<OffPolicyTrainer>(config, directory, mpi, options);
    case AlgorithmFamily::offline: return std::make_unique<OfflineTrainer>(config, directory, mpi, options);
    case AlgorithmFamily::multi_agent: return std::make_unique<MultiAgentTrainer>(config, directory, mpi, options);
  }
  throw std::invalid_argument("make_trainer: unknown family of " + std::string(to_string(config.alg)));
}

}  // namespace bsg::algos
