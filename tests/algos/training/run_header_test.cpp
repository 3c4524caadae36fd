// The run header of both checkpoint formats (algos/training/run_header.h): each layout's bytes are
// the fields written one by one in the order its format has always had (the oracle is that order,
// spelt out here), a header reads back into the same progress, and both layouts refuse the same
// bad fields with the same messages.
#include "algos/training/run_header.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/run_config_yaml.h"

namespace bsg::algos {
namespace {

RunConfig config_of(Algorithm alg) {
  RunConfig config;
  config.alg = alg;
  config.epochs = 5;
  return config;
}

TrainingProgress progress_of(int epochs, double seconds, int ranks) {
  TrainingProgress progress;
  progress.epochs_completed = epochs;
  progress.elapsed_seconds = seconds;
  progress.num_ranks = ranks;
  progress.progress_log = "epoch,time_s\n0,1.5\n";
  return progress;
}

std::string header_bytes(RunHeaderLayout layout, const RunConfig& config, const TrainingProgress& progress) {
  BinaryWriter writer;
  write_run_header(writer, layout, config, progress);
  return writer.bytes();
}

std::string read_error(RunHeaderLayout layout, const RunConfig& written, const RunConfig& read,
                       const TrainingProgress& progress) {
  const std::string bytes = header_bytes(layout, written, progress);
  BinaryReader reader(bytes, "ckpt.bin");
  try {
    read_run_header(reader, layout, read, /*format_version=*/2);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

TEST(RunHeader, OnPolicyLayoutIsRunThenProgressSections) {
  const RunConfig config = config_of(Algorithm::lag_trpo);
  const TrainingProgress progress = progress_of(1, 1.5, 2);
  BinaryWriter by_hand;
  by_hand.write_section("run");
  by_hand.write_string(to_yaml(config));
  by_hand.write_i64(2);
  by_hand.write_section("progress");
  by_hand.write_i64(1);
  by_hand.write_f64(1.5);
  by_hand.write_string("epoch,time_s\n0,1.5\n");
  EXPECT_EQ(header_bytes(RunHeaderLayout::on_policy, config, progress), by_hand.bytes());
}

TEST(RunHeader, OffPolicyLayoutIsOneSectionWithItsMarker) {
  const RunConfig config = config_of(Algorithm::sac_lag);
  const TrainingProgress progress = progress_of(1, 1.5, 2);
  BinaryWriter by_hand;
  by_hand.write_section("off-policy run");
  by_hand.write_string("off-policy");
  by_hand.write_string(to_yaml(config));
  by_hand.write_i64(2);
  by_hand.write_i64(1);
  by_hand.write_f64(1.5);
  by_hand.write_string("epoch,time_s\n0,1.5\n");
  EXPECT_EQ(header_bytes(RunHeaderLayout::off_policy, config, progress), by_hand.bytes());
}

TEST(RunHeader, ReadsBackWhatItWrote) {
  for (const RunHeaderLayout layout : {RunHeaderLayout::on_policy, RunHeaderLayout::off_policy}) {
    const RunConfig config = config_of(Algorithm::sac);
    const std::string bytes = header_bytes(layout, config, progress_of(3, 2.25, 4));
    BinaryReader reader(bytes, "ckpt.bin");
    const TrainingProgress read = read_run_header(reader, layout, config, /*format_version=*/2);
    reader.expect_end();
    EXPECT_EQ(read.epochs_completed, 3);
    EXPECT_EQ(read.elapsed_seconds, 2.25);
    EXPECT_EQ(read.num_ranks, 4);
    EXPECT_EQ(read.progress_log, "epoch,time_s\n0,1.5\n");
  }
}

TEST(RunHeader, AnOnPolicyFormatOneHeaderHasNoProgressLog) {
  const RunConfig config = config_of(Algorithm::trpo);
  BinaryWriter format_one;  // format 1 ended the progress section after the time
  format_one.write_section("run");
  format_one.write_string(to_yaml(config));
  format_one.write_i64(1);
  format_one.write_section("progress");
  format_one.write_i64(2);
  format_one.write_f64(7.0);
  BinaryReader reader(format_one.bytes(), "old.bin");
  const TrainingProgress read = read_run_header(reader, RunHeaderLayout::on_policy, config, 1);
  reader.expect_end();
  EXPECT_EQ(read.epochs_completed, 2);
  EXPECT_FALSE(read.progress_log.has_value());
}

TEST(RunHeader, BothLayoutsRefuseTheSameFieldsWithTheSameMessages) {
  for (const RunHeaderLayout layout : {RunHeaderLayout::on_policy, RunHeaderLayout::off_policy}) {
    const RunConfig config = config_of(Algorithm::ppo_lag);
    RunConfig other = config;
    other.seed = config.seed + 1;
    EXPECT_NE(read_error(layout, other, config, progress_of(1, 1.0, 1)).find("different configuration"),
              std::string::npos);
    EXPECT_NE(read_error(layout, config, config, progress_of(1, 1.0, 0)).find("rank count 0 lies outside [1, 1048576]"),
              std::string::npos);
    EXPECT_NE(read_error(layout, config, config, progress_of(6, 1.0, 1)).find("epochs completed 6 lies outside [0, 5]"),
              std::string::npos);
    EXPECT_NE(read_error(layout, config, config, progress_of(1, -1.0, 1))
                  .find("elapsed seconds -1 is not a finite non-negative time"),
              std::string::npos);
    EXPECT_NE(read_error(layout, config, config, progress_of(1, std::nan(""), 1)).find("elapsed seconds nan"),
              std::string::npos);
    EXPECT_EQ(read_error(layout, config, config, progress_of(1, 1.0, 1)), "");
  }
}

TEST(RunHeader, OneLayoutIsNotTheOther) {
  const RunConfig config = config_of(Algorithm::sac_lag);
  const std::string on_policy = header_bytes(RunHeaderLayout::on_policy, config, progress_of(1, 1.0, 1));
  BinaryReader reader(on_policy, "ckpt.bin");
  EXPECT_THROW(read_run_header(reader, RunHeaderLayout::off_policy, config, /*format_version=*/2),
               CheckpointError);
}

}  // namespace
}  // namespace bsg::algos
