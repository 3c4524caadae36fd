// The C++ side of tests/python/test_policies.py: runs `bsg eval`'s evaluation of a run directory
// (algos/training/run_evaluation.h, one process) and writes every observation its policy acted on
// with the action it took, so that bsg.load_policy's actions can be compared bit for bit.
//   bsg_policy_recorder RUN_DIR EPISODES mean|sampled OUTPUT_FILE
// OUTPUT_FILE receives float64 values (native byte order): the observation and action sizes, then
// per step the observation the policy saw and the action the environment was given.
#include <fstream>
#include <iostream>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "algos/training/run_evaluation.h"
#include "envs/env.h"

namespace {

// Forwards to the evaluated environment, keeping the last observation and each action it is given.
class RecordingEnv final : public bsg::envs::Env {
 public:
  RecordingEnv(std::unique_ptr<bsg::envs::Env> env, std::vector<double>& record)
      : env_(std::move(env)), record_(record) {}

  const bsg::envs::EnvSpec& spec() const override { return env_->spec(); }
  std::span<const double> reset(std::uint64_t seed) override { return keep(env_->reset(seed)); }
  std::span<const double> reset() override { return keep(env_->reset()); }
  std::span<const double> reset_to(const bsg::envs::Layout& layout) override { return keep(env_->reset_to(layout)); }
  const bsg::envs::Layout& layout() const override { return env_->layout(); }
  bsg::envs::StepResult step(std::span<const double> action) override {
    record_.insert(record_.end(), observation_.begin(), observation_.end());
    record_.insert(record_.end(), action.begin(), action.end());
    const bsg::envs::StepResult result = env_->step(action);
    keep(result.observation);
    return result;
  }
  bsg::envs::EnvState state() const override { return env_->state(); }
  void teleport_agent(const bsg::envs::Vec3& com_position) override { env_->teleport_agent(com_position); }

 private:
  std::span<const double> keep(std::span<const double> observation) {
    observation_.assign(observation.begin(), observation.end());
    return observation;
  }

  std::unique_ptr<bsg::envs::Env> env_;
  std::vector<double>& record_;
  std::vector<double> observation_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: bsg_policy_recorder RUN_DIR EPISODES mean|sampled OUTPUT_FILE\n";
    return 2;
  }
  try {
    std::vector<double> record(2);
    const auto actions =
        std::string(argv[3]) == "sampled" ? bsg::algos::EvaluationActions::sampled : bsg::algos::EvaluationActions::mean;
    bsg::algos::evaluate_run_directory(
        bsg::algos::RunDirectory(argv[1]), std::stoi(argv[2]), bsg::MpiContext::single_process(),
        [&](std::unique_ptr<bsg::envs::Env> env) -> std::unique_ptr<bsg::envs::Env> {
          record[0] = env->spec().observation_dim;
          record[1] = env->spec().action_dim;
          return std::make_unique<RecordingEnv>(std::move(env), record);
        },
        actions);
    std::ofstream out(argv[4], std::ios::binary);
    out.write(reinterpret_cast<const char*>(record.data()), static_cast<std::streamsize>(record.size() * sizeof(double)));
    if (!out) {
      std::cerr << "bsg_policy_recorder: cannot write " << argv[4] << "\n";
      return 2;
    }
  } catch (const std::exception& e) {
    std::cerr << "bsg_policy_recorder: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
