#include "algos/multi_agent/sequential_policy_step.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "algos/core/advantage_normalization.h"
#include "algos/multi_agent/happo_update.h"
#include "algos/multi_agent/macpo_update.h"

namespace bsg::algos {

SequentialPolicyStep sequential_policy_step(const RunConfig& config, std::vector<AgentBatch> batches,
                                            std::span<GaussianPolicy* const> policies, std::span<Ppo* const> ppos,
                                            double team_mean_episode_cost, std::span<const int> order,
                                            const MpiContext& mpi, Rng& minibatch_rng) {
  if (config.alg != Algorithm::happo && config.alg != Algorithm::macpo) {
    throw std::invalid_argument("sequential_policy_step: " + std::string(to_string(config.alg)) +
                                " is not a sequential multi-agent learner (happo, macpo)");
  }
  for (AgentBatch& batch : batches) {
    // As one column of cost advantages, or none: the same statistics the family's slots take.
    Eigen::MatrixXd cost_advantages = batch.cost_advantages.size() > 0 ? Eigen::MatrixXd(batch.cost_advantages)
                                                                       : Eigen::MatrixXd(batch.advantages.size(), 0);
    standardize_advantages(batch.advantages, cost_advantages, mpi);  // per agent, as SafePO's buffers
    batch.cost_advantages = cost_advantages.cols() > 0 ? Eigen::VectorXd(cost_advantages.col(0))
                                                       : Eigen::VectorXd::Zero(batch.advantages.size());
  }
  SequentialPolicyStep step;
  if (config.alg == Algorithm::happo) {
    step.round = happo_round(policies, ppos, batches, order, mpi, minibatch_rng);
  } else {
    const double c = macpo_constraint_violation(team_mean_episode_cost, config.cost_limit, config.gamma);
    step.constraint_violations.assign(policies.size(), c);
    step.round = macpo_round(policies, batches, order, step.constraint_violations, config, mpi);
  }
  std::sort(step.round.begin(), step.round.end(),
            [](const AgentRoundStatistics& a, const AgentRoundStatistics& b) { return a.agent < b.agent; });
  return step;
}

}  // namespace bsg::algos
