// A value network (V for rewards or V_C for costs, docs/algorithms.md#networks, #value-fits) with its own
// Adam optimiser and the original's fitting schedule: `iterations` passes,
// each over a fresh shuffle of the local indices in minibatches of
// m = floor(N / num_mini_batches) (the last may be shorter), with the loss
// mean (V(s) - R)^2, the gradient averaged over ranks, then one Adam step.
// That is iterations * ceil(N / m) Adam steps (80 when 16 divides N).
// fit_value_functions fits V and V_C together: one shuffle per pass and one
// gathered minibatch serve both networks, and their two gradients share one
// allreduce (the original fits V, then V_C, each on its own shuffles: the
// same schedule in distribution, half the gathering and messages).
//
// Parameters:
//   hidden_sizes          {64, 64}
//   adam                  lr 1e-3 (vf_lr), betas (0.9, 0.999), eps 1e-8; state persists
//   iterations            5 (train_v_iterations, vf_iters)
//   num_mini_batches      16 (vf_num_mini_batches; Q15)
//   min_mini_batch_size   16 (the original asserts m >= 16)
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "common/adam.h"
#include "common/mlp.h"
#include "common/mpi_context.h"
#include "common/random.h"

namespace bsg::algos {

struct ValueFitOptions {
  int iterations = 5;
  int num_mini_batches = 16;
  int min_mini_batch_size = 16;
};

struct ValueFitStats {
  double loss_before = 0.0;           // full-batch local loss before training (Loss/Value)
  double mean_minibatch_loss = 0.0;   // mean of the minibatch losses during training (local)
  int adam_steps = 0;
};

class ValueFunction {
 public:
  ValueFunction(int observation_size, const std::vector<int>& hidden_sizes, Rng& rng, MlpOptions init = {},
                AdamOptions adam = {});

  Mlp& net() { return net_; }
  const Mlp& net() const { return net_; }
  Adam& optimizer() { return optimizer_; }
  const Adam& optimizer() const { return optimizer_; }

  // V(s) for one normalised observation; no allocation once `workspace` is sized.
  double predict(const Eigen::Ref<const Eigen::VectorXd>& observation, MlpSampleWorkspace& workspace) const;
  // V(s_i) for a batch (one observation per row) into `values` (streamed, net's dtype).
  void predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& observations, Eigen::Ref<Eigen::VectorXd> values);
  // Local mean squared error against `targets`.
  double loss(const Eigen::Ref<const Eigen::MatrixXd>& observations, const Eigen::Ref<const Eigen::VectorXd>& targets);
  // The same loss and its parameter gradient into `gradient`, in one streamed pass.
  double loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                           const Eigen::Ref<const Eigen::VectorXd>& targets, Eigen::Ref<Eigen::VectorXd> gradient);

  // Multiplies the output layer's weights and bias by `factor`, so that every
  // prediction V(s) becomes factor * V(s) (the output layer is linear). With
  // factor = s_old / s_new this is PopArt's preserving step (van Hasselt et
  // al. 2016, eq. 6 without a mean): V keeps its predictions in raw units when
  // the return statistic changes (Q19). The Adam moments are left as they are.
  void scale_output(double factor);

  // The docs/algorithms.md#value-fits schedule. Collective (one gradient allreduce per minibatch); `rng`
  // is the rank's RNG (shuffles).
  ValueFitStats fit(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                    const Eigen::Ref<const Eigen::VectorXd>& targets, Rng& rng, const MpiContext& mpi,
                    const ValueFitOptions& options = {});

 private:
  Mlp net_;
  Adam optimizer_;
  MlpBatchWorkspace workspace_;
  Eigen::VectorXd predictions_;
};

// One network of fit_value_functions and the targets it learns.
struct ValueFitJob {
  ValueFunction& value;
  Eigen::Ref<const Eigen::VectorXd> targets;
};

// The schedule above (docs/algorithms.md#value-fits) for every job on the same shuffles of `observations` (see
// above); returns one ValueFitStats per job. Collective (one allreduce per
// minibatch); `rng` is the rank's RNG.
std::vector<ValueFitStats> fit_value_functions(std::span<const ValueFitJob> jobs,
                                               const Eigen::Ref<const Eigen::MatrixXd>& observations, Rng& rng,
                                               const MpiContext& mpi, const ValueFitOptions& options = {});

}  // namespace bsg::algos
