#include "render/observed_env.h"

namespace bsg::render {

ObservedEnv::ObservedEnv(std::unique_ptr<envs::Env> env, EnvObserver& observer)
    : env_(std::move(env)), observer_(observer) {}

ObservedEnv::~ObservedEnv() { observer_.before_destroy(*env_); }

std::span<const double> ObservedEnv::reset(std::uint64_t seed) {
  observer_.before_reset(*env_);
  const std::span<const double> observation = env_->reset(seed);
  observer_.after_reset(*env_);
  return observation;
}

std::span<const double> ObservedEnv::reset() {
  observer_.before_reset(*env_);
  const std::span<const double> observation = env_->reset();
  observer_.after_reset(*env_);
  return observation;
}

std::span<const double> ObservedEnv::reset_to(const envs::Layout& layout) {
  observer_.before_reset(*env_);
  const std::span<const double> observation = env_->reset_to(layout);
  observer_.after_reset(*env_);
  return observation;
}

envs::StepResult ObservedEnv::step(std::span<const double> action) {
  const envs::StepResult result = env_->step(action);
  observer_.after_step(*env_, result);
  return result;
}

}  // namespace bsg::render
