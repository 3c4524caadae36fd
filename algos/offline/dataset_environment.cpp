#include "algos/offline/dataset_environment.h"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

namespace bsg::algos {

envs::EnvDescription dataset_env_description(const OfflineDataset& dataset) {
  const auto text = dataset.text_attributes.find("env_description");
  if (text == dataset.text_attributes.end()) {
    throw std::invalid_argument("dataset: no env_description attribute (not written by bsg collect?)");
  }
  envs::EnvOverrides overrides;
  try {
    const YAML::Node node = YAML::Load(text->second);
    if (!node.IsMap()) throw std::invalid_argument("not a mapping");
    // agent and task first: changing them restarts from their standard description.
    for (const char* first : {"agent", "task"}) {
      if (node[first]) overrides.emplace_back(first, node[first].as<std::string>());
    }
    for (const auto& entry : node) {
      const std::string key = entry.first.as<std::string>();
      if (key == "agent" || key == "task") continue;
      overrides.emplace_back(key, entry.second.IsSequence() ? YAML::Dump(entry.second) : entry.second.as<std::string>());
    }
    return envs::apply_env_overrides(envs::EnvDescription{}, overrides);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("dataset: the env_description attribute describes no environment: ") +
                                e.what());
  }
}

}  // namespace bsg::algos
