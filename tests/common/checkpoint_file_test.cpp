// The checkpoint container (common/checkpoint_file.h) and the atomic write
// (common/atomic_file.h): round trip, and every kind of damaged file gives a
// CheckpointError that names the file instead of loading garbage.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "../test_support.h"
#include "common/atomic_file.h"
#include "common/binary_io.h"
#include "common/checkpoint_file.h"

namespace fs = std::filesystem;
using bsg::testing::read_text_file;
using bsg::testing::TemporaryDirectory;
using bsg::testing::write_text_file;

namespace {

// Files beside `path` whose names start with its temporary prefix.
int temporaries_of(const fs::path& path) {
  const std::string prefix = bsg::atomic_temporary_prefix(path).filename().string();
  int count = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(path.parent_path())) {
    count += entry.path().filename().string().rfind(prefix, 0) == 0 ? 1 : 0;
  }
  return count;
}

// The message of the CheckpointError thrown by read_checkpoint_file(path), or "" if none.
std::string read_error(const fs::path& path) {
  try {
    bsg::read_checkpoint_file(path);
  } catch (const bsg::CheckpointError& e) {
    return e.what();
  }
  return "";
}

std::string sample_payload() {
  bsg::BinaryWriter writer;
  writer.write_section("numbers");
  writer.write_u32(7);
  writer.write_i64(-42);
  writer.write_f64(-0.0);
  writer.write_vector(Eigen::VectorXd::LinSpaced(5, -1.0, 1.0));
  writer.write_string("hello");
  writer.write_bool(true);
  return writer.bytes();
}

}  // namespace

TEST(BinaryIo, ValuesReadBackBitExactly) {
  const std::string payload = sample_payload();
  bsg::BinaryReader reader(payload, "memory");
  reader.expect_section("numbers");
  EXPECT_EQ(reader.read_u32("u32"), 7u);
  EXPECT_EQ(reader.read_i64("i64"), -42);
  const double zero = reader.read_f64("f64");
  EXPECT_TRUE(std::signbit(zero));
  EXPECT_EQ(reader.read_vector("vector", 5), Eigen::VectorXd::LinSpaced(5, -1.0, 1.0));
  EXPECT_EQ(reader.read_string("string"), "hello");
  EXPECT_TRUE(reader.read_bool("bool"));
  EXPECT_NO_THROW(reader.expect_end());
}

TEST(BinaryIo, ReadingPastTheEndNamesSourceAndField) {
  bsg::BinaryWriter writer;
  writer.write_u32(1);
  bsg::BinaryReader reader(writer.bytes(), "some/file.bin");
  try {
    reader.read_u64("epoch count");
    FAIL() << "expected a CheckpointError";
  } catch (const bsg::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("some/file.bin"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("epoch count"), std::string::npos) << e.what();
  }
}

TEST(BinaryIo, WrongSectionNamesExpectedAndFound) {
  bsg::BinaryWriter writer;
  writer.write_section("policy");
  bsg::BinaryReader reader(writer.bytes(), "x.bin");
  try {
    reader.expect_section("value net");
    FAIL() << "expected a CheckpointError";
  } catch (const bsg::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("'value net'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'policy'"), std::string::npos) << e.what();
  }
}

TEST(BinaryIo, VectorOfUnexpectedLengthIsAnError) {
  bsg::BinaryWriter writer;
  writer.write_vector(Eigen::VectorXd::Zero(3));
  bsg::BinaryReader reader(writer.bytes(), "x.bin");
  EXPECT_THROW(reader.read_vector("weights", 4), bsg::CheckpointError);
}

TEST(CheckpointFile, RoundTripReturnsThePayload) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "checkpoint.bin";
  const std::string payload = sample_payload();
  bsg::write_checkpoint_file(path, payload);
  EXPECT_EQ(bsg::read_checkpoint_file(path), payload);
  EXPECT_EQ(temporaries_of(path), 0);
  EXPECT_EQ(read_text_file(path).substr(0, 8), "BSGCKPT\n");
}

TEST(CheckpointFile, EveryTruncationIsAnErrorNamingTheFile) {
  TemporaryDirectory dir;
  const fs::path good = dir.path() / "good.bin";
  bsg::write_checkpoint_file(good, sample_payload());
  const std::string bytes = read_text_file(good);
  const fs::path cut = dir.path() / "cut.bin";
  for (std::size_t length = 0; length < bytes.size(); ++length) {
    write_text_file(cut, bytes.substr(0, length));
    const std::string message = read_error(cut);
    EXPECT_NE(message.find(cut.string()), std::string::npos) << "length " << length << ": '" << message << "'";
  }
}

TEST(CheckpointFile, AnyFlippedPayloadByteFailsTheChecksum) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "checkpoint.bin";
  bsg::write_checkpoint_file(path, sample_payload());
  const std::string bytes = read_text_file(path);
  const std::size_t header = 8 + 4 + 8;
  for (std::size_t i = header; i + 8 < bytes.size(); ++i) {
    std::string damaged = bytes;
    damaged[i] = static_cast<char>(damaged[i] ^ 0x10);
    write_text_file(path, damaged);
    const std::string message = read_error(path);
    EXPECT_NE(message.find("checksum"), std::string::npos) << "byte " << i << ": '" << message << "'";
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  }
}

TEST(CheckpointFile, ForeignFileAndOtherVersionAreRejected) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "checkpoint.bin";
  write_text_file(path, "progress.csv is not a checkpoint\n");
  EXPECT_NE(read_error(path).find("not a bsg checkpoint"), std::string::npos);

  std::string bytes = bsg::encode_checkpoint_file(sample_payload());
  bytes[8] = 99;  // version field
  write_text_file(path, bytes);
  EXPECT_NE(read_error(path).find("version 99"), std::string::npos) << read_error(path);
}

TEST(CheckpointFile, MissingFileIsAnErrorNamingIt) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "nowhere.bin";
  EXPECT_NE(read_error(path).find(path.string()), std::string::npos);
}

TEST(AtomicFile, ReplacesTheContents) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "file.txt";
  bsg::write_file_atomically(path, "old");
  bsg::write_file_atomically(path, "new contents");
  EXPECT_EQ(read_text_file(path), "new contents");
}

TEST(AtomicFile, AFailedWriteKeepsTheOldContentsAndLeavesNoTemporary) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "checkpoint.bin";
  // The rename cannot replace a non-empty directory.
  fs::create_directories(path / "inside");
  EXPECT_THROW(bsg::write_checkpoint_file(path, "new payload"), std::runtime_error);
  EXPECT_TRUE(fs::is_directory(path / "inside"));
  EXPECT_EQ(temporaries_of(path), 0);
}

// Issue 25, reproduction 4: two sweeps writing sweep_runs.csv at once shared
// one temporary name, and one failed renaming a temporary the other had
// already renamed.
TEST(AtomicFile, ConcurrentWritersOfOneFileNeverShareATemporary) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "sweep_runs.csv";
  const std::string a(100000, 'a');
  const std::string b(100000, 'b');
  std::vector<std::string> errors;
  std::mutex errors_mutex;
  auto writer = [&](const std::string& contents) {
    for (int i = 0; i < 200; ++i) {
      try {
        bsg::write_file_atomically(path, contents);
      } catch (const std::exception& e) {
        const std::lock_guard<std::mutex> lock(errors_mutex);
        errors.push_back(e.what());
      }
    }
  };
  std::thread first(writer, a);
  std::thread second(writer, b);
  first.join();
  second.join();
  EXPECT_TRUE(errors.empty()) << errors.front();
  const std::string final_contents = read_text_file(path);
  EXPECT_TRUE(final_contents == a || final_contents == b) << "a whole file, never a mix";
  EXPECT_EQ(temporaries_of(path), 0);
}

TEST(AtomicFile, AStaleTemporaryFromAKilledWriterIsIgnoredAndReplaced) {
  TemporaryDirectory dir;
  const fs::path path = dir.path() / "checkpoint.bin";
  bsg::write_checkpoint_file(path, "good payload");
  // A writer killed half-way leaves a partial temporary behind.
  write_text_file(fs::path(bsg::atomic_temporary_prefix(path).string() + "12345.AbCdEf"),
                  bsg::encode_checkpoint_file("new payload").substr(0, 10));
  EXPECT_EQ(bsg::read_checkpoint_file(path), "good payload");
  bsg::write_checkpoint_file(path, "next payload");
  EXPECT_EQ(bsg::read_checkpoint_file(path), "next payload");
}
