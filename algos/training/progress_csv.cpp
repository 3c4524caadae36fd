#include "algos/training/progress_csv.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "algos/training/progress_csv_reader.h"
#include "common/atomic_file.h"
#include "common/file_reading.h"

namespace bsg::algos {
namespace {

std::string header_of(const std::vector<NamedScalar>& row) {
  std::string header;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) header += ',';
    header += row[i].name;
  }
  return header;
}

}  // namespace

ProgressCsv::ProgressCsv(std::filesystem::path path, std::string header, std::string contents)
    : path_(std::move(path)), header_(std::move(header)), contents_(std::move(contents)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot open " + path_.string() + " for writing: " + std::strerror(errno));
}

ProgressCsv::ProgressCsv(ProgressCsv&& other) noexcept
    : path_(std::move(other.path_)),
      header_(std::move(other.header_)),
      contents_(std::move(other.contents_)),
      fd_(std::exchange(other.fd_, -1)) {}

ProgressCsv::~ProgressCsv() {
  if (fd_ >= 0) ::close(fd_);
}

ProgressCsv ProgressCsv::create(const std::filesystem::path& path) {
  write_file_atomically(path, "");
  return ProgressCsv(path, "", "");
}

ProgressCsv ProgressCsv::resume(const std::filesystem::path& path, const ProgressResume& resume) {
  const std::string name = path.string();
  const bool exists = file_kind(path) != "missing";
  if (!exists && !resume.checkpoint_log) {
    throw std::runtime_error("cannot read " + name + " (needed to resume the run): it is missing");
  }
  const std::string existing = exists ? read_regular_file(path, "progress log") : std::string();
  const ProgressLogText log = read_progress_log(existing, name, resume.steps_per_epoch);
  const std::size_t checkpointed = static_cast<std::size_t>(resume.epochs_completed);
  std::ostream* notes = resume.notes;
  if (!log.torn_tail.empty() && notes != nullptr) {
    *notes << "note: " << name << ":" << log.rows.size() + (log.header.empty() ? 1 : 2) << " is cut off ("
           << log.torn_tail.size() << " bytes without a line end, what a crash during a write leaves); trimmed\n";
  }
  std::string kept;
  if (resume.checkpoint_log) {
    const ProgressLogText saved =
        read_progress_log(*resume.checkpoint_log, name + " as the checkpoint records it", resume.steps_per_epoch);
    if (saved.rows.size() != checkpointed || !saved.torn_tail.empty()) {
      throw ProgressLogError("the checkpoint beside " + name + " records " + std::to_string(saved.rows.size()) +
                             " progress rows for " + std::to_string(checkpointed) + " epochs");
    }
    if (!log.header.empty() && !saved.header.empty() && log.header != saved.header) {
      throw ProgressLogError(name + ":1: the header differs from the one the checkpoint records: the progress log "
                             "does not belong to this run");
    }
    const std::size_t common = std::min(log.rows.size(), saved.rows.size());
    for (std::size_t i = 0; i < common; ++i) {
      if (log.rows[i] != saved.rows[i]) {
        throw ProgressLogError(name + ":" + std::to_string(i + 2) + ": epoch " + std::to_string(i) +
                               " differs from the row the checkpoint records for it: the progress log does not "
                               "belong to this run");
      }
    }
    if (log.rows.size() < checkpointed && notes != nullptr) {
      *notes << "note: " << name << " held " << log.rows.size() << " of the " << checkpointed
             << " checkpointed epochs' rows; rows of epochs " << log.rows.size() << " to " << checkpointed - 1
             << " restored from the checkpoint\n";
    }
    kept = *resume.checkpoint_log;
  } else {
    if (log.rows.size() < checkpointed || (checkpointed > 0 && log.header.empty())) {
      throw std::runtime_error(name + " holds " + std::to_string(log.rows.size()) + " epoch rows, the checkpoint covers " +
                               std::to_string(checkpointed) + ": the progress log does not belong to this checkpoint");
    }
    kept = progress_log_text(log, checkpointed);
  }
  if (log.rows.size() > checkpointed && notes != nullptr) {
    *notes << "note: " << name << ": the rows of epochs " << checkpointed << " to " << log.rows.size() - 1
           << " were logged after the last checkpoint; they are dropped and those epochs run again\n";
  }
  if (kept != existing || !exists) write_file_atomically(path, kept);
  const std::string header = kept.empty() ? std::string() : kept.substr(0, kept.find('\n'));
  return ProgressCsv(path, header, kept);
}

void ProgressCsv::write_row(const std::vector<NamedScalar>& row) {
  const std::string header = header_of(row);
  std::string lines;
  if (header_.empty()) {
    header_ = header;
    lines = header_ + '\n';
  } else if (header != header_) {
    throw std::logic_error(path_.string() + ": the columns of this epoch (" + header +
                           ") differ from the file's header (" + header_ + ")");
  }
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) lines += ',';
    lines += format_csv_number(row[i].value);
  }
  lines += '\n';
  // One write of whole lines: a crash leaves the row whole or absent, or (if
  // the kernel stops mid-write) a torn last line without its newline.
  std::size_t written = 0;
  while (written < lines.size()) {
    const ssize_t n = ::write(fd_, lines.data() + written, lines.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("cannot write to " + path_.string() + ": " + std::strerror(errno));
    written += static_cast<std::size_t>(n);
  }
  contents_ += lines;
}

}  // namespace bsg::algos
