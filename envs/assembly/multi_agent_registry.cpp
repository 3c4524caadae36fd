// The multi-agent ids (multi_agent_description.h), apart from the single-agent
// registry so that registered_ids() and everything that loops over it (the
// conformance suite, `bsg envs`) stay single-agent. It defines
// make_multi_agent, describe_multi_agent and multi_agent_ids of envs/multi_agent_env.h.
#include <map>

#include "envs/assembly/env_builder.h"
#include "envs/assembly/id_map.h"
#include "envs/multi_agent_env.h"

namespace bsg::envs {
namespace {

const std::map<std::string, MultiAgentDescription>& multi_agent_registry() {
  static const std::map<std::string, MultiAgentDescription> entries =
      id_map({multi_agent_descriptions()}, "multi-agent environment");
  return entries;
}

const MultiAgentDescription& find_multi_agent_description(const std::string& id) {
  return find_id(multi_agent_registry(), id, "multi-agent environment");
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
