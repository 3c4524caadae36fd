// The configs folder a command resolves its run (or grid) file against: the
// search of common/configs_location.h fed with what only the program knows,
// the current folder, $BSG_CONFIGS, where the installed configs lie relative
// to the installed program, and the source tree it was built from.
#pragma once

#include <filesystem>
#include <string>

#include "common/configs_location.h"

namespace bsg::cli {

// `configs_option` is --configs (empty: search); `input_file` the run or grid
// file (empty: none), named `input_kind` in messages. Throws ConfigError
// listing every place tried.
LocatedConfigs find_configs(const std::string& configs_option,
                            const std::filesystem::path& input_file, const std::string& input_kind);

// "configs: DIR (at or above the run file's folder)".
std::string describe_configs(const LocatedConfigs& configs);

}  // namespace bsg::cli
