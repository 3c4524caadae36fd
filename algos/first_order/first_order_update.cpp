#include "algos/first_order/first_order_update.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/adam_state.h"
#include "algos/core/gradient_norm_clipping.h"
#include "algos/core/shuffle.h"

namespace bsg::algos {
namespace {

constexpr std::string_view kAdamPrefix = "policy_adam/";  // adam_state.h's step-then-moments entries
constexpr std::string_view kAdamStep = "policy_adam/t";

}  // namespace

FirstOrderOptions first_order_options(const RunConfig& config) {
  FirstOrderOptions options;
  options.learning_rate = config.first_order.actor_lr;
  options.passes = config.first_order.update_iters;
  options.minibatch_size = config.first_order.policy_minibatch_size;
  options.kl_early_stop = config.first_order.kl_early_stop;
  options.target_kl = config.trust_region.target_kl;
  options.max_grad_norm = config.first_order.max_grad_norm;
  return options;
}

Eigen::MatrixXd policy_means(const GaussianPolicy& policy, const Eigen::MatrixXd& observations) {
  Eigen::MatrixXd means(observations.rows(), policy.action_size());
  MlpBatchWorkspace workspace;
  policy.mean_net().evaluate_batch(observations, means, workspace);
  return means;
}

SampleLossBatch::SampleLossBatch(const PolicySurrogate& surrogate, const Eigen::MatrixXd& anchor_means,
                                 const Eigen::VectorXd& anchor_log_stds)
    : surrogate_(surrogate), anchor_means_(anchor_means), anchor_log_stds_(anchor_log_stds) {
  if (anchor_log_stds.size() != 0 && anchor_log_stds.size() != surrogate.actions().cols()) {
    throw std::invalid_argument("SampleLossBatch: " + std::to_string(anchor_log_stds.size()) +
                                " anchor log sigmas for " + std::to_string(surrogate.actions().cols()) +
                                "-d actions");
  }
  if (anchor_means.rows() != surrogate.num_samples() || anchor_means.cols() != surrogate.actions().cols()) {
    throw std::invalid_argument("SampleLossBatch: anchor means are " + std::to_string(anchor_means.rows()) + " x " +
                                std::to_string(anchor_means.cols()) + ", the batch has " +
                                std::to_string(surrogate.num_samples()) + " samples of " +
                                std::to_string(surrogate.actions().cols()) + "-d actions");
  }
}

void SampleLossBatch::gather(std::span<const Eigen::Index> rows) {
  const auto n = static_cast<Eigen::Index>(rows.size());
  observations_.resize(n, surrogate_.observations().cols());
  actions_.resize(n, surrogate_.actions().cols());
  anchors_.resize(n, anchor_means_.cols());
  means_.resize(n, anchor_means_.cols());
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index i = rows[static_cast<std::size_t>(r)];
    if (i < 0 || i >= num_samples()) {
      throw std::out_of_range("SampleLossBatch: row " + std::to_string(i) + " outside the batch of " +
                              std::to_string(num_samples()));
    }
    observations_.row(r) = surrogate_.observations().row(i);
    actions_.row(r) = surrogate_.actions().row(i);
    anchors_.row(r) = anchor_means_.row(i);
  }
}

void SampleLossBatch::check_sigma_kind(const GaussianPolicy& policy) const {
  if (policy.has_learned_std() != (anchor_log_stds_.size() != 0)) {
    throw std::invalid_argument(policy.has_learned_std()
                                    ? "SampleLossBatch: the policy learns log sigma but the anchor's is not given"
                                    : "SampleLossBatch: an anchor log sigma is given but the policy's sigma is fixed");
  }
}

void SampleLossBatch::chunk_ratios(const GaussianPolicy& policy, std::span<const Eigen::Index> rows, Eigen::Index first,
                                   const Eigen::Ref<const Eigen::MatrixXd>& means) {
  const Eigen::Index count = means.rows();
  ratios_.resize(count);
  policy.log_prob_batch(means, actions_.middleRows(first, count), ratios_);
  for (Eigen::Index r = 0; r < count; ++r) {
    // rho_r = exp(log pi_theta(a|s) - log pi_old)
    ratios_[r] = std::exp(ratios_[r] - surrogate_.old_log_probs()[rows[static_cast<std::size_t>(first + r)]]);
  }
}

void SampleLossBatch::run_mean_net(const GaussianPolicy& policy, const ChunkLosses& chunk,
                                   Eigen::VectorXd* mean_gradient) {
  if (mean_gradient == nullptr) {
    policy.mean_net().evaluate_batch(observations_, means_, workspace_);
    chunk(0, means_, nullptr);
    return;
  }
  mean_gradient->resize(policy.mean_net().num_parameters());
  Eigen::MatrixXd chunk_gradients;
  policy.mean_net().gradient_batch(
      observations_,
      [&](Eigen::Index first, const Eigen::Ref<const Eigen::MatrixXd>& means,
          Eigen::Ref<Eigen::MatrixXd> output_gradients) {
        chunk_gradients.resize(means.rows(), policy.action_size());
        chunk(first, means, &chunk_gradients);
        output_gradients = chunk_gradients;
      },
      workspace_, *mean_gradient);
}

double SampleLossBatch::loss(const GaussianPolicy& policy, std::span<const Eigen::Index> rows,
                             const SampleLossFunction& sample_loss, Eigen::VectorXd* gradient) {
  if (rows.empty()) throw std::invalid_argument("SampleLossBatch::loss: no rows");
  check_sigma_kind(policy);
  gather(rows);
  const double n = static_cast<double>(rows.size());
  const bool learned = policy.has_learned_std();
  const int action_size = policy.action_size();
  const SigmaTerms sigma = sigma_terms(policy);
  const Eigen::ArrayXd& variances = sigma.variances;
  const Eigen::ArrayXd& anchor_variances = sigma.anchor_variances;
  const double kl_sigma_part = sigma.kl_sigma_part;
  const Eigen::ArrayXd kl_d_log_std = variances / anchor_variances - 1.0;  // d KL_i / d s_j
  Eigen::ArrayXd log_std_gradient = Eigen::ArrayXd::Zero(action_size);
  double loss_sum = 0.0;
  Eigen::ArrayXd difference(action_size), deviation(action_size);  // sized once: no allocation per sample
  // Per gathered row r of a chunk: rho_r, KL_r, l_r, and (dl/dmu_r) / n (and dl/ds / n summed).
  const auto chunk = [&](Eigen::Index first, const Eigen::Ref<const Eigen::MatrixXd>& means,
                         Eigen::MatrixXd* output_gradients) {
    const Eigen::Index count = means.rows();
    chunk_ratios(policy, rows, first, means);
    for (Eigen::Index r = 0; r < count; ++r) {
      const Eigen::Index sample = rows[static_cast<std::size_t>(first + r)];
      const double ratio = ratios_[r];
      difference = (means.row(r) - anchors_.row(first + r)).transpose().array();
      const double kl = kl_sigma_part + (difference.square() / (2.0 * anchor_variances)).sum();
      const SampleLoss l = sample_loss(sample, ratio, kl);
      loss_sum += l.value;
      if (output_gradients != nullptr) {
        deviation = (actions_.row(first + r) - means.row(r)).transpose().array();  // a - mu
        // dl/dmu = dl/drho rho (a - mu) / sigma^2 + dl/dKL (mu - mu_anchor) / sigma_a^2, over n for the mean
        output_gradients->row(r) =
            ((l.d_ratio * ratio * deviation / variances + l.d_kl * difference / anchor_variances) / n).transpose().matrix();
        if (learned) {
          log_std_gradient += (l.d_ratio * ratio * (deviation.square() / variances - 1.0) + l.d_kl * kl_d_log_std) / n;
        }
      }
    }
  };
  if (gradient == nullptr || !learned) {
    run_mean_net(policy, chunk, gradient);
  } else {
    const Eigen::Index p = policy.mean_net().num_parameters();
    Eigen::VectorXd mean_gradient;
    run_mean_net(policy, chunk, &mean_gradient);
    gradient->resize(p + action_size);
    gradient->head(p) = mean_gradient;
    gradient->tail(action_size) = log_std_gradient.matrix();
  }
  return loss_sum / n;
}

SampleLossBatch::SigmaTerms SampleLossBatch::sigma_terms(const GaussianPolicy& policy) const {
  // A fixed sigma is the learned case with s = s_a = log sigma in every dimension: the sigma part of
  // KL_i is then 0 (and the loss accumulates nothing for s).
  SigmaTerms terms;
  if (!policy.has_learned_std()) {
    terms.variances = Eigen::ArrayXd::Constant(policy.action_size(), policy.std() * policy.std());
    terms.anchor_variances = terms.variances;
    return terms;
  }
  terms.variances = (2.0 * policy.log_stds().array()).exp();
  terms.anchor_variances = (2.0 * anchor_log_stds_.array()).exp();
  terms.kl_sigma_part =
      (anchor_log_stds_.array() - policy.log_stds().array() + terms.variances / (2.0 * terms.anchor_variances) - 0.5)
          .sum();
  return terms;
}

double SampleLossBatch::mean_kl(const GaussianPolicy& policy) {
  check_sigma_kind(policy);
  means_.resize(num_samples(), anchor_means_.cols());
  policy.mean_net().evaluate_batch(surrogate_.observations(), means_, workspace_);
  // 1/N sum_i KL_i = sigma part + 1/N sum_i sum_j (mu_ij - mu_anchor,ij)^2 / (2 sigma_a,j^2)
  const SigmaTerms sigma = sigma_terms(policy);
  const Eigen::RowVectorXd inverse_double_variances = (0.5 / sigma.anchor_variances).matrix().transpose();
  return sigma.kl_sigma_part +
         ((means_ - anchor_means_).array().square().rowwise() * inverse_double_variances.array()).sum() /
             static_cast<double>(num_samples());
}

PolicyAdam::PolicyAdam(double learning_rate) { options_.learning_rate = learning_rate; }

void PolicyAdam::step(Mlp& net, const Eigen::VectorXd& gradient) {
  if (!adam_) adam_.emplace(net.num_parameters(), options_);
  if (adam_->num_parameters() != net.num_parameters()) {
    throw std::invalid_argument("PolicyAdam: its state holds " + std::to_string(adam_->num_parameters()) +
                                " parameters, the policy has " + std::to_string(net.num_parameters()));
  }
  adam_->step(net.mutable_parameters(), gradient);
}

void PolicyAdam::step(GaussianPolicy& policy, const Eigen::VectorXd& gradient) {
  if (!policy.has_learned_std()) {
    step(policy.mean_net(), gradient);
    return;
  }
  Mlp& net = policy.mean_net();
  const Eigen::Index p = net.num_parameters();
  const Eigen::Index d = policy.action_size();
  if (!adam_) adam_.emplace(p + d, options_);
  if (adam_->num_parameters() != p + d || gradient.size() != p + d) {
    throw std::invalid_argument("PolicyAdam: its state holds " + std::to_string(adam_->num_parameters()) +
                                " parameters and the gradient " + std::to_string(gradient.size()) +
                                ", the policy has " + std::to_string(p) + " + " + std::to_string(d) + " (log sigma)");
  }
  Eigen::VectorXd parameters(p + d);
  parameters << net.parameters(), policy.log_stds();
  adam_->step(parameters, gradient);
  net.mutable_parameters() = parameters.head(p);
  policy.set_log_stds(parameters.tail(d));
}

std::vector<NamedScalar> PolicyAdam::state() const {
  if (!adam_) return {{std::string(kAdamStep), 0.0}};
  return adam_state_entries(*adam_, kAdamPrefix, AdamEntryLayout::step_then_moments);
}

std::size_t PolicyAdam::saved_size(std::span<const NamedScalar> saved) {
  for (std::size_t k = 0; k < saved.size(); ++k) {
    if (saved[k].name == kAdamStep) return saved.size() - k;
  }
  return 0;
}

void PolicyAdam::restore_state(std::span<const NamedScalar> saved) {
  const Eigen::Index parameters = saved_adam_parameters(saved, kAdamPrefix);
  if (parameters == 0) {
    adam_.reset();
    return;
  }
  Adam restored(parameters, options_);
  restore_adam_state_entries(restored, saved, kAdamPrefix, AdamEntryLayout::step_then_moments);
  adam_ = std::move(restored);
}

MinibatchPassesResult minibatch_passes(const PolicyUpdateInputs& inputs, const FirstOrderOptions& options,
                                       PolicyAdam& adam, SampleLossBatch& batch, const SampleLossFunction& sample_loss,
                                       const MinibatchStepHook& before_step) {
  if (inputs.minibatch_rng == nullptr) {
    throw std::invalid_argument("minibatch_passes: the update needs a minibatch RNG (PolicyUpdateInputs::minibatch_rng)");
  }
  const Eigen::Index n = batch.num_samples();
  const double all_samples = inputs.mpi.sum(static_cast<double>(n));
  const auto minibatches =
      std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::floor(all_samples / options.minibatch_size)));
  if (n < minibatches) {
    throw std::invalid_argument("policy_minibatch_size " + std::to_string(options.minibatch_size) + " cuts the batch into " +
                                std::to_string(minibatches) + " minibatches, but this rank holds only " +
                                std::to_string(n) + " samples");
  }
  std::vector<Eigen::Index> permutation(static_cast<std::size_t>(n));
  Eigen::VectorXd gradient;
  MinibatchPassesResult result;
  for (int pass = 0; pass < options.passes; ++pass) {
    shuffle_permutation(permutation, *inputs.minibatch_rng);
    for (Eigen::Index k = 0; k < minibatches; ++k) {
      // Minibatch k: permutation[floor(k N / K), floor((k + 1) N / K)).
      const Eigen::Index begin = k * n / minibatches;
      const Eigen::Index end = (k + 1) * n / minibatches;
      const std::span<const Eigen::Index> rows(permutation.data() + begin, static_cast<std::size_t>(end - begin));
      if (before_step) before_step(batch, rows);
      batch.loss(inputs.policy, rows, sample_loss, &gradient);
      inputs.mpi.average_in_place(gradient);  // one allreduce per step
      result.gradient_norm = clip_gradient_norm(gradient, options.max_grad_norm);  // on the averaged gradient
      adam.step(inputs.policy, gradient);
    }
    result.passes = pass + 1;
    if (options.kl_early_stop && inputs.mpi.average(batch.mean_kl(inputs.policy)) > options.target_kl) break;
  }
  return result;
}

std::vector<std::string> first_order_diagnostic_names() { return {"Misc/StopIter", "Misc/gradient_norm"}; }

void append_first_order_diagnostics(std::vector<NamedScalar>& diagnostics, const MinibatchPassesResult& passes) {
  diagnostics.push_back({"Misc/StopIter", static_cast<double>(passes.passes)});
  diagnostics.push_back({"Misc/gradient_norm", passes.gradient_norm});
}

Eigen::VectorXd combined_advantages(const PolicySurrogate& surrogate, double reward_weight,
                                    std::span<const double> cost_weights) {
  if (static_cast<Eigen::Index>(cost_weights.size()) != surrogate.cost_advantages().cols()) {
    throw std::invalid_argument("combined_advantages: " + std::to_string(cost_weights.size()) + " cost weights for " +
                                std::to_string(surrogate.cost_advantages().cols()) + " constraints");
  }
  Eigen::VectorXd combined = reward_weight * surrogate.advantages();
  for (Eigen::Index j = 0; j < surrogate.cost_advantages().cols(); ++j) {
    combined += cost_weights[static_cast<std::size_t>(j)] * surrogate.cost_advantages().col(j);
  }
  return combined;
}

}  // namespace bsg::algos
