#include "envs/assembly/registry.h"

#include <stdexcept>

#include "envs/assembly/env_builder.h"
#include "envs/description/env_parameters.h"
#include "envs/description/fork_descriptions.h"
#include "envs/description/standard_descriptions.h"

namespace bsg::envs {

const std::map<std::string, EnvDescription>& registry() {
  static const std::map<std::string, EnvDescription> entries = [] {
    std::map<std::string, EnvDescription> result;
    for (const auto& list : {standard_descriptions(), fork_descriptions()}) {
      for (const EnvDescription& description : list) {
        if (!result.emplace(description.name, description).second) {
          throw std::logic_error("environment registered twice: " + description.name);
        }
      }
    }
    return result;
  }();
  return entries;
}

const EnvDescription& find_description(const std::string& id) {
  const auto& entries = registry();
  const auto found = entries.find(id);
  if (found == entries.end()) {
    std::string valid;
    for (const auto& [name, entry] : entries) valid += (valid.empty() ? "" : ", ") + name;
    throw std::invalid_argument("unknown environment id '" + id + "'; valid ids: " + valid);
  }
  return found->second;
}

std::unique_ptr<Env> make(const std::string& id, const EnvOptions& options) {
  return build_env(find_description(id), options);
}

std::unique_ptr<Env> make(const EnvDescription& description, const EnvOptions& options) {
  return build_env(description, options);
}

EnvDescription describe(const std::string& id, const EnvOverrides& overrides) {
  return apply_env_overrides(find_description(id), overrides);
}

bool has_lean_model(const std::string& id) { return agent_has_lean_model(find_description(id).agent); }

bool has_lean_model(const EnvDescription& description) { return agent_has_lean_model(description.agent); }

std::vector<std::string> registered_ids() {
  std::vector<std::string> ids;
  for (const auto& [id, entry] : registry()) ids.push_back(id);
  return ids;
}

}  // namespace bsg::envs
