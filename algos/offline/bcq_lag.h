// BCQ-Lag: batch-constrained deep Q-learning (Fujimoto, Meger and Precup, ICML 2019) with a cost
// critic and a PID multiplier on its estimate, as OSRL's algorithms/bcql.py (offline_algorithm.h).
// Its networks, on standardised observations s and actions in [-1, 1]:
//   VAE        the behaviour policy's conditional VAE (conditional_vae.h), latent L = 2|A|; it proposes
//              a_hat = tanh(d(s, z)) with z ~ N(0, I) clamped to [-0.5, 0.5] (BCQ's "clipped latent")
//   actor      the perturbation xi: [s, a_hat] -> tanh hidden layers -> |A|, acting with
//              a = clamp(a_hat + phi tanh(xi(s, a_hat)), -1, 1), so that it stays within phi of the data;
//              a Polyak-averaged copy xi' for the targets
//   critics    two heads of E = 2 reward critics Q_{h,e}([s, a]) and as many cost critics Qc_{h,e}, each
//              head's value the minimum over its E (OSRL's EnsembleDoubleQCritic with num_q = num_qc = 2),
//              with Polyak-averaged targets
//   lambda     OSRL's PID controller on the cost critic's estimate (below)
// Threshold, for episodes of T steps and the cost limit d (OSRL's): l = d (1 - gamma^T) / ((1 - gamma) T).
// One update on a batch (s, a, r, c, s', terminal) of N rows, in OSRL's order:
//   1. VAE: one Adam step on its loss with eps ~ N(0, I).
//   2. reward critics: for M proposals a'_k = clamp(a_hat_k + phi tanh(xi'(s', a_hat_k))), a_hat_k from
//      the VAE at s', with q_h = min_e Q'_{h,e}(s', a'_k) (the targets),
//        v = max_k [lambda_mix min(q_1, q_2) + (1 - lambda_mix) max(q_1, q_2)]        (BCQ's soft clipped
//        double Q: lambda_mix = 0.75)
//        y = reward_scale r + gamma (1 - terminal) v,   L_Q = sum_{h,e} mean (Q_{h,e}(s, a) - y)^2
//   3. cost critics: the same with fresh proposals and the target cost critics, y_c = cost_scale c +
//      gamma (1 - terminal) v_c.
//   4. actor: a = clamp(a_hat + phi tanh(xi(s, a_hat))) with a_hat from the VAE at s;
//      Q(s, a) = min_{h,e} Q_{h,e}, Qc(s, a) = min_{h,e} Qc_{h,e};
//      multiplier mu = PID(mean Qc(s, a) - l), then L_pi = -mean Q(s, a) + mu mean (Qc(s, a) - l), through
//      dQ/da (the clamp passes no gradient where it binds).
//   5. targets: theta' <- (1 - tau) theta' + tau theta for the critics and the actor.
// OSRL's PID controller, once per update on e = mean Qc(s, a) - l:
//   D = max(0, e - e_prev), I <- max(0, I + e), e_prev <- e, mu = max(0, K_P max(0, e) + K_I I + K_D D)
// (e_prev and I start at 0). Unlike the PID Lagrangian of algos/lagrange (Stooke et al.), it acts on every
// gradient step, on the critic's estimate, with a one-sided P term and K_I outside the integral.
// One choice differs from OSRL's code and follows bsg's rule (design.md: a time-limit truncation
// bootstraps, a termination does not), as CPQ's: OSRL's (1 - done) counts timeouts as ends and its cost
// target bootstraps always. update() returns L_pi. The policy acts with the VAE's proposal at z = 0
// (ActionMode::mean) or at a clamped sample z (sampled; OSRL's act() always samples), then perturbed.
//
// Parameters (BcqLagOptions; defaults: OSRL examples/configs/bcql_configs.py, BCQLTrainConfig):
//   hidden_sizes {256, 256} (a_ and c_hidden_sizes; actor tanh, critics and VAE the MlpOptions' activation,
//   ReLU in OSRL); vae_hidden_size 400; gamma 0.99; tau 0.005; actor_lr, critic_lr, vae_lr 1e-3; beta 0.5;
//   phi 0.05; lambda_mix 0.75 (lmbda); sampled_actions 10; PID {0.1, 0.003, 0.001}; reward_scale 0.1;
//   cost_scale 1; cost_limit 10; episode_length 300.
#pragma once

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algos/offline/conditional_vae.h"
#include "algos/offline/offline_algorithm.h"
#include "algos/offline/offline_batches.h"
#include "common/adam.h"
#include "common/mlp.h"

namespace bsg::algos {

struct BcqLagOptions {
  std::vector<int> hidden_sizes{256, 256};
  MlpOptions mlp{.activation = Activation::relu};  // critics and VAE; the actor's hidden layers are tanh
  int vae_hidden_size = 400;
  double gamma = 0.99;
  double tau = 0.005;
  double actor_lr = 1e-3;
  double critic_lr = 1e-3;
  double vae_lr = 1e-3;
  double vae_kl_weight = 0.5;  // beta
  double phi = 0.05;
  double lambda_mix = 0.75;    // OSRL's lmbda
  int sampled_actions = 10;    // M
  double pid_kp = 0.1;
  double pid_ki = 0.003;
  double pid_kd = 0.001;
  double reward_scale = 0.1;
  double cost_scale = 1.0;
  double cost_limit = 10.0;
  int episode_length = 300;    // T

  // l = d (1 - gamma^T) / ((1 - gamma) T).
  double cost_threshold() const;
};

inline constexpr double kBcqLatentClip = 0.5;  // z clamped to [-0.5, 0.5] (BCQ's and OSRL's decode)
inline constexpr int kBcqEnsemble = 2;         // E: OSRL's num_q and num_qc for every Bullet task

// OSRL's LagrangianPIDController (see above), on the error e = mean Qc - l of each update.
struct BcqPidController {
  double kp = 0.0;
  double ki = 0.0;
  double kd = 0.0;
  double previous_error = 0.0;  // e_prev
  double integral = 0.0;        // I

  // Updates the state with e and returns mu.
  double control(double error);
};

class BcqLag final : public OfflineAlgorithm {
 public:
  // The actor, the reward critics, the cost critics and the VAE, drawn from `init_rng` in that order;
  // the targets start as copies. Throws std::invalid_argument for options out of range.
  BcqLag(int observation_size, int action_size, ObservationScaling scaling, BcqLagOptions options, Rng& init_rng);
  BcqLag(const BcqLag&) = delete;  // its acting policy refers to it
  BcqLag& operator=(const BcqLag&) = delete;

  std::string_view name() const override { return "BCQ-Lag"; }
  double update(const OfflineBatch& batch, Rng& noise) override;
  ActingPolicy& acting() override { return acting_; }
  const ObservationScaling& scaling() const override { return scaling_; }
  void save(BinaryWriter& writer) const override;
  void load(BinaryReader& reader) override;

  const BcqLagOptions& options() const { return options_; }
  const BcqPidController& controller() const { return controller_; }
  Mlp& actor() { return actor_; }
  Mlp& target_actor() { return target_actor_; }
  // Critic e of head h is index h E + e.
  Mlp& reward_critic(int k) { return reward_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& cost_critic(int k) { return cost_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& target_reward_critic(int k) { return target_reward_critics_.at(static_cast<std::size_t>(k)); }
  Mlp& target_cost_critic(int k) { return target_cost_critics_.at(static_cast<std::size_t>(k)); }
  ConditionalVae& vae() { return vae_; }

  // --- the pieces of update(), public for the derivative tests ---
  // clamp(proposals + phi tanh(perturbation([s, proposals])), -1, 1) into `actions` (N x |A|), the
  // perturbation's pass cached in `workspace`.
  void perturb(const Mlp& perturbation, const Eigen::Ref<const Eigen::MatrixXd>& observations,
               const Eigen::Ref<const Eigen::MatrixXd>& proposals, MlpBatchWorkspace& workspace,
               Eigen::MatrixXd& actions);
  // Steps 2 and 3's y (from `reward_latents`) and y_c (from `cost_latents`), each N M x L with row
  // i M + k the latent of row i's proposal k, into reward_targets() and cost_targets().
  void compute_targets(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& reward_latents,
                       const Eigen::Ref<const Eigen::MatrixXd>& cost_latents);
  const Eigen::VectorXd& reward_targets() const { return reward_targets_; }
  const Eigen::VectorXd& cost_targets() const { return cost_targets_; }
  // mean (Q(s, a) - targets)^2 of one critic and its parameter gradient.
  double critic_loss(Mlp& critic, const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& targets,
                     Eigen::Ref<Eigen::VectorXd> gradient);
  // mean Qc(s, a) of the actor's actions from `latents` (N x L): the controller's input (plus l).
  double actor_cost_estimate(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& latents);
  // L_pi for the multiplier mu with `latents` (N x L) and its gradient with respect to the actor's parameters.
  double actor_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::MatrixXd>& latents, double multiplier,
                    Eigen::Ref<Eigen::VectorXd> gradient);

 private:
  class Acting final : public ActingPolicy {
   public:
    explicit Acting(BcqLag& owner);
    int observation_size() const override { return owner_.observation_size_; }
    int action_size() const override { return owner_.action_size_; }
    void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override;

   private:
    BcqLag& owner_;
    Eigen::MatrixXd observation_;
    Eigen::MatrixXd latent_;
    Eigen::MatrixXd proposal_;
    Eigen::MatrixXd action_;
    MlpBatchWorkspace workspace_;
  };

  // The proposals' actions at `observations` (N x S) and `latents`, then perturbed by `perturbation`.
  void propose(const Mlp& perturbation, const Eigen::Ref<const Eigen::MatrixXd>& observations,
               const Eigen::Ref<const Eigen::MatrixXd>& latents, MlpBatchWorkspace& workspace);
  // Step 2's v for N rows of M proposals each from the target `critics`.
  void soft_clipped_value(std::vector<Mlp>& critics, const OfflineBatch& batch,
                          const Eigen::Ref<const Eigen::MatrixXd>& latents, Eigen::VectorXd& values);
  // min over all 2 E `critics` at `inputs_` into `values`, the index of the minimum in `which`; cached passes.
  void minimum_of_all(std::vector<Mlp>& critics, Eigen::VectorXd& values, Eigen::VectorXi& which);

  int observation_size_;
  int action_size_;
  ObservationScaling scaling_;
  BcqLagOptions options_;
  Mlp actor_;
  Mlp target_actor_;
  std::vector<Mlp> reward_critics_;
  std::vector<Mlp> cost_critics_;
  std::vector<Mlp> target_reward_critics_;
  std::vector<Mlp> target_cost_critics_;
  ConditionalVae vae_;
  BcqPidController controller_;
  Adam actor_adam_;
  std::vector<Adam> reward_critic_adams_;
  std::vector<Adam> cost_critic_adams_;
  Adam encoder_adam_;
  Adam decoder_adam_;
  Acting acting_;

  MlpBatchWorkspace actor_workspace_;
  std::vector<MlpBatchWorkspace> critic_workspaces_{2 * kBcqEnsemble};
  Eigen::MatrixXd repeated_;     // N M x S, row i M + k = s'_i
  Eigen::MatrixXd proposals_;    // the VAE's a_hat
  Eigen::MatrixXd perturbations_;  // xi of the last perturb()
  Eigen::MatrixXd actions_;      // the perturbed actions
  Eigen::MatrixXd inputs_;       // [s, a]
  Eigen::MatrixXd column_;
  Eigen::VectorXd reward_targets_;
  Eigen::VectorXd cost_targets_;
  Eigen::VectorXd values_;
  Eigen::VectorXd cost_values_;
  Eigen::VectorXi which_;
  Eigen::VectorXi cost_which_;
  Eigen::MatrixXd output_gradient_;
  Eigen::MatrixXd input_gradient_;
  Eigen::MatrixXd action_gradient_;
  Eigen::VectorXd gradient_;
};

}  // namespace bsg::algos
