#include "algos/training/exploration_noise.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bsg::algos {

double exploration_std(const RunConfig& config, int epoch) {
  if (epoch < 0 || epoch >= config.epochs) {
    throw std::invalid_argument("exploration_std: epoch " + std::to_string(epoch) + " must lie in [0, epochs = " +
                                std::to_string(config.epochs) + ")");
  }
  const double scheduled = config.use_exploration_noise_anneal
                               ? GaussianPolicy::annealed_std(epoch, config.epochs, config.exploration_anneal_epochs)
                               : GaussianPolicy::kInitialStd;
  // A floor of 0 (the default) leaves every sigma as scheduled, bit for bit.
  return std::max(scheduled, config.exploration_std_floor);
}

void set_last_epoch_std(const RunConfig& config, int epochs_completed, GaussianPolicy& policy) {
  if (policy.has_learned_std()) return;
  policy.set_std(exploration_std(config, std::max(0, epochs_completed - 1)));
}

EvaluationActions evaluation_actions(const RunConfig& config) {
  return config.sampled_evaluation ? EvaluationActions::sampled : EvaluationActions::mean;
}

}  // namespace bsg::algos
