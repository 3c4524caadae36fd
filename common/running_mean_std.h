// Online mean and standard deviation, merged across MPI ranks (docs/algorithms.md#observation-normaliser):
// the observation normaliser and the return normaliser of reward scaling.
//
// update() follows the original code, including quirk Q4: the batch variance
// is taken around the *new* running mean m', which slightly over-estimates the
// variance after the first update. `exact_parallel_variance` switches to Chan's
// exact parallel formula (deviations around the pooled batch mean).
//
// Parameters:
//   dimension                 size of one sample (d_o, or 1 for returns)
//   exact_parallel_variance   false (faithful Q4)
//   clip                      0 = no clipping of normalised values (Q3); > 0 clips to ±clip
// State at construction: mean 0, std 1, count 0.
#pragma once

#include <Eigen/Core>

#include "common/mpi_context.h"

namespace bsg {

struct RunningMeanStdOptions {
  bool exact_parallel_variance = false;
  double clip = 0.0;
};

class RunningMeanStd {
 public:
  static constexpr double kStdEpsilon = 1e-5;  // x_hat = (x - m)/(s + 1e-5)

  explicit RunningMeanStd(Eigen::Index dimension, RunningMeanStdOptions options = {});

  Eigen::Index dimension() const { return mean_.size(); }
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::VectorXd& std() const { return std_; }
  double count() const { return count_; }
  const RunningMeanStdOptions& options() const { return options_; }

  // Merge one epoch's samples (one per row) from every rank. Collective: every
  // rank must call it; ranks may hold different row counts (the original's equal
  // counts make this the average of the per-rank means).
  void update(const Eigen::Ref<const Eigen::MatrixXd>& batch, const MpiContext& mpi);

  // x_hat = (x - m)/(s + 1e-5), clipped to ±clip if clip > 0.
  void normalize(const Eigen::Ref<const Eigen::VectorXd>& sample, Eigen::Ref<Eigen::VectorXd> normalized) const;
  // Row-wise normalisation of a batch (one sample per row).
  void normalize_batch(const Eigen::Ref<const Eigen::MatrixXd>& batch,
                       Eigen::Ref<Eigen::MatrixXd> normalized) const;

  // Restores a saved state; sizes must match the dimension.
  void set_state(const Eigen::Ref<const Eigen::VectorXd>& mean, const Eigen::Ref<const Eigen::VectorXd>& std,
                 double count);
  // Every rank takes rank 0's statistics (docs/algorithms.md#set-up, step 5).
  void broadcast_from_root(const MpiContext& mpi);

 private:
  RunningMeanStdOptions options_;
  Eigen::VectorXd mean_;
  Eigen::VectorXd std_;
  double count_ = 0.0;
  Eigen::VectorXd reduction_buffer_;  // d + 1 values: column sums and the row count
};

}  // namespace bsg
