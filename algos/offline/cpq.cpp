#include "algos/offline/cpq.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/adam_state.h"
#include "algos/core/polyak.h"
#include "algos/offline/offline_learner_parts.h"

namespace bsg::algos {
namespace {

constexpr int kCriticPairs = 2;  // OSRL's num_q and num_qc for every Bullet task

std::vector<Mlp> critic_pair(int input, const CpqOptions& options, Rng& init_rng) {
  std::vector<Mlp> critics;
  for (int k = 0; k < kCriticPairs; ++k) critics.emplace_back(mlp_layers(input, options.hidden_sizes, 1), init_rng, options.mlp);
  return critics;
}

const CpqOptions& checked(const CpqOptions& options) {
  const auto positive = [](double value) { return value > 0.0 && std::isfinite(value); };
  if (!positive(options.actor_lr) || !positive(options.critic_lr) || !positive(options.vae_lr) ||
      !positive(options.alpha_lr) || !(options.tau > 0.0 && options.tau <= 1.0) ||
      !(options.gamma > 0.0 && options.gamma <= 1.0) || options.sampled_actions < 1 || options.episode_length < 1 ||
      options.vae_hidden_size < 1 || !(options.cost_limit >= 0.0) || !(options.vae_kl_weight >= 0.0)) {
    throw std::invalid_argument("CPQ: options out of range (learning rates and tau > 0, 0 < gamma <= 1, "
                                "sampled actions, episode length and VAE width >= 1, cost limit and beta >= 0)");
  }
  return options;
}

}  // namespace

double CpqOptions::cost_threshold() const { return per_step_cost_threshold(cost_limit, gamma, episode_length); }

Cpq::Cpq(int observation_size, int action_size, ObservationScaling scaling, CpqOptions options, Rng& init_rng)
    : observation_size_(observation_size),
      action_size_(action_size),
      scaling_(std::move(scaling)),
      options_(checked(options)),
      actor_(mlp_layers(observation_size, options_.hidden_sizes, 2 * action_size), init_rng, options_.mlp),
      reward_critics_(critic_pair(observation_size + action_size, options_, init_rng)),
      cost_critics_(critic_pair(observation_size + action_size, options_, init_rng)),
      target_reward_critics_(reward_critics_),
      target_cost_critics_(cost_critics_),
      vae_(observation_size, action_size, options_.vae_hidden_size, 2 * action_size, options_.mlp, init_rng),
      actor_adam_(actor_.num_parameters(), {.learning_rate = options_.actor_lr}),
      encoder_adam_(vae_.encoder().num_parameters(), {.learning_rate = options_.vae_lr}),
      decoder_adam_(vae_.decoder().num_parameters(), {.learning_rate = options_.vae_lr}),
      acting_(*this) {
  if (scaling_.mean.size() != observation_size || scaling_.std.size() != observation_size) {
    throw std::invalid_argument("CPQ: the observation scaling has " + std::to_string(scaling_.mean.size()) +
                                " features, the observations " + std::to_string(observation_size));
  }
  for (int k = 0; k < kCriticPairs; ++k) {
    reward_critic_adams_.emplace_back(reward_critics_[k].num_parameters(), AdamOptions{.learning_rate = options_.critic_lr});
    cost_critic_adams_.emplace_back(cost_critics_[k].num_parameters(), AdamOptions{.learning_rate = options_.critic_lr});
  }
}

void Cpq::pair_minimum(std::vector<Mlp>& critics, const Eigen::MatrixXd& inputs, Eigen::VectorXd& values,
                       Eigen::VectorXi* which) {
  values = critics[0].forward_batch(inputs, pair_workspaces_[0]).col(0);
  other_values_ = critics[1].forward_batch(inputs, pair_workspaces_[1]).col(0);
  if (which != nullptr) which->setZero(inputs.rows());
  for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
    if (other_values_(i) < values(i)) {  // torch.min keeps the first of equal values
      values(i) = other_values_(i);
      if (which != nullptr) (*which)(i) = 1;
    }
  }
}

void Cpq::compute_targets(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& next_noise) {
  const Eigen::Index n = batch.next_observations.rows();
  const Eigen::MatrixXd& outputs = actor_.forward_batch(batch.next_observations, actor_workspace_);
  squashed_gaussian_sample(outputs, next_noise, sample_);
  inputs_.resize(n, observation_size_ + action_size_);
  inputs_ << batch.next_observations, sample_.actions;
  Eigen::VectorXd next_reward;
  pair_minimum(target_reward_critics_, inputs_, next_reward, nullptr);
  pair_minimum(target_cost_critics_, inputs_, values_, nullptr);
  const double threshold = options_.cost_threshold();
  reward_targets_.resize(n);
  cost_targets_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double bootstrap = options_.gamma * (1.0 - batch.terminals(i));
    const double safe = values_(i) <= threshold ? 1.0 : 0.0;
    reward_targets_(i) = options_.reward_scale * batch.rewards(i) + bootstrap * safe * next_reward(i);
    cost_targets_(i) = options_.cost_scale * batch.costs(i) + bootstrap * values_(i);
  }
}

void Cpq::sample_out_of_distribution(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& sample_noise) {
  const Eigen::Index n = batch.observations.rows();
  const Eigen::Index m = options_.sampled_actions;
  if (sample_noise.rows() != n * m || sample_noise.cols() != action_size_) {
    throw std::invalid_argument("CPQ: the sampling noise must be " + std::to_string(n * m) + " x " +
                                std::to_string(action_size_));
  }
  const Eigen::MatrixXd& outputs = actor_.forward_batch(batch.observations, actor_workspace_);
  ood_inputs_.resize(n * m, observation_size_ + action_size_);
  for (Eigen::Index sample = 0; sample < m; ++sample) {
    squashed_gaussian_sample(outputs, sample_noise.middleRows(sample * n, n), sample_);
    ood_inputs_.middleRows(sample * n, n) << batch.observations, sample_.actions;
  }
  ood_kl_.resize(n * m);
  vae_.latent_kl(ood_inputs_, ood_kl_);
  const double quantile = linear_quantile(ood_kl_, 0.75);  // OSRL's torch.quantile(KL, 0.75)
  ood_flags_ = (ood_kl_.array() >= quantile).cast<double>();
}

double Cpq::critic_loss(Mlp& critic, const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& targets,
                        double ood_weight, Eigen::Ref<Eigen::VectorXd> gradient) {
  const Eigen::Index n = batch.observations.rows();
  inputs_.resize(n, observation_size_ + action_size_);
  inputs_ << batch.observations, batch.actions;
  const Eigen::MatrixXd& q = critic.forward_batch(inputs_, critic_workspace_);
  const Eigen::VectorXd error = q.col(0) - targets;
  double loss = error.squaredNorm() / static_cast<double>(n);
  output_gradient_ = (2.0 / static_cast<double>(n)) * error;
  critic.backward_batch(output_gradient_, critic_workspace_, gradient);
  if (ood_weight != 0.0) {
    // - alpha (mean o Q(s, a_m) - l_ood): dL/dQ(s, a_m) = - alpha o / (N M).
    const double rows = static_cast<double>(ood_inputs_.rows());
    const Eigen::MatrixXd& q_ood = critic.forward_batch(ood_inputs_, ood_workspace_);
    const double ood_mean = ood_flags_.dot(q_ood.col(0)) / rows;
    loss -= ood_weight * (ood_mean - options_.qc_scalar * options_.cost_threshold());
    output_gradient_ = (-ood_weight / rows) * ood_flags_;
    ood_gradient_.resize(gradient.size());
    critic.backward_batch(output_gradient_, ood_workspace_, ood_gradient_);
    gradient += ood_gradient_;
  }
  return loss;
}

double Cpq::actor_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                       Eigen::Ref<Eigen::VectorXd> gradient) {
  const Eigen::Index n = batch.observations.rows();
  const Eigen::MatrixXd& outputs = actor_.forward_batch(batch.observations, actor_workspace_);
  squashed_gaussian_sample(outputs, noise, sample_);
  inputs_.resize(n, observation_size_ + action_size_);
  inputs_ << batch.observations, sample_.actions;
  // The cost critics only decide which rows count (1[min Qc <= l] has no gradient).
  Eigen::VectorXd cost(n);
  Eigen::MatrixXd column(n, 1);
  cost_critics_[0].evaluate_batch(inputs_, column, critic_workspace_);
  cost = column.col(0);
  cost_critics_[1].evaluate_batch(inputs_, column, critic_workspace_);
  cost = cost.cwiseMin(column.col(0));
  pair_minimum(reward_critics_, inputs_, values_, &which_);
  const double threshold = options_.cost_threshold();
  double loss = 0.0;
  action_gradient_.setZero(n, action_size_);
  input_gradient_.resize(n, observation_size_ + action_size_);
  for (int k = 0; k < kCriticPairs; ++k) {
    output_gradient_.setZero(n, 1);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (which_(i) != k || cost(i) > threshold) continue;
      output_gradient_(i, 0) = -1.0 / static_cast<double>(n);  // L = -mean 1[safe] min_k Q_k
      loss -= values_(i) / static_cast<double>(n);
    }
    reward_critics_[k].input_gradient_batch(output_gradient_, pair_workspaces_[k], input_gradient_);
    action_gradient_ += input_gradient_.rightCols(action_size_);
  }
  actor_output_gradient_.resize(n, 2 * action_size_);
  squashed_gaussian_backward(outputs, noise, sample_, action_gradient_, Eigen::VectorXd::Zero(n),
                             actor_output_gradient_);
  actor_.backward_batch(actor_output_gradient_, actor_workspace_, gradient);
  return loss;
}

double Cpq::update(const OfflineBatch& batch, Rng& noise) {
  const Eigen::Index n = batch.observations.rows();
  check_batch_fits(batch, observation_size_, action_size_, "CPQ");
  Eigen::MatrixXd draws;
  // 1. the VAE
  fill_standard_normal(noise, draws, n, vae_.latent_size());
  Eigen::VectorXd encoder_gradient(vae_.encoder().num_parameters());
  Eigen::VectorXd decoder_gradient(vae_.decoder().num_parameters());
  vae_.loss(batch.observations, batch.actions, draws, options_.vae_kl_weight, encoder_gradient, decoder_gradient);
  encoder_adam_.step(vae_.encoder().mutable_parameters(), encoder_gradient);
  decoder_adam_.step(vae_.decoder().mutable_parameters(), decoder_gradient);
  // 2. the reward critics, on the targets of a' ~ pi(s')
  fill_standard_normal(noise, draws, n, action_size_);
  compute_targets(batch, draws);
  for (int k = 0; k < kCriticPairs; ++k) {
    gradient_.resize(reward_critics_[k].num_parameters());
    critic_loss(reward_critics_[k], batch, reward_targets_, 0.0, gradient_);
    reward_critic_adams_[k].step(reward_critics_[k].mutable_parameters(), gradient_);
  }
  // 3. the cost critics with the out-of-distribution term, then alpha (from the critics before their step)
  fill_standard_normal(noise, draws, n * options_.sampled_actions, action_size_);
  sample_out_of_distribution(batch, draws);
  pair_minimum(cost_critics_, ood_inputs_, values_, nullptr);
  const double ood_cost = ood_flags_.dot(values_) / static_cast<double>(ood_flags_.size());
  const double alpha = std::exp(log_alpha_);
  for (int k = 0; k < kCriticPairs; ++k) {
    gradient_.resize(cost_critics_[k].num_parameters());
    critic_loss(cost_critics_[k], batch, cost_targets_, alpha, gradient_);
    cost_critic_adams_[k].step(cost_critics_[k].mutable_parameters(), gradient_);
  }
  log_alpha_ = std::clamp(log_alpha_ + options_.alpha_lr * alpha * (options_.qc_scalar * options_.cost_threshold() - ood_cost),
                          kCpqLogAlphaMin, kCpqLogAlphaMax);
  // 4. the actor
  fill_standard_normal(noise, draws, n, action_size_);
  gradient_.resize(actor_.num_parameters());
  const double loss = actor_loss(batch, draws, gradient_);
  actor_adam_.step(actor_.mutable_parameters(), gradient_);
  // 5. the targets
  for (int k = 0; k < kCriticPairs; ++k) {
    polyak_update(target_reward_critics_[k].mutable_parameters(), reward_critics_[k].parameters(), options_.tau);
    polyak_update(target_cost_critics_[k].mutable_parameters(), cost_critics_[k].parameters(), options_.tau);
  }
  return loss;
}

void Cpq::save(BinaryWriter& writer) const {
  writer.write_section("cpq");
  writer.write_vector(scaling_.mean);
  writer.write_vector(scaling_.std);
  writer.write_vector(actor_.parameters());
  for (const std::vector<Mlp>* pair : {&reward_critics_, &cost_critics_, &target_reward_critics_, &target_cost_critics_}) {
    for (const Mlp& critic : *pair) writer.write_vector(critic.parameters());
  }
  vae_.save(writer);
  writer.write_f64(log_alpha_);
  save_adam_state(actor_adam_, writer);
  for (const Adam& adam : reward_critic_adams_) save_adam_state(adam, writer);
  for (const Adam& adam : cost_critic_adams_) save_adam_state(adam, writer);
  save_adam_state(encoder_adam_, writer);
  save_adam_state(decoder_adam_, writer);
}

void Cpq::load(BinaryReader& reader) {
  reader.expect_section("cpq");
  Eigen::VectorXd mean = reader.read_vector("observation mean", observation_size_);
  Eigen::VectorXd std = reader.read_vector("observation std", observation_size_);
  actor_.set_parameters(reader.read_vector("actor parameters", actor_.num_parameters()));
  for (std::vector<Mlp>* pair : {&reward_critics_, &cost_critics_, &target_reward_critics_, &target_cost_critics_}) {
    for (Mlp& critic : *pair) critic.set_parameters(reader.read_vector("critic parameters", critic.num_parameters()));
  }
  vae_.load(reader);
  log_alpha_ = reader.read_f64("log alpha");
  load_adam_state(actor_adam_, reader, "actor");
  for (Adam& adam : reward_critic_adams_) load_adam_state(adam, reader, "reward critic");
  for (Adam& adam : cost_critic_adams_) load_adam_state(adam, reader, "cost critic");
  load_adam_state(encoder_adam_, reader, "VAE encoder");
  load_adam_state(decoder_adam_, reader, "VAE decoder");
  scaling_.mean = std::move(mean);
  scaling_.std = std::move(std);
}

Cpq::Acting::Acting(const Cpq& owner)
    : owner_(owner), input_(owner.observation_size_), output_(2 * owner.action_size_) {}

void Cpq::Acting::act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) {
  check_acting_sizes(*this, observation, action, "CPQ");
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
