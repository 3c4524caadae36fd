// Measures what the PID Lagrangian (algos/pid_lagrangian.h) does to the cost
// oscillation of TRPO-L on SafetyBallCircle-v0 (d = 25): for each seed, one
// TRPO-L (SGD multiplier) and one TRPO-PID run with the same seed and budget;
// over the second half of training it prints the epoch cost's mean and
// standard deviation and the mean return, per seed and averaged over seeds.
// A benchmark, not a test: on the budgets measured so far the difference
// between the two is not consistent across seeds and gains (docs/
// algorithms.md, PID Lagrangian), so nothing is asserted.
//
// Usage: bsg_pid_learning_bench [EPOCHS [STEPS_PER_EPOCH [SEEDS [key=value ...]]]]
//   defaults 80 8000 3; key=value pairs (e.g. pid_kp=0.1 pid_kd=0.1
//   pid_d_delay=5) are applied to the PID runs only.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../test_support.h"
#include "algos/trainer.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"

namespace fs = std::filesystem;

namespace {

struct SecondHalf {
  double cost_mean = 0.0;
  double cost_std = 0.0;
  double return_mean = 0.0;
};

double mean_of(const std::vector<double>& values) {
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

SecondHalf train_second_half(const std::string& lambda_optimizer, int seed, int epochs, int steps,
                             const std::vector<std::string>& pid_settings) {
  bsg::RunConfigRequest request;
  request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
  request.set_arguments = {"env_id=SafetyBallCircle-v0", "alg=lag-trpo", "seed=" + std::to_string(seed),
                           "epochs=" + std::to_string(epochs), "steps_per_epoch=" + std::to_string(steps),
                           "eval_episodes=0", "lambda_optimizer=" + lambda_optimizer};
  if (lambda_optimizer == "PID") {
    request.set_arguments.insert(request.set_arguments.end(), pid_settings.begin(), pid_settings.end());
  }
  const bsg::RunConfig config = bsg::resolve_run_config(request).config;
  const bsg::testing::TemporaryDirectory directory;
  bsg::OnPolicyTrainer trainer(config, bsg::RunDirectory(directory.path() / "run"),
                               bsg::MpiContext::single_process(), {});
  if (!trainer.run().finished) throw std::runtime_error("training did not finish");
  auto progress = bsg::testing::read_csv_columns(directory.path() / "run" / "progress.csv");
  const std::vector<double>& costs = progress["episode_cost_mean"];
  const std::vector<double>& returns = progress["episode_return_mean"];
  const std::vector<double> cost_half(costs.begin() + epochs / 2, costs.end());
  const std::vector<double> return_half(returns.begin() + epochs / 2, returns.end());
  SecondHalf half;
  half.cost_mean = mean_of(cost_half);
  half.return_mean = mean_of(return_half);
  double squares = 0.0;
  for (double cost : cost_half) squares += (cost - half.cost_mean) * (cost - half.cost_mean);
  half.cost_std = std::sqrt(squares / static_cast<double>(cost_half.size()));
  return half;
}

void print_row(const std::string& label, const SecondHalf& h) {
  std::cout << "  " << std::left << std::setw(22) << label << std::right << std::fixed << std::setprecision(2)
            << " cost " << std::setw(6) << h.cost_mean << " +- " << std::setw(5) << h.cost_std << "  return "
            << std::setw(7) << h.return_mean << "\n";
}

int positive_argument(const char* text, const char* name) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value < 1 || value > 1000000) {
    throw std::invalid_argument(std::string(name) + " must be a whole number >= 1, got '" + text + "'");
  }
  return static_cast<int>(value);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const int epochs = argc > 1 ? positive_argument(argv[1], "EPOCHS") : 80;
    const int steps = argc > 2 ? positive_argument(argv[2], "STEPS_PER_EPOCH") : 8000;
    const int seeds = argc > 3 ? positive_argument(argv[3], "SEEDS") : 3;
    std::vector<std::string> pid_settings(argv + std::min(argc, 4), argv + argc);
    std::cout << "SafetyBallCircle-v0, d = 25, " << epochs << " epochs x " << steps
              << " steps; second half of training; PID settings:";
    for (const std::string& s : pid_settings) std::cout << " " << s;
    std::cout << (pid_settings.empty() ? " (shipped defaults)\n" : "\n");
    SecondHalf sgd_sum, pid_sum;
    for (int seed = 0; seed < seeds; ++seed) {
      const SecondHalf sgd = train_second_half("SGD", seed, epochs, steps, pid_settings);
      const SecondHalf pid = train_second_half("PID", seed, epochs, steps, pid_settings);
      std::cout << "seed " << seed << "\n";
      print_row("TRPO-L (SGD)", sgd);
      print_row("TRPO-PID", pid);
      for (auto [sum, one] : {std::pair{&sgd_sum, &sgd}, std::pair{&pid_sum, &pid}}) {
        sum->cost_mean += one->cost_mean / seeds;
        sum->cost_std += one->cost_std / seeds;
        sum->return_mean += one->return_mean / seeds;
      }
    }
    std::cout << "mean over " << seeds << " seeds\n";
    print_row("TRPO-L (SGD)", sgd_sum);
    print_row("TRPO-PID", pid_sum);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bsg_pid_learning_bench: " << e.what() << "\n";
    return 1;
  }
}
