#include "render/observed_multi_agent_env.h"

namespace bsg::render {

ObservedMultiAgentEnv::ObservedMultiAgentEnv(std::unique_ptr<envs::MultiAgentEnv> env, MultiAgentEnvObserver& observer)
    : env_(std::move(env)), observer_(observer) {}

ObservedMultiAgentEnv::~ObservedMultiAgentEnv() { observer_.before_destroy(*env_); }

std::span<const std::span<const double>> ObservedMultiAgentEnv::reset(std::uint64_t seed) {
  observer_.before_reset(*env_);
  const std::span<const std::span<const double>> observations = env_->reset(seed);
  observer_.after_reset(*env_);
  return observations;
}

std::span<const std::span<const double>> ObservedMultiAgentEnv::reset() {
  observer_.before_reset(*env_);
  const std::span<const std::span<const double>> observations = env_->reset();
  observer_.after_reset(*env_);
  return observations;
}

std::span<const std::span<const double>> ObservedMultiAgentEnv::reset_to(std::span<const envs::Layout> layouts) {
  observer_.before_reset(*env_);
  const std::span<const std::span<const double>> observations = env_->reset_to(layouts);
  observer_.after_reset(*env_);
  return observations;
}

envs::MultiAgentStepResult ObservedMultiAgentEnv::step(std::span<const std::span<const double>> actions) {
  const envs::MultiAgentStepResult result = env_->step(actions);
  observer_.after_step(*env_, result);
  return result;
}

}  // namespace bsg::render
