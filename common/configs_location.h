// Finding the configs directory (the folder holding algorithms/ and envs/)
// that a run file is resolved against, so that `bsg train RUN.yaml` works from
// any folder, in a clone or installed.
//
// The search visits places in a fixed order and takes the first folder that
// holds an `algorithms/` subfolder:
//   1. `configs/` in the run (or grid) file's folder and each folder above it;
//   2. `configs/` in the current folder and each folder above it;
//   3. the folder named by $BSG_CONFIGS (if set, it must be a configs folder);
//   4. the installed configs (e.g. <prefix>/share/bsg/configs);
//   5. the source tree's configs/ (the clone the program was built from).
// An explicit folder (`--configs DIR`) replaces the whole search and must be a
// configs folder. The caller supplies the folders of places 2-5 (the current
// folder, the variable's value, the install layout): this file knows nothing
// of how the program is installed.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace bsg {

// One place of the search: its description for messages and the candidate
// folders it contributes, in order.
struct ConfigsPlace {
  std::string description;  // e.g. "at or above the run file's folder"
  std::vector<std::filesystem::path> candidates;
  // Named by the user ($BSG_CONFIGS, --configs): an error if it is reached
  // and its folder is not a configs folder, rather than a silent fall-through.
  bool required = false;
  std::string unavailable_note;  // why there is no candidate (e.g. "not set")
};

struct ConfigsSearchInputs {
  std::filesystem::path explicit_dir;           // --configs DIR; non-empty: the only place
  std::filesystem::path input_file;             // the run or grid file; empty: none
  std::string input_kind = "run file";          // how messages name input_file
  std::filesystem::path current_dir;            // empty: place 2 is skipped
  std::optional<std::string> configs_variable;  // $BSG_CONFIGS if set
  std::filesystem::path installed_dir;          // empty: unknown
  std::filesystem::path source_dir;             // empty: none
};

struct LocatedConfigs {
  std::filesystem::path dir;  // absolute
  std::string place;          // the description of the place it was found in
};

// True if `dir` holds an algorithms/ folder.
bool is_configs_dir(const std::filesystem::path& dir);

// The place "at or above `start`": start/configs, start/../configs, ... up to
// the filesystem root.
ConfigsPlace configs_at_or_above(const std::filesystem::path& start, std::string description);

// The places of the search above, in order, from the caller's inputs.
std::vector<ConfigsPlace> configs_search_places(const ConfigsSearchInputs& inputs);

// The first candidate that is a configs folder. Throws ConfigError listing
// every place and folder tried if none is, or if a required place is reached
// and is not one.
LocatedConfigs locate_configs_dir(const std::vector<ConfigsPlace>& places);

// The whole search from this process: `inputs` with current_dir (this process's folder) and
// configs_variable ($BSG_CONFIGS) filled in here; the program and the Python module give the
// rest (where their installed configs lie, the source tree).
LocatedConfigs locate_configs_from_here(ConfigsSearchInputs inputs);

}  // namespace bsg
