#include "algos/offline/bcq_lag.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "algos/core/adam_state.h"
#include "algos/core/polyak.h"
#include "algos/offline/offline_learner_parts.h"

namespace bsg::algos {
namespace {

constexpr int kCritics = 2 * kBcqEnsemble;  // two heads of E

std::vector<Mlp> critic_set(int input, const BcqLagOptions& options, Rng& init_rng) {
  std::vector<Mlp> critics;
  for (int k = 0; k < kCritics; ++k) critics.emplace_back(mlp_layers(input, options.hidden_sizes, 1), init_rng, options.mlp);
  return critics;
}

MlpOptions actor_network(const BcqLagOptions& options) {
  MlpOptions actor = options.mlp;
  actor.activation = Activation::tanh;  // OSRL's MLPGaussianPerturbationActor is built with nn.Tanh
  return actor;
}

const BcqLagOptions& checked(const BcqLagOptions& options) {
  const auto positive = [](double value) { return value > 0.0 && std::isfinite(value); };
  const auto gain = [](double value) { return value >= 0.0 && std::isfinite(value); };
  if (!positive(options.actor_lr) || !positive(options.critic_lr) || !positive(options.vae_lr) ||
      !(options.tau > 0.0 && options.tau <= 1.0) || !(options.gamma > 0.0 && options.gamma <= 1.0) ||
      options.sampled_actions < 1 || options.episode_length < 1 || options.vae_hidden_size < 1 ||
      !(options.cost_limit >= 0.0) || !gain(options.vae_kl_weight) || !positive(options.phi) ||
      !(options.lambda_mix >= 0.0 && options.lambda_mix <= 1.0) || !gain(options.pid_kp) || !gain(options.pid_ki) ||
      !gain(options.pid_kd)) {
    throw std::invalid_argument("BCQ-Lag: options out of range (learning rates, tau and phi > 0, 0 < gamma <= 1, "
                                "0 <= lambda <= 1, sampled actions, episode length and VAE width >= 1, cost "
                                "limit, beta and PID gains >= 0)");
  }
  return options;
}

// z ~ N(0, I) clamped to [-0.5, 0.5].
void fill_clipped_latents(Rng& rng, Eigen::MatrixXd& latents, Eigen::Index rows, Eigen::Index cols) {
  fill_standard_normal(rng, latents, rows, cols);
  latents = latents.cwiseMax(-kBcqLatentClip).cwiseMin(kBcqLatentClip);
}

}  // namespace

double BcqLagOptions::cost_threshold() const { return per_step_cost_threshold(cost_limit, gamma, episode_length); }

double BcqPidController::control(double error) {
  const double derivative = std::max(0.0, error - previous_error);
  integral = std::max(0.0, integral + error);
  previous_error = error;
  return std::max(0.0, kp * std::max(0.0, error) + ki * integral + kd * derivative);
}

BcqLag::BcqLag(int observation_size, int action_size, ObservationScaling scaling, BcqLagOptions options,
               Rng& init_rng)
    : observation_size_(observation_size),
      action_size_(action_size),
      scaling_(std::move(scaling)),
      options_(checked(options)),
      actor_(mlp_layers(observation_size + action_size, options_.hidden_sizes, action_size), init_rng,
             actor_network(options_)),
      target_actor_(actor_),
      reward_critics_(critic_set(observation_size + action_size, options_, init_rng)),
      cost_critics_(critic_set(observation_size + action_size, options_, init_rng)),
      target_reward_critics_(reward_critics_),
      target_cost_critics_(cost_critics_),
      vae_(observation_size, action_size, options_.vae_hidden_size, 2 * action_size, options_.mlp, init_rng),
      controller_{.kp = options_.pid_kp, .ki = options_.pid_ki, .kd = options_.pid_kd},
      actor_adam_(actor_.num_parameters(), {.learning_rate = options_.actor_lr}),
      encoder_adam_(vae_.encoder().num_parameters(), {.learning_rate = options_.vae_lr}),
      decoder_adam_(vae_.decoder().num_parameters(), {.learning_rate = options_.vae_lr}),
      acting_(*this) {
  if (scaling_.mean.size() != observation_size || scaling_.std.size() != observation_size) {
    throw std::invalid_argument("BCQ-Lag: the observation scaling has " + std::to_string(scaling_.mean.size()) +
                                " features, the observations " + std::to_string(observation_size));
  }
  for (int k = 0; k < kCritics; ++k) {
    reward_critic_adams_.emplace_back(reward_critics_[k].num_parameters(), AdamOptions{.learning_rate = options_.critic_lr});
    cost_critic_adams_.emplace_back(cost_critics_[k].num_parameters(), AdamOptions{.learning_rate = options_.critic_lr});
  }
}

void BcqLag::perturb(const Mlp& perturbation, const Eigen::Ref<const Eigen::MatrixXd>& observations,
                     const Eigen::Ref<const Eigen::MatrixXd>& proposals, MlpBatchWorkspace& workspace,
                     Eigen::MatrixXd& actions) {
  inputs_.resize(observations.rows(), observation_size_ + action_size_);
  inputs_ << observations, proposals;
  perturbations_ = perturbation.forward_batch(inputs_, workspace);
  // a = clamp(a_hat + phi tanh(xi), -1, 1)  (max_action 1)
  actions = (proposals.array() + options_.phi * perturbations_.array().tanh()).cwiseMax(-1.0).cwiseMin(1.0).matrix();
}

void BcqLag::propose(const Mlp& perturbation, const Eigen::Ref<const Eigen::MatrixXd>& observations,
                     const Eigen::Ref<const Eigen::MatrixXd>& latents, MlpBatchWorkspace& workspace) {
  proposals_.resize(observations.rows(), action_size_);
  vae_.decode(observations, latents, proposals_);
  perturb(perturbation, observations, proposals_, workspace, actions_);
  inputs_.resize(observations.rows(), observation_size_ + action_size_);
  inputs_ << observations, actions_;
}

void BcqLag::soft_clipped_value(std::vector<Mlp>& critics, const OfflineBatch& batch,
                                const Eigen::Ref<const Eigen::MatrixXd>& latents, Eigen::VectorXd& values) {
  const Eigen::Index n = batch.next_observations.rows();
  const Eigen::Index m = options_.sampled_actions;
  if (latents.rows() != n * m || latents.cols() != vae_.latent_size()) {
    throw std::invalid_argument("BCQ-Lag: the target latents must be " + std::to_string(n * m) + " x " +
                                std::to_string(vae_.latent_size()));
  }
  repeated_.resize(n * m, observation_size_);
  for (Eigen::Index i = 0; i < n; ++i) repeated_.middleRows(i * m, m).rowwise() = batch.next_observations.row(i);
  propose(target_actor_, repeated_, latents, actor_workspace_);
  // q_h = min_e Q'_{h,e}
  Eigen::MatrixXd heads = Eigen::MatrixXd::Constant(n * m, 2, std::numeric_limits<double>::infinity());
  column_.resize(n * m, 1);
  for (int k = 0; k < kCritics; ++k) {
    critics[k].evaluate_batch(inputs_, column_, critic_workspaces_[k]);
    const int head = k / kBcqEnsemble;
    heads.col(head) = heads.col(head).cwiseMin(column_.col(0));
  }
  values.resize(n);
  const double mix = options_.lambda_mix;
  for (Eigen::Index i = 0; i < n; ++i) {
    double best = -std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < m; ++k) {
      const double q1 = heads(i * m + k, 0);
      const double q2 = heads(i * m + k, 1);
      best = std::max(best, mix * std::min(q1, q2) + (1.0 - mix) * std::max(q1, q2));
    }
    values(i) = best;
  }
}

void BcqLag::compute_targets(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& reward_latents,
                             const Eigen::Ref<const Eigen::MatrixXd>& cost_latents) {
  const Eigen::Index n = batch.next_observations.rows();
  soft_clipped_value(target_reward_critics_, batch, reward_latents, values_);
  soft_clipped_value(target_cost_critics_, batch, cost_latents, cost_values_);
  reward_targets_.resize(n);
  cost_targets_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double bootstrap = options_.gamma * (1.0 - batch.terminals(i));
    reward_targets_(i) = options_.reward_scale * batch.rewards(i) + bootstrap * values_(i);
    cost_targets_(i) = options_.cost_scale * batch.costs(i) + bootstrap * cost_values_(i);
  }
}

double BcqLag::critic_loss(Mlp& critic, const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& targets,
                           Eigen::Ref<Eigen::VectorXd> gradient) {
  const Eigen::Index n = batch.observations.rows();
  inputs_.resize(n, observation_size_ + action_size_);
  inputs_ << batch.observations, batch.actions;
  const Eigen::VectorXd error = critic.forward_batch(inputs_, critic_workspaces_[0]).col(0) - targets;
  output_gradient_ = (2.0 / static_cast<double>(n)) * error;
  critic.backward_batch(output_gradient_, critic_workspaces_[0], gradient);
  return error.squaredNorm() / static_cast<double>(n);
}

void BcqLag::minimum_of_all(std::vector<Mlp>& critics, Eigen::VectorXd& values, Eigen::VectorXi& which) {
  values = critics[0].forward_batch(inputs_, critic_workspaces_[0]).col(0);
  which.setZero(inputs_.rows());
  for (int k = 1; k < kCritics; ++k) {
    const Eigen::MatrixXd& q = critics[k].forward_batch(inputs_, critic_workspaces_[k]);
    for (Eigen::Index i = 0; i < inputs_.rows(); ++i) {
      if (q(i, 0) < values(i)) {  // torch.min keeps the first of equal values
        values(i) = q(i, 0);
        which(i) = k;
      }
    }
  }
}

double BcqLag::actor_cost_estimate(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& latents) {
  propose(actor_, batch.observations, latents, actor_workspace_);
  minimum_of_all(cost_critics_, cost_values_, cost_which_);
  return cost_values_.mean();
}

double BcqLag::actor_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& latents,
                          double multiplier, Eigen::Ref<Eigen::VectorXd> gradient) {
  const Eigen::Index n = batch.observations.rows();
  const double scale = 1.0 / static_cast<double>(n);
  propose(actor_, batch.observations, latents, actor_workspace_);
  // L = -mean min Q + mu mean (min Qc - l): dL/da through the minimising critic of each row.
  action_gradient_.setZero(n, action_size_);
  input_gradient_.resize(n, observation_size_ + action_size_);
  double loss = 0.0;
  for (std::vector<Mlp>* critics : {&reward_critics_, &cost_critics_}) {
    const bool reward = critics == &reward_critics_;
    Eigen::VectorXd& values = reward ? values_ : cost_values_;
    Eigen::VectorXi& which = reward ? which_ : cost_which_;
    minimum_of_all(*critics, values, which);
    loss += reward ? -values.mean() : multiplier * (values.array() - options_.cost_threshold()).mean();
    const double weight = reward ? -scale : multiplier * scale;
    for (int k = 0; k < kCritics; ++k) {
      output_gradient_ = (which.array() == k).cast<double>().matrix() * weight;
      if (output_gradient_.isZero(0.0)) continue;
      (*critics)[k].input_gradient_batch(output_gradient_, critic_workspaces_[k], input_gradient_);
      action_gradient_ += input_gradient_.rightCols(action_size_);
    }
  }
  // a = clamp(a_hat + phi tanh(xi)): da/dxi = phi (1 - tanh^2 xi) where the clamp does not bind (torch's
  // clamp passes the gradient at the bound itself).
  output_gradient_.resize(n, action_size_);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int j = 0; j < action_size_; ++j) {
      const double t = std::tanh(perturbations_(i, j));
      const double unclamped = proposals_(i, j) + options_.phi * t;
      const bool binds = unclamped < -1.0 || unclamped > 1.0;
      output_gradient_(i, j) = binds ? 0.0 : action_gradient_(i, j) * options_.phi * (1.0 - t * t);
    }
  }
  actor_.backward_batch(output_gradient_, actor_workspace_, gradient);
  return loss;
}

double BcqLag::update(const OfflineBatch& batch, Rng& noise) {
  const Eigen::Index n = batch.observations.rows();
  check_batch_fits(batch, observation_size_, action_size_, "BCQ-Lag");
  const int latent = vae_.latent_size();
  const Eigen::Index proposals = n * options_.sampled_actions;
  Eigen::MatrixXd draws;
  // 1. the VAE
  fill_standard_normal(noise, draws, n, latent);
  Eigen::VectorXd encoder_gradient(vae_.encoder().num_parameters());
  Eigen::VectorXd decoder_gradient(vae_.decoder().num_parameters());
  vae_.loss(batch.observations, batch.actions, draws, options_.vae_kl_weight, encoder_gradient, decoder_gradient);
  encoder_adam_.step(vae_.encoder().mutable_parameters(), encoder_gradient);
  decoder_adam_.step(vae_.decoder().mutable_parameters(), decoder_gradient);
  // 2. and 3. the critics on their targets (each from its own proposals, as OSRL decodes twice)
  Eigen::MatrixXd cost_draws;
  fill_clipped_latents(noise, draws, proposals, latent);
  fill_clipped_latents(noise, cost_draws, proposals, latent);
  compute_targets(batch, draws, cost_draws);
  for (std::vector<Mlp>* critics : {&reward_critics_, &cost_critics_}) {
    const bool reward = critics == &reward_critics_;
    for (int k = 0; k < kCritics; ++k) {
      Mlp& critic = (*critics)[static_cast<std::size_t>(k)];
      gradient_.resize(critic.num_parameters());
      critic_loss(critic, batch, reward ? reward_targets_ : cost_targets_, gradient_);
      (reward ? reward_critic_adams_ : cost_critic_adams_)[static_cast<std::size_t>(k)].step(critic.mutable_parameters(),
                                                                                          gradient_);
    }
  }
  // 4. the actor, its multiplier from the cost critics' estimate before the step
  fill_clipped_latents(noise, draws, n, latent);
  const double multiplier = controller_.control(actor_cost_estimate(batch, draws) - options_.cost_threshold());
  gradient_.resize(actor_.num_parameters());
  const double loss = actor_loss(batch, draws, multiplier, gradient_);
  actor_adam_.step(actor_.mutable_parameters(), gradient_);
  // 5. the targets
  for (int k = 0; k < kCritics; ++k) {
    polyak_update(target_reward_critics_[k].mutable_parameters(), reward_critics_[k].parameters(), options_.tau);
    polyak_update(target_cost_critics_[k].mutable_parameters(), cost_critics_[k].parameters(), options_.tau);
  }
  polyak_update(target_actor_.mutable_parameters(), actor_.parameters(), options_.tau);
  return loss;
}

void BcqLag::save(BinaryWriter& writer) const {
  writer.write_section("bcq-lag");
  writer.write_vector(scaling_.mean);
  writer.write_vector(scaling_.std);
  writer.write_vector(actor_.parameters());
  writer.write_vector(target_actor_.parameters());
  for (const std::vector<Mlp>* set : {&reward_critics_, &cost_critics_, &target_reward_critics_, &target_cost_critics_}) {
    for (const Mlp& critic : *set) writer.write_vector(critic.parameters());
  }
  vae_.save(writer);
  writer.write_f64(controller_.previous_error);
  writer.write_f64(controller_.integral);
  save_adam_state(actor_adam_, writer);
  for (const Adam& adam : reward_critic_adams_) save_adam_state(adam, writer);
  for (const Adam& adam : cost_critic_adams_) save_adam_state(adam, writer);
  save_adam_state(encoder_adam_, writer);
  save_adam_state(decoder_adam_, writer);
}

void BcqLag::load(BinaryReader& reader) {
  reader.expect_section("bcq-lag");
  Eigen::VectorXd mean = reader.read_vector("observation mean", observation_size_);
  Eigen::VectorXd std = reader.read_vector("observation std", observation_size_);
  actor_.set_parameters(reader.read_vector("actor parameters", actor_.num_parameters()));
  target_actor_.set_parameters(reader.read_vector("target actor parameters", target_actor_.num_parameters()));
  for (std::vector<Mlp>* set : {&reward_critics_, &cost_critics_, &target_reward_critics_, &target_cost_critics_}) {
    for (Mlp& critic : *set) critic.set_parameters(reader.read_vector("critic parameters", critic.num_parameters()));
  }
  vae_.load(reader);
  controller_.previous_error = reader.read_f64("PID previous error");
  controller_.integral = reader.read_f64("PID integral");
  load_adam_state(actor_adam_, reader, "actor");
  for (Adam& adam : reward_critic_adams_) load_adam_state(adam, reader, "reward critic");
  for (Adam& adam : cost_critic_adams_) load_adam_state(adam, reader, "cost critic");
  load_adam_state(encoder_adam_, reader, "VAE encoder");
  load_adam_state(decoder_adam_, reader, "VAE decoder");
  scaling_.mean = std::move(mean);
  scaling_.std = std::move(std);
}

BcqLag::Acting::Acting(BcqLag& owner) : owner_(owner) {}

void BcqLag::Acting::act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) {
  check_acting_sizes(*this, observation, action, "BCQ-Lag");
  const Eigen::Index s = owner_.observation_size_;
  observation_ = ((Eigen::Map<const Eigen::VectorXd>(observation.data(), s) - owner_.scaling_.mean)
                      .cwiseQuotient(owner_.scaling_.std))
                     .transpose();
  latent_.setZero(1, owner_.vae_.latent_size());  // z = 0: the proposal at the latent prior's mean
  if (mode == ActionMode::sampled) fill_clipped_latents(noise, latent_, 1, owner_.vae_.latent_size());
  proposal_.resize(1, owner_.action_size_);
  owner_.vae_.decode(observation_, latent_, proposal_);
  owner_.perturb(owner_.actor_, observation_, proposal_, workspace_, action_);
  for (int j = 0; j < owner_.action_size_; ++j) action[static_cast<std::size_t>(j)] = action_(0, j);
}

}  // namespace bsg::algos
