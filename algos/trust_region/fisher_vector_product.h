// Fisher-vector product of docs/algorithms.md#fisher-vector-product: the Hessian of the mean KL of docs/algorithms.md#mean-kl at
// theta_old, in closed (Gauss–Newton) form, averaged over ranks and damped:
//   F v = avg( 1/(N_f d_a sigma^2) sum_{i in fvp} J_i^T (J_i v) ) + damping_coeff v
// over the sub-sampled rows 0, 4, 8, ... (N_f = ceil(N/4)) of the local batch.
//
// The operator is linearised at construction: it copies the mean net
// (theta_old) and sigma, so later changes of the policy (line search) do not
// affect it. apply() makes one JVP and one VJP per chunk of rows on the kept
// forward pass (in the net's dtype) and one allreduce of length P; it
// allocates nothing.
//
// Parameters:
//   damping_coeff      0.1 (cg_damping), added after the rank average
//   subsample_stride   4
#pragma once

#include <Eigen/Core>

#include "algos/core/gaussian_policy.h"
#include "common/mlp.h"
#include "common/mpi_context.h"

namespace bsg::algos {

struct FisherVectorProductOptions {
  double damping_coeff = 0.1;
  int subsample_stride = 4;
};

class FisherVectorProduct {
 public:
  // `observations`: the local batch of normalised observations (N x d_o).
  FisherVectorProduct(const GaussianPolicy& policy, const Eigen::Ref<const Eigen::MatrixXd>& observations,
                      const MpiContext& mpi, FisherVectorProductOptions options = {});

  // product = F direction; `product` must not alias `direction`. Collective.
  void apply(const Eigen::Ref<const Eigen::VectorXd>& direction, Eigen::Ref<Eigen::VectorXd> product);

  Eigen::Index num_parameters() const { return mean_net_.num_parameters(); }
  Eigen::Index num_samples() const { return subsampled_observations_.rows(); }  // N_f
  long long call_count() const { return call_count_; }
  const FisherVectorProductOptions& options() const { return options_; }

 private:
  Mlp mean_net_;  // copy at theta_old
  double std_;    // sigma at theta_old
  MpiContext mpi_;
  FisherVectorProductOptions options_;
  Eigen::MatrixXd subsampled_observations_;
  MlpBatchWorkspace workspace_;  // the forward pass at theta_old over the N_f rows, kept
  long long call_count_ = 0;
};

}  // namespace bsg::algos
