#include "algos/first_order/first_order_algorithm.h"

#include <stdexcept>
#include <utility>

namespace bsg::algos {

FirstOrderAlgorithm::FirstOrderAlgorithm(const RunConfig& config, bool constrained,
                                         std::vector<std::string> own_columns)
    : OnPolicyAlgorithm(config),
      constrained_(constrained),
      own_columns_(std::move(own_columns)),
      multipliers_(config),
      adam_(config.first_order.actor_lr) {}

std::vector<std::string> FirstOrderAlgorithm::diagnostic_names() const {
  std::vector<std::string> names = common_diagnostic_names();
  for (std::string& name : first_order_diagnostic_names()) names.push_back(std::move(name));
  names.insert(names.end(), own_columns_.begin(), own_columns_.end());
  if (constrained_) {
    multipliers_.append_diagnostic_names(names);
  }
  return names;
}

std::vector<NamedScalar> FirstOrderAlgorithm::state() const {
  std::vector<NamedScalar> state = constrained_ ? multipliers_.state() : std::vector<NamedScalar>{};
  for (NamedScalar& entry : adam_.state()) state.push_back(std::move(entry));
  return state;
}

void FirstOrderAlgorithm::restore_state(std::span<const NamedScalar> saved) {
  const std::size_t adam_entries = PolicyAdam::saved_size(saved);
  const std::span<const NamedScalar> multiplier_state = saved.first(saved.size() - adam_entries);
  if (constrained_) {
    multipliers_.restore_state(multiplier_state);
  } else if (!multiplier_state.empty()) {
    throw std::invalid_argument(std::string(name()) + ": unexpected state entry '" + multiplier_state.front().name +
                                "'");
  }
  adam_.restore_state(saved.last(adam_entries));
}

std::vector<double> FirstOrderAlgorithm::update_multipliers(const PolicyUpdateInputs& inputs) {
  return multipliers_.update(inputs, config(), name());
}

FirstOrderAlgorithm::PassesFromStart FirstOrderAlgorithm::passes_from_start(const PolicyUpdateInputs& inputs,
                                                                            const SampleLossFunction& sample_loss,
                                                                            const MinibatchStepHook& before_step) {
  PassesFromStart result{begin_policy_update(inputs), {}};
  SampleLossBatch batch(inputs.surrogate, inputs.surrogate.reference_means(), inputs.policy.log_stds());  // KL_i to theta_old
  result.passes = minibatch_passes(inputs, first_order_options(config()), adam_, batch, sample_loss, before_step);
  return result;
}

PolicyUpdateResult FirstOrderAlgorithm::make_result(std::vector<NamedScalar> common,
                                                    const MinibatchPassesResult& passes,
                                                    std::vector<NamedScalar> own) const {
  PolicyUpdateResult result;
  result.diagnostics = std::move(common);
  append_first_order_diagnostics(result.diagnostics, passes);
  for (NamedScalar& entry : own) result.diagnostics.push_back(std::move(entry));
  if (constrained_) {
    multipliers_.append_to(result);
  }
  return result;
}

}  // namespace bsg::algos
