#include "algos/multi_agent/sequential_correction.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

void check_length(const char* where, const char* what, Eigen::Index size, Eigen::Index expected) {
  if (size != expected) {
    throw std::invalid_argument(std::string(where) + ": " + what + " has " + std::to_string(size) +
                                " entries, the factor " + std::to_string(expected));
  }
}

}  // namespace

CorrectionFactor::CorrectionFactor(Eigen::Index samples) : log_factor_(Eigen::VectorXd::Zero(samples)) {
  if (samples <= 0) {
    throw std::invalid_argument("CorrectionFactor: the number of samples must be positive, got " +
                                std::to_string(samples));
  }
}

void CorrectionFactor::include_agent(const Eigen::Ref<const Eigen::VectorXd>& new_log_probs,
                                     const Eigen::Ref<const Eigen::VectorXd>& old_log_probs) {
  check_length("CorrectionFactor::include_agent", "new_log_probs", new_log_probs.size(), num_samples());
  check_length("CorrectionFactor::include_agent", "old_log_probs", old_log_probs.size(), num_samples());
  log_factor_ += new_log_probs - old_log_probs;  // log M += log pi_new - log pi_old
}

Eigen::VectorXd CorrectionFactor::factor() const { return log_factor_.array().exp().matrix(); }

Eigen::VectorXd CorrectionFactor::corrected(const Eigen::Ref<const Eigen::VectorXd>& advantages) const {
  check_length("CorrectionFactor::corrected", "advantages", advantages.size(), num_samples());
  return (factor().array() * advantages.array()).matrix();  // M_i A_i
}

CorrectionFactorStatistics CorrectionFactor::statistics() const {
  const Eigen::VectorXd m = factor();
  return {m.mean(), m.minCoeff(), m.maxCoeff()};
}

}  // namespace bsg::algos
