#include "algos/core/polyak.h"

#include <stdexcept>

namespace bsg::algos {

void polyak_update(Eigen::Ref<Eigen::VectorXd> target, const Eigen::Ref<const Eigen::VectorXd>& online, double tau) {
  if (target.size() != online.size()) throw std::invalid_argument("polyak_update: target and online sizes differ");
  target = (1.0 - tau) * target + tau * online;
}

}  // namespace bsg::algos
