#include "train_benchmark.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "algos/training/make_trainer.h"
#include "common/config_error.h"
#include "common/mpi_context.h"
#include "common/run_config_resolve.h"
#include "configs_search.h"
#include "envs/env.h"
#include "mpi_abort_on_error.h"

namespace bsg::cli {
namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

RunConfig benchmark_config(const TrainBenchArguments& args) {
  RunConfigRequest request;
  request.configs_dir = find_configs("", {}, "run file").dir;  // the search of bsg train without a run file
  request.valid_env_ids = envs::registered_ids();
  request.set_arguments = {"env_id=" + args.env_id, "alg=" + args.alg, "epochs=" + std::to_string(args.epochs),
                           "eval_episodes=0"};
  request.set_arguments.insert(request.set_arguments.end(), args.set_arguments.begin(), args.set_arguments.end());
  return resolve_run_config(request).config;
}

struct TemporaryDirectory {
  std::filesystem::path path;
  TemporaryDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / "bsg_bench_train_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("bsg bench --train: cannot create " + pattern);
    path = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
};

void print_table(const RunConfig& config, int ranks, const std::vector<algos::EpochTimings>& epochs) {
  std::printf("%s on %s, B = %d, dtype %s, %d rank(s); seconds per epoch on rank 0 (wall clock; cpu: processor time)\n",
              std::string(to_string(config.alg)).c_str(), config.env_id.c_str(), config.steps_per_epoch,
              std::string(to_string(config.dtype)).c_str(), ranks);
  std::printf("%6s %9s %9s %9s %9s %9s %11s %10s\n", "epoch", "collect", "policy", "value", "update", "total",
              "update cpu", "total cpu");
  for (const algos::EpochTimings& t : epochs) {
    std::printf("%6d %9.3f %9.3f %9.3f %9.3f %9.3f %11.3f %10.3f\n", t.epoch, t.collect_seconds,
                t.policy_update_seconds, t.value_fit_seconds, t.update_seconds, t.total_seconds,
                t.update_cpu_seconds, t.total_cpu_seconds);
  }
}

template <typename Field>
std::vector<double> column(const std::vector<algos::EpochTimings>& epochs, Field field) {
  std::vector<double> values;
  for (const algos::EpochTimings& t : epochs) values.push_back(t.*field);
  return values;
}

}  // namespace

int run_train_benchmark(const TrainBenchArguments& args) {
  const RunConfig config = benchmark_config(args);  // bad keys fail before MPI starts
  MpiSession session;
  const MpiContext mpi = session.context();
  return run_or_abort_job(mpi, [&]() {
    std::optional<TemporaryDirectory> directory;
    if (mpi.is_root()) directory.emplace();
    std::vector<algos::EpochTimings> epochs;
    algos::TrainerOptions options;
    options.on_epoch_timed = [&epochs](const algos::EpochTimings& timings) { epochs.push_back(timings); };
    algos::make_trainer(config, algos::RunDirectory(directory ? directory->path / "run" : std::filesystem::path()), mpi,
                        options)
        ->run();
    if (!mpi.is_root()) return 0;

    const double collect = median(column(epochs, &algos::EpochTimings::collect_seconds));
    const double policy = median(column(epochs, &algos::EpochTimings::policy_update_seconds));
    const double value = median(column(epochs, &algos::EpochTimings::value_fit_seconds));
    const double update = median(column(epochs, &algos::EpochTimings::update_seconds));
    const double total = median(column(epochs, &algos::EpochTimings::total_seconds));
    const double update_cpu = median(column(epochs, &algos::EpochTimings::update_cpu_seconds));
    const double total_cpu = median(column(epochs, &algos::EpochTimings::total_cpu_seconds));
    if (args.json) {
      nlohmann::json list = nlohmann::json::array();
      for (const algos::EpochTimings& t : epochs) {
        list.push_back({{"epoch", t.epoch},
                        {"collect_s", t.collect_seconds},
                        {"policy_update_s", t.policy_update_seconds},
                        {"value_fit_s", t.value_fit_seconds},
                        {"update_s", t.update_seconds},
                        {"total_s", t.total_seconds},
                        {"update_cpu_s", t.update_cpu_seconds},
                        {"total_cpu_s", t.total_cpu_seconds}});
      }
      const nlohmann::json result = {
          {"env_id", config.env_id},
          {"alg", to_string(config.alg)},
          {"dtype", to_string(config.dtype)},
          {"steps_per_epoch", config.steps_per_epoch},
          {"ranks", mpi.size()},
          {"epochs", list},
          {"median", {{"collect_s", collect}, {"policy_update_s", policy}, {"value_fit_s", value},
                      {"update_s", update}, {"total_s", total}, {"update_cpu_s", update_cpu},
                      {"total_cpu_s", total_cpu}}}};
      std::cout << result.dump(2) << "\n";
    } else {
      print_table(config, mpi.size(), epochs);
      std::printf("%6s %9.3f %9.3f %9.3f %9.3f %9.3f %11.3f %10.3f\n", "median", collect, policy, value, update,
                  total, update_cpu, total_cpu);
    }
    return 0;
  });
}

}  // namespace bsg::cli
