#include "configs_lookup.h"

#include <utility>

namespace bsg::python {

LocatedConfigs find_configs(const std::string& configs_option, const std::filesystem::path& input_file,
                            const std::string& input_kind, const std::filesystem::path& package_dir) {
  ConfigsSearchInputs inputs;
  inputs.explicit_dir = configs_option;
  inputs.input_file = input_file;
  inputs.input_kind = input_kind;
  // python/CMakeLists.txt: <prefix>/share/bsg/configs from <prefix>/<python dir>/bsg.
  if (!package_dir.empty()) inputs.installed_dir = package_dir / BSG_INSTALLED_CONFIGS_FROM_PACKAGE;
  inputs.source_dir = BSG_SOURCE_CONFIGS_DIR;
  return locate_configs_from_here(std::move(inputs));
}

}  // namespace bsg::python
