#include "algos/offline/conditional_vae.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace bsg::algos {

ConditionalVae::ConditionalVae(int observation_size, int action_size, int hidden_size, int latent_size,
                               MlpOptions options, Rng& init_rng)
    : observation_size_(observation_size),
      action_size_(action_size),
      latent_size_(latent_size),
      encoder_({observation_size + action_size, hidden_size, hidden_size, 2 * latent_size}, init_rng, options),
      decoder_({observation_size + latent_size, hidden_size, hidden_size, action_size}, init_rng, options) {}

double ConditionalVae::loss(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                            const Eigen::Ref<const Eigen::MatrixXd>& actions,
                            const Eigen::Ref<const Eigen::MatrixXd>& noise, double beta,
                            Eigen::Ref<Eigen::VectorXd> encoder_gradient, Eigen::Ref<Eigen::VectorXd> decoder_gradient) {
  const Eigen::Index n = observations.rows();
  const int s = observation_size_;
  const int l = latent_size_;
  if (actions.rows() != n || noise.rows() != n || observations.cols() != s || actions.cols() != action_size_ ||
      noise.cols() != l || n < 1) {
    throw std::invalid_argument("conditional VAE: a batch of " + std::to_string(n) + " rows does not fit its sizes");
  }
  encoder_inputs_.resize(n, s + action_size_);
  encoder_inputs_ << observations, actions;
  encoder_outputs_ = encoder_.forward_batch(encoder_inputs_, encoder_workspace_);
  // z = mu + sigma eps with the clamped log sigma; the KL term of each entry.
  decoder_inputs_.resize(n, s + l);
  decoder_inputs_.leftCols(s) = observations;
  const double kl_scale = 1.0 / static_cast<double>(n * l);
  double kl_sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int j = 0; j < l; ++j) {
      const double mu = encoder_outputs_(i, j);
      const double log_std = std::clamp(encoder_outputs_(i, l + j), kVaeLogStdMin, kVaeLogStdMax);
      const double sigma = std::exp(log_std);
      decoder_inputs_(i, s + j) = mu + sigma * noise(i, j);
      kl_sum += -0.5 * (1.0 + 2.0 * log_std - mu * mu - sigma * sigma);
    }
  }
  const Eigen::MatrixXd& pre_tanh = decoder_.forward_batch(decoder_inputs_, decoder_workspace_);
  const double reconstruction_scale = 1.0 / static_cast<double>(n * action_size_);
  double reconstruction_sum = 0.0;
  decoder_gradient_.resize(n, action_size_);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int j = 0; j < action_size_; ++j) {
      const double a_hat = std::tanh(pre_tanh(i, j));
      const double error = a_hat - actions(i, j);
      reconstruction_sum += error * error;
      decoder_gradient_(i, j) = 2.0 * error * reconstruction_scale * (1.0 - a_hat * a_hat);  // dL/d pre-tanh
    }
  }
  decoder_.backward_batch(decoder_gradient_, decoder_workspace_, decoder_gradient);
  decoder_input_gradient_.resize(n, s + l);
  decoder_.input_gradient_batch(decoder_gradient_, decoder_workspace_, decoder_input_gradient_);
  // Through z = mu + sigma eps and the KL term: dL/dmu = dL/dz + beta mu / (N L),
  // dL/dlog sigma = dL/dz sigma eps + beta (sigma^2 - 1) / (N L); none through a clamped log sigma.
  encoder_gradient_.resize(n, 2 * l);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int j = 0; j < l; ++j) {
      const double mu = encoder_outputs_(i, j);
      const double raw_log_std = encoder_outputs_(i, l + j);
      const double sigma = std::exp(std::clamp(raw_log_std, kVaeLogStdMin, kVaeLogStdMax));
      const double dz = decoder_input_gradient_(i, s + j);
      encoder_gradient_(i, j) = dz + beta * mu * kl_scale;
      const bool clamped = raw_log_std < kVaeLogStdMin || raw_log_std > kVaeLogStdMax;
      encoder_gradient_(i, l + j) =
          clamped ? 0.0 : dz * sigma * noise(i, j) + beta * (sigma * sigma - 1.0) * kl_scale;
    }
  }
  encoder_.backward_batch(encoder_gradient_, encoder_workspace_, encoder_gradient);
  return reconstruction_sum * reconstruction_scale + beta * kl_sum * kl_scale;
}

void ConditionalVae::latent_kl(const Eigen::Ref<const Eigen::MatrixXd>& inputs, Eigen::Ref<Eigen::VectorXd> kl) {
  const int l = latent_size_;
  encoder_outputs_.resize(inputs.rows(), 2 * l);
  encoder_.evaluate_batch(inputs, encoder_outputs_, encoder_workspace_);
  for (Eigen::Index i = 0; i < inputs.rows(); ++i) {
    double sum = 0.0;
    for (int j = 0; j < l; ++j) {
      const double mu = encoder_outputs_(i, j);
      const double log_std = std::clamp(encoder_outputs_(i, l + j), kVaeLogStdMin, kVaeLogStdMax);
      sum += -0.5 * (1.0 + 2.0 * log_std - mu * mu - std::exp(2.0 * log_std));
    }
    kl(i) = sum / l;
  }
}

void ConditionalVae::decode(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                            const Eigen::Ref<const Eigen::MatrixXd>& latents, Eigen::Ref<Eigen::MatrixXd> actions) {
  const Eigen::Index n = observations.rows();
  if (latents.rows() != n || actions.rows() != n || observations.cols() != observation_size_ ||
      latents.cols() != latent_size_ || actions.cols() != action_size_) {
    throw std::invalid_argument("conditional VAE: " + std::to_string(n) + " rows to decode do not fit its sizes");
  }
  decoder_inputs_.resize(n, observation_size_ + latent_size_);
  decoder_inputs_ << observations, latents;
  decoder_.evaluate_batch(decoder_inputs_, actions, decoder_workspace_);
  actions = actions.array().tanh().matrix();
}

void ConditionalVae::save(BinaryWriter& writer) const {
  writer.write_vector(encoder_.parameters());
  writer.write_vector(decoder_.parameters());
}

void ConditionalVae::load(BinaryReader& reader) {
  const Eigen::VectorXd encoder = reader.read_vector("VAE encoder parameters", encoder_.num_parameters());
  const Eigen::VectorXd decoder = reader.read_vector("VAE decoder parameters", decoder_.num_parameters());
  encoder_.set_parameters(encoder);
  decoder_.set_parameters(decoder);
}

double linear_quantile(const Eigen::Ref<const Eigen::VectorXd>& values, double q) {
  if (values.size() < 1 || !(q >= 0.0 && q <= 1.0)) {
    throw std::invalid_argument("linear_quantile: needs values and q in [0, 1]");
  }
  std::vector<double> sorted(values.data(), values.data() + values.size());
  std::sort(sorted.begin(), sorted.end());
  const double position = q * static_cast<double>(sorted.size() - 1);
  const auto lower = static_cast<std::size_t>(std::floor(position));
  const std::size_t upper = std::min(lower + 1, sorted.size() - 1);
  const double fraction = position - static_cast<double>(lower);
  return sorted[lower] + fraction * (sorted[upper] - sorted[lower]);
}

}  // namespace bsg::algos
