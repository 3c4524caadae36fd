// TensorBoard's event file of a run (docs/algorithms.md#logged-columns): beside progress.csv,
// events.out.tfevents.<seconds>.<host> holds one Event per epoch whose Summary has a scalar per
// progress.csv column (tag = the column's name, simple_value = its value as float32, step = the
// epoch), so that `tensorboard --logdir` shows a run's curves, and a sweep's runs side by side.
// Rank 0 writes it when the key tensorboard is true (the default); nothing else of the run changes.
//
// The format is TensorFlow's, public: a file of TFRecord records (uint64 length, its masked
// CRC-32C, the bytes, their masked CRC-32C; little-endian; common/crc32c.h) around Event protocol
// buffers (tensorflow/core/util/event.proto: wall_time = 1 double, step = 2 int64, file_version =
// 3 string, summary = 5 Summary; Summary.value = 1 repeated Value; Value.tag = 1 string,
// simple_value = 2 float), the first event naming the file version "brain.Event:2". The few fields
// are encoded here by hand rather than through a protobuf library.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "algos/core/algorithm.h"

namespace bsg::algos {

class EventFile {
 public:
  // Creates the file in `directory` with its first event; throws std::runtime_error naming the
  // file if it cannot be written.
  explicit EventFile(const std::filesystem::path& directory);

  // One event at `step`: a scalar per entry, written and flushed (TensorBoard reads it live).
  void write_scalars(std::int64_t step, const std::vector<NamedScalar>& scalars);
  // An event per row of a progress.csv text (a resumed run's kept rows), at the row's epoch.
  void write_progress_log(std::string_view progress_csv_text);

  const std::filesystem::path& path() const { return path_; }

 private:
  void write_record(const std::string& event);

  std::filesystem::path path_;
  std::ofstream out_;
};

// Removes the event files of a run directory (a resumed run writes its kept rows anew).
void remove_event_files(const std::filesystem::path& directory);

}  // namespace bsg::algos
