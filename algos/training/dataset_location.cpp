#include "algos/training/dataset_location.h"

#include <algorithm>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace bsg::algos {

namespace fs = std::filesystem;

namespace {

fs::path normalised(const fs::path& path) { return fs::absolute(path).lexically_normal(); }

bool is_existing_file(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

}  // namespace

fs::path locate_dataset(const fs::path& location, const std::string& env_id) {
  std::error_code error;
  if (!fs::exists(location, error)) {
    // A missing file keeps its path: the reader's own error names it, as for every dataset.
    return normalised(location);
  }
  if (!fs::is_directory(location, error)) return normalised(location);
  const std::string file_name = env_id + ".hdf5";
  std::vector<fs::path> found;
  if (is_existing_file(location / file_name)) found.push_back(location / file_name);
  // Sorted, so that the message naming several candidates reads the same on every machine.
  std::vector<fs::path> subdirectories;
  for (const fs::directory_entry& entry : fs::directory_iterator(location, error)) {
    if (entry.is_directory(error)) subdirectories.push_back(entry.path());
  }
  std::sort(subdirectories.begin(), subdirectories.end());
  for (const fs::path& subdirectory : subdirectories) {
    if (is_existing_file(subdirectory / file_name)) found.push_back(subdirectory / file_name);
  }
  const std::string where = "dataset " + location.string() + ": ";
  if (found.empty()) {
    throw std::invalid_argument(where + "a directory with no " + file_name + " in it or in its subdirectories (" +
                                env_id + "'s dataset, as bsg dataset make names it)");
  }
  if (found.size() > 1) {
    std::string names;
    for (const fs::path& path : found) names += (names.empty() ? "" : ", ") + path.string();
    throw std::invalid_argument(where + "holds " + std::to_string(found.size()) + " files named " + file_name + " (" +
                                names + "): name the one to learn from");
  }
  return normalised(found.front());
}

}  // namespace bsg::algos
