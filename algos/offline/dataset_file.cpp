#include "algos/offline/dataset_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <hdf5.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

#include "common/atomic_file.h"

namespace bsg::algos {
namespace {

// HDF5 prints its error stack to stderr by default; we report one line of our
// own instead. The handler is the library's, so it is restored on exit.
class QuietHdf5Errors {
 public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

// One HDF5 identifier, closed by its own close function.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw std::runtime_error("dataset file " + path.string() + ": " + what);
}

void check(herr_t status, const std::filesystem::path& path, const std::string& what) {
  if (status < 0) fail(path, what);
}

// Rows are chunked and compressed (gzip level 4): observations of a sampled
// policy compress little, the flags and many costs a lot.
constexpr hsize_t kChunkRows = 4096;

void write_array(hid_t file, const std::filesystem::path& path, const char* name, const std::vector<float>& values,
                 hsize_t rows, hsize_t columns) {
  const bool matrix = columns > 0;
  const std::array<hsize_t, 2> dims{rows, columns};
  Handle space(H5Screate_simple(matrix ? 2 : 1, dims.data(), nullptr), H5Sclose);
  Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!space.valid() || !properties.valid()) fail(path, std::string("cannot describe ") + name);
  // No modification times: the same data gives the same bytes.
  check(H5Pset_obj_track_times(properties.get(), false), path, "cannot describe " + std::string(name));
  if (rows > 0) {
    const std::array<hsize_t, 2> chunk{std::min(rows, kChunkRows), columns};
    check(H5Pset_chunk(properties.get(), matrix ? 2 : 1, chunk.data()), path, "cannot chunk " + std::string(name));
    check(H5Pset_deflate(properties.get(), 4), path, "cannot compress " + std::string(name));
  }
  Handle dataset(H5Dcreate2(file, name, H5T_IEEE_F32LE, space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                 H5Dclose);
  if (!dataset.valid()) fail(path, std::string("cannot create ") + name);
  if (rows > 0) {
    check(H5Dwrite(dataset.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), path,
          std::string("cannot write ") + name);
  }
}

void write_text_attribute(hid_t file, const std::filesystem::path& path, const std::string& name,
                          const std::string& value) {
  // Variable-length UTF-8, which h5py reads as a Python str.
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  check(H5Tset_size(type.get(), H5T_VARIABLE), path, "cannot describe attribute " + name);
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), path, "cannot describe attribute " + name);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(file, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) fail(path, "cannot create attribute " + name);
  const char* text = value.c_str();
  check(H5Awrite(attribute.get(), type.get(), &text), path, "cannot write attribute " + name);
}

void write_number_attribute(hid_t file, const std::filesystem::path& path, const std::string& name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(file, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) fail(path, "cannot create attribute " + name);
  check(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value), path, "cannot write attribute " + name);
}

void write_contents(const std::filesystem::path& temporary, const std::filesystem::path& path,
                    const OfflineDataset& dataset) {
  Handle creation(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  check(H5Pset_obj_track_times(creation.get(), false), path, "cannot describe the file");
  Handle file(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, creation.get(), H5P_DEFAULT), H5Fclose);
  if (!file.valid()) fail(path, "cannot create the HDF5 file " + temporary.string());
  const hsize_t n = dataset.size();
  const auto obs = static_cast<hsize_t>(dataset.observation_dim);
  write_array(file.get(), path, "observations", dataset.observations, n, obs);
  write_array(file.get(), path, "next_observations", dataset.next_observations, n, obs);
  write_array(file.get(), path, "actions", dataset.actions, n, static_cast<hsize_t>(dataset.action_dim));
  write_array(file.get(), path, "rewards", dataset.rewards, n, 0);
  write_array(file.get(), path, "costs", dataset.costs, n, 0);
  write_array(file.get(), path, "terminals", dataset.terminals, n, 0);
  write_array(file.get(), path, "timeouts", dataset.timeouts, n, 0);
  if (!dataset.constraint_names.empty()) {
    write_array(file.get(), path, "constraint_costs", dataset.constraint_costs, n, dataset.constraint_names.size());
    std::string names;
    for (const std::string& name : dataset.constraint_names) names += (names.empty() ? "" : ",") + name;
    write_text_attribute(file.get(), path, "constraint_names", names);
  }
  for (const auto& [name, value] : dataset.text_attributes) write_text_attribute(file.get(), path, name, value);
  for (const auto& [name, value] : dataset.number_attributes) write_number_attribute(file.get(), path, name, value);
  check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), path, "cannot flush " + temporary.string());
}

// A fresh temporary beside `path`, named as common/atomic_file.h names its own
// (<path>.tmp.<pid>.<6 characters>) so that remove_stale_temporaries knows it.
std::filesystem::path make_temporary(const std::filesystem::path& path) {
  std::string name = atomic_temporary_prefix(path).string() + std::to_string(::getpid()) + ".XXXXXX";
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0) fail(path, std::string("cannot create a temporary file: ") + std::strerror(errno));
  ::fchmod(fd, 0644);  // as common/atomic_file does: mkostemp makes 0600
  ::close(fd);
  return name;
}

void sync_file(const std::filesystem::path& file, const std::filesystem::path& path) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    fail(path, "cannot sync " + file.string() + ": " + std::strerror(error));
  }
  ::close(fd);
}

}  // namespace

void write_dataset_file(const std::filesystem::path& path, const OfflineDataset& dataset) {
  check_dataset_shapes(dataset);
  for (const auto& [name, value] : dataset.text_attributes) {
    if (dataset.number_attributes.count(name) > 0) fail(path, "attribute " + name + " is both text and a number");
  }
  const QuietHdf5Errors quiet;
  const std::filesystem::path temporary = make_temporary(path);
  try {
    write_contents(temporary, path, dataset);
    sync_file(temporary, path);
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) fail(path, "cannot rename " + temporary.string() + " over it: " + error.message());
    const std::filesystem::path directory = path.parent_path().empty() ? "." : path.parent_path();
    sync_file(directory, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

namespace {

const char* const kRequiredKeys[] = {"observations", "next_observations", "actions", "rewards",
                                     "costs",        "terminals",         "timeouts"};

// Whether HDF5 converts the element type to float by value: reals and
// integers of any width and byte order (D4RL's and DSRL's float32 and
// float64, int64 or uint8 flags), and enumerations over an integer, which is
// how h5py stores NumPy's bool (FALSE = 0, TRUE = 1): D4RL's terminals and
// timeouts, and most likely DSRL's.
bool holds_numbers(hid_t type) {
  const H5T_class_t type_class = H5Tget_class(type);
  if (type_class == H5T_FLOAT || type_class == H5T_INTEGER) return true;
  if (type_class != H5T_ENUM) return false;
  Handle base(H5Tget_super(type), H5Tclose);
  return base.valid() && H5Tget_class(base.get()) == H5T_INTEGER;
}

// Reads `name` as float32; `columns` is 0 for a vector, else the expected
// second dimension (-1: take it from the file). Returns the rows and columns.
std::vector<float> read_array(hid_t file, const std::filesystem::path& path, const char* name, int rank,
                              hsize_t& rows, hsize_t& columns) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) {
    fail(path, std::string("missing key '") + name +
                   "' (a DSRL dataset has observations, next_observations, actions, rewards, costs, terminals, "
                   "timeouts)");
  }
  Handle dataset(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) fail(path, std::string("'") + name + "' is not an array");
  Handle type(H5Dget_type(dataset.get()), H5Tclose);
  if (!holds_numbers(type.get())) {
    fail(path, std::string("'") + name + "' holds neither real numbers, integers nor booleans");
  }
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  const int file_rank = H5Sget_simple_extent_ndims(space.get());
  std::array<hsize_t, 2> dims{0, 1};
  if (file_rank == 2 && rank == 1) {
    // DSRL accepts (N, 1) for a vector.
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    if (dims[1] != 1) fail(path, std::string("'") + name + "' has shape (" + std::to_string(dims[0]) + ", " +
                                     std::to_string(dims[1]) + "), expected (N,)");
  } else if (file_rank != rank) {
    fail(path, std::string("'") + name + "' has " + std::to_string(file_rank) + " dimensions, expected " +
                   std::to_string(rank));
  } else {
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  }
  rows = dims[0];
  columns = rank == 2 ? dims[1] : 0;
  std::vector<float> values(static_cast<std::size_t>(dims[0] * dims[1]));
  if (!values.empty()) {
    check(H5Dread(dataset.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), path,
          std::string("cannot read '") + name + "'");
  }
  return values;
}

struct AttributeSink {
  OfflineDataset* dataset;
  const std::filesystem::path* path;
};

herr_t read_attribute(hid_t location, const char* name, const H5A_info_t*, void* data) {
  AttributeSink& sink = *static_cast<AttributeSink*>(data);
  Handle attribute(H5Aopen(location, name, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) return -1;
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  Handle space(H5Aget_space(attribute.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) return 0;  // arrays of values: not ours, left out
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (type_class == H5T_FLOAT || type_class == H5T_INTEGER) {
    double value = 0.0;
    if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0) return -1;
    sink.dataset->number_attributes[name] = value;
  } else if (type_class == H5T_STRING) {
    if (H5Tis_variable_str(type.get()) > 0) {
      Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(memory_type.get(), H5T_VARIABLE);
      H5Tset_cset(memory_type.get(), H5Tget_cset(type.get()));
      char* text = nullptr;
      if (H5Aread(attribute.get(), memory_type.get(), &text) < 0) return -1;
      sink.dataset->text_attributes[name] = text == nullptr ? "" : text;
      H5free_memory(text);
    } else {
      const std::size_t size = H5Tget_size(type.get());
      std::string text(size, '\0');
      if (H5Aread(attribute.get(), type.get(), text.data()) < 0) return -1;
      text.resize(std::strlen(text.c_str()));
      sink.dataset->text_attributes[name] = text;
    }
  }
  return 0;
}

}  // namespace

OfflineDataset read_dataset_file(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) fail(path, "no such file");
  const QuietHdf5Errors quiet;
  if (H5Fis_hdf5(path.c_str()) <= 0) fail(path, "not an HDF5 file");
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) fail(path, "cannot open it as HDF5");
  OfflineDataset dataset;
  for (const char* key : kRequiredKeys) {
    if (H5Lexists(file.get(), key, H5P_DEFAULT) <= 0) {
      fail(path, std::string("missing key '") + key +
                     "' (a DSRL dataset has observations, next_observations, actions, rewards, costs, "
                     "terminals, timeouts)");
    }
  }
  hsize_t n = 0;
  hsize_t rows = 0;
  hsize_t columns = 0;
  dataset.observations = read_array(file.get(), path, "observations", 2, n, columns);
  dataset.observation_dim = static_cast<int>(columns);
  const auto expect_rows = [&](const char* name) {
    if (rows != n) {
      fail(path, std::string("'") + name + "' has " + std::to_string(rows) + " rows, observations " +
                     std::to_string(n));
    }
  };
  hsize_t next_columns = 0;
  dataset.next_observations = read_array(file.get(), path, "next_observations", 2, rows, next_columns);
  expect_rows("next_observations");
  if (next_columns != columns) {
    fail(path, "'next_observations' has " + std::to_string(next_columns) + " columns, observations " +
                   std::to_string(columns));
  }
  dataset.actions = read_array(file.get(), path, "actions", 2, rows, columns);
  expect_rows("actions");
  dataset.action_dim = static_cast<int>(columns);
  struct VectorKey {
    const char* name;
    std::vector<float> OfflineDataset::*array;
  };
  for (const VectorKey& key : {VectorKey{"rewards", &OfflineDataset::rewards}, VectorKey{"costs", &OfflineDataset::costs},
                               VectorKey{"terminals", &OfflineDataset::terminals},
                               VectorKey{"timeouts", &OfflineDataset::timeouts}}) {
    dataset.*key.array = read_array(file.get(), path, key.name, 1, rows, columns);
    expect_rows(key.name);
  }
  AttributeSink sink{&dataset, &path};
  hsize_t index = 0;
  check(H5Aiterate2(file.get(), H5_INDEX_NAME, H5_ITER_INC, &index, read_attribute, &sink), path,
        "cannot read its attributes");
  if (H5Lexists(file.get(), "constraint_costs", H5P_DEFAULT) > 0) {
    dataset.constraint_costs = read_array(file.get(), path, "constraint_costs", 2, rows, columns);
    expect_rows("constraint_costs");
    const auto names = dataset.text_attributes.find("constraint_names");
    if (names == dataset.text_attributes.end()) fail(path, "'constraint_costs' without a constraint_names attribute");
    std::string list = names->second;
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t comma = std::min(list.find(',', start), list.size());
      dataset.constraint_names.push_back(list.substr(start, comma - start));
      start = comma + 1;
    }
    dataset.text_attributes.erase(names);
    if (dataset.constraint_names.size() != columns) {
      fail(path, "'constraint_costs' has " + std::to_string(columns) + " columns but constraint_names lists " +
                     std::to_string(dataset.constraint_names.size()));
    }
  }
  try {
    check_dataset_shapes(dataset);
  } catch (const std::invalid_argument& e) {
    fail(path, e.what());
  }
  return dataset;
}

}  // namespace bsg::algos
