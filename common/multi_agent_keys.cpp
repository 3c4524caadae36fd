// The rows of MultiAgentKeys (common/multi_agent_keys.h) in the key table, after the budget rows.
#include "common/multi_agent_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg::key_rows {

// clang-format off
std::vector<ConfigKeyRow> multi_agent_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using K = MultiAgentKeys;
  return {
    // --- multi-agent learners (docs/multi_agent.md#learners) ---
    boolean("share_policy", field<&R::multi_agent, &K::share_policy>(), L::algorithm, kMultiAgent,
            "one actor and one pair of centralised critics for every agent, each input with the agent's "
            "one-hot id appended (agents' observation sizes must be equal); false: one of each per agent"),
  };
}
// clang-format on

}  // namespace bsg::key_rows
