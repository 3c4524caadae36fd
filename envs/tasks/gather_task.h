// Gather (docs/environments.md#gather, `GatherTask`): collect 8 apples (+10 each) and avoid 8
// bombs (cost) in the SmallRoom, seeing both through two pseudo-LIDARs.
//
// Parameters (docs/environments.md#gather; EnvDescription keys in brackets):
//   apples, bombs       8 and 8 (apples, bombs), placed with agent clearance 1.0
//                       (gather_agent_clearance), pairwise 2.0 (gather_spacing) in
//                       the square [−7, 7]² (placement_half_width)
//   detection distance  1.0 m in the plane (gather_detection_distance)
//   apple reward        +10 (apple_reward); death reward −10 (death_reward,
//                       replaces the step's reward)
//   sensors             pseudo-LIDAR 16 bins (gather_sensor_bins), range env_dim = 10
//                       (gather_sensor_range): apples, then bombs
//   out of range        agent z > 2 (max_altitude; cost_out_of_range)
//   ends the episode    when every apple is collected
#pragma once

#include <array>
#include <vector>

#include "envs/tasks/collectibles.h"
#include "envs/description/env_description.h"
#include "envs/sensors/pseudo_lidar_sensor.h"
#include "envs/tasks/task.h"

namespace bsg::envs {

class GatherTask final : public Task {
 public:
  GatherTask(World& world, Agent& agent, const EnvDescription& description);

  int observation_dim() const override { return 2 * sensor_.bins(); }
  std::span<const CostTerm> cost_terms() const override { return terms_; }
  void sample_layout(Rng& rng, Layout& layout) override;
  void place(const Layout& layout, double clock_seconds) override;
  TaskOutcome evaluate(Rng& rng) override;
  void write_observation(std::span<double> out) const override;
  void write_state(EnvState& state) const override;

  void add_markings(std::vector<Marking>& out) const override;

 private:
  Agent& agent_;
  const EnvDescription description_;
  PseudoLidarSensor sensor_;
  Collectibles apples_;
  Collectibles bombs_;
  std::vector<btVector3> placement_;  // reused by place()
  std::array<CostTerm, 2> terms_{CostTerm{"cost_gathered_bombs", 0},
                                 CostTerm{"cost_out_of_range", 0}};
};

}  // namespace bsg::envs
