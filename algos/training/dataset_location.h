// Where a run's `dataset:` key points. A file is taken as it is; a directory
// holds one dataset per environment, named `<env_id>.hdf5` as
// `bsg dataset make` writes them, either in the directory itself or in one of
// its subdirectories (one level down: `bsg dataset make RECIPE --out
// DIR/<recipe>` for several recipes), so that one grid can sweep offline
// learners over the datasets of several environments (docs/datasets.md).
#pragma once

#include <filesystem>
#include <string>

namespace bsg::algos {

// The dataset file of environment `env_id` at `location` (a file or a
// directory), absolute and normalised. Throws std::invalid_argument with one
// line when `location` does not exist, when a directory holds no
// `<env_id>.hdf5` at either level, or holds more than one (naming them).
std::filesystem::path locate_dataset(const std::filesystem::path& location, const std::string& env_id);

}  // namespace bsg::algos
