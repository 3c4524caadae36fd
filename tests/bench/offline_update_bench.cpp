// Speed of one offline gradient step (printed, never asserted): CPQ, BCQ-Lag and COptiDICE, each
// update() on one batch, at the shapes of OSRL's Bullet configs (examples/configs/{cpq,bcql,
// coptidice}_configs.py, which are also the learners' defaults): SafetyBallCircle-v0's 8 observations
// and 2 actions, batch 512, actor and critics 256 x 256, the VAE 400 x 400 with a latent of 2|A|, 10
// sampled actions, two critics per ensemble (BCQ-Lag: two heads of two), ReLU as OSRL's, in float32
// (the shipped dtype) and float64. Microseconds per step, medians over the steps: wall time and this
// process's CPU time (on a machine shared with other jobs the CPU time is the fairer figure).
//   bsg_offline_update_bench [--torch] [--rounds R]
// --torch also runs the same steps in PyTorch on one thread (tests/bench/torch_offline_updates.py
// --serve, with /usr/bin/python3; it says SKIPPED where torch is missing). The two sides then
// alternate in R rounds (default 5) of about two seconds each per learner and dtype, and each round's
// ratio bsg / PyTorch of the median CPU times is printed with their median (torch_server.h says why).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "algos/offline/bcq_lag.h"
#include "algos/offline/coptidice.h"
#include "algos/offline/cpq.h"
#include "algos/offline/offline_algorithm.h"
#include "common/random.h"
#include "torch_server.h"

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kObservations = 8, kActions = 2, kBatch = 512;
constexpr int kEpisodeLength = 200;  // OSRL's BallCircle episode_len: the thresholds' T, the share of initial rows

// Medians over the steps of one timing round.
struct Timing {
  double wall_us = 0.0;
  double cpu_us = 0.0;
  int steps = 0;
};

double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

bsg::algos::OfflineBatch random_batch(bsg::Rng& rng) {
  const auto random = [&](int r, int c) {
    Eigen::MatrixXd m(r, c);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = bsg::uniform(rng, -1.0, 1.0);
    return m;
  };
  bsg::algos::OfflineBatch batch;
  batch.observations = random(kBatch, kObservations);
  batch.next_observations = random(kBatch, kObservations);
  batch.actions = random(kBatch, kActions);
  batch.rewards = random(kBatch, 1);
  batch.costs = random(kBatch, 1).cwiseAbs();
  batch.terminals = Eigen::VectorXd::Zero(kBatch);
  batch.initial = Eigen::VectorXd::Zero(kBatch);
  for (int i = 0; i < kBatch; i += kEpisodeLength) batch.initial(i) = 1.0;
  return batch;
}

enum class Learner { cpq, bcq_lag, coptidice };

const char* learner_name(Learner learner) {
  switch (learner) {
    case Learner::cpq: return "cpq";
    case Learner::bcq_lag: return "bcq-lag";
    case Learner::coptidice: return "coptidice";
  }
  return "?";
}

// The learner with its defaults (OSRL's) but the dtype and T; standardisation the identity.
std::unique_ptr<bsg::algos::OfflineAlgorithm> make_learner(Learner learner, bsg::Dtype dtype, bsg::Rng& rng) {
  const bsg::algos::ObservationScaling scaling{Eigen::VectorXd::Zero(kObservations),
                                               Eigen::VectorXd::Ones(kObservations)};
  switch (learner) {
    case Learner::cpq: {
      bsg::algos::CpqOptions options;
      options.mlp.dtype = dtype;
      options.episode_length = kEpisodeLength;
      return std::make_unique<bsg::algos::Cpq>(kObservations, kActions, scaling, options, rng);
    }
    case Learner::bcq_lag: {
      bsg::algos::BcqLagOptions options;
      options.mlp.dtype = dtype;
      options.episode_length = kEpisodeLength;
      return std::make_unique<bsg::algos::BcqLag>(kObservations, kActions, scaling, options, rng);
    }
    case Learner::coptidice: {
      bsg::algos::COptiDiceOptions options;
      options.mlp.dtype = dtype;
      options.episode_length = kEpisodeLength;
      options.initial_state_proportion = 1.0 / kEpisodeLength;
      options.action_std = Eigen::VectorXd::Constant(kActions, 0.5);
      return std::make_unique<bsg::algos::COptiDice>(kObservations, kActions, scaling, options, rng);
    }
  }
  return nullptr;
}

class BenchLearner {
 public:
  BenchLearner(Learner learner, bsg::Dtype dtype)
      : rng_(1), learner_(make_learner(learner, dtype, rng_)), batch_(random_batch(rng_)) {
    for (int i = 0; i < 5; ++i) learner_->update(batch_, rng_);  // warm-up
  }
  // At least `seconds` of steps, and at least 3 of them.
  Timing time_steps(double seconds) {
    std::vector<double> walls, cpus;
    const auto start = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - start).count() < seconds || walls.size() < 3) {
      const auto wall = Clock::now();
      const double cpu = process_cpu_seconds();
      learner_->update(batch_, rng_);
      cpus.push_back(1e6 * (process_cpu_seconds() - cpu));
      walls.push_back(1e6 * std::chrono::duration<double>(Clock::now() - wall).count());
    }
    return {bsg::bench::median(walls), bsg::bench::median(cpus), static_cast<int>(walls.size())};
  }

 private:
  bsg::Rng rng_;
  std::unique_ptr<bsg::algos::OfflineAlgorithm> learner_;
  bsg::algos::OfflineBatch batch_;
};

// PyTorch's timing of `learner` in `dtype` for about `seconds`, or nothing if it did not answer
// "WALL_US CPU_US STEPS".
std::optional<Timing> torch_time_steps(bsg::bench::TorchServer& server, Learner learner, bsg::Dtype dtype,
                                       double seconds) {
  char request[64];
  std::snprintf(request, sizeof request, "%s %s %.3f", learner_name(learner), std::string(to_string(dtype)).c_str(),
                seconds);
  const std::optional<std::string> line = server.ask(request);
  if (!line) return std::nullopt;
  Timing timing;
  if (std::sscanf(line->c_str(), "%lf %lf %d", &timing.wall_us, &timing.cpu_us, &timing.steps) != 3) {
    std::fprintf(stderr, "bsg_offline_update_bench: PyTorch answered '%s'\n", line->c_str());
    return std::nullopt;
  }
  return timing;
}

void print_timing(const char* side, Learner learner, bsg::Dtype dtype, const Timing& t, const char* suffix = "") {
  std::printf("  %-5s %-9s %-7s %9.0f us wall  %9.0f us cpu  (median of %d steps)%s\n", side, learner_name(learner),
              std::string(to_string(dtype)).c_str(), t.wall_us, t.cpu_us, t.steps, suffix);
  std::fflush(stdout);
}

int usage_error(const std::string& problem) {
  std::fprintf(stderr, "bsg_offline_update_bench: %s\nusage: bsg_offline_update_bench [--torch] [--rounds R]\n",
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
  std::printf("offline update: obs %d, act %d, batch %d, 256 x 256 networks, VAE 400 x 400, 10 sampled actions "
              "(us per gradient step, medians over the steps)\n",
              kObservations, kActions, kBatch);
  std::optional<bsg::bench::TorchServer> server;
  if (torch) {
    server.emplace(std::string(BSG_SOURCE_DIR) + "/tests/bench/torch_offline_updates.py", "bsg_offline_update_bench");
    std::printf("%s\n", server->banner().c_str());
    if (server->available()) {
      std::printf("  %d alternating rounds per learner and dtype; ratio = bsg cpu / torch cpu of the same round\n",
                  rounds);
    }
  }
  bool torch_failed = false;
  for (const Learner learner : {Learner::cpq, Learner::bcq_lag, Learner::coptidice}) {
    for (const bsg::Dtype dtype : {bsg::Dtype::float32, bsg::Dtype::float64}) {
      BenchLearner bench(learner, dtype);
      if (!server || !server->available() || torch_failed) {
        print_timing("bsg", learner, dtype, bench.time_steps(3.0));
        continue;
      }
      std::vector<double> ratios;
      for (int round = 0; round < rounds && !torch_failed; ++round) {
        const Timing ours = bench.time_steps(2.0);
        const std::optional<Timing> theirs = torch_time_steps(*server, learner, dtype, 2.0);
        if (!theirs) {
          torch_failed = true;
          break;
        }
        ratios.push_back(ours.cpu_us / theirs->cpu_us);
        char ratio[64];
        std::snprintf(ratio, sizeof ratio, "   round %d ratio %.2f", round + 1, ratios.back());
        print_timing("bsg", learner, dtype, ours);
        print_timing("torch", learner, dtype, *theirs, ratio);
      }
      if (!ratios.empty()) {
        const auto [low, high] = std::minmax_element(ratios.begin(), ratios.end());
        std::printf("  ratio bsg / torch, %s %s: median %.2f (%.2f to %.2f over %zu rounds)\n", learner_name(learner),
                    std::string(to_string(dtype)).c_str(), bsg::bench::median(ratios), *low, *high, ratios.size());
        std::fflush(stdout);
      }
    }
  }
  return torch_failed ? 1 : 0;
}
