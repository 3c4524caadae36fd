#include "algos/training/off_policy_checkpoint.h"

#include <cmath>
#include <string>

#include "common/checkpoint_file.h"
#include "common/run_config_yaml.h"

namespace bsg::algos {
namespace {

constexpr std::string_view kMarker = "off-policy";

}  // namespace

std::string encode_off_policy_checkpoint(const RunConfig& config, const OffPolicyCheckpoint& state,
                                         const OffPolicyLearner& learner) {
  BinaryWriter writer;
  writer.write_section("off-policy run");
  writer.write_string(kMarker);
  writer.write_string(to_yaml(config));
  writer.write_i64(state.progress.num_ranks);
  writer.write_i64(state.progress.epochs_completed);
  writer.write_f64(state.progress.elapsed_seconds);
  writer.write_string(state.progress.progress_log.value_or(""));
  save_training_cost(state.progress.training_cost, writer);
  writer.write_i64(state.replay_transitions);
  writer.write_i64(state.steps_since_update);
  writer.write_f64(state.owed_updates);
  writer.write_section("multipliers");
  writer.write_u64(state.multipliers.size());
  for (const NamedScalar& entry : state.multipliers) {
    writer.write_string(entry.name);
    writer.write_f64(entry.value);
  }
  learner.save(writer);
  return writer.bytes();
}

OffPolicyCheckpoint load_off_policy_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                               OffPolicyLearner& learner) {
  const std::string payload = read_checkpoint_file(path);
  BinaryReader reader(payload, path.string());
  reader.expect_section("off-policy run");
  if (reader.read_string("marker") != kMarker) reader.fail("not an off-policy checkpoint");
  if (reader.read_string("config") != to_yaml(config)) {
    reader.fail("written for another configuration than the run directory's config.yaml");
  }
  OffPolicyCheckpoint state;
  const std::int64_t ranks = reader.read_i64("rank count");
  const std::int64_t epochs = reader.read_i64("epochs completed");
  if (ranks < 1 || ranks > kMaxCheckpointRanks) reader.fail("rank count out of range");
  if (epochs < 0 || epochs > config.epochs) reader.fail("epochs completed out of range");
  state.progress.num_ranks = static_cast<int>(ranks);
  state.progress.epochs_completed = static_cast<int>(epochs);
  state.progress.elapsed_seconds = reader.read_f64("elapsed seconds");
  if (!(state.progress.elapsed_seconds >= 0.0) || !std::isfinite(state.progress.elapsed_seconds)) {
    reader.fail("elapsed seconds negative or not finite");
  }
  state.progress.progress_log = reader.read_string("progress log");
  const int constraint_count = config.constraints.empty() ? 1 : static_cast<int>(config.constraints.size());
  state.progress.training_cost = load_training_cost(reader, constraint_count);
  state.replay_transitions = reader.read_i64("replay transitions");
  if (state.replay_transitions < 0) reader.fail("replay transitions negative");
  state.steps_since_update = reader.read_i64("steps since the last update");
  state.owed_updates = reader.read_f64("owed updates");
  if (state.steps_since_update < 0 || !(state.owed_updates >= 0.0 && state.owed_updates < 1e9)) {
    reader.fail("update schedule out of range");
  }
  reader.expect_section("multipliers");
  const std::uint64_t count = reader.read_u64("multiplier entries");
  if (count > 1000) reader.fail("too many multiplier entries");
  for (std::uint64_t i = 0; i < count; ++i) {
    NamedScalar entry;
    entry.name = reader.read_string("multiplier entry name");
    entry.value = reader.read_f64("multiplier entry value");
    state.multipliers.push_back(std::move(entry));
  }
  learner.load(reader);
  reader.expect_end();
  return state;
}

}  // namespace bsg::algos
