// Bounded, seeded fuzzing of the readers of untrusted files (issue 25): the
// run file (YAML, resolve_run_config), the checkpoint (container and
// training payload) and the run directory's progress log on resume. Every
// mutated input must give either a clean error (the reader's own exception
// type, with a printable message of bounded length) or, where acceptance is
// possible at all, the original data: a mutated progress log or checkpoint
// field is never taken silently. (A payload whose checksum the test recomputes
// may carry other numbers in the log's rows, as opaque as the network's
// parameters, but never another header, row count, epoch, step count or time.) A crash, a hang (the ctest
// timeout) or another exception type fails the test. The counts are printed.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "../test_support.h"
#include "algos/core/actor_critic.h"
#include "algos/training/epoch_log.h"
#include "algos/training/make_algorithm.h"
#include "algos/training/progress_csv.h"
#include "algos/training/progress_csv_reader.h"
#include "algos/training/training_checkpoint.h"
#include "common/checkpoint_file.h"
#include "common/config_error.h"
#include "common/run_config_resolve.h"
#include "reader_mutations.h"

namespace fs = std::filesystem;
using bsg::testing::mutate;
using bsg::testing::read_text_file;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

constexpr std::uint64_t kSeed = 20261126;

struct Counts {
  int inputs = 0;
  int clean_errors = 0;
  int accepted = 0;
  void print(const char* reader, const char* accepted_as) const {
    std::printf("[ figures  ] %s: %d mutated inputs, %d clean errors, %d accepted (%s), 0 crashes\n", reader, inputs,
                clean_errors, accepted, accepted_as);
  }
};

// A message fit to print: bounded, no raw control bytes but line ends.
::testing::AssertionResult printable(const std::string& message) {
  if (message.size() > 16384) return ::testing::AssertionFailure() << "message of " << message.size() << " bytes";
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && byte != '\n') || byte == 0x7f) {
      return ::testing::AssertionFailure() << "raw control byte " << int(byte) << " in: " << message.substr(0, 300);
    }
  }
  return ::testing::AssertionSuccess();
}

bsg::RunConfig small_config() {
  bsg::RunConfig config;
  config.alg = bsg::Algorithm::lag_trpo;
  config.use_cost_value_function = true;
  config.hidden_sizes = {8};
  config.steps_per_epoch = 400;
  config.epochs = 10;
  return config;
}

// A progress log of `epochs` rows with the columns a run of small_config()
// writes; the last time_s is `elapsed`, the other values vary by row and column.
std::string progress_log(int epochs, double elapsed, long long steps_per_epoch) {
  const bsg::RunConfig config = small_config();
  const std::vector<std::string> columns =
      bsg::algos::epoch_log_columns(bsg::algos::epoch_log_layout(config, *bsg::algos::make_algorithm(config)));
  std::string text;
  for (std::size_t i = 0; i < columns.size(); ++i) text += (i > 0 ? "," : "") + columns[i];
  text += "\n";
  for (int k = 0; k < epochs; ++k) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const std::string& column = columns[i];
      const std::string value = column == "epoch"             ? std::to_string(k)
                                : column == "total_env_steps" ? std::to_string((k + 1) * steps_per_epoch)
                                : column == "time_s"  ? bsg::algos::format_csv_number(k == epochs - 1 ? elapsed : 0.5 * (k + 1))
                                : column == "fps"     ? std::string("nan")
                                                      : bsg::algos::format_csv_number(-3.25 + k * 1.5 + 0.0071 * static_cast<double>(i));
      text += (i > 0 ? "," : "") + value;
    }
    text += "\n";
  }
  return text;
}

TEST(ReadersFuzz, AMutatedProgressLogIsAnErrorOrRestoredToTheCheckpointsRecord) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "progress.csv";
  const std::string original = progress_log(6, 4.75, 400);
  std::mt19937_64 rng(kSeed);
  Counts counts;
  for (int i = 0; i < 4000; ++i) {
    const std::string mutated = mutate(original, rng);
    if (mutated == original) continue;
    ++counts.inputs;
    write_text_file(path, mutated);
    // Odd inputs: a format-1 checkpoint without a record (only the checks of the log itself).
    const bool recorded = i % 2 == 0;
    const bsg::algos::ProgressResume resume{6, recorded ? std::optional<std::string>(original) : std::nullopt, 400, nullptr};
    try {
      bsg::algos::ProgressCsv::resume(path, resume);
    } catch (const std::runtime_error& e) {  // algos::ProgressLogError or rows missing
      ++counts.clean_errors;
      EXPECT_TRUE(printable(e.what()));
      EXPECT_EQ(read_text_file(path), mutated) << "a refused log is left as it was";
      continue;
    }
    ++counts.accepted;
    if (recorded) {
      EXPECT_EQ(read_text_file(path), original) << "accepted mutation:\n" << mutated;
    } else {
      // Without a record only a mutation of a value into another number (or
      // of the torn tail) can pass; every kept row is well formed.
      const bsg::algos::ProgressLogText kept = bsg::algos::read_progress_log(read_text_file(path), "kept", 400);
      EXPECT_EQ(kept.rows.size(), 6u);
      EXPECT_TRUE(kept.torn_tail.empty());
    }
  }
  counts.print("progress.csv on resume", "restored to the checkpoint's record, or well-formed rows");
  EXPECT_GT(counts.clean_errors, counts.inputs / 2);
}

// The header, the row count and each row's epoch, total_env_steps and time_s.
void expect_same_log_shape(const std::string& got, const std::string& original) {
  const bsg::algos::ProgressLogText got_log = bsg::algos::read_progress_log(got, "got", 0);
  const bsg::algos::ProgressLogText original_log = bsg::algos::read_progress_log(original, "original", 0);
  ASSERT_EQ(got_log.header, original_log.header);
  ASSERT_EQ(got_log.rows.size(), original_log.rows.size());
  const std::vector<std::string> columns = bsg::algos::split_csv_line(original_log.header);
  for (std::size_t row = 0; row < got_log.rows.size(); ++row) {
    const std::vector<std::string> got_fields = bsg::algos::split_csv_line(got_log.rows[row]);
    const std::vector<std::string> original_fields = bsg::algos::split_csv_line(original_log.rows[row]);
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (columns[i] == "epoch" || columns[i] == "total_env_steps" || columns[i] == "time_s") {
        EXPECT_EQ(got_fields[i], original_fields[i]) << columns[i] << " of row " << row;
      }
    }
  }
}

TEST(ReadersFuzz, AMutatedCheckpointIsAnErrorOrHoldsTheOriginalFields) {
  const bsg::RunConfig config = small_config();
  bsg::Rng rng_init(5);
  bsg::algos::ActorCritic saved(7, 2, config, rng_init);
  auto algorithm = bsg::algos::make_algorithm(config);
  const bsg::algos::TrainingProgress progress{6, 4.75, 2, progress_log(6, 4.75, config.steps_per_epoch)};
  const std::string payload = bsg::algos::encode_training_checkpoint(config, progress, saved, *algorithm);
  const std::string file = bsg::encode_checkpoint_file(payload);
  // The seed of the libFuzzer checkpoint target (tests/fuzz/libfuzzer/run_libfuzzer.sh).
  if (const char* corpus = std::getenv("BSG_FUZZ_CHECKPOINT_SEED")) write_text_file(corpus, payload);

  std::mt19937_64 rng(kSeed + 1);
  Counts file_counts;
  Counts payload_counts;
  for (int i = 0; i < 6000; ++i) {
    bsg::Rng rng_load(9);
    bsg::algos::ActorCritic loaded(7, 2, config, rng_load);
    auto loaded_algorithm = bsg::algos::make_algorithm(config);
    // Even inputs: the file's bytes (the checksum must catch every change).
    // Odd inputs: the payload, checksummed again, so that the field checks
    // behind the checksum are reached.
    const bool whole_file = i % 2 == 0;
    const std::string mutated = mutate(whole_file ? file : payload, rng);
    if (mutated == (whole_file ? file : payload)) continue;
    Counts& counts = whole_file ? file_counts : payload_counts;
    ++counts.inputs;
    try {
      const bsg::CheckpointContents contents =
          bsg::decode_checkpoint_contents(whole_file ? mutated : bsg::encode_checkpoint_file(mutated), "fuzz.bin");
      const bsg::algos::TrainingProgress got = bsg::algos::decode_training_checkpoint(contents.payload, "fuzz.bin", config, loaded,
                                                                        *loaded_algorithm, contents.format_version);
      ++counts.accepted;
      EXPECT_FALSE(whole_file) << "the checksum let a changed file through";
      // Network parameters are opaque numbers; the fields are not.
      EXPECT_EQ(got.epochs_completed, progress.epochs_completed);
      EXPECT_EQ(got.elapsed_seconds, progress.elapsed_seconds);
      // A payload whose checksum was recomputed is a deliberate edit: the
      // numbers of the log's rows are as opaque as the parameters, but its
      // shape is checked: the header, the row count and the epoch, step and
      // time columns are the original's.
      expect_same_log_shape(got.progress_log.value_or(""), *progress.progress_log);
      EXPECT_GE(got.num_ranks, 1);
      EXPECT_LE(got.num_ranks, bsg::algos::kMaxCheckpointRanks);
    } catch (const bsg::CheckpointError& e) {
      ++counts.clean_errors;
      EXPECT_NE(std::string(e.what()).find("fuzz.bin"), std::string::npos) << e.what();
      EXPECT_TRUE(printable(e.what()));
    }
  }
  file_counts.print("checkpoint file", "none may be");
  payload_counts.print("checkpoint payload (checksum recomputed)", "fields as the original, parameters opaque");
  EXPECT_EQ(file_counts.accepted, 0);
}

TEST(ReadersFuzz, AMutatedRunFileIsAConfigErrorWithAPrintableMessageOrAValidConfig) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "run.yaml";
  const std::string original =
      "# a run\nenv_id: SafetyBallCircle-v0\nalg: lag-trpo\nseed: 3\nepochs: 3\nsteps_per_epoch: 1000\n"
      "hidden_sizes: [64, 64]\ntarget_kl: 0.01\ncost_limit: 25\nlambda_lr: 0.05\nphysics: faithful\n";
  std::mt19937_64 rng(kSeed + 2);
  Counts counts;
  for (int i = 0; i < 1500; ++i) {
    const std::string mutated = mutate(original, rng);
    if (mutated == original) continue;
    ++counts.inputs;
    write_text_file(path, mutated);
    bsg::RunConfigRequest request;
    request.configs_dir = fs::path(BSG_SOURCE_DIR) / "configs";
    request.run_file = path;
    try {
      const bsg::ResolvedRunConfig resolved = bsg::resolve_run_config(request);
      ++counts.accepted;
      EXPECT_GE(resolved.config.steps_per_epoch, resolved.config.max_ep_len);
      EXPECT_LE(resolved.config.hidden_sizes.size(), bsg::kMaxHiddenLayers);
    } catch (const bsg::ConfigError& e) {
      ++counts.clean_errors;
      EXPECT_TRUE(printable(e.what()));
    }
  }
  counts.print("run file", "another valid configuration");
  EXPECT_GT(counts.clean_errors, 0);
}

}  // namespace
