// The HDF5 file of an offline dataset, in DSRL's layout (docs/datasets.md):
// at the root, the float32 datasets observations (N x obs), next_observations
// (N x obs), actions (N x act), rewards, costs, terminals and timeouts (N),
// with several constraints also constraint_costs (N x m); the root's
// attributes say how the data was made (strings, and float64 numbers such as
// the normalisation constants). DSRL's own loader (OfflineEnv.get_dataset)
// reads such a file as it reads its published ones.
#pragma once

#include <filesystem>

#include "algos/offline/offline_dataset.h"

namespace bsg::algos {

// Writes `dataset` (checked with check_dataset_shapes) to a temporary file
// beside `path` and renames it over `path`, so that a reader, or a collection
// killed half-way, never leaves a half-written file under that name. Throws
// std::runtime_error naming the path on failure.
void write_dataset_file(const std::filesystem::path& path, const OfflineDataset& dataset);

// Reads a file written by write_dataset_file, by DSRL or by D4RL. Arrays of
// any real or integer type, or booleans as h5py writes NumPy's bool (an HDF5
// enumeration over int8), are converted to float32 by value. Throws std::runtime_error with one
// line naming the file and what is wrong: missing, not HDF5, a missing key,
// an array of the wrong rank or length.
OfflineDataset read_dataset_file(const std::filesystem::path& path);

}  // namespace bsg::algos
