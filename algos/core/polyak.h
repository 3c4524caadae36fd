// Polyak averaging of target networks (Lillicrap et al. 2016, "soft target updates"):
//   theta' <- (1 - tau) theta' + tau theta
#pragma once

#include <Eigen/Core>

namespace bsg::algos {

void polyak_update(Eigen::Ref<Eigen::VectorXd> target, const Eigen::Ref<const Eigen::VectorXd>& online, double tau);

}  // namespace bsg::algos
