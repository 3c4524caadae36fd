// A MultiAgentEnv that forwards every call to another and tells an observer about resets and
// steps: observed_env.h's ObservedEnv for the multi-agent environments, so that `bsg eval` records
// a multi-agent run's episodes (episode_recorders.h) without its evaluation loop knowing.
#pragma once

#include <memory>
#include <vector>

#include "envs/multi_agent_env.h"

namespace bsg::render {

class MultiAgentEnvObserver {
 public:
  virtual ~MultiAgentEnvObserver() = default;
  // The environment is about to reset (it still shows the last episode's end).
  virtual void before_reset(const envs::MultiAgentEnv& /*env*/) {}
  virtual void after_reset(const envs::MultiAgentEnv& /*env*/) {}
  virtual void after_step(const envs::MultiAgentEnv& /*env*/, const envs::MultiAgentStepResult& /*result*/) {}
  // The observed environment is about to be destroyed (it still shows the last episode's end).
  // Must not throw.
  virtual void before_destroy(const envs::MultiAgentEnv& /*env*/) noexcept {}
};

class ObservedMultiAgentEnv final : public envs::MultiAgentEnv {
 public:
  // `observer` must outlive this environment.
  ObservedMultiAgentEnv(std::unique_ptr<envs::MultiAgentEnv> env, MultiAgentEnvObserver& observer);
  ~ObservedMultiAgentEnv() override;
  ObservedMultiAgentEnv(const ObservedMultiAgentEnv&) = delete;
  ObservedMultiAgentEnv& operator=(const ObservedMultiAgentEnv&) = delete;

  const envs::MultiAgentSpec& spec() const override { return env_->spec(); }
  std::span<const std::span<const double>> reset(std::uint64_t seed) override;
  std::span<const std::span<const double>> reset() override;
  std::span<const std::span<const double>> reset_to(std::span<const envs::Layout> layouts) override;
  envs::MultiAgentStepResult step(std::span<const std::span<const double>> actions) override;
  std::span<const double> global_state() const override { return env_->global_state(); }
  std::vector<envs::EnvState> body_states() const override { return env_->body_states(); }

 private:
  std::unique_ptr<envs::MultiAgentEnv> env_;
  MultiAgentEnvObserver& observer_;
};

}  // namespace bsg::render
