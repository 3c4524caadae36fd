#include "algos/lagrange/multiplier_rule.h"

#include <stdexcept>
#include <string>

#include "algos/lagrange/adam_multiplier_rule.h"
#include "algos/lagrange/pid_multiplier_rule.h"
#include "algos/lagrange/sgd_multiplier_rule.h"

namespace bsg::algos {

std::unique_ptr<MultiplierRule> make_multiplier_rule(LambdaOptimizer optimizer, double learning_rate,
                                                     double initial_lambda, const PidLagrangianOptions& pid) {
  switch (optimizer) {
    case LambdaOptimizer::sgd: return std::make_unique<SgdMultiplierRule>(learning_rate);
    case LambdaOptimizer::adam: return std::make_unique<AdamMultiplierRule>(learning_rate);
    case LambdaOptimizer::pid: return std::make_unique<PidMultiplierRule>(initial_lambda, pid);
  }
  throw std::invalid_argument("make_multiplier_rule: unknown lambda_optimizer value " +
                              std::to_string(static_cast<int>(optimizer)));
}

}  // namespace bsg::algos
