// An environment that wraps another and forwards every call to it: the base of the
// training-time decorators (design.md "Families and the run skeleton": Saute's budget in the
// observation, early termination), which override only what they change.
#pragma once

#include <memory>
#include <span>
#include <stdexcept>
#include <utility>

#include "envs/env.h"

namespace bsg::envs {

class DecoratedEnv : public Env {
 public:
  explicit DecoratedEnv(std::unique_ptr<Env> inner) : inner_(std::move(inner)) {
    if (inner_ == nullptr) throw std::invalid_argument("DecoratedEnv: no environment to decorate");
  }

  const EnvSpec& spec() const override { return inner_->spec(); }
  std::span<const double> reset(std::uint64_t seed) override { return inner_->reset(seed); }
  std::span<const double> reset() override { return inner_->reset(); }
  std::span<const double> reset_to(const Layout& layout) override { return inner_->reset_to(layout); }
  const Layout& layout() const override { return inner_->layout(); }
  StepResult step(std::span<const double> action) override { return inner_->step(action); }
  EnvState state() const override { return inner_->state(); }
  void teleport_agent(const Vec3& com_position) override { inner_->teleport_agent(com_position); }

 protected:
  Env& inner() { return *inner_; }
  const Env& inner() const { return *inner_; }

 private:
  std::unique_ptr<Env> inner_;
};

}  // namespace bsg::envs
