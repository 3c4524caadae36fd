// Seconds per training epoch, split into collection and update: runs a few
// epochs of OnPolicyTrainer into a temporary run directory and prints the
// median of progress.csv's time columns (rank 0). Works under mpirun.
//   bsg_train_epoch_bench [alg] [steps_per_epoch] [epochs] [env_id]
// defaults: lag-trpo 32000 5 SafetyBallCircle-v0
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "algos/progress_csv.h"
#include "algos/trainer.h"
#include "common/configs_location.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  bsg::MpiSession session(argc, argv);
  const bsg::MpiContext mpi = session.context();
  const std::string alg = argc > 1 ? argv[1] : "lag-trpo";
  const std::string steps = argc > 2 ? argv[2] : "32000";
  const std::string epochs = argc > 3 ? argv[3] : "5";
  const std::string env_id = argc > 4 ? argv[4] : "SafetyBallCircle-v0";

  bsg::RunConfigRequest request;
  // $BSG_CONFIGS, else configs/ at or above the program (build directories live in the source tree).
  const char* configs_override = std::getenv("BSG_CONFIGS");
  request.configs_dir =
      configs_override != nullptr
          ? std::filesystem::path(configs_override)
          : bsg::locate_configs_dir({bsg::configs_at_or_above(std::filesystem::canonical("/proc/self/exe").parent_path(),
                                                              "at or above the benchmark program")})
                .dir;
  request.set_arguments = {"env_id=" + env_id, "alg=" + alg, "steps_per_epoch=" + steps, "epochs=" + epochs,
                           "eval_episodes=0", "save_freq=1000"};
  const bsg::RunConfig config = bsg::resolve_run_config(request).config;

  std::filesystem::path dir;
  if (mpi.is_root()) {
    char pattern[] = "/tmp/bsg_train_bench_XXXXXX";
    if (mkdtemp(pattern) == nullptr) return 1;
    dir = pattern;
  }
  bsg::OnPolicyTrainer trainer(config, bsg::RunDirectory(dir / "run"), mpi, bsg::TrainerOptions{});
  const std::clock_t cpu_start = std::clock();
  const auto wall_start = std::chrono::steady_clock::now();
  trainer.run();
  // CPU and wall time of this rank: on a busy machine the wall-clock columns
  // include waiting for a core; CPU time does not.
  const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const double wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (!mpi.is_root()) return 0;

  std::ifstream csv(dir / "run" / "progress.csv");
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = bsg::split_csv_line(line);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  std::vector<double> collect, update;
  while (std::getline(csv, line)) {
    const std::vector<std::string> fields = bsg::split_csv_line(line);
    collect.push_back(std::stod(fields.at(column("time_collect_s"))));
    update.push_back(std::stod(fields.at(column("time_update_s"))));
  }
  const double c = median(collect);
  const double u = median(update);
  std::printf("%s on %s, B = %s, %d rank(s), median of %zu epochs: collect %.3f s, update %.3f s, total %.3f s\n",
              alg.c_str(), env_id.c_str(), steps.c_str(), mpi.size(), collect.size(), c, u, c + u);
  std::printf("rank 0: %.3f CPU s per epoch (%.0f%% of its wall time)\n", cpu_seconds / collect.size(),
              100.0 * cpu_seconds / wall_seconds);
  std::filesystem::remove_all(dir);
  return 0;
}
