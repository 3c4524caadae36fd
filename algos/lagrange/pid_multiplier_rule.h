// The PID multiplier rule: PidLagrangian (pid_lagrangian.h) behind the MultiplierRule
// interface. lambda is the PID's own max(0, P + I + D) (at most pid_lambda_max); its terms are
// the columns PID/P, PID/I, PID/D and its integral, EMAs and delay queue the checkpoint entries.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "algos/lagrange/multiplier_rule.h"
#include "algos/lagrange/pid_lagrangian.h"

namespace bsg::algos {

class PidMultiplierRule final : public MultiplierRule {
 public:
  PidMultiplierRule(double initial_integral, const PidLagrangianOptions& options) : pid_(initial_integral, options) {}

  std::unique_ptr<MultiplierRule> clone() const override { return std::make_unique<PidMultiplierRule>(*this); }
  double step(double lambda, double mean_episode_cost, double cost_limit) override;
  std::vector<NamedScalar> diagnostics() const override;
  std::vector<NamedScalar> state() const override { return pid_.state(); }
  void restore_state(std::span<const NamedScalar> saved) override { pid_.restore_state(saved); }

 private:
  PidLagrangian pid_;
};

}  // namespace bsg::algos
