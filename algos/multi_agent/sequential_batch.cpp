#include "algos/multi_agent/sequential_batch.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {

void check_agent_batches(std::span<const AgentBatch> batches, std::span<const GaussianPolicy> policies) {
  if (batches.size() != policies.size() || batches.empty()) {
    throw std::invalid_argument("sequential update: " + std::to_string(batches.size()) + " agent batches for " +
                                std::to_string(policies.size()) + " policies (expected one per policy, at least one)");
  }
  const Eigen::Index n = batches.front().observations.rows();
  if (n == 0) throw std::invalid_argument("sequential update: agent 0's batch is empty");
  for (std::size_t k = 0; k < batches.size(); ++k) {
    const AgentBatch& batch = batches[k];
    const GaussianPolicy& policy = policies[k];
    const std::string agent = "sequential update: agent " + std::to_string(k) + "'s ";
    const auto expect_rows = [&](Eigen::Index rows, const char* field) {
      if (rows != n) {
        throw std::invalid_argument(agent + field + " has " + std::to_string(rows) + " rows, agent 0's batch " +
                                    std::to_string(n) + " (row i must be the same joint step for every agent)");
      }
    };
    expect_rows(batch.observations.rows(), "observations");
    expect_rows(batch.actions.rows(), "actions");
    expect_rows(batch.old_log_probs.size(), "old_log_probs");
    expect_rows(batch.advantages.size(), "advantages");
    expect_rows(batch.cost_advantages.size(), "cost_advantages");
    if (batch.observations.cols() != policy.observation_size() || batch.actions.cols() != policy.action_size()) {
      throw std::invalid_argument(agent + "batch holds " + std::to_string(batch.observations.cols()) +
                                  "-d observations and " + std::to_string(batch.actions.cols()) +
                                  "-d actions, its policy maps " + std::to_string(policy.observation_size()) + " -> " +
                                  std::to_string(policy.action_size()));
    }
  }
}

}  // namespace bsg::algos
