// The conditional variational auto-encoder of the behaviour policy that CPQ (cpq.h) uses to tell
// out-of-distribution actions and BCQ-Lag (bcq_lag.h) to propose in-distribution ones (Kingma and Welling 2014; as OSRL's common/net.py VAE, which BCQ-L and
// CPQ share). Given an observation s and an action a:
//   encoder   [s, a] -> hidden -> hidden -> (mu, log sigma), L each; log sigma clamped to [-4, 15]
//   sample    z = mu + sigma eps, eps ~ N(0, I_L)       (reparameterised)
//   decoder   [s, z] -> hidden -> hidden -> A, then tanh: a_hat = tanh(d(s, z))  (actions in [-1, 1])
//   loss      L = mean_{rows, A} (a_hat - a)^2 + beta KL,
//             KL = mean_{rows, L} -1/2 (1 + log sigma^2 - mu^2 - sigma^2)
// which is the negative ELBO with a Gaussian likelihood of fixed variance and KL weight beta (OSRL's
// vae_loss). latent_kl gives each row's KL term alone (mean over the L dimensions): CPQ's measure of
// how far an action lies from the data. Hidden layers use the MlpOptions' activation (ReLU in OSRL).
#pragma once

#include <Eigen/Core>

#include "common/binary_io.h"
#include "common/mlp.h"
#include "common/random.h"

namespace bsg::algos {

inline constexpr double kVaeLogStdMin = -4.0;  // OSRL's clamp "for numerical stability"
inline constexpr double kVaeLogStdMax = 15.0;

class ConditionalVae {
 public:
  // The encoder, then the decoder, drawn from `init_rng`.
  ConditionalVae(int observation_size, int action_size, int hidden_size, int latent_size, MlpOptions options,
                 Rng& init_rng);

  int observation_size() const { return observation_size_; }
  int action_size() const { return action_size_; }
  int latent_size() const { return latent_size_; }
  Mlp& encoder() { return encoder_; }
  Mlp& decoder() { return decoder_; }
  const Mlp& encoder() const { return encoder_; }
  const Mlp& decoder() const { return decoder_; }

  // L on the rows (observations N x S, actions N x A) with `noise` (N x L, eps) and KL weight `beta`,
  // and its gradients with respect to the encoder's and the decoder's parameters (overwritten).
  double loss(const Eigen::Ref<const Eigen::MatrixXd>& observations, const Eigen::Ref<const Eigen::MatrixXd>& actions,
              const Eigen::Ref<const Eigen::MatrixXd>& noise, double beta, Eigen::Ref<Eigen::VectorXd> encoder_gradient,
              Eigen::Ref<Eigen::VectorXd> decoder_gradient);

  // Each row's KL(q(z | s, a) || N(0, I)) / L: -1/2 mean_l (1 + log sigma_l^2 - mu_l^2 - sigma_l^2).
  // `inputs` N x (S + A) are the rows [s, a].
  void latent_kl(const Eigen::Ref<const Eigen::MatrixXd>& inputs, Eigen::Ref<Eigen::VectorXd> kl);

  // The decoder's actions tanh(d(s, z)) (N x A) of the rows [s, z] (observations N x S, latents N x L):
  // how BCQ-Lag (bcq_lag.h) draws actions the data could have taken.
  void decode(const Eigen::Ref<const Eigen::MatrixXd>& observations, const Eigen::Ref<const Eigen::MatrixXd>& latents,
              Eigen::Ref<Eigen::MatrixXd> actions);

  // Both networks' parameters.
  void save(BinaryWriter& writer) const;
  void load(BinaryReader& reader);

 private:
  int observation_size_;
  int action_size_;
  int latent_size_;
  Mlp encoder_;
  Mlp decoder_;
  MlpBatchWorkspace encoder_workspace_;
  MlpBatchWorkspace decoder_workspace_;
  Eigen::MatrixXd encoder_inputs_;    // N x (S + A)
  Eigen::MatrixXd decoder_inputs_;    // N x (S + L)
  Eigen::MatrixXd encoder_outputs_;   // N x 2L
  Eigen::MatrixXd decoder_gradient_;  // N x A: dL/d pre-tanh
  Eigen::MatrixXd decoder_input_gradient_;  // N x (S + L)
  Eigen::MatrixXd encoder_gradient_;  // N x 2L
};

// The q-quantile of `values` as torch.quantile computes it by default (linear interpolation between
// the sorted values at positions floor and ceil of q (n - 1)). Throws std::invalid_argument for no
// values or q outside [0, 1].
double linear_quantile(const Eigen::Ref<const Eigen::VectorXd>& values, double q);

}  // namespace bsg::algos
