// Size and write time of the off-policy checkpoint's replay buffer record (printed, never asserted;
// algos/training/replay_buffer_log.h): a buffer of 10^6 transitions of SafetyBallCircle-v0's and
// SafetyCarReach-v0's shapes (8 and 57 observations, 2 actions, one constraint), its bytes per
// transition, the time to write it whole (the first checkpoint after it filled, or a compaction)
// and to append one save_freq's worth (20 000 transitions: 10 epochs of 2 000 steps).
//   bsg_replay_buffer_record_bench [DIRECTORY]   (default: a fresh folder under /tmp, removed after)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "algos/off_policy/replay_buffer.h"
#include "algos/training/replay_buffer_log.h"
#include "common/random.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void fill(bsg::algos::ReplayBuffer& buffer, std::int64_t count, bsg::Rng& rng) {
  std::vector<double> observation(static_cast<std::size_t>(buffer.observation_size()));
  std::vector<double> next(observation.size());
  std::vector<double> action(static_cast<std::size_t>(buffer.action_size()));
  std::vector<double> costs(static_cast<std::size_t>(buffer.cost_count()));
  for (std::int64_t k = 0; k < count; ++k) {
    for (double& value : observation) value = bsg::uniform(rng, -1.0, 1.0);
    for (double& value : next) value = bsg::uniform(rng, -1.0, 1.0);
    for (double& value : action) value = bsg::uniform(rng, -1.0, 1.0);
    for (double& value : costs) value = bsg::uniform01(rng) < 0.1 ? 1.0 : 0.0;
    buffer.add(observation, action, bsg::uniform(rng, -1.0, 1.0), costs, next, 0.99, false);
  }
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const bool own_directory = argc < 2;
  const fs::path directory = own_directory ? fs::temp_directory_path() / "bsg_replay_buffer_record_bench" : fs::path(argv[1]);
  fs::create_directories(directory);
  constexpr std::int64_t kCapacity = 1'000'000;
  constexpr std::int64_t kSaveFreqSteps = 20'000;
  std::printf("replay buffer record: capacity %lld transitions, one constraint\n", static_cast<long long>(kCapacity));
  for (const auto& [name, observations] : std::vector<std::pair<std::string, int>>{{"SafetyBallCircle-v0", 8},
                                                                                    {"SafetyCarReach-v0", 57}}) {
    bsg::Rng rng(1);
    bsg::algos::ReplayBuffer buffer(observations, 2, 1, kCapacity);
    fill(buffer, kCapacity, rng);
    const fs::path path = directory / ("replay_buffer_" + name + ".log");
    fs::remove(path);
    bsg::algos::ReplayBufferLog log(path);
    auto start = Clock::now();
    log.append(buffer);  // a new file: the whole buffer
    const double whole_seconds = seconds_since(start);
    const auto whole_bytes = fs::file_size(path);
    fill(buffer, kSaveFreqSteps, rng);
    start = Clock::now();
    log.append(buffer);  // one save_freq's new transitions
    const double append_seconds = seconds_since(start);
    const auto appended_bytes = fs::file_size(path) - whole_bytes;
    std::printf("  %-20s obs %2d: %lld bytes per transition; whole buffer %.1f MB written in %.2f s; "
                "%lld new transitions appended (%.2f MB) in %.3f s\n",
                name.c_str(), observations,
                static_cast<long long>(bsg::algos::ReplayBuffer::bytes_per_transition(observations, 2, 1)),
                static_cast<double>(whole_bytes) / 1e6, whole_seconds, static_cast<long long>(kSaveFreqSteps),
                static_cast<double>(appended_bytes) / 1e6, append_seconds);
    std::fflush(stdout);
    fs::remove(path);
  }
  if (own_directory) fs::remove_all(directory);
  return 0;
}
