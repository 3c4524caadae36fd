#include "env_set_arguments.h"

#include <stdexcept>

namespace bsg::cli {

envs::EnvOverrides parse_env_set_arguments(const std::vector<std::string>& arguments) {
  envs::EnvOverrides overrides;
  for (const std::string& argument : arguments) {
    const size_t equals = argument.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw std::invalid_argument("--set " + argument + ": expected key=value, e.g. --set bombs=12");
    }
    overrides.emplace_back(argument.substr(0, equals), argument.substr(equals + 1));
  }
  return overrides;
}

}  // namespace bsg::cli
