// An Env that forwards every call to another and tells an observer about
// resets and steps: how `bsg eval` and `bsg rollout` record videos and
// trajectories of episodes they run, without the loops that run them knowing.
#pragma once

#include <memory>

#include "envs/env.h"

namespace bsg::render {

class EnvObserver {
 public:
  virtual ~EnvObserver() = default;
  // The environment is about to reset (it still shows the last episode's end).
  virtual void before_reset(const envs::Env& /*env*/) {}
  virtual void after_reset(const envs::Env& /*env*/) {}
  virtual void after_step(const envs::Env& /*env*/, const envs::StepResult& /*result*/) {}
  // The observed environment is about to be destroyed (it still shows the last
  // episode's end). Must not throw.
  virtual void before_destroy(const envs::Env& /*env*/) noexcept {}
};

class ObservedEnv final : public envs::Env {
 public:
  // `observer` must outlive this environment.
  ObservedEnv(std::unique_ptr<envs::Env> env, EnvObserver& observer);
  ~ObservedEnv() override;
  ObservedEnv(const ObservedEnv&) = delete;
  ObservedEnv& operator=(const ObservedEnv&) = delete;

  const envs::Env& inner() const { return *env_; }

  const envs::EnvSpec& spec() const override { return env_->spec(); }
  std::span<const double> reset(std::uint64_t seed) override;
  std::span<const double> reset() override;
  std::span<const double> reset_to(const envs::Layout& layout) override;
  const envs::Layout& layout() const override { return env_->layout(); }
  envs::StepResult step(std::span<const double> action) override;
  envs::EnvState state() const override { return env_->state(); }
  void teleport_agent(const envs::Vec3& com_position) override { env_->teleport_agent(com_position); }

 private:
  std::unique_ptr<envs::Env> env_;
  EnvObserver& observer_;
};

}  // namespace bsg::render
