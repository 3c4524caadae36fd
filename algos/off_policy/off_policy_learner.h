// The networks and the gradient step of the six off-policy learners (docs/algorithms.md#off-policy-learners):
//   SAC  (Haarnoja et al. 2018): tanh-squashed Gaussian actor (squashed_gaussian.h), twin reward
//        critics, the entropy temperature alpha (fixed, or learnt towards the target entropy -|A|);
//   TD3  (Fujimoto et al. 2018): deterministic actor tanh(mu(s)), twin reward critics, target policy
//        smoothing (target_smoothing.h), actor and target updates every policy_delay critic steps;
//   DDPG (Lillicrap et al. 2016): deterministic actor, one reward critic, Gaussian exploration;
// and their Lagrangian forms (-lag; Ha et al. 2020 for SAC-Lag) with one cost critic Q_Ci per
// constraint. One gradient step on a batch (s, a, R, C, s', discount, terminal) of the replay buffer:
//   targets  y   = R   + discount (1 - terminal) (min_k Q'_k(s', a') - alpha log pi(a'|s'))   [SAC]
//            y   = R   + discount (1 - terminal)  min_k Q'_k(s', a')   [TD3: a' smoothed; DDPG: one Q']
//            y_i = C_i + discount (1 - terminal)  Q'_Ci(s', a')
//   critics  L_Q = mean (Q(s, a) - y)^2 for each Q_k and each Q_Ci (Adam, critic_lr)
//   actor    L_pi = mean [alpha log pi(a|s) - min_k Q_k(s, a) + sum_i lambda_i Q_Ci(s, a)] / (1 + sum_i lambda_i)
//            with a = tanh(mu + sigma eps) [SAC], or tanh(mu(s)) and Q_1 alone [TD3, DDPG]
//            (the 1 + sum lambda rescaling is OmniSafe's and FSRL's; Adam, actor_lr)
//   alpha    L_alpha = -log alpha mean(log pi(a|s) + target entropy)   [SAC with auto_alpha]
//   targets  theta' <- (1 - tau) theta' + tau theta (polyak.h)
// Every gradient is averaged over the MPI ranks before its Adam step, so ranks that start equal stay
// equal; with max_grad_norm > 0 the averaged gradients of each step are then rescaled to at most
// that norm as OmniSafe does (the twin reward critics together, as its one module holding both;
// each cost critic; the actor). The derivative of a critic with respect to its action input (dQ/da) is Mlp::input_gradient_batch.
//
// Batches are sized by the first update; later updates of that size allocate nothing.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "algos/off_policy/replay_buffer.h"
#include "algos/off_policy/squashed_gaussian.h"
#include "common/adam.h"
#include "common/binary_io.h"
#include "common/mlp.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "common/run_config.h"

namespace bsg::algos {

enum class ActorKind { squashed_gaussian, deterministic };

// What the step reads from the RunConfig.
struct OffPolicyOptions {
  ActorKind actor = ActorKind::squashed_gaussian;
  int reward_critics = 2;          // 2 (SAC, TD3) or 1 (DDPG)
  bool target_smoothing = false;   // TD3
  int policy_delay = 1;            // TD3: policy_delay; else 1
  bool target_actor = false;       // TD3, DDPG: the target actor mu' gives a'
  double gamma = 0.99;             // only for reporting; the discounts come with the batch
  double polyak = 0.005;
  double actor_lr = 3e-4;
  double critic_lr = 1e-3;
  double exploration_noise = 0.1;  // deterministic actors while collecting
  double policy_noise = 0.2;
  double noise_clip = 0.5;
  double alpha_init = 0.2;
  bool auto_alpha = false;
  double alpha_lr = 3e-4;
  double target_entropy = -1.0;    // -|A|
  double max_grad_norm = 0.0;      // 0: gradients are not rescaled
  std::vector<int> hidden_sizes{64, 64};
  MlpOptions mlp{};

  static OffPolicyOptions from_config(const RunConfig& config, int action_size);
};

// Diagnostics of one step (reward_* over the twin critics summed, as OmniSafe logs Loss/Loss_reward_critic).
struct OffPolicyStepStats {
  double reward_critic_loss = 0.0;
  double reward_q_mean = 0.0;                 // mean over the batch of Q_1(s, a)
  std::vector<double> cost_critic_losses{};  // one per constraint
  std::vector<double> cost_q_means{};        // mean Q_Ci(s, a)
  bool actor_updated = false;
  double actor_loss = 0.0;                    // when actor_updated
  double log_prob_mean = 0.0;                 // SAC, when actor_updated
  double alpha = 0.0;                         // after the step (SAC)
};

class OffPolicyLearner {
 public:
  // Networks drawn from `init_rng`: the actor, then each reward critic, then each cost critic;
  // the targets start as copies. cost_count = 0 for the unconstrained algorithms.
  OffPolicyLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count, Rng& init_rng);

  const OffPolicyOptions& options() const { return options_; }
  int observation_size() const { return observation_size_; }
  int action_size() const { return action_size_; }
  int cost_count() const { return static_cast<int>(cost_critics_.size()); }
  double alpha() const;
  double log_alpha() const { return log_alpha_(0); }
  std::int64_t update_count() const { return update_count_; }

  Mlp& actor() { return actor_; }
  const Mlp& actor() const { return actor_; }
  Mlp& reward_critic(int k) { return reward_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& cost_critic(int i) { return cost_critics_.at(static_cast<std::size_t>(i)); }
  Mlp& target_reward_critic(int k) { return target_reward_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& target_cost_critic(int i) { return target_cost_critics_.at(static_cast<std::size_t>(i)); }
  Mlp& target_actor() { return target_actor_; }
  std::vector<Mlp*> all_networks();  // online then target, in checkpoint order
  std::vector<const Mlp*> all_networks() const;

  // One action for observation `observation`: deterministic (evaluation) or exploring (SAC's
  // sample; the deterministic actors' tanh(mu) + N(0, exploration_noise^2) clipped to [-1, 1]).
  void act(std::span<const double> observation, bool deterministic, Rng& rng, Eigen::Ref<Eigen::VectorXd> action);

  // One gradient step of every network on `batch`; `lambdas` holds lambda_1..lambda_m (empty
  // without constraints). Draws the noise it needs from `rng`.
  // `stats` is overwritten; its vectors keep their capacity, so that a step on a batch of the size
  // of the previous one allocates nothing.
  void update(const ReplayBatch& batch, std::span<const double> lambdas, Rng& rng, const MpiContext& mpi,
              OffPolicyStepStats& stats);
  OffPolicyStepStats update(const ReplayBatch& batch, std::span<const double> lambdas, Rng& rng, const MpiContext& mpi);

  // --- the pieces of update(), public for the derivative tests ---
  // The targets y (N) and y_i (N x m) of `batch` into reward_targets() and cost_targets().
  // `next_noise` N x |A|: SAC's eps for a' ~ pi(.|s'), TD3's smoothing draws (unused by DDPG).
  void compute_targets(const ReplayBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& next_noise);
  const Eigen::VectorXd& reward_targets() const { return reward_targets_; }
  const Eigen::MatrixXd& cost_targets() const { return cost_targets_; }
  // mean (Q(s, a) - y)^2 of `critic` on the batch's (s, a) and its parameter gradient.
  double critic_loss(const Mlp& critic, const ReplayBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& targets,
                     Eigen::Ref<Eigen::VectorXd> gradient);
  // L_pi on the batch's states with `noise` (N x |A|; SAC's eps, unused by the deterministic actors)
  // and its gradient with respect to the actor's parameters; the batch's mean log pi into log_prob_mean.
  double actor_loss(const ReplayBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                    std::span<const double> lambdas, Eigen::Ref<Eigen::VectorXd> gradient, double* log_prob_mean);
  // L_alpha at log alpha for a batch whose mean log pi is `log_prob_mean`; `gradient` = dL/dlog alpha.
  double alpha_loss(double log_prob_mean, double* gradient) const;
  // theta' <- (1 - tau) theta' + tau theta for every target net.
  void update_targets();

  void save(BinaryWriter& writer) const;
  // Fails on the reader if a size differs.
  void load(BinaryReader& reader);

 private:
  void build_critic_inputs(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                           const Eigen::Ref<const Eigen::MatrixXd>& actions);
  void actor_actions(const Mlp& actor, const Eigen::Ref<const Eigen::MatrixXd>& outputs, Eigen::MatrixXd& actions) const;

  OffPolicyOptions options_;
  int observation_size_;
  int action_size_;
  Mlp actor_;
  Mlp target_actor_;  // a copy kept equal to the actor's shape; updated only with options_.target_actor
  std::vector<Mlp> reward_critics_;
  std::vector<Mlp> target_reward_critics_;
  std::vector<Mlp> cost_critics_;
  std::vector<Mlp> target_cost_critics_;
  Adam actor_adam_;
  std::vector<Adam> reward_critic_adams_;
  std::vector<Adam> cost_critic_adams_;
  Eigen::VectorXd log_alpha_;  // one entry, for Adam
  Eigen::VectorXd alpha_gradient_;
  Adam alpha_adam_;
  std::int64_t update_count_ = 0;

  // Workspaces and batch buffers, sized by the first update.
  MlpSampleWorkspace act_workspace_;
  Eigen::VectorXd act_outputs_;
  MlpBatchWorkspace actor_workspace_;
  MlpBatchWorkspace critic_workspace_;
  MlpBatchWorkspace twin_critic_workspace_;  // the second reward critic's pass in the actor step
  Eigen::MatrixXd critic_inputs_;     // N x (|S| + |A|)
  Eigen::MatrixXd next_actions_;      // N x |A|
  Eigen::MatrixXd policy_actions_;    // N x |A|
  Eigen::MatrixXd noise_;             // N x |A|
  Eigen::MatrixXd next_noise_;        // N x |A|
  Eigen::MatrixXd q_values_;          // N x 1
  Eigen::MatrixXd q_min_;             // N x 1
  Eigen::MatrixXd q_argmin_;          // N x 1: which twin is the minimum
  Eigen::MatrixXd output_gradient_;   // N x 1: dL/dQ
  Eigen::MatrixXd input_gradient_;    // N x (|S| + |A|)
  Eigen::MatrixXd action_gradient_;   // N x |A|: dL/da
  Eigen::VectorXd log_prob_gradient_; // N
  Eigen::MatrixXd actor_output_gradient_;
  SquashedGaussianSample sample_;
  Eigen::VectorXd reward_targets_;
  Eigen::MatrixXd cost_targets_;
  Eigen::VectorXd gradient_;          // one cost critic's parameter gradient
  std::vector<Eigen::VectorXd> reward_gradients_;  // the reward critics' parameter gradients
  std::vector<Eigen::VectorXd*> reward_gradient_views_;
  Eigen::VectorXd actor_gradient_;
};

}  // namespace bsg::algos
