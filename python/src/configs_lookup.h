// The configs folder bsg.train and bsg.sweep resolve a run or grid against: the search of
// common/configs_location.h, as `bsg train` searches (cli/configs_search.h), with the installed
// configs found relative to the installed package instead of the installed program.
#pragma once

#include <filesystem>
#include <string>

#include "common/configs_location.h"

namespace bsg::python {

// `configs_option` is the configs= argument (empty: search); `input_file` the run or grid file
// (empty: none), named `input_kind` in messages; `package_dir` the folder of the bsg package.
// Throws ConfigError listing every place tried.
LocatedConfigs find_configs(const std::string& configs_option, const std::filesystem::path& input_file,
                            const std::string& input_kind, const std::filesystem::path& package_dir);

}  // namespace bsg::python
