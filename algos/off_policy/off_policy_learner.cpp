#include "algos/off_policy/off_policy_learner.h"

#include <numeric>
#include <stdexcept>
#include <string>

#include "algos/core/adam_state.h"
#include "algos/core/gradient_norm_clipping.h"
#include "algos/core/polyak.h"

namespace bsg::algos {
namespace {

void resize_if_needed(Eigen::MatrixXd& matrix, Eigen::Index rows, Eigen::Index cols) {
  if (matrix.rows() != rows || matrix.cols() != cols) matrix.resize(rows, cols);
}
void resize_if_needed(Eigen::VectorXd& vector, Eigen::Index size) {
  if (vector.size() != size) vector.resize(size);
}

std::vector<int> layer_sizes(int input, const std::vector<int>& hidden, int output) {
  std::vector<int> sizes{input};
  sizes.insert(sizes.end(), hidden.begin(), hidden.end());
  sizes.push_back(output);
  return sizes;
}

void fill_standard_normal(Eigen::MatrixXd& matrix, Rng& rng) {
  for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) matrix(i, j) = standard_normal(rng);
  }
}

}  // namespace

OffPolicyLearner::OffPolicyLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count,
                                   int actor_output_size, int reward_critics, Rng& init_rng)
    : options_(std::move(options)),
      observation_size_(observation_size),
      action_size_(action_size),
      actor_(layer_sizes(observation_size, options_.hidden_sizes, actor_output_size), init_rng, options_.mlp),
      target_actor_(actor_),
      actor_adam_(actor_.num_parameters(), AdamOptions{.learning_rate = options_.actor_lr}) {
  if (reward_critics < 1 || reward_critics > 2 || options_.policy_delay < 1 || cost_count < 0) {
    throw std::invalid_argument("OffPolicyLearner: reward_critics must be 1 or 2, policy_delay >= 1, cost_count >= 0");
  }
  const std::vector<int> critic_sizes = layer_sizes(observation_size + action_size, options_.hidden_sizes, 1);
  for (int k = 0; k < reward_critics; ++k) {
    reward_critics_.emplace_back(critic_sizes, init_rng, options_.mlp);
    reward_critic_adams_.emplace_back(reward_critics_.back().num_parameters(),
                                      AdamOptions{.learning_rate = options_.critic_lr});
  }
  for (int i = 0; i < cost_count; ++i) {
    cost_critics_.emplace_back(critic_sizes, init_rng, options_.mlp);
    cost_critic_adams_.emplace_back(cost_critics_.back().num_parameters(),
                                    AdamOptions{.learning_rate = options_.critic_lr});
  }
  target_reward_critics_ = reward_critics_;
  target_cost_critics_ = cost_critics_;
  act_outputs_.resize(actor_.output_size());
}

double OffPolicyLearner::alpha() const {
  const Temperature* held = temperature();
  return held != nullptr ? held->alpha() : 0.0;
}

std::vector<const Mlp*> OffPolicyLearner::all_networks() const {
  std::vector<const Mlp*> networks{&actor_};
  for (const Mlp& net : reward_critics_) networks.push_back(&net);
  for (const Mlp& net : cost_critics_) networks.push_back(&net);
  networks.push_back(&target_actor_);
  for (const Mlp& net : target_reward_critics_) networks.push_back(&net);
  for (const Mlp& net : target_cost_critics_) networks.push_back(&net);
  return networks;
}

std::vector<Mlp*> OffPolicyLearner::all_networks() {
  std::vector<Mlp*> networks{&actor_};
  for (Mlp& net : reward_critics_) networks.push_back(&net);
  for (Mlp& net : cost_critics_) networks.push_back(&net);
  networks.push_back(&target_actor_);
  for (Mlp& net : target_reward_critics_) networks.push_back(&net);
  for (Mlp& net : target_cost_critics_) networks.push_back(&net);
  return networks;
}

void OffPolicyLearner::act(std::span<const double> observation, bool deterministic, Rng& rng,
                           Eigen::Ref<Eigen::VectorXd> action) {
  const Eigen::Map<const Eigen::VectorXd> input(observation.data(), static_cast<Eigen::Index>(observation.size()));
  actor_.forward(input, act_outputs_, act_workspace_);
  action_from_outputs(act_outputs_, deterministic, rng, action);
}

void OffPolicyLearner::build_critic_inputs(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                           const Eigen::Ref<const Eigen::MatrixXd>& actions) {
  resize_if_needed(critic_inputs_, observations.rows(), observation_size_ + action_size_);
  critic_inputs_.leftCols(observation_size_) = observations;
  critic_inputs_.rightCols(action_size_) = actions;
}

void OffPolicyLearner::compute_targets(const ReplayBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& next_noise) {
  const Eigen::Index rows = batch.rows();
  resize_if_needed(next_actions_, rows, action_size_);
  resize_if_needed(reward_targets_, rows);
  resize_if_needed(cost_targets_, rows, cost_count());
  resize_if_needed(q_min_, rows, 1);
  next_actions(batch.next_observations, next_noise, next_actions_);  // a' for s'
  build_critic_inputs(batch.next_observations, next_actions_);
  for (std::size_t k = 0; k < target_reward_critics_.size(); ++k) {
    const Eigen::MatrixXd& q = target_reward_critics_[k].forward_batch(critic_inputs_, critic_workspace_);
    if (k == 0) {
      q_min_ = q;
    } else {
      q_min_ = q_min_.cwiseMin(q);  // clipped double Q: min_k Q'_k
    }
  }
  add_next_value_terms(q_min_);
  // y = R + discount (1 - terminal) V'(s')
  reward_targets_ = batch.rewards.array() +
                    batch.discounts.array() * (1.0 - batch.terminals.array()) * q_min_.col(0).array();
  for (int i = 0; i < cost_count(); ++i) {
    const Eigen::MatrixXd& qc = target_cost_critics_[static_cast<std::size_t>(i)].forward_batch(critic_inputs_, critic_workspace_);
    cost_targets_.col(i) = batch.costs.col(i).array() +
                           batch.discounts.array() * (1.0 - batch.terminals.array()) * qc.col(0).array();
  }
}

double OffPolicyLearner::critic_loss(const Mlp& critic, const ReplayBatch& batch,
                                     const Eigen::Ref<const Eigen::VectorXd>& targets,
                                     Eigen::Ref<Eigen::VectorXd> gradient) {
  const Eigen::Index rows = batch.rows();
  build_critic_inputs(batch.observations, batch.actions);
  const Eigen::MatrixXd& q = critic.forward_batch(critic_inputs_, critic_workspace_);
  resize_if_needed(output_gradient_, rows, 1);
  output_gradient_.col(0) = q.col(0) - targets;
  const double loss = output_gradient_.squaredNorm() / static_cast<double>(rows);  // mean (Q - y)^2
  output_gradient_ *= 2.0 / static_cast<double>(rows);
  critic.backward_batch(output_gradient_, critic_workspace_, gradient);
  return loss;
}

double OffPolicyLearner::actor_loss(const ReplayBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                                    std::span<const double> lambdas, Eigen::Ref<Eigen::VectorXd> gradient,
                                    double* log_prob_mean) {
  if (static_cast<int>(lambdas.size()) != cost_count()) {
    throw std::invalid_argument("OffPolicyLearner::actor_loss: " + std::to_string(lambdas.size()) +
                                " multipliers for " + std::to_string(cost_count()) + " cost critics");
  }
  const Eigen::Index rows = batch.rows();
  const double lambda_sum = std::accumulate(lambdas.begin(), lambdas.end(), 0.0);
  const double scale = 1.0 / (static_cast<double>(rows) * (1.0 + lambda_sum));  // mean, / (1 + sum lambda)
  const Eigen::MatrixXd& outputs = actor_.forward_batch(batch.observations, actor_workspace_);
  policy_actions(outputs, noise, policy_actions_);
  build_critic_inputs(batch.observations, policy_actions_);
  resize_if_needed(action_gradient_, rows, action_size_);
  resize_if_needed(input_gradient_, rows, observation_size_ + action_size_);
  resize_if_needed(output_gradient_, rows, 1);
  resize_if_needed(q_min_, rows, 1);
  resize_if_needed(q_argmin_, rows, 1);
  action_gradient_.setZero();
  double loss_sum = 0.0;
  // - min_k Q_k(s, a) over the critics of the actor's loss
  if (critics_in_actor_loss() == 2) {
    // each twin's pass in its own workspace, so that both are cached for their input gradients
    const Eigen::MatrixXd& q0 = reward_critics_[0].forward_batch(critic_inputs_, critic_workspace_);
    const Eigen::MatrixXd& q1 = reward_critics_[1].forward_batch(critic_inputs_, twin_critic_workspace_);
    q_argmin_ = (q1.array() < q0.array()).cast<double>();  // ties go to Q_1
    q_min_ = q0.cwiseMin(q1);
    output_gradient_ = -scale * (1.0 - q_argmin_.array()).matrix();
    reward_critics_[0].input_gradient_batch(output_gradient_, critic_workspace_, input_gradient_);
    action_gradient_ += input_gradient_.rightCols(action_size_);
    output_gradient_ = -scale * q_argmin_;
    reward_critics_[1].input_gradient_batch(output_gradient_, twin_critic_workspace_, input_gradient_);
    action_gradient_ += input_gradient_.rightCols(action_size_);
  } else {
    q_min_ = reward_critics_[0].forward_batch(critic_inputs_, critic_workspace_);
    output_gradient_.setConstant(-scale);
    reward_critics_[0].input_gradient_batch(output_gradient_, critic_workspace_, input_gradient_);
    action_gradient_ += input_gradient_.rightCols(action_size_);
  }
  loss_sum -= q_min_.sum();
  // + sum_i lambda_i Q_Ci(s, a)
  for (int i = 0; i < cost_count(); ++i) {
    const double lambda = lambdas[static_cast<std::size_t>(i)];
    if (lambda == 0.0) continue;  // no value and no gradient
    const Eigen::MatrixXd& qc = cost_critics_[static_cast<std::size_t>(i)].forward_batch(critic_inputs_, critic_workspace_);
    loss_sum += lambda * qc.sum();
    output_gradient_.setConstant(lambda * scale);
    cost_critics_[static_cast<std::size_t>(i)].input_gradient_batch(output_gradient_, critic_workspace_, input_gradient_);
    action_gradient_ += input_gradient_.rightCols(action_size_);
  }
  resize_if_needed(actor_output_gradient_, rows, actor_.output_size());
  actor_output_gradient(outputs, noise, policy_actions_, action_gradient_, scale, loss_sum, log_prob_mean,
                        actor_output_gradient_);
  actor_.backward_batch(actor_output_gradient_, actor_workspace_, gradient);
  return loss_sum * scale;
}

void OffPolicyLearner::update_targets() {
  const double tau = options_.polyak;
  if (uses_target_actor()) polyak_update(target_actor_.mutable_parameters(), actor_.parameters(), tau);
  for (std::size_t k = 0; k < reward_critics_.size(); ++k) {
    polyak_update(target_reward_critics_[k].mutable_parameters(), reward_critics_[k].parameters(), tau);
  }
  for (std::size_t i = 0; i < cost_critics_.size(); ++i) {
    polyak_update(target_cost_critics_[i].mutable_parameters(), cost_critics_[i].parameters(), tau);
  }
}

OffPolicyStepStats OffPolicyLearner::update(const ReplayBatch& batch, std::span<const double> lambdas, Rng& rng,
                                            const MpiContext& mpi) {
  OffPolicyStepStats stats;
  update(batch, lambdas, rng, mpi, stats);
  return stats;
}

void OffPolicyLearner::update(const ReplayBatch& batch, std::span<const double> lambdas, Rng& rng,
                              const MpiContext& mpi, OffPolicyStepStats& stats) {
  const Eigen::Index rows = batch.rows();
  stats.reward_critic_loss = stats.reward_q_mean = stats.actor_loss = stats.log_prob_mean = stats.alpha = 0.0;
  stats.actor_updated = false;
  // 1. targets
  resize_if_needed(next_noise_, rows, action_size_);
  if (draws_target_noise()) fill_standard_normal(next_noise_, rng);
  compute_targets(batch, next_noise_);
  // 2. critics: the reward critics' gradients (each depends only on its own critic and the targets),
  // rescaled together, then their steps
  reward_gradients_.resize(reward_critics_.size());
  reward_gradient_views_.resize(reward_critics_.size());
  for (std::size_t k = 0; k < reward_critics_.size(); ++k) {
    resize_if_needed(reward_gradients_[k], reward_critics_[k].num_parameters());
    reward_gradient_views_[k] = &reward_gradients_[k];
    stats.reward_critic_loss += critic_loss(reward_critics_[k], batch, reward_targets_, reward_gradients_[k]);
    if (k == 0) stats.reward_q_mean = critic_workspace_.outputs.mean();
    mpi.average_in_place(reward_gradients_[k]);
  }
  if (options_.max_grad_norm > 0.0) clip_gradient_norm(reward_gradient_views_, options_.max_grad_norm);
  for (std::size_t k = 0; k < reward_critics_.size(); ++k) {
    reward_critic_adams_[k].step(reward_critics_[k].mutable_parameters(), reward_gradients_[k]);
  }
  stats.cost_critic_losses.assign(cost_critics_.size(), 0.0);
  stats.cost_q_means.assign(cost_critics_.size(), 0.0);
  for (std::size_t i = 0; i < cost_critics_.size(); ++i) {
    resize_if_needed(gradient_, cost_critics_[i].num_parameters());
    stats.cost_critic_losses[i] =
        critic_loss(cost_critics_[i], batch, cost_targets_.col(static_cast<Eigen::Index>(i)), gradient_);
    stats.cost_q_means[i] = critic_workspace_.outputs.mean();
    mpi.average_in_place(gradient_);
    if (options_.max_grad_norm > 0.0) clip_gradient_norm(gradient_, options_.max_grad_norm);
    cost_critic_adams_[i].step(cost_critics_[i].mutable_parameters(), gradient_);
  }
  // 3. actor, what follows its step (the temperature) and targets every policy_delay critic steps
  ++update_count_;
  if (update_count_ % options_.policy_delay == 0) {
    stats.actor_updated = true;
    resize_if_needed(noise_, rows, action_size_);
    if (draws_actor_noise()) fill_standard_normal(noise_, rng);
    resize_if_needed(actor_gradient_, actor_.num_parameters());
    double log_prob_mean = 0.0;
    stats.actor_loss = actor_loss(batch, noise_, lambdas, actor_gradient_, &log_prob_mean);
    stats.log_prob_mean = log_prob_mean;
    mpi.average_in_place(actor_gradient_);
    if (options_.max_grad_norm > 0.0) clip_gradient_norm(actor_gradient_, options_.max_grad_norm);
    actor_adam_.step(actor_.mutable_parameters(), actor_gradient_);
    after_actor_step(log_prob_mean, mpi);
    update_targets();
  }
  stats.alpha = alpha();
}

void OffPolicyLearner::save(BinaryWriter& writer) const {
  writer.write_section("off-policy networks");
  for (const Mlp* net : all_networks()) writer.write_vector(net->parameters());
  save_adam_state(actor_adam_, writer);
  for (const Adam& adam : reward_critic_adams_) save_adam_state(adam, writer);
  for (const Adam& adam : cost_critic_adams_) save_adam_state(adam, writer);
  if (const Temperature* held = temperature(); held != nullptr) {
    held->save(writer);
  } else {
    Temperature(options_.alpha_init, options_.alpha_lr, options_.target_entropy).save(writer);
  }
  writer.write_i64(update_count_);
}

void OffPolicyLearner::load(BinaryReader& reader) {
  reader.expect_section("off-policy networks");
  for (Mlp* net : all_networks()) net->set_parameters(reader.read_vector("network parameters", net->num_parameters()));
  load_adam_state(actor_adam_, reader, "actor");
  for (Adam& adam : reward_critic_adams_) load_adam_state(adam, reader, "reward critic");
  for (Adam& adam : cost_critic_adams_) load_adam_state(adam, reader, "cost critic");
  if (Temperature* held = mutable_temperature(); held != nullptr) {
    held->load(reader);
  } else {
    Temperature unused(options_.alpha_init, options_.alpha_lr, options_.target_entropy);
    unused.load(reader);  // checked, then dropped: the deterministic actors have no temperature
  }
  update_count_ = reader.read_i64("update count");
  if (update_count_ < 0) reader.fail("update count is negative");
}

}  // namespace bsg::algos
