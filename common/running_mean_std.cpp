#include "common/running_mean_std.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg {

RunningMeanStd::RunningMeanStd(Eigen::Index dimension, RunningMeanStdOptions options)
    : options_(options),
      mean_(Eigen::VectorXd::Zero(dimension)),
      std_(Eigen::VectorXd::Ones(dimension)),
      reduction_buffer_(dimension + 1) {
  if (dimension <= 0) {
    throw std::invalid_argument("RunningMeanStd: dimension must be positive, got " +
                                std::to_string(dimension));
  }
  if (options.clip < 0.0) {
    throw std::invalid_argument("RunningMeanStd: clip must be >= 0 (0 = off), got " +
                                std::to_string(options.clip));
  }
}

void RunningMeanStd::update(const Eigen::Ref<const Eigen::MatrixXd>& batch, const MpiContext& mpi) {
  const Eigen::Index d = dimension();
  if (batch.cols() != d) {
    throw std::invalid_argument("RunningMeanStd::update: batch has " + std::to_string(batch.cols()) +
                                " columns, the statistics have dimension " + std::to_string(d));
  }
  // 1.-2. n_B and the pooled batch mean x_bar (one allreduce of column sums and row count).
  reduction_buffer_.head(d) = batch.colwise().sum().transpose();
  reduction_buffer_[d] = static_cast<double>(batch.rows());
  mpi.sum_in_place(reduction_buffer_);
  const double n_b = reduction_buffer_[d];  // n_B
  if (n_b == 0.0) return;
  const Eigen::VectorXd batch_mean = reduction_buffer_.head(d) / n_b;  // x_bar
  const double n_a = count_;                                           // n_A
  const double n_ab = n_a + n_b;                                       // n_AB
  // 3. Delta = x_bar - m,  m' = m + Delta n_B / n_AB
  const Eigen::VectorXd delta = batch_mean - mean_;
  const Eigen::VectorXd new_mean = mean_ + delta * (n_b / n_ab);
  // 4. v_B = mean of (X - m')^2 (Q4), or of (X - x_bar)^2 with the exact formula.
  const Eigen::VectorXd& center = options_.exact_parallel_variance ? batch_mean : new_mean;
  reduction_buffer_.head(d) =
      (batch.rowwise() - center.transpose()).array().square().colwise().sum().transpose();
  mpi.sum_in_place(reduction_buffer_.data(), static_cast<std::size_t>(d));
  const Eigen::ArrayXd batch_variance = reduction_buffer_.head(d).array() / n_b;  // v_B
  // 5. M2 = n_A s^2 + n_B v_B + Delta^2 n_A n_B / n_AB,  s = sqrt(M2 / n_AB)
  const Eigen::ArrayXd m2 = n_a * std_.array().square() + n_b * batch_variance +
                            delta.array().square() * (n_a * n_b / n_ab);
  mean_ = new_mean;
  count_ = n_ab;
  std_ = (m2 / n_ab).sqrt().matrix();
}

void RunningMeanStd::normalize(const Eigen::Ref<const Eigen::VectorXd>& sample,
                               Eigen::Ref<Eigen::VectorXd> normalized) const {
  if (sample.size() != dimension() || normalized.size() != dimension()) {
    throw std::invalid_argument("RunningMeanStd::normalize: sample has " + std::to_string(sample.size()) +
                                " and normalized " + std::to_string(normalized.size()) +
                                " entries, expected " + std::to_string(dimension()));
  }
  normalized.array() = (sample - mean_).array() / (std_.array() + kStdEpsilon);
  if (options_.clip > 0.0) normalized = normalized.cwiseMax(-options_.clip).cwiseMin(options_.clip);
}

void RunningMeanStd::normalize_batch(const Eigen::Ref<const Eigen::MatrixXd>& batch,
                                     Eigen::Ref<Eigen::MatrixXd> normalized) const {
  if (batch.cols() != dimension() || normalized.cols() != dimension() ||
      normalized.rows() != batch.rows()) {
    throw std::invalid_argument("RunningMeanStd::normalize_batch: batch is " + std::to_string(batch.rows()) +
                                " x " + std::to_string(batch.cols()) + " and normalized " +
                                std::to_string(normalized.rows()) + " x " +
                                std::to_string(normalized.cols()) + ", expected N x " +
                                std::to_string(dimension()) + " for both");
  }
  normalized.array() = (batch.rowwise() - mean_.transpose()).array().rowwise() /
                       (std_.array() + kStdEpsilon).transpose();
  if (options_.clip > 0.0) normalized = normalized.cwiseMax(-options_.clip).cwiseMin(options_.clip);
}

void RunningMeanStd::set_state(const Eigen::Ref<const Eigen::VectorXd>& mean,
                               const Eigen::Ref<const Eigen::VectorXd>& std, double count) {
  if (mean.size() != dimension() || std.size() != dimension()) {
    throw std::invalid_argument("RunningMeanStd::set_state: mean has " + std::to_string(mean.size()) +
                                " and std " + std::to_string(std.size()) + " entries, expected " +
                                std::to_string(dimension()));
  }
  if (!(count >= 0.0)) {
    throw std::invalid_argument("RunningMeanStd::set_state: count must be >= 0, got " +
                                std::to_string(count));
  }
  mean_ = mean;
  std_ = std;
  count_ = count;
}

void RunningMeanStd::broadcast_from_root(const MpiContext& mpi) {
  mpi.broadcast_from_root(mean_);
  mpi.broadcast_from_root(std_);
  mpi.broadcast_from_root(&count_, 1);
}

}  // namespace bsg
