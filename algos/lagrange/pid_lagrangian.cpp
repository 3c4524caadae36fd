#include "algos/lagrange/pid_lagrangian.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

void check_gain(double value, const char* key) {
  if (!std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument(std::string("PidLagrangian: ") + key + " must be finite and >= 0, got " +
                                std::to_string(value));
  }
}

void check_ema(double value, const char* key) {
  if (!(value >= 0.0 && value < 1.0)) {
    throw std::invalid_argument(std::string("PidLagrangian: ") + key + " must be in [0, 1), got " +
                                std::to_string(value));
  }
}

}  // namespace

PidLagrangianOptions pid_lagrangian_options(const RunConfig& config) {
  PidLagrangianOptions options;
  options.proportional_gain = config.multiplier.pid_kp;
  options.integral_gain = config.multiplier.pid_ki;
  options.derivative_gain = config.multiplier.pid_kd;
  options.derivative_delay = config.multiplier.pid_d_delay;
  options.proportional_ema = config.multiplier.pid_delta_p_ema_alpha;
  options.derivative_ema = config.multiplier.pid_delta_d_ema_alpha;
  options.lambda_max = config.multiplier.pid_lambda_max;
  return options;
}

PidLagrangian::PidLagrangian(double initial_integral, const PidLagrangianOptions& options)
    : options_(options), integral_(initial_integral) {
  check_gain(options.proportional_gain, "pid_kp");
  check_gain(options.integral_gain, "pid_ki");
  check_gain(options.derivative_gain, "pid_kd");
  check_gain(options.lambda_max, "pid_lambda_max");
  check_ema(options.proportional_ema, "pid_delta_p_ema_alpha");
  check_ema(options.derivative_ema, "pid_delta_d_ema_alpha");
  if (options.derivative_delay < 1) {
    throw std::invalid_argument("PidLagrangian: pid_d_delay must be >= 1, got " +
                                std::to_string(options.derivative_delay));
  }
  if (!std::isfinite(initial_integral) || initial_integral < 0.0) {
    throw std::invalid_argument("PidLagrangian: the initial integral (lagrangian_multiplier_init) must be finite "
                                "and >= 0, got " + std::to_string(initial_integral));
  }
  cost_history_.assign(static_cast<std::size_t>(options.derivative_delay), 0.0);
  terms_.integral = integral_;
  terms_.lambda = integral_;
}

PidTerms PidLagrangian::update(double mean_episode_cost, double cost_limit) {
  if (!std::isfinite(mean_episode_cost)) {
    throw std::invalid_argument("PidLagrangian::update: mean_episode_cost (J_C) is not finite: " +
                                std::to_string(mean_episode_cost));
  }
  const double delta = mean_episode_cost - cost_limit;                         // Delta = J_C - d
  integral_ = std::max(0.0, integral_ + options_.integral_gain * delta);       // I <- max(0, I + K_I Delta)
  const double a_p = options_.proportional_ema;
  delta_p_ema_ = a_p * delta_p_ema_ + (1.0 - a_p) * delta;                     // Delta_ema
  const double a_d = options_.derivative_ema;
  cost_d_ema_ = a_d * cost_d_ema_ + (1.0 - a_d) * mean_episode_cost;           // J_ema
  const double delayed_cost = cost_history_[history_start_];                   // J_ema[k - delay]

  PidTerms terms;
  terms.proportional = options_.proportional_gain * delta_p_ema_;              // K_P Delta_ema
  terms.integral = integral_;
  terms.derivative = options_.derivative_gain * std::max(0.0, cost_d_ema_ - delayed_cost);
  terms.lambda = std::max(0.0, terms.proportional + terms.integral + terms.derivative);
  if (options_.lambda_max > 0.0) terms.lambda = std::min(terms.lambda, options_.lambda_max);

  // J_ema[k] replaces the oldest entry, which becomes J_ema[k - delay] `delay` epochs from now.
  cost_history_[history_start_] = cost_d_ema_;
  history_start_ = (history_start_ + 1) % cost_history_.size();
  terms_ = terms;
  return terms;
}

std::vector<NamedScalar> PidLagrangian::state() const {
  std::vector<NamedScalar> saved = {
      {"pid_integral", integral_}, {"pid_delta_p_ema", delta_p_ema_}, {"pid_cost_d_ema", cost_d_ema_}};
  for (std::size_t i = 0; i < cost_history_.size(); ++i) {
    saved.push_back({"pid_cost_d_history_" + std::to_string(i),
                     cost_history_[(history_start_ + i) % cost_history_.size()]});
  }
  return saved;
}

void PidLagrangian::restore_state(std::span<const NamedScalar> saved) {
  const std::vector<NamedScalar> expected = state();
  if (saved.size() != expected.size()) {
    throw std::invalid_argument("PidLagrangian::restore_state: expected " + std::to_string(expected.size()) +
                                " values (pid_d_delay = " + std::to_string(options_.derivative_delay) + "), got " +
                                std::to_string(saved.size()));
  }
  for (std::size_t i = 0; i < saved.size(); ++i) {
    if (saved[i].name != expected[i].name) {
      throw std::invalid_argument("PidLagrangian::restore_state: entry " + std::to_string(i) + " is '" +
                                  saved[i].name + "', expected '" + expected[i].name + "'");
    }
    if (!std::isfinite(saved[i].value)) {
      throw std::invalid_argument("PidLagrangian::restore_state: " + saved[i].name + " is not finite");
    }
  }
  if (saved[0].value < 0.0) {
    throw std::invalid_argument("PidLagrangian::restore_state: pid_integral must be >= 0, got " +
                                std::to_string(saved[0].value));
  }
  integral_ = saved[0].value;
  delta_p_ema_ = saved[1].value;
  cost_d_ema_ = saved[2].value;
  for (std::size_t i = 0; i < cost_history_.size(); ++i) cost_history_[i] = saved[3 + i].value;
  history_start_ = 0;
  terms_ = PidTerms{};
  terms_.integral = integral_;
}

}  // namespace bsg::algos
