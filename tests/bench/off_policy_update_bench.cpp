// Speed of one off-policy gradient step (printed, never asserted): SAC-Lag with one constraint on
// SafetyBallCircle-v0's shapes (8 observations, 2 actions), batch 256, twin reward critics, one
// cost critic, the actor and the temperature, for 64 x 64, 128 x 128 and 256 x 256 networks: ReLU
// (the off-policy learners' shipped activation) and tanh in float32 (the shipped dtype), ReLU in
// float64. Milliseconds per step: wall time and this process's CPU time (on a machine shared with
// other jobs the CPU time is the fairer figure).
//   bsg_off_policy_update_bench [--torch] [--rounds R]
// --torch also runs the same steps in PyTorch on one thread (tests/bench/torch_sac_lag_update.py
// --serve, with /usr/bin/python3; it says SKIPPED where torch is missing). The two sides then
// alternate in R rounds (default 5) of about a second each per float32 network, and each round's
// ratio bsg / PyTorch of CPU times is printed with their median: a virtual machine's speed drifts
// over minutes, so a ratio of two timings taken seconds apart is fairer than one of two taken
// a minute apart.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "algos/off_policy/make_off_policy_learner.h"
#include "algos/off_policy/off_policy_learner.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "torch_server.h"

namespace {

using Clock = std::chrono::steady_clock;

bsg::algos::ReplayBatch random_batch(int rows, int observations, int actions, bsg::Rng& rng) {
  const auto random = [&](int r, int c) {
    Eigen::MatrixXd m(r, c);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = bsg::uniform(rng, -1.0, 1.0);
    return m;
  };
  bsg::algos::ReplayBatch batch;
  batch.observations = random(rows, observations);
  batch.actions = random(rows, actions);
  batch.rewards = random(rows, 1);
  batch.costs = random(rows, 1).cwiseAbs();
  batch.next_observations = random(rows, observations);
  batch.discounts = Eigen::VectorXd::Constant(rows, 0.99);
  batch.terminals = Eigen::VectorXd::Zero(rows);
  return batch;
}

struct Timing {
  double wall_ms = 0.0;
  double cpu_ms = 0.0;
  int steps = 0;
};

class BenchLearner {
 public:
  BenchLearner(bsg::Dtype dtype, bsg::Activation activation, int hidden)
      : rng_(1),
        learner_(bsg::algos::make_off_policy_learner(learner_config(dtype, activation, hidden), kObservations,
                                                     kActions, 1, rng_)),
        batch_(random_batch(kBatch, kObservations, kActions, rng_)) {
    for (int i = 0; i < 20; ++i) step();  // warm-up
  }
  Timing time_steps(double seconds) {
    int steps = 0;
    const auto start = Clock::now();
    const std::clock_t cpu_start = std::clock();
    double elapsed = 0.0;
    do {
      for (int i = 0; i < 10; ++i) step();
      steps += 10;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < seconds);
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    return {1e3 * elapsed / steps, 1e3 * cpu / steps, steps};
  }

  static constexpr int kObservations = 8, kActions = 2, kBatch = 256;

 private:
  static bsg::RunConfig learner_config(bsg::Dtype dtype, bsg::Activation activation, int hidden) {
    bsg::RunConfig config;
    config.alg = bsg::Algorithm::sac_lag;
    config.hidden_sizes = {hidden, hidden};
    config.dtype = dtype;
    config.activation = activation;
    config.first_order.max_grad_norm = 0.0;  // FSRL's: no rescaling
    config.off_policy.auto_alpha = true;
    config.off_policy.policy_delay = 1;  // actor and temperature at every step, as the PyTorch script
    return config;
  }
  void step() { learner_->update(batch_, lambdas_, rng_, mpi_); }

  bsg::Rng rng_;
  std::unique_ptr<bsg::algos::OffPolicyLearner> learner_;
  bsg::algos::ReplayBatch batch_;
  std::vector<double> lambdas_{0.5};
  bsg::MpiContext mpi_ = bsg::MpiContext::single_process();
};

// PyTorch's timing of `hidden` x `hidden` SAC-Lag with `activation` layers for about `seconds`
// (tests/bench/torch_sac_lag_update.py --serve), or nothing if it did not answer "WALL_MS CPU_MS STEPS".
std::optional<Timing> torch_time_steps(bsg::bench::TorchServer& server, const char* activation, int hidden,
                                       double seconds) {
  char request[64];
  std::snprintf(request, sizeof request, "%s %d %.3f", activation, hidden, seconds);
  const std::optional<std::string> line = server.ask(request);
  Timing timing;
  if (!line) return std::nullopt;
  if (std::sscanf(line->c_str(), "%lf %lf %d", &timing.wall_ms, &timing.cpu_ms, &timing.steps) != 3) {
    std::fprintf(stderr, "bsg_off_policy_update_bench: PyTorch answered '%s'\n", line->c_str());
    return std::nullopt;
  }
  return timing;
}

void print_timing(const char* side, bsg::Dtype dtype, bsg::Activation activation, int hidden, const Timing& t,
                  const char* suffix = "") {
  std::printf("  %-5s %-7s %-4s %3d x %-3d  %7.3f ms wall  %7.3f ms cpu  (%d steps)%s\n", side,
              std::string(to_string(dtype)).c_str(), std::string(to_string(activation)).c_str(), hidden, hidden,
              t.wall_ms, t.cpu_ms, t.steps, suffix);
  std::fflush(stdout);
}

int usage_error(const std::string& problem) {
  std::fprintf(stderr, "bsg_off_policy_update_bench: %s\nusage: bsg_off_policy_update_bench [--torch] [--rounds R]\n",
               problem.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  bsg::bench::TorchComparisonOptions options;
  if (const std::string problem = bsg::bench::parse_torch_comparison_options(argc, argv, options); !problem.empty()) {
    return usage_error(problem);
  }
  const bool torch = options.torch;
  const int rounds = options.rounds;
  std::printf("off-policy update: SAC-Lag, 1 constraint, obs %d, act %d, batch %d (ms per gradient step)\n",
              BenchLearner::kObservations, BenchLearner::kActions, BenchLearner::kBatch);
  std::optional<bsg::bench::TorchServer> server;
  if (torch) {
    server.emplace(std::string(BSG_SOURCE_DIR) + "/tests/bench/torch_sac_lag_update.py",
                   "bsg_off_policy_update_bench");
    std::printf("%s\n", server->banner().c_str());
    if (server->available()) {
      std::printf("  %d alternating rounds per float32 network; ratio = bsg cpu / torch cpu of the same round\n",
                  rounds);
    }
  }
  const std::pair<bsg::Dtype, bsg::Activation> kinds[] = {{bsg::Dtype::float32, bsg::Activation::relu},
                                                          {bsg::Dtype::float32, bsg::Activation::tanh},
                                                          {bsg::Dtype::float64, bsg::Activation::relu}};
  bool torch_failed = false;
  for (const auto& [dtype, activation] : kinds) {
    for (const int hidden : {64, 128, 256}) {
      BenchLearner learner(dtype, activation, hidden);
      const bool compare = server && server->available() && !torch_failed && dtype == bsg::Dtype::float32;
      if (!compare) {
        print_timing("bsg", dtype, activation, hidden, learner.time_steps(2.0));
        continue;
      }
      const std::string activation_name(to_string(activation));
      std::vector<double> ratios;
      for (int round = 0; round < rounds && !torch_failed; ++round) {
        const Timing ours = learner.time_steps(1.0);
        const std::optional<Timing> theirs = torch_time_steps(*server, activation_name.c_str(), hidden, 1.0);
        if (!theirs) {
          torch_failed = true;
          break;
        }
        ratios.push_back(ours.cpu_ms / theirs->cpu_ms);
        char ratio[64];
        std::snprintf(ratio, sizeof ratio, "   round %d ratio %.2f", round + 1, ratios.back());
        print_timing("bsg", dtype, activation, hidden, ours);
        print_timing("torch", dtype, activation, hidden, *theirs, ratio);
      }
      if (!ratios.empty()) {
        const auto [low, high] = std::minmax_element(ratios.begin(), ratios.end());
        std::printf("  ratio bsg / torch, float32 %s %d x %d: median %.2f (%.2f to %.2f over %zu rounds)\n",
                    activation_name.c_str(), hidden, hidden, bsg::bench::median(ratios), *low, *high, ratios.size());
        std::fflush(stdout);
      }
    }
  }
  return torch_failed ? 1 : 0;
}
