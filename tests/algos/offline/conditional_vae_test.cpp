// The conditional VAE of CPQ (algos/offline/conditional_vae.h): its loss (the negative ELBO with
// OSRL's weights) on a case with a closed form, where the encoder gives the same (mu, log sigma)
// and the decoder the same action for every input, its clamp of log sigma, its gradients against
// central differences of the loss, and torch.quantile's linear interpolation on hand-sorted values.
#include "algos/offline/conditional_vae.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bsg::algos {
namespace {

// Zero weights and these biases in the last layer: the network's output is `bias` for every input.
void make_constant(Mlp& network, const Eigen::VectorXd& bias) {
  const int last = network.num_layers() - 1;
  Eigen::VectorXd parameters = network.parameters();
  const Eigen::Index weights = network.bias_offset(last) - network.weight_offset(last);
  parameters.segment(network.weight_offset(last), weights).setZero();
  parameters.segment(network.bias_offset(last), bias.size()) = bias;
  network.set_parameters(parameters);
}

TEST(ConditionalVae, ElboOfConstantNetworksInClosedForm) {
  Rng init(3);
  ConditionalVae vae(2, 2, 5, 2, MlpOptions{}, init);
  // mu = (0.5, -1), log sigma = (0.2, -6): the second is clamped to -4.
  make_constant(vae.encoder(), Eigen::Vector4d(0.5, -1.0, 0.2, -6.0));
  make_constant(vae.decoder(), Eigen::Vector2d(0.3, -0.7));  // a_hat = tanh(0.3), tanh(-0.7) whatever z is
  Eigen::MatrixXd observations(3, 2), actions(3, 2), noise(3, 2);
  observations << 1, 2, -1, 0.5, 0, 3;
  actions << 0.1, -0.2, 0.9, 0.0, -0.5, -0.6;
  noise << 0.3, -1.2, 2.0, 0.1, -0.4, 0.8;
  const double beta = 0.5;
  // KL per latent dimension: -1/2 (1 + 2 log sigma - mu^2 - sigma^2).
  const double kl0 = -0.5 * (1.0 + 0.4 - 0.25 - std::exp(0.4));
  const double kl1 = -0.5 * (1.0 - 8.0 - 1.0 - std::exp(-8.0));
  double reconstruction = 0.0;
  for (int i = 0; i < 3; ++i) {
    reconstruction += std::pow(std::tanh(0.3) - actions(i, 0), 2) + std::pow(std::tanh(-0.7) - actions(i, 1), 2);
  }
  reconstruction /= 6.0;
  Eigen::VectorXd encoder_gradient(vae.encoder().num_parameters());
  Eigen::VectorXd decoder_gradient(vae.decoder().num_parameters());
  EXPECT_NEAR(vae.loss(observations, actions, noise, beta, encoder_gradient, decoder_gradient),
              reconstruction + beta * (kl0 + kl1) / 2.0, 1e-12);
  // Each row's latent KL alone: the mean over the two dimensions.
  Eigen::MatrixXd inputs(3, 4);
  inputs << observations, actions;
  Eigen::VectorXd kl(3);
  vae.latent_kl(inputs, kl);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(kl(i), (kl0 + kl1) / 2.0, 1e-12);
}

TEST(ConditionalVae, GradientsMatchCentralDifferences) {
  Rng init(7);
  ConditionalVae vae(3, 2, 6, 4, MlpOptions{}, init);  // tanh hidden layers: smooth everywhere
  Rng draws(11);
  Eigen::MatrixXd observations(5, 3), actions(5, 2), noise(5, 4);
  for (Eigen::Index k = 0; k < observations.size(); ++k) observations.data()[k] = uniform(draws, -1.0, 1.0);
  for (Eigen::Index k = 0; k < actions.size(); ++k) actions.data()[k] = uniform(draws, -0.9, 0.9);
  for (Eigen::Index k = 0; k < noise.size(); ++k) noise.data()[k] = standard_normal(draws);
  const double beta = 0.7;
  Eigen::VectorXd encoder_gradient(vae.encoder().num_parameters());
  Eigen::VectorXd decoder_gradient(vae.decoder().num_parameters());
  vae.loss(observations, actions, noise, beta, encoder_gradient, decoder_gradient);
  Eigen::VectorXd scratch_e(encoder_gradient.size()), scratch_d(decoder_gradient.size());
  const double h = 1e-6;
  for (Mlp* network : {&vae.encoder(), &vae.decoder()}) {
    const Eigen::VectorXd& analytic = network == &vae.encoder() ? encoder_gradient : decoder_gradient;
    const Eigen::VectorXd theta = network->parameters();
    for (Eigen::Index k = 0; k < theta.size(); ++k) {
      Eigen::VectorXd shifted = theta;
      shifted[k] += h;
      network->set_parameters(shifted);
      const double up = vae.loss(observations, actions, noise, beta, scratch_e, scratch_d);
      shifted[k] -= 2 * h;
      network->set_parameters(shifted);
      const double down = vae.loss(observations, actions, noise, beta, scratch_e, scratch_d);
      network->set_parameters(theta);
      EXPECT_NEAR(analytic[k], (up - down) / (2 * h), 1e-7) << k;
    }
  }
}

TEST(ConditionalVae, LinearQuantileAsTorch) {
  // Sorted 1, 2, 3, 4: position 0.75 * 3 = 2.25 lies a quarter of the way from 3 to 4.
  EXPECT_DOUBLE_EQ(linear_quantile(Eigen::Vector4d(4, 1, 3, 2), 0.75), 3.25);
  // Five values: position 3 exactly.
  Eigen::VectorXd five(5);
  five << 5, 3, 1, 4, 2;
  EXPECT_DOUBLE_EQ(linear_quantile(five, 0.75), 4.0);
  EXPECT_DOUBLE_EQ(linear_quantile(five, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(linear_quantile(five, 1.0), 5.0);
  EXPECT_THROW(linear_quantile(Eigen::VectorXd(0), 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
