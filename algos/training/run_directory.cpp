#include "algos/training/run_directory.h"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "common/file_reading.h"

namespace bsg::algos {

std::filesystem::path default_run_directory(const RunConfig& config) {
  char seed[32];
  std::snprintf(seed, sizeof(seed), "seed_%05lld", static_cast<long long>(config.seed));
  return std::filesystem::path(config.log_dir) / config.env_id / std::string(to_string(config.alg)) / seed;
}

void check_is_run_directory(const RunDirectory& directory) {
  if (!std::filesystem::is_directory(directory.root)) {
    throw std::runtime_error("run directory " + directory.root.string() + " does not exist");
  }
  for (const std::filesystem::path& file : {directory.config(), directory.checkpoint()}) {
    const std::string kind = file_kind(file);
    if (kind != "a regular file") {
      throw std::runtime_error(directory.root.string() + " is not a run directory: " + file.filename().string() +
                               " is " + kind + (kind == "missing" ? "" : ", not a file"));
    }
  }
}

void prepare_new_run_directory(const RunDirectory& directory) {
  if (std::filesystem::exists(directory.checkpoint()) || std::filesystem::exists(directory.progress())) {
    throw std::runtime_error("run directory " + directory.root.string() +
                             " already holds a run; continue it with 'bsg train --resume " +
                             directory.root.string() + "' or choose another --out");
  }
  std::error_code error;
  std::filesystem::create_directories(directory.root, error);
  if (error) throw std::runtime_error("cannot create run directory " + directory.root.string() + ": " + error.message());
}

}  // namespace bsg::algos
