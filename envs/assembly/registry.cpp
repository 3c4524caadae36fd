#include "envs/assembly/registry.h"

#include <stdexcept>

#include "envs/assembly/env_builder.h"
#include "envs/assembly/id_map.h"
#include "envs/description/env_parameters.h"
#include "envs/description/fork_descriptions.h"
#include "envs/description/standard_descriptions.h"

namespace bsg::envs {

const std::map<std::string, EnvDescription>& registry() {
  static const std::map<std::string, EnvDescription> entries =
      id_map({standard_descriptions(), fork_descriptions()}, "environment");
  return entries;
}

const EnvDescription& find_description(const std::string& id) {
  return find_id(registry(), id, "environment");
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
