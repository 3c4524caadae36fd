// The rows of OfflineKeys (common/offline_keys.h) in the key table, after the
// off-policy rows. An offline algorithm's own key is a member of OfflineKeys
// and a row here applying to its algorithms.
#include "common/offline_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg {

std::string_view to_string(FDivergence f) { return key_rows::enum_name(kFDivergenceNames, f); }

namespace key_rows {

// clang-format off
std::vector<ConfigKeyRow> offline_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = OfflineKeys;
  constexpr AlgorithmSet kCpq = algorithm_bit(Algorithm::cpq);
  constexpr AlgorithmSet kBcqLag = algorithm_bit(Algorithm::bcq_lag);
  constexpr AlgorithmSet kVaeLearners = kCpq | kBcqLag;
  constexpr AlgorithmSet kCOptiDice = algorithm_bit(Algorithm::coptidice);
  return {
    // --- offline (docs/datasets.md#offline-runs) ---
    text("dataset", field<&R::offline, &K::dataset>(), L::run,
         "offline: the HDF5 dataset (DSRL's layout, e.g. from bsg collect) the policy learns from, or a directory "
         "holding <env_id>.hdf5 itself or one level down (as bsg dataset make writes); its env_id must be the run's", kOffline),
    integer("updates_per_epoch", field<&R::offline, &K::updates_per_epoch>(), L::algorithm, N::closed(1, kIntMax), kOffline,
            "offline: gradient steps per epoch, each on batch_size rows drawn uniformly with replacement"),
    integer("eval_every", field<&R::offline, &K::eval_every>(), L::algorithm, N::closed(1, kIntMax), kOffline,
            "offline: evaluate online (eval_episodes episodes) after every eval_every-th epoch and the last"),
    // --- CPQ (algos/offline/cpq.h); OSRL's names: reward_scale, cost_scale, vae_lr, beta,
    // vae_hidden_sizes, sample_action_num, qc_scalar, alpha_lr ---
    real("reward_scale", field<&R::offline, &K::reward_scale>(), L::algorithm, N::above(0), kVaeLearners | kCOptiDice,
         "cpq: rewards are multiplied by reward_scale in the reward critics' targets"),
    real("cost_scale", field<&R::offline, &K::cost_scale>(), L::algorithm, N::above(0), kVaeLearners | kCOptiDice,
         "cpq: costs are multiplied by cost_scale in the cost critics' targets"),
    real("vae_lr", field<&R::offline, &K::vae_lr>(), L::algorithm, N::above(0), kVaeLearners,
         "cpq: Adam step size of the behaviour policy's conditional VAE"),
    real("vae_kl_weight", field<&R::offline, &K::vae_kl_weight>(), L::algorithm, N::at_least(0), kVaeLearners,
         "cpq: beta, the weight of the VAE's KL term in its loss"),
    integer("vae_hidden_size", field<&R::offline, &K::vae_hidden_size>(), L::algorithm, N::closed(1, 100000), kVaeLearners,
            "cpq: units of each of the two hidden layers of the VAE's encoder and decoder"),
    integer("cpq_sampled_actions", field<&R::offline, &K::cpq_sampled_actions>(), L::algorithm, N::closed(1, 1000), kCpq,
            "cpq: policy actions sampled per row; those whose VAE latent KL is in the top quarter are out of "
            "distribution"),
    real("cpq_qc_scalar", field<&R::offline, &K::cpq_qc_scalar>(), L::algorithm, N::above(0), kCpq,
         "cpq: the cost critics are pushed to value out-of-distribution actions above cpq_qc_scalar times the "
         "threshold l = cost_limit (1 - gamma^T) / ((1 - gamma) T), T = max_ep_len"),
    real("cpq_alpha_lr", field<&R::offline, &K::cpq_alpha_lr>(), L::algorithm, N::above(0), kCpq,
         "cpq: step size of log alpha, the multiplier of the out-of-distribution term (clamped to [-5, 5])"),
    // --- BCQ-Lag (algos/offline/bcq_lag.h); OSRL's names: phi, lmbda, sample_action_num, PID ---
    real("bcq_phi", field<&R::offline, &K::bcq_phi>(), L::algorithm, N::above(0), kBcqLag,
         "bcq-lag: the perturbation actor moves the VAE's proposal by at most bcq_phi per action dimension"),
    real("bcq_lambda", field<&R::offline, &K::bcq_lambda>(), L::algorithm, N::closed(0, 1), kBcqLag,
         "bcq-lag: targets use bcq_lambda min(q1, q2) + (1 - bcq_lambda) max(q1, q2) of the two critic heads"),
    integer("bcq_sampled_actions", field<&R::offline, &K::bcq_sampled_actions>(), L::algorithm, N::closed(1, 1000),
            kBcqLag, "bcq-lag: perturbed VAE proposals per next observation; the target takes their best value"),
    real("bcq_pid_kp", field<&R::offline, &K::bcq_pid_kp>(), L::algorithm, N::at_least(0), kBcqLag,
         "bcq-lag: K_P of OSRL's PID controller on e = mean Qc(s, pi(s)) - l, each gradient step"),
    real("bcq_pid_ki", field<&R::offline, &K::bcq_pid_ki>(), L::algorithm, N::at_least(0), kBcqLag,
         "bcq-lag: K_I of the controller, times its integral I <- max(0, I + e)"),
    real("bcq_pid_kd", field<&R::offline, &K::bcq_pid_kd>(), L::algorithm, N::at_least(0), kBcqLag,
         "bcq-lag: K_D of the controller, times max(0, e - e_previous)"),
    // --- COptiDICE (algos/offline/coptidice.h); OSRL's names: alpha, cost_ub_epsilon, f_type, scalar_lr ---
    real("coptidice_alpha", field<&R::offline, &K::coptidice_alpha>(), L::algorithm, N::above(0), kCOptiDice,
         "coptidice: weight alpha of the f-divergence between the policy's stationary distribution and the data's"),
    real("coptidice_cost_ub_epsilon", field<&R::offline, &K::coptidice_cost_ub_epsilon>(), L::algorithm, N::at_least(0),
         kCOptiDice, "coptidice: KL budget of the upper bound on the policy's cost (chi, tau); 0 = the plain estimate"),
    choice("coptidice_f_divergence", enum_access<&R::offline, &K::coptidice_f_divergence>(), kFDivergenceNames,
           L::algorithm, kCOptiDice, "coptidice: the f-divergence: chi2, softchi (x log x - x + 1 below 1, chi2 above) or kl"),
    real("coptidice_scalar_lr", field<&R::offline, &K::coptidice_scalar_lr>(), L::algorithm, N::above(0), kCOptiDice,
         "coptidice: Adam step size of the cost multiplier lambda and the upper bound's temperature tau"),
  };
}
// clang-format on

}  // namespace key_rows
}  // namespace bsg
