// CPQ, constraints penalised Q-learning (Xu, Zhan and Zhu, AAAI 2022; OSRL's algorithms/cpq.py), as an
// offline algorithm (offline_algorithm.h). Its networks, on standardised observations s (the family's
// scaling) and actions in [-1, 1]:
//   actor      pi: SAC's squashed Gaussian (algos/core/squashed_gaussian.h), s -> (mu, log sigma)
//   critics    Q_1, Q_2 of the scaled reward and Qc_1, Qc_2 of the scaled cost, each [s, a] -> 1,
//              with Polyak-averaged targets Q'_k, Qc'_k (algos/core/polyak.h); min over each pair
//   VAE        the behaviour policy's conditional VAE (conditional_vae.h), latent 2|A|
//   alpha      the multiplier of the out-of-distribution term, log alpha in [-5, 5]
// Thresholds, for episodes of T steps and the cost limit d (OSRL's):
//   l = d (1 - gamma^T) / ((1 - gamma) T)      (a safe state-action's discounted cost; d at gamma = 1)
//   l_ood = qc_scalar l
// One update on a batch (s, a, r, c, s', terminal) of N rows, in OSRL's order:
//   1. VAE: one Adam step on its loss with eps ~ N(0, I).
//   2. a' = tanh(mu(s') + sigma(s') eps') from the current actor;
//      reward critics: y  = reward_scale r + gamma (1 - terminal) 1[min Qc'(s', a') <= l] min Q'(s', a'),
//                      L_Qk = mean (Q_k(s, a) - y)^2 (the constraints-penalised Bellman operator).
//   3. cost critics: y_c = cost_scale c + gamma (1 - terminal) min Qc'(s', a');
//      M sampled actions a_m = tanh(mu(s) + sigma(s) eps_m) per row, each out of distribution when the
//      VAE's latent KL of (s, a_m) is at least the 0.75 quantile of all N M of them (o_m = 1);
//      L_Qck = mean (Qc_k(s, a) - y_c)^2 - alpha (mean_rows mean_m o_m Qc_k(s, a_m) - l_ood),
//      which raises the cost of out-of-distribution actions above l so that 1[...] shuts them out;
//      then log alpha += alpha_lr alpha (l_ood - mean_rows mean_m o_m min_k Qc_k(s, a_m)), clamped.
//   4. actor: L_pi = -mean 1[min Qc(s, a) <= l] min Q(s, a), a = tanh(mu(s) + sigma(s) eps), through
//      dQ/da (no entropy term, as OSRL's).
//   5. targets: theta' <- (1 - tau) theta' + tau theta for the four critics.
// Two choices differ from OSRL's code and follow the paper and bsg's rule (design.md: a time-limit
// truncation bootstraps, a termination does not): OSRL's (1 - done) counts timeouts as ends and its
// cost target bootstraps always; and OSRL evaluates the out-of-distribution term with the target cost
// critic under no_grad, so that it moves no parameter (only alpha), and on the pre-tanh samples u_m.
// Here the term acts on the online cost critics, as the paper's cost-critic objective, at the squashed
// actions the policy takes. update() returns L_pi; the policy acts with tanh(mu) (OSRL evaluates
// deterministically) or its squashed sample.
//
// Parameters (CpqOptions; defaults: OSRL examples/configs/cpq_configs.py, CPQTrainConfig):
//   hidden_sizes {256, 256} (a_ and c_hidden_sizes), ReLU; vae_hidden_size 400; gamma 0.99; tau 0.005;
//   actor_lr 1e-4; critic_lr 1e-3; vae_lr 1e-3; alpha_lr 1e-4; beta 0.5; sampled_actions 10;
//   qc_scalar 1.5; reward_scale 0.1; cost_scale 1; cost_limit 10; episode_length 300.
#pragma once

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algos/core/squashed_gaussian.h"
#include "algos/offline/conditional_vae.h"
#include "algos/offline/offline_algorithm.h"
#include "algos/offline/offline_batches.h"
#include "common/adam.h"
#include "common/mlp.h"

namespace bsg::algos {

struct CpqOptions {
  std::vector<int> hidden_sizes{256, 256};
  MlpOptions mlp{.activation = Activation::relu};
  int vae_hidden_size = 400;
  double gamma = 0.99;
  double tau = 0.005;
  double actor_lr = 1e-4;
  double critic_lr = 1e-3;
  double vae_lr = 1e-3;
  double alpha_lr = 1e-4;
  double vae_kl_weight = 0.5;  // beta
  int sampled_actions = 10;    // M
  double qc_scalar = 1.5;
  double reward_scale = 0.1;
  double cost_scale = 1.0;
  double cost_limit = 10.0;
  int episode_length = 300;    // T

  // l = d (1 - gamma^T) / ((1 - gamma) T).
  double cost_threshold() const;
};

inline constexpr double kCpqLogAlphaMin = -5.0;  // OSRL's clamp of log alpha
inline constexpr double kCpqLogAlphaMax = 5.0;

class Cpq final : public OfflineAlgorithm {
 public:
  // The actor, the reward critics, the cost critics and the VAE, drawn from `init_rng` in that order;
  // the targets start as copies, log alpha at 0. Throws std::invalid_argument for options out of range.
  Cpq(int observation_size, int action_size, ObservationScaling scaling, CpqOptions options, Rng& init_rng);
  Cpq(const Cpq&) = delete;  // its acting policy refers to it
  Cpq& operator=(const Cpq&) = delete;

  std::string_view name() const override { return "CPQ"; }
  double update(const OfflineBatch& batch, Rng& noise) override;
  ActingPolicy& acting() override { return acting_; }
  const ObservationScaling& scaling() const override { return scaling_; }
  void save(BinaryWriter& writer) const override;
  void load(BinaryReader& reader) override;

  const CpqOptions& options() const { return options_; }
  double log_alpha() const { return log_alpha_; }
  void set_log_alpha(double log_alpha) { log_alpha_ = log_alpha; }
  Mlp& actor() { return actor_; }
  Mlp& reward_critic(int k) { return reward_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& cost_critic(int k) { return cost_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& target_reward_critic(int k) { return target_reward_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& target_cost_critic(int k) { return target_cost_critics_.at(static_cast<std::size_t>(k)); }
  ConditionalVae& vae() { return vae_; }

  // --- the pieces of update(), public for the derivative tests ---
  // Step 2's a' (from `next_noise`, N x |A|), then y and y_c into reward_targets() and cost_targets().
  void compute_targets(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& next_noise);
  const Eigen::VectorXd& reward_targets() const { return reward_targets_; }
  const Eigen::VectorXd& cost_targets() const { return cost_targets_; }
  // Step 3's sampled actions from `sample_noise` (N M x |A|, row m N + i for row i's sample m) and
  // their out-of-distribution flags into ood_inputs() ([s, a_m], N M rows) and ood_flags().
  void sample_out_of_distribution(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& sample_noise);
  const Eigen::MatrixXd& ood_inputs() const { return ood_inputs_; }
  const Eigen::VectorXd& ood_flags() const { return ood_flags_; }
  // mean (Q(s, a) - targets)^2 of `critic`, minus alpha (mean o Q(ood inputs) - l_ood) when
  // `ood_weight` (alpha) is not 0, and its parameter gradient.
  double critic_loss(Mlp& critic, const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& targets,
                     double ood_weight, Eigen::Ref<Eigen::VectorXd> gradient);
  // L_pi with `noise` (N x |A|) and its gradient with respect to the actor's parameters.
  double actor_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                    Eigen::Ref<Eigen::VectorXd> gradient);

 private:
  class Acting final : public ActingPolicy {
   public:
    explicit Acting(const Cpq& owner);
    int observation_size() const override { return owner_.actor_.input_size(); }
    int action_size() const override { return owner_.action_size_; }
    void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override;

   private:
    const Cpq& owner_;
    Eigen::VectorXd input_;
    Eigen::VectorXd output_;
    MlpSampleWorkspace workspace_;
  };

  // min over the pair of `critics` at [observations, actions] into `values` (N); with `which`, the
  // index of the minimum of each row. Uses the pair's workspaces (cached passes).
  void pair_minimum(std::vector<Mlp>& critics, const Eigen::MatrixXd& inputs, Eigen::VectorXd& values,
                    Eigen::VectorXi* which);

  int observation_size_;
  int action_size_;
  ObservationScaling scaling_;
  CpqOptions options_;
  Mlp actor_;
  std::vector<Mlp> reward_critics_;
  std::vector<Mlp> cost_critics_;
  std::vector<Mlp> target_reward_critics_;
  std::vector<Mlp> target_cost_critics_;
  ConditionalVae vae_;
  double log_alpha_ = 0.0;
  Adam actor_adam_;
  std::vector<Adam> reward_critic_adams_;
  std::vector<Adam> cost_critic_adams_;
  Adam encoder_adam_;
  Adam decoder_adam_;
  Acting acting_;

  MlpBatchWorkspace actor_workspace_;
  std::vector<MlpBatchWorkspace> pair_workspaces_{2};
  MlpBatchWorkspace critic_workspace_;
  MlpBatchWorkspace ood_workspace_;
  SquashedGaussianSample sample_;
  Eigen::MatrixXd inputs_;       // N x (S + |A|) or N M x (S + |A|)
  Eigen::MatrixXd ood_inputs_;   // N M x (S + |A|)
  Eigen::VectorXd ood_flags_;    // N M
  Eigen::VectorXd ood_kl_;       // N M
  Eigen::VectorXd reward_targets_;
  Eigen::VectorXd cost_targets_;
  Eigen::VectorXd values_;
  Eigen::VectorXd other_values_;
  Eigen::VectorXi which_;
  Eigen::MatrixXd output_gradient_;
  Eigen::MatrixXd input_gradient_;
  Eigen::MatrixXd action_gradient_;
  Eigen::MatrixXd actor_output_gradient_;
  Eigen::VectorXd gradient_;
  Eigen::VectorXd ood_gradient_;
};

}  // namespace bsg::algos
