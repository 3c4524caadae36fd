// SAC's entropy temperature alpha (Haarnoja et al. 2018b, section 5): kept as log alpha so that
// alpha stays positive, fixed at alpha_init or, with auto_alpha, learnt by Adam (alpha_lr) along
//   L(log alpha) = -log alpha (E[log pi(a|s)] + H_target),  dL/dlog alpha = -(E[log pi] + H_target)
// towards the target entropy H_target = -|A|: alpha falls while the policy's entropy is above it.
//
// Parameters: alpha_init 0.2, alpha_lr 3e-4, target_entropy -|A| (off_policy_options.h).
#pragma once

#include <Eigen/Core>

#include "common/adam.h"
#include "common/binary_io.h"

namespace bsg::algos {

class Temperature {
 public:
  Temperature(double alpha_init, double alpha_lr, double target_entropy);

  double alpha() const;
  double log_alpha() const { return log_alpha_(0); }
  double target_entropy() const { return target_entropy_; }

  // L at the current log alpha for a batch whose mean log pi is `log_prob_mean`; `gradient` (if not
  // null) receives dL/dlog alpha.
  double loss(double log_prob_mean, double* gradient) const;
  // One Adam step of log alpha on the (rank-averaged) mean log pi of the actor's batch.
  void step(double log_prob_mean);

  // log alpha (f64), then its Adam state (adam_state.h).
  void save(BinaryWriter& writer) const;
  // Fails on the reader on a log alpha that is not finite or an Adam state of another size.
  void load(BinaryReader& reader);

 private:
  double target_entropy_;
  Eigen::VectorXd log_alpha_;  // one entry, for Adam
  Eigen::VectorXd gradient_;
  Adam adam_;
};

}  // namespace bsg::algos
