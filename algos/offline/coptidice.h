// COptiDICE: offline constrained policy optimisation by stationary distribution correction
// estimation (Lee, Paduraru, Mankowitz, Heess, Precup, Kim and Guez, ICLR 2022), as OSRL's
// algorithms/coptidice.py (offline_algorithm.h). It learns the ratio w(s, a) = d_pi(s, a) / d_D(s, a)
// of the optimal policy's stationary distribution to the data's through a dual, then extracts the
// policy by behaviour cloning weighted by w. Its networks, on standardised observations s:
//   nu         two MLPs s -> 1, nu(s) their minimum (OSRL's EnsembleQCritic, num_nu = 2): the dual of
//              the Bellman flow constraints
//   chi        two more, chi(s) their minimum (num_chi = 2): the cost's dual in the upper bound
//   actor      SAC's squashed Gaussian (algos/core/squashed_gaussian.h), s -> (mu, log sigma)
//   lambda     the cost multiplier, softplus of a parameter; tau, the upper bound's temperature, alike
// With f the chosen f-divergence (f_divergence: chi2 (x - 1)^2 / 2, softchi (x log x - x + 1 below 1,
// (x - 1)^2 / 2 above), kl x log x; OSRL adds 1e-10 inside the logs), alpha its weight, p0 the share of
// initial rows (the first of each episode) among the training rows, r and c scaled by reward_scale
// and cost_scale, and l = d (1 - gamma^T) / ((1 - gamma) T) (OSRL's threshold):
//   e(s, a, s') = r - lambda c + gamma (1 - terminal) nu(s') - nu(s)
//   w(s, a)     = max(0, (f')^{-1}(e / alpha))                       (the closed-form inner maximiser)
//   L_nu        = (1 - gamma) mean(1[initial] nu(s)) / p0 + mean(w e - alpha f(w))
// and, when cost_ub_epsilon > 0, the upper bound on the policy's cost (COptiDICE's section 3.2):
//   ell   = (1 - gamma) 1[initial] chi(s) / p0 + w (c + gamma (1 - terminal) chi(s') - chi(s))   (w fixed)
//   q     = N softmax(ell / tau) over the batch (tau fixed), D_KL = mean(q log q - q + 1)
//   L_chi = mean(q ell) (through q too), L_tau = tau (epsilon - D_KL), C_hat = mean(q w c)
// else C_hat = mean(w c). Then L_lambda = lambda (l - C_hat) (C_hat fixed).
// One update on a batch of N rows, in OSRL's order: chi's Adam step on L_chi and tau's on L_tau; nu's on
// L_nu; lambda's on L_lambda; then, with w recomputed from the stepped nu (and the lambda of the step's
// start), the actor's on
//   L_pi = -mean w log pi(a + 0.1 sigma_a eps_a | s + 0.1 eps_s)
// (noise on the standardised observation, 0.1 of the dataset's standard deviation as OSRL's, and on the
// action, 0.1 of each action dimension's standard deviation over the training rows). update() returns L_pi.
// Two choices differ from OSRL's code: a time-limit truncation bootstraps and a termination does not
// (design.md; OSRL's (1 - done) counts timeouts as ends too, as CPQ's note says); and the likelihood is the
// squashed Gaussian's, log pi(a|s) = log N(atanh(a); mu, sigma) - sum log(1 - a^2) with a clipped to
// [-1 + 1e-4, 1 - 1e-4], as the paper's tanh-squashed policy (OSRL scores the raw action under the Gaussian
// before tanh, yet acts with tanh(mu), which shrinks every action towards 0). The policy acts with tanh(mu)
// (OSRL evaluates deterministically) or its squashed sample.
//
// Parameters (COptiDiceOptions; defaults: OSRL examples/configs/coptidice_configs.py,
// COptiDICETrainConfig): hidden_sizes {256, 256} (a_ and c_hidden_sizes), ReLU; gamma 0.99; actor_lr,
// critic_lr (nu and chi), scalar_lr (lambda and tau) 1e-4; alpha 0.5; cost_ub_epsilon 0.01;
// f_divergence softchi; reward_scale 0.1; cost_scale 1; cost_limit 10; episode_length 300.
#pragma once

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algos/core/squashed_gaussian.h"
#include "algos/offline/offline_algorithm.h"
#include "algos/offline/offline_batches.h"
#include "common/adam.h"
#include "common/mlp.h"
#include "common/offline_keys.h"

namespace bsg::algos {

struct COptiDiceOptions {
  std::vector<int> hidden_sizes{256, 256};
  MlpOptions mlp{.activation = Activation::relu};
  double gamma = 0.99;
  double actor_lr = 1e-4;
  double critic_lr = 1e-4;
  double scalar_lr = 1e-4;
  double alpha = 0.5;
  double cost_ub_epsilon = 0.01;
  FDivergence f_divergence = FDivergence::softchi;
  double reward_scale = 0.1;
  double cost_scale = 1.0;
  double cost_limit = 10.0;
  int episode_length = 300;  // T
  // From the training rows (the checkpoint keeps them): p0 and each action dimension's standard deviation.
  double initial_state_proportion = 1.0;
  Eigen::VectorXd action_std;  // empty: 1 in every dimension

  double cost_threshold() const;
};

inline constexpr double kCOptiDiceNoiseScale = 0.1;         // OSRL's 0.1 standard deviations of noise
inline constexpr double kCOptiDiceActionClip = 1.0 - 1e-4;  // |a| bound before atanh

// f, f' and (f')^{-1} with its derivative, as OSRL's get_f_div_fn (1e-10 inside the logs).
double f_divergence_value(FDivergence f, double x);
double f_divergence_derivative(FDivergence f, double x);
double f_divergence_derivative_inverse(FDivergence f, double y);
double f_divergence_derivative_inverse_slope(FDivergence f, double y);

double softplus(double x);

class COptiDice final : public OfflineAlgorithm {
 public:
  // The actor, the nu networks and the chi networks, drawn from `init_rng` in that order; the lambda and
  // tau parameters start at 1 (OSRL's torch.ones). Throws std::invalid_argument for options out of range.
  COptiDice(int observation_size, int action_size, ObservationScaling scaling, COptiDiceOptions options,
            Rng& init_rng);
  COptiDice(const COptiDice&) = delete;  // its acting policy refers to it
  COptiDice& operator=(const COptiDice&) = delete;

  std::string_view name() const override { return "COptiDICE"; }
  double update(const OfflineBatch& batch, Rng& noise) override;
  ActingPolicy& acting() override { return acting_; }
  const ObservationScaling& scaling() const override { return scaling_; }
  void save(BinaryWriter& writer) const override;
  void load(BinaryReader& reader) override;

  const COptiDiceOptions& options() const { return options_; }
  Mlp& actor() { return actor_; }
  Mlp& nu(int k) { return nu_.at(static_cast<std::size_t>(k)); }
  Mlp& chi(int k) { return chi_.at(static_cast<std::size_t>(k)); }
  double lambda_parameter() const { return lambda_parameter_; }
  double tau_parameter() const { return tau_parameter_; }
  void set_lambda_parameter(double value) { lambda_parameter_ = value; }
  void set_tau_parameter(double value) { tau_parameter_ = value; }

  // --- the pieces of update(), public for the derivative tests ---
  // e and w of the batch for the multiplier `lambda` into advantages() and ratios() (nu's passes cached).
  void compute_ratios(const OfflineBatch& batch, double lambda);
  const Eigen::VectorXd& advantages() const { return advantages_; }
  const Eigen::VectorXd& ratios() const { return ratios_; }
  // L_nu at the multiplier `lambda` and its gradients with respect to nu(0)'s and nu(1)'s parameters.
  double nu_loss(const OfflineBatch& batch, double lambda, std::vector<Eigen::VectorXd>& gradients);
  // L_chi at the ratios `w` (fixed) and the temperature `tau`, its gradients with respect to chi(0)'s
  // and chi(1)'s parameters, and D_KL and C_hat into upper_bound_kl() and upper_bound_cost().
  double chi_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& w, double tau,
                  std::vector<Eigen::VectorXd>& gradients);
  double upper_bound_kl() const { return upper_bound_kl_; }
  double upper_bound_cost() const { return upper_bound_cost_; }
  // L_pi with the ratios `w`, the observation noise (N x S, eps_s) and the action noise (N x |A|, eps_a),
  // and its gradient with respect to the actor's parameters.
  double actor_loss(const OfflineBatch& batch, const Eigen::Ref<const Eigen::VectorXd>& w,
                    const Eigen::Ref<const Eigen::MatrixXd>& observation_noise,
                    const Eigen::Ref<const Eigen::MatrixXd>& action_noise, Eigen::Ref<Eigen::VectorXd> gradient);

 private:
  class Acting final : public ActingPolicy {
   public:
    explicit Acting(const COptiDice& owner);
    int observation_size() const override { return owner_.observation_size_; }
    int action_size() const override { return owner_.action_size_; }
    void act(std::span<const double> observation, ActionMode mode, Rng& noise, std::span<double> action) override;

   private:
    const COptiDice& owner_;
    Eigen::VectorXd input_;
    Eigen::VectorXd output_;
    MlpSampleWorkspace workspace_;
  };

  // min(first, second) at `inputs` into `values` and the index of the minimum into `which`, the
  // passes cached in the workspaces.
  static void pair_minimum(const Mlp& first, const Mlp& second, const Eigen::MatrixXd& inputs,
                           MlpBatchWorkspace& first_workspace, MlpBatchWorkspace& second_workspace,
                           Eigen::VectorXd& values, Eigen::VectorXi& which);
  // The pair's minimum at s (workspaces 0 and 1) and at s' (workspaces 2 and 3).
  static void pair_minimum_at_both(std::vector<Mlp>& networks, const OfflineBatch& batch,
                                   std::vector<MlpBatchWorkspace>& workspaces, Eigen::VectorXd& at_s,
                                   Eigen::VectorXi& which, Eigen::VectorXd& at_next, Eigen::VectorXi& next_which);
  // Each network's gradient from dL/d value at s (`at_s`) and at s' (`at_next`), each routed to the rows
  // whose minimum that network gave.
  void pair_gradients(std::vector<Mlp>& networks, std::vector<MlpBatchWorkspace>& workspaces,
                      const Eigen::VectorXi& which, const Eigen::VectorXi& next_which, const Eigen::VectorXd& at_s,
                      const Eigen::VectorXd& at_next, std::vector<Eigen::VectorXd>& gradients);

  int observation_size_;
  int action_size_;
  ObservationScaling scaling_;
  COptiDiceOptions options_;
  Mlp actor_;
  std::vector<Mlp> nu_;
  std::vector<Mlp> chi_;
  double lambda_parameter_ = 1.0;
  double tau_parameter_ = 1.0;
  Adam actor_adam_;
  std::vector<Adam> nu_adams_;
  std::vector<Adam> chi_adams_;
  Adam lambda_adam_;
  Adam tau_adam_;
  Acting acting_;

  MlpBatchWorkspace actor_workspace_;
  std::vector<MlpBatchWorkspace> nu_workspaces_{4};   // nu_0(s), nu_1(s), nu_0(s'), nu_1(s')
  std::vector<MlpBatchWorkspace> chi_workspaces_{4};
  Eigen::VectorXd nu_s_, nu_next_, chi_s_, chi_next_;
  Eigen::VectorXi nu_which_, nu_next_which_, chi_which_, chi_next_which_;
  Eigen::VectorXd advantages_;  // e
  Eigen::VectorXd ratios_;      // w
  Eigen::VectorXd ratio_slopes_;  // dw/de
  double upper_bound_kl_ = 0.0;
  double upper_bound_cost_ = 0.0;
  Eigen::MatrixXd noisy_observations_;
  Eigen::MatrixXd actor_output_gradient_;
  Eigen::VectorXd gradient_;
  Eigen::VectorXd next_part_;
  std::vector<Eigen::VectorXd> gradients_;
};

}  // namespace bsg::algos
