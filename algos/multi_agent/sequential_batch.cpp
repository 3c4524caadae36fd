#include "algos/multi_agent/sequential_batch.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {

void check_agent_batch(const AgentBatch& batch, const GaussianPolicy& policy, std::size_t agent, Eigen::Index rows) {
  const std::string where = "sequential update: agent " + std::to_string(agent) + "'s ";
  if (rows <= 0) throw std::invalid_argument(where + "batch is empty");
  const auto expect_rows = [&](Eigen::Index actual, const char* field) {
    if (actual != rows) {
      throw std::invalid_argument(where + field + " has " + std::to_string(actual) + " rows, expected " +
                                  std::to_string(rows) + " (row i must be the same joint step for every agent)");
    }
  };
  expect_rows(batch.observations.rows(), "observations");
  expect_rows(batch.actions.rows(), "actions");
  expect_rows(batch.old_log_probs.size(), "old_log_probs");
  expect_rows(batch.advantages.size(), "advantages");
  expect_rows(batch.cost_advantages.size(), "cost_advantages");
  if (batch.observations.cols() != policy.observation_size() || batch.actions.cols() != policy.action_size()) {
    throw std::invalid_argument(where + "batch holds " + std::to_string(batch.observations.cols()) +
                                "-d observations and " + std::to_string(batch.actions.cols()) +
                                "-d actions, its policy maps " + std::to_string(policy.observation_size()) + " -> " +
                                std::to_string(policy.action_size()));
  }
}

void check_agent_batches(std::span<const AgentBatch> batches, std::span<GaussianPolicy* const> policies) {
  if (batches.size() != policies.size() || batches.empty()) {
    throw std::invalid_argument("sequential update: " + std::to_string(batches.size()) + " agent batches for " +
                                std::to_string(policies.size()) + " policies (expected one per policy, at least one)");
  }
  for (std::size_t k = 0; k < batches.size(); ++k) {
    if (policies[k] == nullptr) {
      throw std::invalid_argument("sequential update: agent " + std::to_string(k) + "'s policy is null");
    }
    check_agent_batch(batches[k], *policies[k], k, batches.front().observations.rows());
  }
}

}  // namespace bsg::algos
