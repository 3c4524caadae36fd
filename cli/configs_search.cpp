#include "configs_search.h"

#include <utility>

#include "experiments/child_process.h"

namespace bsg::cli {
namespace {

// The installed configs relative to the installed program (e.g.
// ../share/bsg/configs from <prefix>/bin/bsg, set by CMake from the install
// directories), so that a prefix moved or staged with DESTDIR still finds its
// own configs. Empty if the program's location cannot be read.
std::filesystem::path installed_configs_dir() {
  try {
    return experiments::current_executable().parent_path() / BSG_INSTALLED_CONFIGS_FROM_PROGRAM;
  } catch (const std::exception&) {
    return {};
  }
}

}  // namespace

LocatedConfigs find_configs(const std::string& configs_option,
                            const std::filesystem::path& input_file,
                            const std::string& input_kind) {
  ConfigsSearchInputs inputs;
  inputs.explicit_dir = configs_option;
  inputs.input_file = input_file;
  inputs.input_kind = input_kind;
  inputs.installed_dir = installed_configs_dir();
  inputs.source_dir = BSG_SOURCE_CONFIGS_DIR;
  return locate_configs_from_here(std::move(inputs));
}

std::string describe_configs(const LocatedConfigs& configs) {
  return "configs: " + configs.dir.string() + " (" + configs.place + ")";
}

}  // namespace bsg::cli
