// How steady the epoch cost of a TRPO-L run on SafetyBallCircle-v0 (d = 25)
// is, for comparing Lagrange multiplier rules (docs/algorithms.md, PID
// Lagrangian): one in-process training run, then over the second half of its
// epochs the mean and the standard deviation of the epoch cost
// (episode_cost_mean) and the mean return. Shared by
// tests/algos/training/pid_learning_test.cpp and tests/bench/pid_learning_bench.cpp.
#pragma once

#include <cmath>
#include <filesystem>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "../test_support.h"
#include "algos/training/on_policy_trainer.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"

namespace bsg::testing {

struct SecondHalf {
  double cost_mean = 0.0;
  double cost_std = 0.0;  // population standard deviation over the epochs
  double return_mean = 0.0;
};

// Mean, standard deviation and return over epochs [epochs/2, epochs).
inline SecondHalf second_half_of(const std::vector<double>& costs, const std::vector<double>& returns) {
  if (costs.size() < 2 || costs.size() != returns.size()) {
    throw std::invalid_argument("second_half_of: need at least 2 epochs of cost and return");
  }
  const std::size_t first = costs.size() / 2;
  const auto count = static_cast<double>(costs.size() - first);
  SecondHalf half;
  half.cost_mean = std::accumulate(costs.begin() + static_cast<long>(first), costs.end(), 0.0) / count;
  half.return_mean = std::accumulate(returns.begin() + static_cast<long>(first), returns.end(), 0.0) / count;
  double squares = 0.0;
  for (std::size_t k = first; k < costs.size(); ++k) {
    squares += (costs[k] - half.cost_mean) * (costs[k] - half.cost_mean);
  }
  half.cost_std = std::sqrt(squares / count);
  return half;
}

// TRPO-L on SafetyBallCircle-v0 with the given multiplier rule ("SGD" or
// "PID"), seed and budget, no evaluation; `settings` (key=value) are applied
// after those.
inline SecondHalf train_ball_circle_second_half(const std::string& lambda_optimizer, int seed, int epochs,
                                                int steps_per_epoch, const std::vector<std::string>& settings) {
  RunConfigRequest request;
  request.configs_dir = std::filesystem::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=lag-trpo", "seed=" + std::to_string(seed),
                           "epochs=" + std::to_string(epochs), "steps_per_epoch=" + std::to_string(steps_per_epoch),
                           "eval_episodes=0", "lambda_optimizer=" + lambda_optimizer};
  request.set_arguments.insert(request.set_arguments.end(), settings.begin(), settings.end());
  const RunConfig config = resolve_run_config(request).config;
  const TemporaryDirectory directory;
  algos::OnPolicyTrainer trainer(config, algos::RunDirectory(directory.path() / "run"), MpiContext::single_process(), {});
  if (!trainer.run().finished) throw std::runtime_error("training did not finish");
  auto progress = read_csv_columns(directory.path() / "run" / "progress.csv");
  return second_half_of(progress["episode_cost_mean"], progress["episode_return_mean"]);
}

}  // namespace bsg::testing
