#include "algos/core/acting_policy.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {

void check_acting_sizes(const ActingPolicy& policy, std::span<const double> observation, std::span<double> action,
                        const char* who) {
  if (static_cast<int>(observation.size()) != policy.observation_size() ||
      static_cast<int>(action.size()) != policy.action_size()) {
    throw std::invalid_argument(std::string(who) + ": the policy takes " + std::to_string(policy.observation_size()) +
                                " observations and gives " + std::to_string(policy.action_size()) +
                                " actions, the environment has " + std::to_string(observation.size()) + " and " +
                                std::to_string(action.size()));
  }
}

}  // namespace bsg::algos
