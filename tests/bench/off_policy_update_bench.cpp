// Speed of one off-policy gradient step (printed, never asserted): SAC-Lag with one constraint on
// SafetyBallCircle-v0's shapes (8 observations, 2 actions), batch 256, twin reward critics, one
// cost critic, the actor and the temperature, for 64 x 64, 128 x 128 and 256 x 256 networks: ReLU
// (the off-policy learners' shipped activation) and tanh in float32 (the shipped dtype), ReLU in
// float64. Milliseconds per step: wall time and this process's CPU
// time (on a machine shared with other jobs the CPU time is the fairer figure).
//   bsg_off_policy_update_bench [--torch]
// --torch also runs tests/bench/torch_sac_lag_update.py (the same steps in PyTorch on one thread)
// with /usr/bin/python3 and prints its lines after these; it says SKIPPED where torch is missing.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "algos/off_policy/off_policy_learner.h"
#include "common/mpi_context.h"
#include "common/random.h"

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

}  // namespace

int main(int argc, char** argv) {
  const bool torch = argc > 1 && std::string(argv[1]) == "--torch";
  constexpr int kObservations = 8, kActions = 2, kBatch = 256;
  std::printf("off-policy update: SAC-Lag, 1 constraint, obs %d, act %d, batch %d (ms per gradient step)\n",
              kObservations, kActions, kBatch);
  const std::pair<bsg::Dtype, bsg::Activation> kinds[] = {{bsg::Dtype::float32, bsg::Activation::relu},
                                                          {bsg::Dtype::float32, bsg::Activation::tanh},
                                                          {bsg::Dtype::float64, bsg::Activation::relu}};
  for (const auto& [dtype, activation] : kinds) {
    for (const int hidden : {64, 128, 256}) {
      bsg::RunConfig config;
      config.alg = bsg::Algorithm::sac_lag;
      config.hidden_sizes = {hidden, hidden};
      config.dtype = dtype;
      config.activation = activation;
      config.max_grad_norm = 0.0;  // FSRL's: no rescaling
      config.auto_alpha = true;
      config.policy_delay = 1;  // actor and temperature at every step, as the PyTorch script
      bsg::Rng rng(1);
      bsg::algos::OffPolicyLearner learner(bsg::algos::OffPolicyOptions::from_config(config, kActions), kObservations,
                                           kActions, 1, rng);
      const bsg::algos::ReplayBatch batch = random_batch(kBatch, kObservations, kActions, rng);
      const std::vector<double> lambdas{0.5};
      const bsg::MpiContext mpi = bsg::MpiContext::single_process();
      for (int i = 0; i < 20; ++i) learner.update(batch, lambdas, rng, mpi);  // warm-up
      int steps = 0;
      const auto start = Clock::now();
      const std::clock_t cpu_start = std::clock();
      double elapsed = 0.0;
      do {
        for (int i = 0; i < 10; ++i) learner.update(batch, lambdas, rng, mpi);
        steps += 10;
        elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      } while (elapsed < 2.0);
      const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      std::printf("  bsg %-7s %-4s %3d x %-3d  %7.3f ms wall  %7.3f ms cpu  (%d steps)\n",
                  std::string(to_string(dtype)).c_str(), std::string(to_string(activation)).c_str(), hidden, hidden, 1e3 * elapsed / steps, 1e3 * cpu / steps, steps);
      std::fflush(stdout);
    }
  }
  if (torch) {
    const std::string command = "/usr/bin/python3 " + std::string(BSG_SOURCE_DIR) + "/tests/bench/torch_sac_lag_update.py";
    std::fflush(stdout);
    return std::system(command.c_str()) == 0 ? 0 : 1;
  }
  return 0;
}
