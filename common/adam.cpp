#include "common/adam.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg {

Adam::Adam(Eigen::Index num_parameters, AdamOptions options)
    : options_(options),
      first_moment_(Eigen::VectorXd::Zero(num_parameters)),
      second_moment_(Eigen::VectorXd::Zero(num_parameters)) {
  if (num_parameters <= 0) {
    throw std::invalid_argument("Adam: num_parameters must be positive, got " +
                                std::to_string(num_parameters));
  }
  if (!(options.learning_rate > 0.0)) {
    throw std::invalid_argument("Adam: learning_rate must be positive, got " +
                                std::to_string(options.learning_rate));
  }
  if (!(options.beta1 >= 0.0 && options.beta1 < 1.0) || !(options.beta2 >= 0.0 && options.beta2 < 1.0)) {
    throw std::invalid_argument("Adam: beta1 and beta2 must lie in [0, 1), got " +
                                std::to_string(options.beta1) + " and " + std::to_string(options.beta2));
  }
}

void Adam::step(Eigen::Ref<Eigen::VectorXd> parameters,
                const Eigen::Ref<const Eigen::VectorXd>& gradient) {
  if (parameters.size() != num_parameters() || gradient.size() != num_parameters()) {
    throw std::invalid_argument("Adam::step: parameters has " + std::to_string(parameters.size()) +
                                " and gradient " + std::to_string(gradient.size()) +
                                " entries, the optimiser was built for " +
                                std::to_string(num_parameters()));
  }
  ++step_count_;
  const double beta1 = options_.beta1;
  const double beta2 = options_.beta2;
  first_moment_ = beta1 * first_moment_ + (1.0 - beta1) * gradient;                    // m = b1 m + (1-b1) g
  second_moment_ = beta2 * second_moment_ + (1.0 - beta2) * gradient.cwiseAbs2();      // v = b2 v + (1-b2) g^2
  const double bias_correction1 = 1.0 - std::pow(beta1, static_cast<double>(step_count_));
  const double bias_correction2 = 1.0 - std::pow(beta2, static_cast<double>(step_count_));
  const double step_size = options_.learning_rate / bias_correction1;
  // PyTorch: p -= lr/(1-b1^t) * m / (sqrt(v)/sqrt(1-b2^t) + eps)
  parameters.array() -= step_size * first_moment_.array() /
                        (second_moment_.array().sqrt() / std::sqrt(bias_correction2) + options_.epsilon);
}

void Adam::set_state(const Eigen::Ref<const Eigen::VectorXd>& first_moment,
                     const Eigen::Ref<const Eigen::VectorXd>& second_moment, long long step_count) {
  if (first_moment.size() != num_parameters() || second_moment.size() != num_parameters()) {
    throw std::invalid_argument("Adam::set_state: first_moment has " +
                                std::to_string(first_moment.size()) + " and second_moment " +
                                std::to_string(second_moment.size()) + " entries, expected " +
                                std::to_string(num_parameters()));
  }
  if (step_count < 0) {
    throw std::invalid_argument("Adam::set_state: step_count must be >= 0, got " +
                                std::to_string(step_count));
  }
  first_moment_ = first_moment;
  second_moment_ = second_moment;
  step_count_ = step_count;
}

}  // namespace bsg
