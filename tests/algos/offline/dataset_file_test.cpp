// The dataset file (algos/offline/dataset_file.h): a hand-made dataset written
// and read back is the same, value for value; the file has DSRL's keys,
// shapes and float32 type (checked with the HDF5 library directly, not through
// our reader); files written by h5py with the element types DSRL and D4RL
// use (bool flags, float64, float16, big-endian, integers, (N, 1) vectors)
// read by value; a file that is not HDF5 or lacks a key is refused with one line.
#include "algos/offline/dataset_file.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>

#include "../../test_support.h"

namespace bsg::algos {
namespace {

// Two episodes of 2 and 1 steps; observations 3-wide, actions 2-wide.
OfflineDataset small_dataset() {
  OfflineDataset d;
  d.observation_dim = 3;
  d.action_dim = 2;
  d.observations = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  d.next_observations = {3, 4, 5, 6.5f, 7, 8, 9, 10, 11};
  d.actions = {0.5f, -0.5f, 1, -1, 0.25f, 0};
  d.rewards = {1.5f, -2, 4};
  d.costs = {0, 1, 1};
  d.terminals = {0, 1, 0};
  d.timeouts = {0, 0, 1};
  d.text_attributes["env_id"] = "SafetyBallCircle-v0";
  d.number_attributes["cost_limit"] = 10.0;
  return d;
}

// The shape and element type of `name` in `file`, read with the HDF5 C API.
struct ArrayInfo {
  std::vector<hsize_t> dims;
  H5T_class_t type_class;
  std::size_t type_size;
};
ArrayInfo array_info(const std::filesystem::path& file, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  const hid_t s = H5Dget_space(d);
  const hid_t t = H5Dget_type(d);
  ArrayInfo info;
  info.dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(s)));
  H5Sget_simple_extent_dims(s, info.dims.data(), nullptr);
  info.type_class = H5Tget_class(t);
  info.type_size = H5Tget_size(t);
  H5Tclose(t);
  H5Sclose(s);
  H5Dclose(d);
  H5Fclose(f);
  return info;
}

TEST(DatasetFile, WrittenAndReadBackIsTheSame) {
  testing::TemporaryDirectory dir("dataset_file");
  const OfflineDataset d = small_dataset();
  write_dataset_file(dir.path() / "d.hdf5", d);
  const OfflineDataset back = read_dataset_file(dir.path() / "d.hdf5");
  EXPECT_EQ(back.observation_dim, 3);
  EXPECT_EQ(back.action_dim, 2);
  EXPECT_EQ(back.observations, d.observations);
  EXPECT_EQ(back.next_observations, d.next_observations);
  EXPECT_EQ(back.actions, d.actions);
  EXPECT_EQ(back.rewards, d.rewards);
  EXPECT_EQ(back.costs, d.costs);
  EXPECT_EQ(back.terminals, d.terminals);
  EXPECT_EQ(back.timeouts, d.timeouts);
  EXPECT_EQ(back.text_attributes.at("env_id"), "SafetyBallCircle-v0");
  EXPECT_EQ(back.number_attributes.at("cost_limit"), 10.0);
  EXPECT_TRUE(back.constraint_names.empty());
  // Readable by others, as common/atomic_file's files are.
  EXPECT_EQ(std::filesystem::status(dir.path() / "d.hdf5").permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write |
                std::filesystem::perms::group_read | std::filesystem::perms::others_read);
  // Nothing but the file itself is left in the directory (no temporary).
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator()), 1);
}

TEST(DatasetFile, HasDsrlKeysShapesAndFloat32) {
  testing::TemporaryDirectory dir("dataset_file");
  write_dataset_file(dir.path() / "d.hdf5", small_dataset());
  const std::filesystem::path file = dir.path() / "d.hdf5";
  const std::vector<std::pair<const char*, std::vector<hsize_t>>> expected = {
      {"observations", {3, 3}}, {"next_observations", {3, 3}}, {"actions", {3, 2}}, {"rewards", {3}},
      {"costs", {3}},           {"terminals", {3}},            {"timeouts", {3}}};
  for (const auto& [name, dims] : expected) {
    const ArrayInfo info = array_info(file, name);
    EXPECT_EQ(info.dims, dims) << name;
    EXPECT_EQ(info.type_class, H5T_FLOAT) << name;
    EXPECT_EQ(info.type_size, 4u) << name;
  }
}

TEST(DatasetFile, SeveralConstraintsKeepTheirMatrix) {
  testing::TemporaryDirectory dir("dataset_file");
  OfflineDataset d = small_dataset();
  d.constraint_names = {"cost_outside_bounds", "cost_velocity_violation"};
  d.constraint_costs = {0, 0, 1, 0, 0, 1};
  d.costs = {0, 1, 1};  // their sums
  write_dataset_file(dir.path() / "d.hdf5", d);
  const OfflineDataset back = read_dataset_file(dir.path() / "d.hdf5");
  EXPECT_EQ(back.constraint_names, d.constraint_names);
  EXPECT_EQ(back.constraint_costs, d.constraint_costs);
  EXPECT_EQ(array_info(dir.path() / "d.hdf5", "constraint_costs").dims, (std::vector<hsize_t>{3, 2}));
}

TEST(DatasetFile, EpisodesAndReturnRanges) {
  const std::vector<DatasetEpisode> episodes = dataset_episodes(small_dataset());
  ASSERT_EQ(episodes.size(), 2u);
  EXPECT_EQ(episodes[0].begin, 0u);
  EXPECT_EQ(episodes[0].end, 2u);
  EXPECT_TRUE(episodes[0].terminated);
  EXPECT_DOUBLE_EQ(episodes[0].reward_return, -0.5);
  EXPECT_DOUBLE_EQ(episodes[0].cost_return, 1.0);
  EXPECT_FALSE(episodes[1].terminated);
  const ReturnRanges r = return_ranges(episodes);
  EXPECT_DOUBLE_EQ(r.min_episode_reward, -0.5);
  EXPECT_DOUBLE_EQ(r.max_episode_reward, 4.0);
  EXPECT_DOUBLE_EQ(r.min_episode_cost, 1.0);
  EXPECT_DOUBLE_EQ(r.max_episode_cost, 1.0);
}

// One file per case, written by h5py with Debian's /usr/bin/python3 in one run: the small dataset's
// three rows, each array with the NumPy type its case gives ({key: dtype} as Python text, float32
// for the keys it leaves out), the vectors of shape `flat_shape`. Exit code 77: no h5py.
struct H5pyCase {
  const char* types;
  const char* flat_shape;  // "(3,)" or "(3, 1)"
};
int write_with_h5py(const std::filesystem::path& directory, const std::vector<H5pyCase>& cases) {
  const std::filesystem::path script = directory / "write.py";
  std::ofstream out(script);
  out << "import sys\n"
      << "try:\n    import h5py, numpy as np\nexcept ImportError:\n    sys.exit(77)\n"
      << "values = {'observations': [[0, 1, 2], [3, 4, 5], [6, 7, 8]],\n"
      << "          'next_observations': [[3, 4, 5], [6.5, 7, 8], [9, 10, 11]],\n"
      << "          'actions': [[0.5, -0.5], [1, -1], [0.25, 0]],\n"
      << "          'rewards': [1.5, -2, 4], 'costs': [0, 1, 1],\n"
      << "          'terminals': [False, True, False], 'timeouts': [False, False, True]}\n"
      << "def write(name, types, flat_shape):\n"
      << "    with h5py.File(name, 'w') as f:\n"
      << "        for key, value in values.items():\n"
      << "            array = np.array(value, dtype=types.get(key, np.float32))\n"
      << "            f.create_dataset(key, data=array if array.ndim == 2 else array.reshape(flat_shape),\n"
      << "                             compression='gzip')\n"
      << "        f.attrs['env_id'] = 'SafetyBallCircle-v0'\n"
      << "        f.attrs['cost_limit'] = 10.0\n";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    out << "write('" << (directory / ("d" + std::to_string(i) + ".hdf5")).string() << "', " << cases[i].types << ", "
        << cases[i].flat_shape << ")\n";
  }
  out.close();
  const int status = std::system(("/usr/bin/python3 " + script.string() + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(DatasetFile, ReadsTheTypesH5pyWritesForDsrlAndD4rl) {
  testing::TemporaryDirectory dir("dataset_file");
  const std::vector<H5pyCase> cases = {
      // D4RL's and DSRL's own: float32 arrays, NumPy bool flags (an HDF5 enum over int8).
      {"{'terminals': np.bool_, 'timeouts': np.bool_}", "(3,)"},
      // The same flags as (N, 1) columns, which DSRL's loader flattens.
      {"{'terminals': np.bool_, 'timeouts': np.bool_}", "(3, 1)"},
      // float64 observations and rewards, float16 actions, big-endian costs, integer flags.
      {"{'observations': np.float64, 'next_observations': np.float64, 'actions': np.float16,"
       " 'rewards': np.float64, 'costs': '>f4', 'terminals': np.int64, 'timeouts': np.uint8}",
       "(3,)"},
      // Integer costs, as a count of violations might be stored; int8 flags.
      {"{'costs': np.int32, 'terminals': np.int8, 'timeouts': np.int8}", "(3,)"},
  };
  const int status = write_with_h5py(dir.path(), cases);
  if (status == 77 || status == 127) GTEST_SKIP() << "no h5py for /usr/bin/python3 (Debian: python3-h5py)";
  ASSERT_EQ(status, 0);
  // h5py stores NumPy's bool as an enumeration of one byte, the type the reader once refused.
  EXPECT_EQ(array_info(dir.path() / "d0.hdf5", "terminals").type_class, H5T_ENUM);
  EXPECT_EQ(array_info(dir.path() / "d0.hdf5", "terminals").type_size, 1u);
  const OfflineDataset expected = small_dataset();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const OfflineDataset back = read_dataset_file(dir.path() / ("d" + std::to_string(i) + ".hdf5"));
    const char* types = cases[i].types;
    EXPECT_EQ(back.observation_dim, 3) << types;
    EXPECT_EQ(back.action_dim, 2) << types;
    // Every value of small_dataset() is exact in float16 and float32.
    EXPECT_EQ(back.observations, expected.observations) << types;
    EXPECT_EQ(back.next_observations, expected.next_observations) << types;
    EXPECT_EQ(back.actions, expected.actions) << types;
    EXPECT_EQ(back.rewards, expected.rewards) << types;
    EXPECT_EQ(back.costs, expected.costs) << types;
    EXPECT_EQ(back.terminals, expected.terminals) << types;
    EXPECT_EQ(back.timeouts, expected.timeouts) << types;
    EXPECT_EQ(back.text_attributes.at("env_id"), "SafetyBallCircle-v0");
    EXPECT_EQ(back.number_attributes.at("cost_limit"), 10.0);
  }
}

TEST(DatasetFile, RefusesAnArrayOfText) {
  testing::TemporaryDirectory dir("dataset_file");
  // Fixed-length text: b'False' and b'True'.
  const int status = write_with_h5py(dir.path(), {{"{'terminals': 'S5'}", "(3,)"}});
  if (status == 77 || status == 127) GTEST_SKIP() << "no h5py for /usr/bin/python3 (Debian: python3-h5py)";
  ASSERT_EQ(status, 0);
  const std::filesystem::path file = dir.path() / "d0.hdf5";
  try {
    read_dataset_file(file);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "dataset file " + file.string() +
                                         ": 'terminals' holds neither real numbers, integers nor booleans");
  }
}

TEST(DatasetFile, RefusesANonHdf5File) {
  testing::TemporaryDirectory dir("dataset_file");
  std::ofstream(dir.path() / "x.hdf5") << "observations,actions\n1,2\n";
  try {
    read_dataset_file(dir.path() / "x.hdf5");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "dataset file " + (dir.path() / "x.hdf5").string() + ": not an HDF5 file");
  }
}

TEST(DatasetFile, RefusesAMissingFile) {
  EXPECT_THROW(
      {
        try {
          read_dataset_file("/nonexistent/d.hdf5");
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "dataset file /nonexistent/d.hdf5: no such file");
          throw;
        }
      },
      std::runtime_error);
}

TEST(DatasetFile, RefusesAFileWithoutAKey) {
  testing::TemporaryDirectory dir("dataset_file");
  const std::filesystem::path file = dir.path() / "d.hdf5";
  write_dataset_file(file, small_dataset());
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(f, "timeouts", H5P_DEFAULT), 0);
  H5Fclose(f);
  try {
    read_dataset_file(file);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("missing key 'timeouts'"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(DatasetFile, RefusesMismatchedRowsBeforeWriting) {
  testing::TemporaryDirectory dir("dataset_file");
  OfflineDataset d = small_dataset();
  d.costs.pop_back();
  EXPECT_THROW(write_dataset_file(dir.path() / "d.hdf5", d), std::invalid_argument);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace bsg::algos
