#include "algos/lagrange/pid_multiplier_rule.h"

namespace bsg::algos {

double PidMultiplierRule::step(double /*lambda*/, double mean_episode_cost, double cost_limit) {
  return pid_.update(mean_episode_cost, cost_limit).lambda;  // max(0, P + I + D), at most lambda_max
}

std::vector<NamedScalar> PidMultiplierRule::diagnostics() const {
  const PidTerms& terms = pid_.last_terms();
  return {{"PID/P", terms.proportional}, {"PID/I", terms.integral}, {"PID/D", terms.derivative}};
}

}  // namespace bsg::algos
