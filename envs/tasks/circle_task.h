// Circle (docs/environments.md#circle, `CircleTask`): run clockwise along a circle of radius 7
// in the Octagon while staying inside the band |x| ≤ 6.
//
// Parameters (docs/environments.md#circle; EnvDescription keys in brackets):
//   circle radius R     7 m (circle_radius)
//   safe band           |x| ≤ 6 m (circle_x_limit; cost_outside_bounds)
//   reward              0.1·(y·v_x − x·v_y)/(1 + |‖p‖ − R|) + 0.01·s_agent
//   task observation    (‖p‖ − R)/env_dim, env_dim = 10
//   reset               ‖p‖ in [2, 4] (circle_spawn_min_radius, circle_spawn_max_radius;
//                       rejection in the square [−4, 4]²)
#pragma once

#include <array>
#include <memory>

#include "envs/description/env_description.h"
#include "envs/tasks/task.h"

namespace bsg::envs {

inline constexpr double kCircleRadius = 7.0;
inline constexpr double kCircleXLimit = 6.0;

// The first reward term, positive for clockwise motion (docs/environments.md#circle).
double circle_reward_core(double x, double y, double vx, double vy,
                          double circle_radius = kCircleRadius);

class CircleTask final : public Task {
 public:
  CircleTask(World& world, Agent& agent, const EnvDescription& description);

  int observation_dim() const override { return 1; }
  std::span<const CostTerm> cost_terms() const override { return terms_; }
  void sample_layout(Rng& rng, Layout& layout) override;
  void place(const Layout& layout, double clock_seconds) override;
  TaskOutcome evaluate(Rng& rng) override;
  void write_observation(std::span<double> out) const override;

  void add_markings(std::vector<Marking>& out) const override;

 private:
  World& world_;
  Agent& agent_;
  const double radius_;
  const double x_limit_;
  const double spawn_min_radius_;
  const double spawn_max_radius_;
  const bool count_outside_bounds_;
  std::array<CostTerm, 1> terms_{CostTerm{"cost_outside_bounds", 0}};
};

}  // namespace bsg::envs
