// Safety during training (docs/algorithms.md#safety-during-training): the cost the agent
// incurred while learning, as Safety Gym scores it, kept across epochs and resumes.
//   cumulative cost   the environment's cost summed over every training step
//                     of every rank (complete episodes or not)
//   cost rate         cumulative cost / environment steps taken (Safety Gym's
//                     definition: all training cost over all training steps)
//   per constraint i  its own cumulative cost and rate, and the epochs over
//                     its limit: epochs whose pooled mean episode cost J_Ci exceeded d_i
//                     (an epoch without a completed episode counts as not over)
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "algos/core/algorithm.h"
#include "common/binary_io.h"

namespace bsg::algos {

struct TrainingCost {
  double cumulative_cost = 0.0;
  std::vector<double> constraint_cumulative_costs{};  // one per constraint
  std::vector<long long> epochs_over_limit{};       // one per constraint

  // Zeroes for m constraints.
  static TrainingCost for_constraints(int constraint_count);

  // Adds one epoch: its total cost over all ranks, each constraint's total,
  // and the constraints' J_Ci and d_i (to count the epochs over the limit).
  void add_epoch(double epoch_cost, const Eigen::Ref<const Eigen::VectorXd>& epoch_constraint_costs,
                 std::span<const ConstraintEstimate> constraints);

  // cumulative / steps (NaN before the first step).
  static double rate(double cumulative, long long steps);

  bool operator==(const TrainingCost&) const = default;
};

void save_training_cost(const TrainingCost& cost, BinaryWriter& writer);
// Reads what save_training_cost wrote for `constraint_count` constraints (a
// record without per-constraint entries reads back as saved, without them);
// fails on the reader otherwise.
TrainingCost load_training_cost(BinaryReader& reader, int constraint_count);

}  // namespace bsg::algos
