// Gather (docs/environments.md#gather, `GatherTask`): collect 8 apples (+10 each) and avoid 8
// bombs (cost) in the SmallRoom, seeing both through two pseudo-LIDARs.
//
// Parameters (docs/environments.md#gather):
//   apples, bombs       8 and 8, placed with agent clearance 1.0, pairwise 2.0
//   detection distance  1.0 m in the plane
//   apple reward        +10; death reward −10 (replaces the step's reward)
//   sensors             pseudo-LIDAR 16 bins, range env_dim = 10: apples, then bombs
//   out of range        agent z > 2 (cost_out_of_range)
//   ends the episode    when every apple is collected
#pragma once

#include <array>

#include "collectibles.h"
#include "pseudo_lidar_sensor.h"
#include "task.h"

namespace bsg::envs {

class GatherTask final : public Task {
 public:
  static constexpr int kApples = 8;
  static constexpr int kBombs = 8;
  static constexpr double kAppleReward = 10;
  static constexpr double kDeathReward = -10;
  static constexpr double kAgentClearance = 1.0;
  static constexpr double kPairwiseClearance = 2.0;
  static constexpr double kMaxAltitude = 2.0;

  GatherTask(World& world, Agent& agent);

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
  PseudoLidarSensor sensor_;
  Collectibles apples_{kApples};
  Collectibles bombs_{kBombs};
  std::array<CostTerm, 2> terms_{CostTerm{"cost_gathered_bombs", 0},
                                 CostTerm{"cost_out_of_range", 0}};
};

TaskBlueprint gather_task();

}  // namespace bsg::envs
