// Circle (docs/environments.md#circle, `CircleTask`): run clockwise along a circle of radius 7
// in the Octagon while staying inside the band |x| ≤ 6.
//
// Parameters (docs/environments.md#circle):
//   circle radius R     7 m
//   safe band           |x| ≤ 6 m (cost_outside_bounds)
//   reward              0.1·(y·v_x − x·v_y)/(1 + |‖p‖ − 7|) + 0.01·s_agent
//   task observation    (‖p‖ − 7)/env_dim, env_dim = 10
//   reset               ‖p‖ in [2, 4] (rejection in the square [−4, 4]²)
#pragma once

#include <array>
#include <memory>

#include "task.h"

namespace bsg::envs {

inline constexpr double kCircleRadius = 7.0;
inline constexpr double kCircleXLimit = 6.0;

// The first reward term, positive for clockwise motion (docs/environments.md#circle).
double circle_reward_core(double x, double y, double vx, double vy);

class CircleTask final : public Task {
 public:
  CircleTask(World& world, Agent& agent);

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
  std::array<CostTerm, 1> terms_{CostTerm{"cost_outside_bounds", 0}};
};

TaskBlueprint circle_task();

}  // namespace bsg::envs
