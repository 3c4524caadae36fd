#include "algos/training/off_policy_checkpoint.h"

#include <string>

#include "algos/training/run_header.h"
#include "common/checkpoint_file.h"

namespace bsg::algos {

std::string encode_off_policy_checkpoint(const RunConfig& config, const OffPolicyCheckpoint& state,
                                         const OffPolicyLearner& learner) {
  BinaryWriter writer;
  write_run_header(writer, RunHeaderLayout::off_policy, config, state.progress);
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
  const CheckpointContents contents = read_checkpoint_contents(path);
  BinaryReader reader(contents.payload, path.string());
  OffPolicyCheckpoint state;
  state.progress = read_run_header(reader, RunHeaderLayout::off_policy, config, contents.format_version);
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
