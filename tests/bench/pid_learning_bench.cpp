// Measures what the PID Lagrangian (algos/lagrange/pid_lagrangian.h) does to the cost
// oscillation of TRPO-L on SafetyBallCircle-v0 (d = 25): for each seed, one
// TRPO-L (SGD multiplier) and one TRPO-PID run with the same seed and budget;
// over the second half of training it prints the epoch cost's mean and
// standard deviation and the mean return, per seed and averaged over seeds.
// Any budget and gains, for exploring; tests/algos/training/pid_learning_test.cpp
// asserts the comparison for the shipped gains on a short budget, and
// docs/algorithms.md (PID Lagrangian) has the figures at the report's batch.
//
// Usage: bsg_pid_learning_bench [EPOCHS [STEPS_PER_EPOCH [SEEDS [key=value ...]]]]
//   defaults 80 8000 3; key=value pairs (e.g. pid_kp=0.1 pid_kd=0.1
//   pid_d_delay=5) are applied to the PID runs only.
#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../algos/cost_steadiness.h"

namespace {

using bsg::testing::SecondHalf;
using bsg::testing::train_ball_circle_second_half;

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
      const SecondHalf sgd = train_ball_circle_second_half("SGD", seed, epochs, steps, {});
      const SecondHalf pid = train_ball_circle_second_half("PID", seed, epochs, steps, pid_settings);
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
