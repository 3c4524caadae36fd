// The one-line epoch summary that `bsg train` prints on rank 0:
//   epoch   12/500  return   31.52  cost   40.10 (limit 25)  lambda 0.0510  KL 0.00812  0.38 s/epoch  ETA 3m08s
// The cost limit is shown for the constrained algorithms only, lambda for
// TRPO-L and PDO. Before any epoch like the ones to come has been timed (an off-policy run's
// epochs of random actions before start_steps) the ETA reads "ETA once learning starts".
#pragma once

#include <optional>
#include <string>

namespace bsg::algos {

struct ProgressLineInputs {
  int epoch = 0;   // 0-based; printed 1-based as "epoch/epochs"
  int epochs = 0;
  double mean_return = 0.0;
  double mean_cost = 0.0;
  std::optional<double> cost_limit;
  std::optional<double> lagrange_multiplier;
  double kl = 0.0;  // NaN: not shown (the off-policy learners)
  double epoch_seconds = 0.0;
  std::optional<double> eta_seconds;  // nullopt: not known yet (learning has not started)
};

std::string format_progress_line(const ProgressLineInputs& inputs);

// "45s", "3m08s", "2h05m", "3d04h"; "?" if not finite or negative.
std::string format_duration(double seconds);

}  // namespace bsg::algos
