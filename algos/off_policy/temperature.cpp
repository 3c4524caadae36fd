#include "algos/off_policy/temperature.h"

#include <cmath>

#include "algos/core/adam_state.h"

namespace bsg::algos {

Temperature::Temperature(double alpha_init, double alpha_lr, double target_entropy)
    : target_entropy_(target_entropy),
      log_alpha_(Eigen::VectorXd::Constant(1, std::log(alpha_init))),
      adam_(1, AdamOptions{.learning_rate = alpha_lr}) {}

double Temperature::alpha() const { return std::exp(log_alpha_(0)); }

double Temperature::loss(double log_prob_mean, double* gradient) const {
  // L(log alpha) = -log alpha (E[log pi] + H_target)
  const double shortfall = log_prob_mean + target_entropy_;
  if (gradient != nullptr) *gradient = -shortfall;
  return -log_alpha_(0) * shortfall;
}

void Temperature::step(double log_prob_mean) {
  double gradient = 0.0;
  loss(log_prob_mean, &gradient);
  gradient_.setConstant(1, gradient);
  adam_.step(log_alpha_, gradient_);
}

void Temperature::save(BinaryWriter& writer) const {
  writer.write_f64(log_alpha_(0));
  save_adam_state(adam_, writer);
}

void Temperature::load(BinaryReader& reader) {
  const double log_alpha = reader.read_f64("log alpha");
  if (!std::isfinite(log_alpha)) reader.fail("log alpha is not finite");
  load_adam_state(adam_, reader, "alpha");
  log_alpha_(0) = log_alpha;
}

}  // namespace bsg::algos
