#include "algos/training_checkpoint.h"

#include <stdexcept>

#include "common/checkpoint_file.h"
#include "common/run_config_yaml.h"

namespace bsg {

std::string encode_training_checkpoint(const RunConfig& config, const TrainingProgress& progress,
                                       const ActorCritic& actor_critic, const TrustRegionAlgorithm& algorithm) {
  BinaryWriter writer;
  writer.write_section("run");
  writer.write_string(to_yaml(config));
  writer.write_i64(progress.num_ranks);
  writer.write_section("progress");
  writer.write_i64(progress.epochs_completed);
  writer.write_f64(progress.elapsed_seconds);
  actor_critic.save(writer);
  writer.write_section("algorithm");
  writer.write_string(algorithm.name());
  const std::vector<NamedScalar> state = algorithm.state();
  writer.write_u64(state.size());
  for (const NamedScalar& entry : state) {
    writer.write_string(entry.name);
    writer.write_f64(entry.value);
  }
  save_training_cost(progress.training_cost, writer);
  return writer.bytes();
}

void save_training_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                              const TrainingProgress& progress, const ActorCritic& actor_critic,
                              const TrustRegionAlgorithm& algorithm) {
  write_checkpoint_file(path, encode_training_checkpoint(config, progress, actor_critic, algorithm));
}

TrainingProgress decode_training_checkpoint(std::string_view payload, const std::string& source_name,
                                            const RunConfig& config, ActorCritic& actor_critic,
                                            TrustRegionAlgorithm& algorithm) {
  BinaryReader reader(payload, source_name);
  TrainingProgress progress;
  reader.expect_section("run");
  if (reader.read_string("config") != to_yaml(config)) {
    reader.fail("it was written for a different configuration than the run directory's config.yaml");
  }
  progress.num_ranks = static_cast<int>(reader.read_i64("rank count"));
  reader.expect_section("progress");
  const std::int64_t epochs_completed = reader.read_i64("epochs completed");
  if (epochs_completed < 0 || epochs_completed > config.epochs) {
    reader.fail("epochs completed " + std::to_string(epochs_completed) + " lies outside [0, " +
                std::to_string(config.epochs) + "]");
  }
  progress.epochs_completed = static_cast<int>(epochs_completed);
  progress.elapsed_seconds = reader.read_f64("elapsed seconds");
  actor_critic.load(reader);
  reader.expect_section("algorithm");
  const std::string name = reader.read_string("algorithm name");
  if (name != algorithm.name()) {
    reader.fail("holds the state of algorithm '" + name + "', the run uses '" + std::string(algorithm.name()) + "'");
  }
  const std::uint64_t count = reader.read_u64("algorithm state size");
  if (count > reader.remaining()) reader.fail("corrupt algorithm state size " + std::to_string(count));
  std::vector<NamedScalar> state;
  for (std::uint64_t i = 0; i < count; ++i) {
    NamedScalar entry;
    entry.name = reader.read_string("algorithm state name");
    entry.value = reader.read_f64("algorithm state value");
    state.push_back(std::move(entry));
  }
  const int constraints = actor_critic.constraint_count();
  if (reader.remaining() > 0) progress.training_cost = load_training_cost(reader, constraints);
  reader.expect_end();
  try {
    algorithm.restore_state(state);
  } catch (const std::invalid_argument& e) {
    reader.fail(std::string("algorithm state: ") + e.what());
  }
  return progress;
}

TrainingProgress load_training_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                          ActorCritic& actor_critic, TrustRegionAlgorithm& algorithm) {
  return decode_training_checkpoint(read_checkpoint_file(path), path.string(), config, actor_critic, algorithm);
}

}  // namespace bsg
