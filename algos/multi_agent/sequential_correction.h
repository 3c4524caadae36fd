// The correction factor of a sequential update (HAPPO, Kuba et al. 2022; MACPO, Gu et al.
// 2021): once agents i_1 .. i_{m-1} have been updated, sample i of agent i_m's
// surrogate is weighted by
//   M_i = prod_{j < m} pi_new^{i_j}(a_i^{i_j} | o_i^{i_j}) / pi_old^{i_j}(a_i^{i_j} | o_i^{i_j})
// kept here as log M_i = sum_j (log pi_new - log pi_old), so that a long product of ratios
// neither overflows nor underflows before the exponential.
//
// As SafePO (safepo/multi_agent/happo.py and macpo.py, Runner.train): pi_old is the agent's
// policy just before its own update and pi_new just after it (both evaluated on the batch, both
// detached: M is a constant weight, no gradient flows through it), the ratio is the product over
// the agent's action dimensions (a sum of log-probabilities here), and M is neither clipped nor
// normalised. HAPPO multiplies min(rho A, clip(rho) A) by it; MACPO multiplies both the reward
// and the cost advantage by the same M (ratio * factor_batch * adv_targ and
// ratio * factor_batch * cost_adv_targ in macpo.py's trpo_update).
#pragma once

#include <Eigen/Core>

namespace bsg::algos {

// M over a round's samples.
struct CorrectionFactorStatistics {
  double mean = 1.0;
  double min = 1.0;
  double max = 1.0;
};

class CorrectionFactor {
 public:
  // M_i = 1 (log M_i = 0) for `samples` > 0 rows.
  explicit CorrectionFactor(Eigen::Index samples);

  Eigen::Index num_samples() const { return log_factor_.size(); }

  // log M_i += new_log_probs_i - old_log_probs_i: an agent's update has been taken. Throws
  // std::invalid_argument unless both have num_samples() entries.
  void include_agent(const Eigen::Ref<const Eigen::VectorXd>& new_log_probs,
                     const Eigen::Ref<const Eigen::VectorXd>& old_log_probs);

  const Eigen::VectorXd& log_factor() const { return log_factor_; }
  // M_i = exp(log M_i); exactly 1 before any agent was included.
  Eigen::VectorXd factor() const;
  // M_i A_i, the advantage the next agent's surrogate sees (A itself, bit for bit, while M = 1).
  // Throws std::invalid_argument unless `advantages` has num_samples() entries.
  Eigen::VectorXd corrected(const Eigen::Ref<const Eigen::VectorXd>& advantages) const;
  CorrectionFactorStatistics statistics() const;

 private:
  Eigen::VectorXd log_factor_;
};

}  // namespace bsg::algos
