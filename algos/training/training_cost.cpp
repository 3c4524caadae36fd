#include "algos/training/training_cost.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

TrainingCost TrainingCost::for_constraints(int constraint_count) {
  TrainingCost cost;
  cost.constraint_cumulative_costs.assign(static_cast<std::size_t>(constraint_count), 0.0);
  cost.epochs_over_limit.assign(static_cast<std::size_t>(constraint_count), 0);
  return cost;
}

void TrainingCost::add_epoch(double epoch_cost, const Eigen::Ref<const Eigen::VectorXd>& epoch_constraint_costs,
                             std::span<const ConstraintEstimate> constraints) {
  const std::size_t m = constraint_cumulative_costs.size();
  if (static_cast<std::size_t>(epoch_constraint_costs.size()) != m || constraints.size() != m) {
    throw std::invalid_argument("TrainingCost::add_epoch: " + std::to_string(epoch_constraint_costs.size()) +
                                " constraint costs and " + std::to_string(constraints.size()) + " constraints for " +
                                std::to_string(m));
  }
  cumulative_cost += epoch_cost;
  for (std::size_t i = 0; i < m; ++i) {
    constraint_cumulative_costs[i] += epoch_constraint_costs[static_cast<Eigen::Index>(i)];
    if (constraints[i].mean_episode_cost > constraints[i].limit) ++epochs_over_limit[i];  // NaN: not over
  }
}

double TrainingCost::rate(double cumulative, long long steps) {
  return steps > 0 ? cumulative / static_cast<double>(steps) : std::nan("");
}

void save_training_cost(const TrainingCost& cost, BinaryWriter& writer) {
  writer.write_section("training cost");
  writer.write_f64(cost.cumulative_cost);
  writer.write_u64(cost.constraint_cumulative_costs.size());
  for (std::size_t i = 0; i < cost.constraint_cumulative_costs.size(); ++i) {
    writer.write_f64(cost.constraint_cumulative_costs[i]);
    writer.write_i64(cost.epochs_over_limit[i]);
  }
}

TrainingCost load_training_cost(BinaryReader& reader, int constraint_count) {
  reader.expect_section("training cost");
  TrainingCost cost;
  cost.cumulative_cost = reader.read_f64("cumulative training cost");
  if (!std::isfinite(cost.cumulative_cost)) reader.fail("the cumulative training cost is not finite");
  const std::uint64_t count = reader.read_u64("training cost constraint count");
  if (count == 0) return cost;  // none recorded: as saved (the trainer starts them at 0)
  const double cumulative = cost.cumulative_cost;
  cost = TrainingCost::for_constraints(constraint_count);
  cost.cumulative_cost = cumulative;
  if (count != static_cast<std::uint64_t>(constraint_count)) {
    reader.fail("training cost for " + std::to_string(count) + " constraints, the run has " +
                std::to_string(constraint_count));
  }
  for (std::size_t i = 0; i < count; ++i) {
    cost.constraint_cumulative_costs[i] = reader.read_f64("constraint cumulative cost");
    const std::int64_t epochs = reader.read_i64("epochs over the limit");
    if (epochs < 0) reader.fail("negative count of epochs over the limit");
    cost.epochs_over_limit[i] = epochs;
  }
  return cost;
}

}  // namespace bsg::algos
