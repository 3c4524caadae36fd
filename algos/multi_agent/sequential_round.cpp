#include "algos/multi_agent/sequential_round.h"

#include <stdexcept>

#include "algos/first_order/first_order_update.h"
#include "algos/multi_agent/sequential_order.h"

namespace bsg::algos {
namespace {

// [theta, s] with a learned log sigma, else theta.
Eigen::VectorXd all_parameters(const GaussianPolicy& policy) {
  const Eigen::VectorXd& theta = policy.mean_net().parameters();
  if (!policy.has_learned_std()) return theta;
  Eigen::VectorXd parameters(theta.size() + policy.log_stds().size());
  parameters << theta, policy.log_stds();
  return parameters;
}

Eigen::VectorXd log_probs_of(const GaussianPolicy& policy, const Eigen::MatrixXd& means, const AgentBatch& batch) {
  Eigen::VectorXd log_probs(means.rows());
  policy.log_prob_batch(means, batch.actions, log_probs);  // log pi(a_i|o_i), summed over the action dims
  return log_probs;
}

}  // namespace

std::vector<AgentRoundStatistics> sequential_round(std::span<GaussianPolicy* const> policies,
                                                   std::span<const AgentBatch> batches, std::span<const int> order,
                                                   const AgentUpdate& update_agent) {
  check_agent_batches(batches, policies);
  check_agent_order(order, static_cast<int>(policies.size()));
  if (!update_agent) throw std::invalid_argument("sequential_round: update_agent is empty");
  CorrectionFactor factor(batches.front().observations.rows());
  std::vector<AgentRoundStatistics> statistics;
  for (std::size_t position = 0; position < order.size(); ++position) {
    const int agent = order[position];
    GaussianPolicy& policy = *policies[static_cast<std::size_t>(agent)];
    const AgentBatch& batch = batches[static_cast<std::size_t>(agent)];
    const Eigen::MatrixXd means_before = policy_means(policy, batch.observations);
    const Eigen::VectorXd log_probs_before = log_probs_of(policy, means_before, batch);
    const Eigen::VectorXd parameters_before = all_parameters(policy);
    const Eigen::VectorXd log_stds_before = policy.log_stds();

    AgentRoundStatistics entry;
    entry.agent = agent;
    entry.position = static_cast<int>(position);
    entry.factor = factor.statistics();
    entry.diagnostics = update_agent(agent, factor);

    const Eigen::MatrixXd means_after = policy_means(policy, batch.observations);
    entry.kl = policy.has_learned_std() ? policy.mean_kl(means_before, means_after, log_stds_before)
                                        : policy.mean_kl(means_before, means_after);
    entry.step_norm = (all_parameters(policy) - parameters_before).norm();
    factor.include_agent(log_probs_of(policy, means_after, batch), log_probs_before);  // M *= pi_new / pi_old
    statistics.push_back(std::move(entry));
  }
  return statistics;
}

}  // namespace bsg::algos
