#include "algos/multi_agent/happo_update.h"

#include <stdexcept>
#include <string>

#include "algos/core/policy_surrogate.h"
#include "algos/first_order/first_order_update.h"

namespace bsg::algos {
namespace {

// The agent's batch with the advantages M A (and M A^C, which PPO does not read).
PolicySurrogate corrected_surrogate(const AgentBatch& batch, const CorrectionFactor& factor) {
  return PolicySurrogate(batch.observations, batch.actions, batch.old_log_probs, factor.corrected(batch.advantages),
                         factor.corrected(batch.cost_advantages));
}

}  // namespace

double happo_clipped_loss(const GaussianPolicy& policy, const AgentBatch& batch, const CorrectionFactor& factor,
                          double clip, Eigen::VectorXd* gradient) {
  check_agent_batch(batch, policy, 0, batch.observations.rows());
  const PolicySurrogate surrogate = corrected_surrogate(batch, factor);
  const Eigen::MatrixXd anchor_means = policy_means(policy, batch.observations);  // KL_i plays no part
  SampleLossBatch losses(surrogate, anchor_means, policy.log_stds());
  std::vector<Eigen::Index> rows(static_cast<std::size_t>(surrogate.num_samples()));
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<Eigen::Index>(i);
  return losses.loss(policy, rows, clipped_surrogate_loss(surrogate.advantages(), clip), gradient);
}

PolicyUpdateResult happo_agent_update(Ppo& ppo, GaussianPolicy& policy, const AgentBatch& batch,
                                      const CorrectionFactor& factor, const MpiContext& mpi, Rng& minibatch_rng) {
  check_agent_batch(batch, policy, 0, batch.observations.rows());
  PolicySurrogate surrogate = corrected_surrogate(batch, factor);
  // PPO reads neither J_C nor L.
  const PolicyUpdateInputs inputs{policy, surrogate, 0.0, 0.0, mpi, {}, &minibatch_rng};
  return ppo.update(inputs);
}

std::vector<AgentRoundStatistics> happo_round(std::span<GaussianPolicy* const> policies, std::span<Ppo* const> ppos,
                                              std::span<const AgentBatch> batches, std::span<const int> order,
                                              const MpiContext& mpi, Rng& minibatch_rng) {
  if (ppos.size() != policies.size()) {
    throw std::invalid_argument("happo_round: " + std::to_string(ppos.size()) + " PPO updates for " +
                                std::to_string(policies.size()) + " policies");
  }
  for (std::size_t k = 0; k < ppos.size(); ++k) {
    if (ppos[k] == nullptr) throw std::invalid_argument("happo_round: agent " + std::to_string(k) + "'s PPO is null");
  }
  return sequential_round(policies, batches, order, [&](int agent, const CorrectionFactor& factor) {
    const auto k = static_cast<std::size_t>(agent);
    return happo_agent_update(*ppos[k], *policies[k], batches[k], factor, mpi, minibatch_rng).diagnostics;
  });
}

}  // namespace bsg::algos
