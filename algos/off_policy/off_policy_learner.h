// The base of the off-policy learners (docs/algorithms.md#networks-and-the-gradient-step): what SAC
// (sac_learner.h), TD3 (td3_learner.h) and DDPG (ddpg_learner.h) share, and the hooks by which each
// says how it acts and what its actor and critic targets are. make_off_policy_learner.h builds one.
//
// The base owns the actor net (its outputs are the learner's business), its target copy, the reward
// critics (1 or 2) and one cost critic Q_Ci per constraint with their targets, an Adam for each
// network, and one gradient step on a batch (s, a, R, C, s', discount, terminal) of the replay buffer:
//   targets  y   = R   + discount (1 - terminal) (min_k Q'_k(s', a') + next_value_term)
//            y_i = C_i + discount (1 - terminal)  Q'_Ci(s', a')
//            a' and next_value_term from the learner (next_actions, add_next_value_terms)
//   critics  L_Q = mean (Q(s, a) - y)^2 for each Q_k and each Q_Ci (Adam, critic_lr)
//   actor    every policy_delay critic steps:
//            L_pi = mean [actor_term - min_k Q_k(s, a) + sum_i lambda_i Q_Ci(s, a)] / (1 + sum_i lambda_i)
//            over the first critics_in_actor_loss() reward critics, a = policy_actions(s), the
//            actor_term and the backward pass from dL/da to the actor's outputs from the learner
//            (the 1 + sum lambda rescaling is OmniSafe's and FSRL's; Adam, actor_lr); then
//            after_actor_step (SAC's temperature)
//   targets  theta' <- (1 - tau) theta' + tau theta (polyak.h); the target actor only if the
//            learner has one (uses_target_actor)
// Every gradient is averaged over the MPI ranks before its Adam step, so ranks that start equal stay
// equal; with max_grad_norm > 0 the averaged gradients of each step are then rescaled to at most
// that norm as OmniSafe does (the twin reward critics together, as its one module holding both;
// each cost critic; the actor). The derivative of a critic with respect to its action input (dQ/da)
// is Mlp::input_gradient_batch. The Lagrange multipliers lambda_i are the trainer's; a -lag
// algorithm is its learner with cost critics and multipliers.
//
// Batches are sized by the first update; later updates of that size allocate nothing.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "algos/off_policy/off_policy_options.h"
#include "algos/off_policy/replay_buffer.h"
#include "algos/off_policy/temperature.h"
#include "common/adam.h"
#include "common/binary_io.h"
#include "common/mlp.h"
#include "common/mpi_context.h"
#include "common/random.h"

namespace bsg::algos {

enum class ActorKind { squashed_gaussian, deterministic };

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
  virtual ~OffPolicyLearner() = default;
  OffPolicyLearner(const OffPolicyLearner&) = delete;
  OffPolicyLearner& operator=(const OffPolicyLearner&) = delete;

  virtual ActorKind actor_kind() const = 0;
  // SAC's temperature; null for the deterministic actors.
  virtual const Temperature* temperature() const { return nullptr; }

  const OffPolicyOptions& options() const { return options_; }
  int observation_size() const { return observation_size_; }
  int action_size() const { return action_size_; }
  int reward_critic_count() const { return static_cast<int>(reward_critics_.size()); }
  int cost_count() const { return static_cast<int>(cost_critics_.size()); }
  // The temperature's alpha, 0 without one.
  double alpha() const;
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

  // One action for observation `observation`: deterministic (evaluation) or exploring.
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
  // and its gradient with respect to the actor's parameters; the batch's mean log pi (0 for the
  // deterministic actors) into log_prob_mean.
  double actor_loss(const ReplayBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                    std::span<const double> lambdas, Eigen::Ref<Eigen::VectorXd> gradient, double* log_prob_mean);
  // theta' <- (1 - tau) theta' + tau theta for every target net.
  void update_targets();

  // Every network's parameters (all_networks() order), the Adam states of the actor, the reward
  // critics and the cost critics, the temperature (the deterministic actors write an unused one
  // built from the options, as the format has always held one), the update count.
  void save(BinaryWriter& writer) const;
  // Fails on the reader if a size differs.
  void load(BinaryReader& reader);

 protected:
  // Networks drawn from `init_rng`: the actor (|S| -> hidden -> actor_output_size), then each of the
  // reward_critics reward critics, then each cost critic; the targets start as copies.
  OffPolicyLearner(OffPolicyOptions options, int observation_size, int action_size, int cost_count,
                   int actor_output_size, int reward_critics, Rng& init_rng);

  // --- the hooks of a learner ---
  // One action from the actor's outputs for one observation; exploring ones draw from `rng`.
  virtual void action_from_outputs(const Eigen::VectorXd& outputs, bool deterministic, Rng& rng,
                                   Eigen::Ref<Eigen::VectorXd> action) const = 0;
  // Whether a step draws next_noise for the targets (SAC's a' ~ pi, TD3's smoothing) and noise
  // for the actor's loss (SAC's reparameterised sample), before using them.
  virtual bool draws_target_noise() const = 0;
  virtual bool draws_actor_noise() const = 0;
  // Critic target: a' for the batch's next observations (N x |A|).
  virtual void next_actions(const Eigen::MatrixXd& next_observations, const Eigen::Ref<const Eigen::MatrixXd>& next_noise,
                            Eigen::MatrixXd& actions) = 0;
  // Critic target: terms added to min_k Q'_k(s', a') (N x 1) before the bootstrap (SAC's
  // -alpha log pi(a'|s')); the a' of the last next_actions call.
  virtual void add_next_value_terms(Eigen::MatrixXd& next_values) const { (void)next_values; }
  // Actor target: a = pi(s) from the actor's outputs on the batch's observations (N x |A|).
  virtual void policy_actions(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                              Eigen::MatrixXd& actions) = 0;
  // How many reward critics enter the actor's loss (min over them): SAC's twins, TD3's Q_1.
  virtual int critics_in_actor_loss() const = 0;
  // The actor's own terms: adds them (unscaled sums over the batch) to `loss_sum`, writes the mean
  // log pi, and turns dL/da (`action_gradient`, already scaled) into dL/d outputs. `actions` are
  // the last policy_actions.
  virtual void actor_output_gradient(const Eigen::MatrixXd& outputs, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                                     const Eigen::MatrixXd& actions, const Eigen::MatrixXd& action_gradient,
                                     double scale, double& loss_sum, double* log_prob_mean,
                                     Eigen::MatrixXd& output_gradient) = 0;
  // After the actor's Adam step, with the rank's mean log pi (collective if it averages over ranks).
  virtual void after_actor_step(double log_prob_mean, const MpiContext& mpi) {
    (void)log_prob_mean;
    (void)mpi;
  }
  virtual bool uses_target_actor() const = 0;
  virtual Temperature* mutable_temperature() { return nullptr; }

  // The workspace of the actor's batch passes (next_actions and policy_actions use it).
  MlpBatchWorkspace& actor_workspace() { return actor_workspace_; }

 private:
  void build_critic_inputs(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                           const Eigen::Ref<const Eigen::MatrixXd>& actions);

  OffPolicyOptions options_;
  int observation_size_;
  int action_size_;
  Mlp actor_;
  Mlp target_actor_;  // a copy kept equal to the actor's shape; updated only if uses_target_actor()
  std::vector<Mlp> reward_critics_;
  std::vector<Mlp> target_reward_critics_;
  std::vector<Mlp> cost_critics_;
  std::vector<Mlp> target_cost_critics_;
  Adam actor_adam_;
  std::vector<Adam> reward_critic_adams_;
  std::vector<Adam> cost_critic_adams_;
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
  Eigen::MatrixXd q_min_;             // N x 1
  Eigen::MatrixXd q_argmin_;          // N x 1: which twin is the minimum
  Eigen::MatrixXd output_gradient_;   // N x 1: dL/dQ
  Eigen::MatrixXd input_gradient_;    // N x (|S| + |A|)
  Eigen::MatrixXd action_gradient_;   // N x |A|: dL/da
  Eigen::MatrixXd actor_output_gradient_;
  Eigen::VectorXd reward_targets_;
  Eigen::MatrixXd cost_targets_;
  Eigen::VectorXd gradient_;          // one cost critic's parameter gradient
  std::vector<Eigen::VectorXd> reward_gradients_;  // the reward critics' parameter gradients
  std::vector<Eigen::VectorXd*> reward_gradient_views_;
  Eigen::VectorXd actor_gradient_;
};

}  // namespace bsg::algos
