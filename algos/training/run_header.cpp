#include "algos/training/run_header.h"

#include <cmath>
#include <string_view>

#include "algos/training/progress_csv_fields.h"
#include "common/run_config_yaml.h"

namespace bsg::algos {
namespace {

// The section and the marker of the layouts that have one (not on_policy's).
std::string_view section_of(RunHeaderLayout layout) {
  if (layout == RunHeaderLayout::multi_agent) return "multi-agent run";
  return layout == RunHeaderLayout::offline ? "offline run" : "off-policy run";
}
std::string_view marker_of(RunHeaderLayout layout) {
  if (layout == RunHeaderLayout::multi_agent) return "multi-agent";
  return layout == RunHeaderLayout::offline ? "offline" : "off-policy";
}

void read_config(BinaryReader& reader, const RunConfig& config) {
  if (reader.read_string("config") != to_yaml(config)) {
    reader.fail("it was written for a different configuration than the run directory's config.yaml");
  }
}

int read_rank_count(BinaryReader& reader) {
  const std::int64_t num_ranks = reader.read_i64("rank count");
  if (num_ranks < 1 || num_ranks > kMaxCheckpointRanks) {
    reader.fail("rank count " + std::to_string(num_ranks) + " lies outside [1, " +
                std::to_string(kMaxCheckpointRanks) + "]");
  }
  return static_cast<int>(num_ranks);
}

int read_epochs_completed(BinaryReader& reader, const RunConfig& config) {
  const std::int64_t epochs_completed = reader.read_i64("epochs completed");
  if (epochs_completed < 0 || epochs_completed > config.epochs) {
    reader.fail("epochs completed " + std::to_string(epochs_completed) + " lies outside [0, " +
                std::to_string(config.epochs) + "]");
  }
  return static_cast<int>(epochs_completed);
}

double read_elapsed_seconds(BinaryReader& reader) {
  const double seconds = reader.read_f64("elapsed seconds");
  if (!std::isfinite(seconds) || seconds < 0) {
    reader.fail("elapsed seconds " + format_csv_number(seconds) + " is not a finite non-negative time");
  }
  return seconds;
}

}  // namespace

void write_run_header(BinaryWriter& writer, RunHeaderLayout layout, const RunConfig& config,
                      const TrainingProgress& progress) {
  const bool on_policy = layout == RunHeaderLayout::on_policy;
  writer.write_section(on_policy ? "run" : section_of(layout));
  if (!on_policy) writer.write_string(marker_of(layout));
  writer.write_string(to_yaml(config));
  writer.write_i64(progress.num_ranks);
  if (on_policy) writer.write_section("progress");
  writer.write_i64(progress.epochs_completed);
  writer.write_f64(progress.elapsed_seconds);
  writer.write_string(progress.progress_log.value_or(""));
}

TrainingProgress read_run_header(BinaryReader& reader, RunHeaderLayout layout, const RunConfig& config,
                                 std::uint32_t format_version) {
  const bool on_policy = layout == RunHeaderLayout::on_policy;
  TrainingProgress progress;
  reader.expect_section(on_policy ? "run" : section_of(layout));
  if (!on_policy && reader.read_string("marker") != marker_of(layout)) {
    reader.fail("not an " + std::string(marker_of(layout)) + " checkpoint");
  }
  read_config(reader, config);
  progress.num_ranks = read_rank_count(reader);
  if (on_policy) reader.expect_section("progress");
  progress.epochs_completed = read_epochs_completed(reader, config);
  progress.elapsed_seconds = read_elapsed_seconds(reader);
  // The on-policy format 1 had no log; the off-policy and offline formats began later.
  if (!on_policy || format_version >= 2) progress.progress_log = reader.read_string("progress log");
  return progress;
}

}  // namespace bsg::algos
