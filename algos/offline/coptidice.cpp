#include "algos/offline/coptidice.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/adam_state.h"
#include "algos/offline/offline_learner_parts.h"

namespace bsg::algos {
namespace {

constexpr int kPair = 2;             // OSRL's num_nu and num_chi for every Bullet task
constexpr double kLogOffset = 1e-10;  // OSRL's torch.log(x + 1e-10)

std::vector<Mlp> network_pair(int input, const COptiDiceOptions& options, Rng& init_rng) {
  std::vector<Mlp> networks;
  for (int k = 0; k < kPair; ++k) networks.emplace_back(mlp_layers(input, options.hidden_sizes, 1), init_rng, options.mlp);
  return networks;
}

const COptiDiceOptions& checked(const COptiDiceOptions& options, int action_size) {
  const auto positive = [](double value) { return value > 0.0 && std::isfinite(value); };
  if (!positive(options.actor_lr) || !positive(options.critic_lr) || !positive(options.scalar_lr) ||
      !positive(options.alpha) || !(options.gamma > 0.0 && options.gamma <= 1.0) || options.episode_length < 1 ||
      !(options.cost_limit >= 0.0) || !(options.cost_ub_epsilon >= 0.0) ||
      !(options.initial_state_proportion > 0.0 && options.initial_state_proportion <= 1.0) ||
      (options.action_std.size() != 0 && options.action_std.size() != action_size)) {
    throw std::invalid_argument("COptiDICE: options out of range (learning rates and alpha > 0, 0 < gamma <= 1, "
                                "episode length >= 1, cost limit and epsilon >= 0, 0 < initial share <= 1, one "
                                "action standard deviation per action dimension)");
  }
  return options;
}

double sigmoid(double x) { return 1.0 / (1.0 + std::exp(-x)); }

}  // namespace

double softplus(double x) { return x > 20.0 ? x : std::log1p(std::exp(x)); }  // torch's threshold 20

double f_divergence_value(FDivergence f, double x) {
  switch (f) {
    case FDivergence::chi2: return 0.5 * (x - 1.0) * (x - 1.0);
    case FDivergence::softchi: return x < 1.0 ? x * (std::log(x + kLogOffset) - 1.0) + 1.0 : 0.5 * (x - 1.0) * (x - 1.0);
    case FDivergence::kl: return x * std::log(x + kLogOffset);
  }
  return 0.0;
}

double f_divergence_derivative(FDivergence f, double x) {
  switch (f) {
    case FDivergence::chi2: return x - 1.0;
    case FDivergence::softchi:
      return x < 1.0 ? std::log(x + kLogOffset) - 1.0 + x / (x + kLogOffset) : x - 1.0;
    case FDivergence::kl: return std::log(x + kLogOffset) + x / (x + kLogOffset);
  }
  return 0.0;
}

double f_divergence_derivative_inverse(FDivergence f, double y) {
  switch (f) {
    case FDivergence::chi2: return y + 1.0;
    case FDivergence::softchi: return y < 0.0 ? std::exp(y) : y + 1.0;
    case FDivergence::kl: return std::exp(y - 1.0);
  }
  return 0.0;
}

double f_divergence_derivative_inverse_slope(FDivergence f, double y) {
  switch (f) {
    case FDivergence::chi2: return 1.0;
    case FDivergence::softchi: return y < 0.0 ? std::exp(y) : 1.0;
    case FDivergence::kl: return std::exp(y - 1.0);
  }
  return 0.0;
}

double COptiDiceOptions::cost_threshold() const { return per_step_cost_threshold(cost_limit, gamma, episode_length); }

COptiDice::COptiDice(int observation_size, int action_size, ObservationScaling scaling, COptiDiceOptions options,
                     Rng& init_rng)
    : observation_size_(observation_size),
      action_size_(action_size),
      scaling_(std::move(scaling)),
      options_(checked(options, action_size)),
      actor_(mlp_layers(observation_size, options_.hidden_sizes, 2 * action_size), init_rng, options_.mlp),
      nu_(network_pair(observation_size, options_, init_rng)),
      chi_(network_pair(observation_size, options_, init_rng)),
      actor_adam_(actor_.num_parameters(), {.learning_rate = options_.actor_lr}),
      lambda_adam_(1, {.learning_rate = options_.scalar_lr}),
      tau_adam_(1, {.learning_rate = options_.scalar_lr}),
      acting_(*this) {
  if (scaling_.mean.size() != observation_size || scaling_.std.size() != observation_size) {
    throw std::invalid_argument("COptiDICE: the observation scaling has " + std::to_string(scaling_.mean.size()) +
                                " features, the observations " + std::to_string(observation_size));
  }
  if (options_.action_std.size() == 0) options_.action_std = Eigen::VectorXd::Ones(action_size);
  for (int k = 0; k < kPair; ++k) {
    nu_adams_.emplace_back(nu_[k].num_parameters(), AdamOptions{.learning_rate = options_.critic_lr});
    chi_adams_.emplace_back(chi_[k].num_parameters(), AdamOptions{.learning_rate = options_.critic_lr});
  }
}

void COptiDice::pair_minimum(const Mlp& first, const Mlp& second, const Eigen::MatrixXd& inputs,
                             MlpBatchWorkspace& first_workspace, MlpBatchWorkspace& second_workspace,
                             Eigen::VectorXd& values, Eigen::VectorXi& which) {
  values = first.forward_batch(inputs, first_workspace).col(0);
  const Eigen::MatrixXd& other = second.forward_batch(inputs, second_workspace);
  which.setZero(inputs.rows());
  for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
    if (other(i, 0) < values(i)) {  // torch.min keeps the first of equal values
      values(i) = other(i, 0);
      which(i) = 1;
    }
  }
}

void COptiDice::pair_gradients(std::vector<Mlp>& networks, std::vector<MlpBatchWorkspace>& workspaces,
                               const Eigen::VectorXi& which, const Eigen::VectorXi& next_which,
                               const Eigen::VectorXd& at_s, const Eigen::VectorXd& at_next,
                               std::vector<Eigen::VectorXd>& gradients) {
  gradients.resize(kPair);
  for (int k = 0; k < kPair; ++k) {
    Mlp& network = networks[static_cast<std::size_t>(k)];
    const Eigen::MatrixXd routed = ((which.array() == k).cast<double>() * at_s.array()).matrix();
    const Eigen::MatrixXd routed_next = ((next_which.array() == k).cast<double>() * at_next.array()).matrix();
    Eigen::VectorXd& gradient = gradients[static_cast<std::size_t>(k)];
    gradient.resize(network.num_parameters());
    next_part_.resize(network.num_parameters());
    network.backward_batch(routed, workspaces[static_cast<std::size_t>(k)], gradient);
    network.backward_batch(routed_next, workspaces[static_cast<std::size_t>(2 + k)], next_part_);
    gradient += next_part_;
  }
}

void COptiDice::pair_minimum_at_both(std::vector<Mlp>& networks, const OfflineBatch& batch,
                                     std::vector<MlpBatchWorkspace>& workspaces, Eigen::VectorXd& at_s,
                                     Eigen::VectorXi& which, Eigen::VectorXd& at_next, Eigen::VectorXi& next_which) {
  pair_minimum(networks[0], networks[1], batch.observations, workspaces[0], workspaces[1], at_s, which);
  pair_minimum(networks[0], networks[1], batch.next_observations, workspaces[2], workspaces[3], at_next, next_which);
}

void COptiDice::compute_ratios(const OfflineBatch& batch, double lambda) {
  const Eigen::Index n = batch.observations.rows();
  pair_minimum_at_both(nu_, batch, nu_workspaces_, nu_s_, nu_which_, nu_next_, nu_next_which_);
  advantages_.resize(n);
  ratios_.resize(n);
  ratio_slopes_.resize(n);
  const FDivergence f = options_.f_divergence;
  for (Eigen::Index i = 0; i < n; ++i) {
    // e = r - lambda c + gamma (1 - terminal) nu(s') - nu(s);  w = max(0, (f')^{-1}(e / alpha))
    const double e = options_.reward_scale * batch.rewards(i) - lambda * options_.cost_scale * batch.costs(i) +
                     options_.gamma * (1.0 - batch.terminals(i)) * nu_next_(i) - nu_s_(i);
    const double y = e / options_.alpha;
    const double inverse = f_divergence_derivative_inverse(f, y);
    advantages_(i) = e;
    ratios_(i) = std::max(0.0, inverse);
    ratio_slopes_(i) = inverse > 0.0 ? f_divergence_derivative_inverse_slope(f, y) / options_.alpha : 0.0;
  }
}

double COptiDice::nu_loss(const OfflineBatch& batch, double lambda, std::vector<Eigen::VectorXd>& gradients) {
  compute_ratios(batch, lambda);
  const Eigen::Index n = batch.observations.rows();
  const double scale = 1.0 / static_cast<double>(n);
  const double initial_weight = (1.0 - options_.gamma) / options_.initial_state_proportion;
  const FDivergence f = options_.f_divergence;
  double loss = 0.0;
  Eigen::VectorXd at_s(n), at_next(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = ratios_(i);
    const double e = advantages_(i);
    loss += scale * (initial_weight * batch.initial(i) * nu_s_(i) + w * e - options_.alpha * f_divergence_value(f, w));
    // d/de [w e - alpha f(w)] = w + (e - alpha f'(w)) dw/de
    const double de = scale * (w + (e - options_.alpha * f_divergence_derivative(f, w)) * ratio_slopes_(i));
    at_s(i) = scale * initial_weight * batch.initial(i) - de;
    at_next(i) = de * options_.gamma * (1.0 - batch.terminals(i));
  }
  pair_gradients(nu_, nu_workspaces_, nu_which_, nu_next_which_, at_s, at_next, gradients);
  return loss;
}

double COptiDice::chi_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& w, double tau,
                           std::vector<Eigen::VectorXd>& gradients) {
  const Eigen::Index n = batch.observations.rows();
  pair_minimum_at_both(chi_, batch, chi_workspaces_, chi_s_, chi_which_, chi_next_, chi_next_which_);
  const double initial_weight = (1.0 - options_.gamma) / options_.initial_state_proportion;
  // ell = (1 - gamma) 1[initial] chi(s) / p0 + w (c + gamma (1 - terminal) chi(s') - chi(s))
  Eigen::VectorXd ell(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    ell(i) = initial_weight * batch.initial(i) * chi_s_(i) +
             w(i) * (options_.cost_scale * batch.costs(i) + options_.gamma * (1.0 - batch.terminals(i)) * chi_next_(i) -
                     chi_s_(i));
  }
  // p = softmax(ell / tau), q = N p; log q = log_softmax + log N (stable: shifted by the maximum)
  const Eigen::ArrayXd logits = ell.array() / tau;
  const double shift = logits.maxCoeff();
  const double log_sum = shift + std::log((logits - shift).exp().sum());
  const Eigen::ArrayXd log_p = logits - log_sum;
  const Eigen::ArrayXd p = log_p.exp();
  const double count = static_cast<double>(n);
  const Eigen::ArrayXd q = count * p;
  const Eigen::ArrayXd log_q = log_p + std::log(count);
  upper_bound_kl_ = (q * log_q - q + 1.0).mean();
  upper_bound_cost_ = (q * w.array() * (options_.cost_scale * batch.costs.array())).mean();
  // L = mean(q ell) = sum p ell;  dL/dell_j = p_j (1 + (ell_j - sum p ell) / tau)
  const double loss = (p * ell.array()).sum();
  const Eigen::ArrayXd d_ell = p * (1.0 + (ell.array() - loss) / tau);
  Eigen::VectorXd at_s(n), at_next(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    at_s(i) = d_ell(i) * (initial_weight * batch.initial(i) - w(i));
    at_next(i) = d_ell(i) * w(i) * options_.gamma * (1.0 - batch.terminals(i));
  }
  pair_gradients(chi_, chi_workspaces_, chi_which_, chi_next_which_, at_s, at_next, gradients);
  return loss;
}

double COptiDice::actor_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& w,
                             const Eigen::Ref<const Eigen::MatrixXd>& observation_noise,
                             const Eigen::Ref<const Eigen::MatrixXd>& action_noise,
                             Eigen::Ref<Eigen::VectorXd> gradient) {
  const Eigen::Index n = batch.observations.rows();
  const int a = action_size_;
  // The standardised observation's noise is 0.1 eps: 0.1 of the raw observation's standard deviation.
  noisy_observations_ = batch.observations + kCOptiDiceNoiseScale * observation_noise;
  const Eigen::MatrixXd& outputs = actor_.forward_batch(noisy_observations_, actor_workspace_);
  constexpr double kHalfLogTwoPi = 0.91893853320467274178;
  double loss = 0.0;
  actor_output_gradient_.setZero(n, 2 * a);
  for (Eigen::Index i = 0; i < n; ++i) {
    double log_prob = 0.0;
    for (int j = 0; j < a; ++j) {
      const double noisy = batch.actions(i, j) + kCOptiDiceNoiseScale * options_.action_std(j) * action_noise(i, j);
      const double action = std::clamp(noisy, -kCOptiDiceActionClip, kCOptiDiceActionClip);
      const double u = std::atanh(action);
      const double mu = outputs(i, j);
      const double raw_log_std = outputs(i, a + j);
      const double log_std = std::clamp(raw_log_std, kLogStdMin, kLogStdMax);
      const double z = (u - mu) / std::exp(log_std);
      // log pi = log N(u; mu, sigma) - log(1 - a^2)
      log_prob += -0.5 * z * z - log_std - kHalfLogTwoPi - std::log(1.0 - action * action);
      const double weight = w(i) / static_cast<double>(n);
      actor_output_gradient_(i, j) = -weight * z / std::exp(log_std);  // dL/dmu
      const bool clamped = raw_log_std < kLogStdMin || raw_log_std > kLogStdMax;
      actor_output_gradient_(i, a + j) = clamped ? 0.0 : -weight * (z * z - 1.0);  // dL/dlog sigma
    }
    loss -= w(i) * log_prob / static_cast<double>(n);
  }
  actor_.backward_batch(actor_output_gradient_, actor_workspace_, gradient);
  return loss;
}

double COptiDice::update(const OfflineBatch& batch, Rng& noise) {
  const Eigen::Index n = batch.observations.rows();
  check_batch_fits(batch, observation_size_, action_size_, "COptiDICE");
  if (batch.initial.size() != n) throw std::invalid_argument("COptiDICE: the batch has no initial-row flags");
  const double lambda = softplus(lambda_parameter_);
  compute_ratios(batch, lambda);
  const Eigen::VectorXd w = ratios_;
  Eigen::VectorXd step(1);
  // 1.1 chi and tau, the upper bound on the policy's cost
  double cost_estimate = (w.array() * (options_.cost_scale * batch.costs.array())).mean();
  if (options_.cost_ub_epsilon > 0.0) {
    chi_loss(batch, w, softplus(tau_parameter_), gradients_);
    cost_estimate = upper_bound_cost_;
    for (int k = 0; k < kPair; ++k) chi_adams_[k].step(chi_[k].mutable_parameters(), gradients_[k]);
    // L_tau = tau (epsilon - D_KL): dL/d tau_parameter = sigmoid(tau_parameter) (epsilon - D_KL)
    step(0) = sigmoid(tau_parameter_) * (options_.cost_ub_epsilon - upper_bound_kl_);
    Eigen::Map<Eigen::VectorXd> tau_value(&tau_parameter_, 1);
    tau_adam_.step(tau_value, step);
  }
  // 1.2 nu
  nu_loss(batch, lambda, gradients_);
  for (int k = 0; k < kPair; ++k) nu_adams_[k].step(nu_[k].mutable_parameters(), gradients_[k]);
  // 1.3 lambda: L = lambda (l - C_hat), dL/d lambda_parameter = sigmoid(lambda_parameter) (l - C_hat)
  step(0) = sigmoid(lambda_parameter_) * (options_.cost_threshold() - cost_estimate);
  Eigen::Map<Eigen::VectorXd> lambda_value(&lambda_parameter_, 1);
  lambda_adam_.step(lambda_value, step);
  // 2. the policy, weighted by w from the stepped nu at the step's starting lambda (as OSRL)
  Eigen::MatrixXd observation_noise, action_noise;
  fill_standard_normal(noise, observation_noise, n, observation_size_);
  fill_standard_normal(noise, action_noise, n, action_size_);
  compute_ratios(batch, lambda);
  const Eigen::VectorXd policy_weights = ratios_;
  gradient_.resize(actor_.num_parameters());
  const double loss = actor_loss(batch, policy_weights, observation_noise, action_noise, gradient_);
  actor_adam_.step(actor_.mutable_parameters(), gradient_);
  return loss;
}

void COptiDice::save(BinaryWriter& writer) const {
  writer.write_section("coptidice");
  writer.write_vector(scaling_.mean);
  writer.write_vector(scaling_.std);
  writer.write_f64(options_.initial_state_proportion);
  writer.write_vector(options_.action_std);
  writer.write_vector(actor_.parameters());
  for (const std::vector<Mlp>* pair : {&nu_, &chi_}) {
    for (const Mlp& network : *pair) writer.write_vector(network.parameters());
  }
  writer.write_f64(lambda_parameter_);
  writer.write_f64(tau_parameter_);
  save_adam_state(actor_adam_, writer);
  for (const Adam& adam : nu_adams_) save_adam_state(adam, writer);
  for (const Adam& adam : chi_adams_) save_adam_state(adam, writer);
  save_adam_state(lambda_adam_, writer);
  save_adam_state(tau_adam_, writer);
}

void COptiDice::load(BinaryReader& reader) {
  reader.expect_section("coptidice");
  Eigen::VectorXd mean = reader.read_vector("observation mean", observation_size_);
  Eigen::VectorXd std = reader.read_vector("observation std", observation_size_);
  const double initial = reader.read_f64("initial state proportion");
  Eigen::VectorXd action_std = reader.read_vector("action std", action_size_);
  actor_.set_parameters(reader.read_vector("actor parameters", actor_.num_parameters()));
  for (std::vector<Mlp>* pair : {&nu_, &chi_}) {
    for (Mlp& network : *pair) network.set_parameters(reader.read_vector("nu or chi parameters", network.num_parameters()));
  }
  lambda_parameter_ = reader.read_f64("lambda parameter");
  tau_parameter_ = reader.read_f64("tau parameter");
  load_adam_state(actor_adam_, reader, "actor");
  for (Adam& adam : nu_adams_) load_adam_state(adam, reader, "nu");
  for (Adam& adam : chi_adams_) load_adam_state(adam, reader, "chi");
  load_adam_state(lambda_adam_, reader, "lambda");
  load_adam_state(tau_adam_, reader, "tau");
  scaling_.mean = std::move(mean);
  scaling_.std = std::move(std);
  options_.initial_state_proportion = initial;
  options_.action_std = std::move(action_std);
}

COptiDice::Acting::Acting(const COptiDice& owner)
    : owner_(owner), input_(owner.observation_size_), output_(2 * owner.action_size_) {}

void COptiDice::Acting::act(std::span<const double> observation, ActionMode mode, Rng& noise,
                            std::span<double> action) {
  check_acting_sizes(*this, observation, action, "COptiDICE");
  input_ = (Eigen::Map<const Eigen::VectorXd>(observation.data(), input_.size()) - owner_.scaling_.mean)
               .cwiseQuotient(owner_.scaling_.std);
  owner_.actor_.forward(input_, output_, workspace_);
  const int a = owner_.action_size_;
  for (int j = 0; j < a; ++j) {
    double u = output_(j);
    if (mode == ActionMode::sampled) u += std::exp(std::clamp(output_(a + j), kLogStdMin, kLogStdMax)) * standard_normal(noise);
    action[static_cast<std::size_t>(j)] = std::tanh(u);
  }
}

}  // namespace bsg::algos
