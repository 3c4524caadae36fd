#include "algos/training/training_checkpoint.h"

#include <algorithm>
#include <stdexcept>

#include "algos/training/progress_csv.h"
#include "algos/training/epoch_log.h"
#include "algos/training/progress_csv_reader.h"
#include "common/message_text.h"

namespace bsg::algos {
namespace {

// The recorded log must hold exactly the completed epochs' rows, with this
// run's step counts, and its last time_s is the checkpoint's elapsed time
// (both are written from the same number at the end of that epoch).
void check_progress_log(const BinaryReader& reader, const std::string& text, const TrainingProgress& progress,
                        const RunConfig& config, const OnPolicyAlgorithm& algorithm) {
  ProgressLogText log;
  try {
    log = read_progress_log(text, "its progress log", config.steps_per_epoch);
  } catch (const ProgressLogError& e) {
    reader.fail(e.what());
  }
  if (!log.torn_tail.empty() || log.rows.size() != static_cast<std::size_t>(progress.epochs_completed) ||
      (progress.epochs_completed > 0) == log.header.empty()) {
    reader.fail("its progress log holds " + std::to_string(log.rows.size()) + " rows" +
                (log.torn_tail.empty() ? "" : " and a cut-off line") + " for " +
                std::to_string(progress.epochs_completed) + " completed epochs");
  }
  if (log.rows.empty()) return;
  const std::vector<std::string> columns = split_csv_line(log.header);
  // The columns this run's trainer writes (epoch_log.cpp): a header with any
  // other column, missing or renamed, was not written by a run of this config.
  const std::vector<std::string> expected = epoch_log_columns(epoch_log_layout(config, algorithm));
  for (std::size_t i = 0; i < std::max(columns.size(), expected.size()); ++i) {
    const std::string got = i < columns.size() ? columns[i] : "(none)";
    const std::string want = i < expected.size() ? expected[i] : "(none)";
    if (got != want) {
      reader.fail("its progress log's column " + std::to_string(i + 1) + " is " + printable_excerpt(got) +
                  ", this run writes " + want);
    }
  }
  const std::vector<std::string> last = split_csv_line(log.rows.back());
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == "time_s" && last[i] != format_csv_number(progress.elapsed_seconds)) {
      reader.fail("its progress log's last time_s " + last[i] + " differs from its elapsed seconds " +
                  format_csv_number(progress.elapsed_seconds));
    }
  }
}

}  // namespace

std::string encode_training_checkpoint(const RunConfig& config, const TrainingProgress& progress,
                                       const ActorCritic& actor_critic, const OnPolicyAlgorithm& algorithm) {
  BinaryWriter writer;
  write_run_header(writer, RunHeaderLayout::on_policy, config, progress);
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
                              const OnPolicyAlgorithm& algorithm) {
  write_checkpoint_file(path, encode_training_checkpoint(config, progress, actor_critic, algorithm));
}

TrainingProgress decode_training_checkpoint(std::string_view payload, const std::string& source_name,
                                            const RunConfig& config, ActorCritic& actor_critic,
                                            OnPolicyAlgorithm& algorithm, std::uint32_t format_version) {
  BinaryReader reader(payload, source_name);
  TrainingProgress progress = read_run_header(reader, RunHeaderLayout::on_policy, config, format_version);
  if (progress.progress_log) check_progress_log(reader, *progress.progress_log, progress, config, algorithm);
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
  // The training cost so far ends the payload; checkpoints written before it
  // existed have none (the sums start at 0).
  if (reader.remaining() > 0) progress.training_cost = load_training_cost(reader, actor_critic.constraint_count());
  reader.expect_end();
  try {
    algorithm.restore_state(state);
  } catch (const std::invalid_argument& e) {
    reader.fail(std::string("algorithm state: ") + e.what());
  }
  return progress;
}

TrainingProgress load_training_checkpoint(const std::filesystem::path& path, const RunConfig& config,
                                          ActorCritic& actor_critic, OnPolicyAlgorithm& algorithm) {
  const CheckpointContents contents = read_checkpoint_contents(path);
  return decode_training_checkpoint(contents.payload, path.string(), config, actor_critic, algorithm,
                                    contents.format_version);
}

}  // namespace bsg::algos
