// The multi-agent ids (multi_agent_description.h), apart from the single-agent
// registry so that registered_ids() and everything that loops over it (the
// conformance suite, `bsg envs`) stay single-agent. It defines
// make_multi_agent, describe_multi_agent and multi_agent_ids of envs/multi_agent_env.h.
#include <map>
#include <stdexcept>

#include "envs/assembly/env_builder.h"
#include "envs/multi_agent_env.h"

namespace bsg::envs {
namespace {

const std::map<std::string, MultiAgentDescription>& multi_agent_registry() {
  static const std::map<std::string, MultiAgentDescription> entries = [] {
    std::map<std::string, MultiAgentDescription> result;
    for (const MultiAgentDescription& description : multi_agent_descriptions()) {
      if (!result.emplace(description.name, description).second) {
        throw std::logic_error("multi-agent environment registered twice: " + description.name);
      }
    }
    return result;
  }();
  return entries;
}

const MultiAgentDescription& find_multi_agent_description(const std::string& id) {
  const auto& entries = multi_agent_registry();
  const auto found = entries.find(id);
  if (found == entries.end()) {
    std::string valid;
    for (const auto& [name, entry] : entries) valid += (valid.empty() ? "" : ", ") + name;
    throw std::invalid_argument("unknown multi-agent environment id '" + id + "'; valid ids: " + valid);
  }
  return found->second;
}

}  // namespace

std::unique_ptr<MultiAgentEnv> make_multi_agent(const std::string& id, const EnvOptions& options) {
  return build_multi_agent_env(find_multi_agent_description(id), options);
}

std::unique_ptr<MultiAgentEnv> make_multi_agent(const MultiAgentDescription& description,
                                                const EnvOptions& options) {
  return build_multi_agent_env(description, options);
}

MultiAgentDescription describe_multi_agent(const std::string& id, const EnvOverrides& overrides) {
  return apply_multi_agent_overrides(find_multi_agent_description(id), overrides);
}

std::vector<std::string> multi_agent_ids() {
  std::vector<std::string> ids;
  for (const auto& [id, entry] : multi_agent_registry()) ids.push_back(id);
  return ids;
}

}  // namespace bsg::envs
