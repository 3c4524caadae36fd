// Run (docs/environments.md#run, `RunTask`): run along +x on a 500-m plane towards a target
// 1000 m away, staying in the lane |y| ≤ 2 and under the agent's speed limit.
//
// Parameters (docs/environments.md#run; EnvDescription keys in brackets):
//   potential          Φ(p) = −60·‖p − (1000, 0)‖
//   reward             Φ(p) − Φ_prev + s_agent (unscaled agent term)
//   lane               |y| ≤ 2 m (run_y_limit; cost_outside_bounds)
//   speed limit        ‖v_xy‖ ≤ the agent's limit (run_speed_limit; cost_velocity_violation)
//   reset              p = (U(−0.01, 0.01), U(−0.01, 0.01)) (run_spawn_range),
//                      initial orientation kept
#pragma once

#include <array>

#include "envs/description/env_description.h"
#include "envs/tasks/task.h"

namespace bsg::envs {

inline constexpr double kRunYLimit = 2.0;

// Φ(p) = −60·‖p − (1000, 0)‖ with NumPy's norm (docs/environments.md#planar-distances).
double run_potential(double x, double y);

class RunTask final : public Task {
 public:
  RunTask(World& world, Agent& agent, const EnvDescription& description);

  int observation_dim() const override { return 0; }
  std::span<const CostTerm> cost_terms() const override { return terms_; }
  void sample_layout(Rng& rng, Layout& layout) override;
  void place(const Layout& layout, double clock_seconds) override;
  TaskOutcome evaluate(Rng& rng) override;
  void write_observation(std::span<double> /*out*/) const override {}
  void write_state(EnvState& state) const override;

  void add_markings(std::vector<Marking>& out) const override;

 private:
  Agent& agent_;
  const double y_limit_;
  const double speed_limit_;
  const double spawn_range_;
  const bool count_outside_bounds_;
  const bool count_velocity_violation_;
  double phi_prev_ = 0;
  std::array<CostTerm, 2> terms_{CostTerm{"cost_outside_bounds", 0},
                                 CostTerm{"cost_velocity_violation", 0}};
};

}  // namespace bsg::envs
