#include "algos/off_policy/make_off_policy_learner.h"

#include <stdexcept>
#include <string>

#include "algos/off_policy/ddpg_learner.h"
#include "algos/off_policy/sac_learner.h"
#include "algos/off_policy/td3_learner.h"

namespace bsg::algos {

std::unique_ptr<OffPolicyLearner> make_off_policy_learner(const RunConfig& config, int observation_size,
                                                          int action_size, int cost_count, Rng& init_rng) {
  OffPolicyOptions options = OffPolicyOptions::from_config(config, action_size);
  switch (config.alg) {
    case Algorithm::sac:
    case Algorithm::sac_lag:
      return std::make_unique<SacLearner>(std::move(options), observation_size, action_size, cost_count, init_rng);
    case Algorithm::td3:
    case Algorithm::td3_lag:
      return std::make_unique<Td3Learner>(std::move(options), observation_size, action_size, cost_count, init_rng);
    case Algorithm::ddpg:
    case Algorithm::ddpg_lag:
      return std::make_unique<DdpgLearner>(std::move(options), observation_size, action_size, cost_count, init_rng);
    default:
      break;
  }
  throw std::invalid_argument("make_off_policy_learner: " + std::string(to_string(config.alg)) +
                              " is not an off-policy algorithm");
}

}  // namespace bsg::algos
