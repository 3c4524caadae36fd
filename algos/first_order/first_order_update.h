// The first-order policy update of PPO, PPO-Lag, FOCOPS, CUP, P3O and IPO
// (docs/algorithms.md#first-order-updates), beside the trust-region one: several
// passes over shuffled minibatches of the batch, one Adam step on the policy
// per minibatch with the gradient averaged over ranks (so `mpirun -np N` takes
// the steps one process takes on the same data), an optional early stop once
// the KL to the update's anchor policy exceeds target_kl.
//
// Every loss here is a mean over the minibatch of a per-sample loss (P3O's, whose ReLU holds a
// minibatch mean, is one once a step's hook has evaluated that mean: MinibatchStepHook)
// l_i(rho_i, KL_i) of
//   rho_i = exp(log pi_theta(a_i|s_i) - log pi_old,i)   pi_old: the policy that collected the batch
//   KL_i  = KL(pi_theta || pi_anchor)[s_i] = sum_j (mu_ij - mu_anchor,ij)^2 / (2 sigma^2)
// (both policies share sigma, the epoch's exploration std; summed over the
// action dimensions as FOCOPS's and CUP's losses are). The algorithm gives l_i
// and its partial derivatives; the chain rule through
//   d rho_i / d mu_i = rho_i (a_i - mu_i) / sigma^2,   d KL_i / d mu_i = (mu_i - mu_anchor,i) / sigma^2
// and one backward pass of the mean net give the parameter gradient.
//
// With a learned log sigma (s_j = log sigma_j, docs/algorithms.md#learned-log-sigma)
// the parameters are [theta, s] and, sigma_a the anchor's,
//   KL_i = sum_j s_a,j - s_j + (sigma_j^2 + (mu_ij - mu_anchor,ij)^2) / (2 sigma_a,j^2) - 1/2
//   d rho_i / d mu_ij = rho_i (a_ij - mu_ij) / sigma_j^2,  d rho_i / d s_j = rho_i ((a_ij - mu_ij)^2 / sigma_j^2 - 1)
//   d KL_i / d mu_ij = (mu_ij - mu_anchor,ij) / sigma_a,j^2, d KL_i / d s_j = sigma_j^2 / sigma_a,j^2 - 1.
//
// Parameters (RunConfig): actor_lr 3e-4, update_iters 40, policy_minibatch_size
// 64, kl_early_stop true, target_kl 0.02, max_grad_norm 40 (OmniSafe's defaults).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/core/gaussian_policy.h"
#include "algos/core/policy_surrogate.h"
#include "common/adam.h"
#include "common/mlp.h"
#include "common/run_config.h"

namespace bsg::algos {

// l_i and its partial derivatives at (rho_i, KL_i).
struct SampleLoss {
  double value = 0.0;
  double d_ratio = 0.0;  // d l_i / d rho_i
  double d_kl = 0.0;     // d l_i / d KL_i
};
// l_i of batch sample `sample` (its index in the rank's batch).
using SampleLossFunction = std::function<SampleLoss(Eigen::Index sample, double ratio, double kl)>;

struct FirstOrderOptions {
  double learning_rate = 3e-4;  // actor_lr: Adam's step size on theta
  int passes = 40;              // update_iters: passes over the batch
  int minibatch_size = 64;      // policy_minibatch_size: samples per minibatch, summed over ranks
  bool kl_early_stop = true;    // stop after a pass whose mean KL_i exceeds target_kl
  double target_kl = 0.02;
  double max_grad_norm = 40.0;  // rescale the averaged gradient to at most this norm; 0: never
};
FirstOrderOptions first_order_options(const RunConfig& config);

// mu_theta(s_i) of every row of `observations` at the policy's parameters.
Eigen::MatrixXd policy_means(const GaussianPolicy& policy, const Eigen::MatrixXd& observations);

// A rank's batch (the surrogate's) with the anchor means of KL_i: the mean of
// l_i over chosen rows and its gradient.
class SampleLossBatch {
 public:
  // Both must outlive this object; anchor_means is N x d_a. anchor_log_stds:
  // the anchor policy's learned log sigma (its log_stds()), empty for a fixed sigma.
  SampleLossBatch(const PolicySurrogate& surrogate, const Eigen::MatrixXd& anchor_means,
                  const Eigen::VectorXd& anchor_log_stds = Eigen::VectorXd());
  // Temporary anchor means would dangle (the batch keeps a reference), so they do not compile.
  SampleLossBatch(const PolicySurrogate&, Eigen::MatrixXd&&, const Eigen::VectorXd& = Eigen::VectorXd()) = delete;

  Eigen::Index num_samples() const { return surrogate_.num_samples(); }

  // 1/n sum_{i in rows} l_i at the policy's parameters (local); if `gradient`
  // is given, it is overwritten with d/dtheta of that mean (d/d[theta, s] with
  // a learned log sigma).
  double loss(const GaussianPolicy& policy, std::span<const Eigen::Index> rows, const SampleLossFunction& sample_loss,
              Eigen::VectorXd* gradient);

  // 1/N sum_i KL_i over the whole local batch.
  double mean_kl(const GaussianPolicy& policy);

 private:
  void gather(std::span<const Eigen::Index> rows);
  // sigma_j^2, sigma_a,j^2 and the part of KL_i that does not depend on the means,
  // sum_j s_a,j - s_j + sigma_j^2 / (2 sigma_a,j^2) - 1/2 (0 for a fixed sigma).
  struct SigmaTerms {
    Eigen::ArrayXd variances;
    Eigen::ArrayXd anchor_variances;
    double kl_sigma_part = 0.0;
  };
  SigmaTerms sigma_terms(const GaussianPolicy& policy) const;
  void check_sigma_kind(const GaussianPolicy& policy) const;
  // Per chunk of gathered rows (first row, their means): the losses, and if the
  // matrix is given, d(mean loss)/d mu of each row into it.
  using ChunkLosses = std::function<void(Eigen::Index, const Eigen::Ref<const Eigen::MatrixXd>&, Eigen::MatrixXd*)>;
  // Runs the mean net over the gathered rows with `chunk`; with `mean_gradient`,
  // back-propagates the chunks' output gradients into it (d/dtheta).
  void run_mean_net(const GaussianPolicy& policy, const ChunkLosses& chunk, Eigen::VectorXd* mean_gradient);
  // rho of the chunk's rows (gathered rows first, first + 1, ...) into ratios_.
  void chunk_ratios(const GaussianPolicy& policy, std::span<const Eigen::Index> rows, Eigen::Index first,
                    const Eigen::Ref<const Eigen::MatrixXd>& means);

  const PolicySurrogate& surrogate_;
  const Eigen::MatrixXd& anchor_means_;
  Eigen::VectorXd anchor_log_stds_;
  Eigen::MatrixXd observations_;  // the gathered rows
  Eigen::MatrixXd actions_;
  Eigen::MatrixXd anchors_;
  Eigen::MatrixXd means_;
  Eigen::VectorXd ratios_;  // of the current chunk
  MlpBatchWorkspace workspace_;
};

// Adam on the policy mean net's parameters, created at the first step (the
// algorithm is built before the net's size is known). Its state is saved as
// named scalars "policy_adam/t", "policy_adam/m/<i>", "policy_adam/v/<i>"
// (only t = 0 before the first step).
class PolicyAdam {
 public:
  explicit PolicyAdam(double learning_rate);

  // One descent step of `net`'s parameters along the loss gradient.
  void step(Mlp& net, const Eigen::VectorXd& gradient);
  // One step of the policy's parameters: theta, or [theta, s] with a learned log
  // sigma (one Adam over both, as OmniSafe's over the actor's parameters).
  void step(GaussianPolicy& policy, const Eigen::VectorXd& gradient);

  std::vector<NamedScalar> state() const;
  // Throws std::invalid_argument if the entries are not state()'s kind (nothing changes then).
  void restore_state(std::span<const NamedScalar> saved);
  // How many of state()'s entries a saved state holds at its end, read from its "policy_adam/t" entry.
  static std::size_t saved_size(std::span<const NamedScalar> saved);

 private:
  AdamOptions options_;
  std::optional<Adam> adam_;
};

// Called before each minibatch step with the batch and the minibatch's rows, on every rank
// (collective): an update whose loss depends on the whole minibatch (P3O's ReLU of a mean) reads it here.
using MinibatchStepHook = std::function<void(SampleLossBatch& batch, std::span<const Eigen::Index> rows)>;

// What the minibatch passes did.
struct MinibatchPassesResult {
  int passes = 0;              // passes completed (<= update_iters; fewer after an early stop)
  double gradient_norm = 0.0;  // norm of the last averaged gradient, before any rescaling
};

// The passes (collective: every rank must call it with the same options):
// per pass, the rank's batch shuffled by inputs.minibatch_rng and cut into
// K = max(1, floor(N_all / minibatch_size)) nearly equal minibatches (N_all:
// the batch summed over ranks), and per minibatch the rank-averaged gradient of
// its mean l_i, rescaled to max_grad_norm, and one Adam step (before_step, if given,
// first); after each pass, stop if kl_early_stop and the rank-averaged mean KL_i exceeds target_kl.
MinibatchPassesResult minibatch_passes(const PolicyUpdateInputs& inputs, const FirstOrderOptions& options,
                                       PolicyAdam& adam, SampleLossBatch& batch, const SampleLossFunction& sample_loss,
                                       const MinibatchStepHook& before_step = {});

// The progress columns every first-order update adds after the common ones:
// Misc/StopIter (passes completed) and Misc/gradient_norm.
std::vector<std::string> first_order_diagnostic_names();
void append_first_order_diagnostics(std::vector<NamedScalar>& diagnostics, const MinibatchPassesResult& passes);

// The per-sample advantages w_R A_i + sum_j w_j A^Cj_i of the rank's batch.
Eigen::VectorXd combined_advantages(const PolicySurrogate& surrogate, double reward_weight,
                                    std::span<const double> cost_weights);

}  // namespace bsg::algos
