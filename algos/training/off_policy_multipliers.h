// When the Lagrange multipliers of an off-policy -lag run step, and on which cost
// (docs/algorithms.md#when-the-off-policy-multipliers-step). multiplier_schedule:
//   epoch         one step after the epoch on the pooled mean cost of the epoch's completed episodes
//                 (none without one): the on-policy loop's schedule, bsg's only one before;
//   update_round  one step before every round of gradient steps (every update_every environment
//                 steps of a rank once learning has begun) on the mean cost of the last
//                 multiplier_window completed episodes of each rank, pooled over the ranks (none
//                 while no episode has completed). The round's gradient steps use the new lambda.
//                 This is the schedule of the libraries whose defaults the -lag configurations
//                 take: OmniSafe steps its multiplier in every _update (after every update_cycle
//                 environment steps, on the mean of the last window_lens episode costs), FSRL in
//                 pre_update_fn before every round of updates (on the round's episodes).
// The window starts empty with the environments (the first epoch and after every checkpoint, when
// the family restarts them), so a run resumed from a checkpoint steps as the uninterrupted run did
// without the window in the checkpoint.
#pragma once

#include <cstddef>
#include <deque>
#include <span>
#include <vector>

#include "algos/core/algorithm.h"
#include "algos/lagrange/constraint_multipliers.h"
#include "common/mpi_context.h"
#include "common/run_config.h"

namespace bsg::algos {

class OffPolicyMultipliers {
 public:
  // The config's multipliers (one per constraint), schedule, window and limits.
  explicit OffPolicyMultipliers(const RunConfig& config);

  LagrangeMultipliers& multipliers() { return multipliers_; }
  const LagrangeMultipliers& multipliers() const { return multipliers_; }
  MultiplierSchedule schedule() const { return schedule_; }

  // The window empties (the environments restart).
  void restart();
  // Completed episodes into the window: constraint_costs[i][e] is episode e's cost of constraint i;
  // episodes first, first + 1, ... are new.
  void record(const std::vector<std::vector<double>>& constraint_costs, std::size_t first);

  // Before a round of gradient steps (`learning`: the round takes gradient steps). update_round: one
  // step on the window (collective over the ranks of `mpi`: every rank calls it in the same rounds).
  // Returns whether the multipliers stepped.
  bool before_gradient_round(bool learning, const MpiContext& mpi);
  // After the epoch, with its pooled constraint costs and its completed episodes over all ranks.
  // epoch: one step. Returns whether the multipliers stepped.
  bool after_epoch(std::span<const ConstraintEstimate> constraints, long long episode_count);

 private:
  LagrangeMultipliers multipliers_;
  MultiplierSchedule schedule_;
  std::size_t window_;
  std::vector<double> limits_;
  std::vector<std::deque<double>> recent_costs_;  // per constraint, the last window_ episodes
  std::vector<double> pooled_;                    // per constraint the window's sum, then its count
  std::vector<ConstraintEstimate> estimates_;
};

}  // namespace bsg::algos
