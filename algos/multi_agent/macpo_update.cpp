#include "algos/multi_agent/macpo_update.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "algos/core/policy_surrogate.h"

namespace bsg::algos {

double macpo_constraint_violation(double mean_episode_cost, double cost_limit, double gamma) {
  if (!std::isfinite(mean_episode_cost)) {
    throw std::invalid_argument("macpo_constraint_violation: mean_episode_cost (J_C) is not finite: " +
                                std::to_string(mean_episode_cost));
  }
  if (!(gamma >= 0.0 && gamma <= 1.0)) {
    throw std::invalid_argument("macpo_constraint_violation: gamma must lie in [0, 1], got " + std::to_string(gamma));
  }
  const double c = (mean_episode_cost - cost_limit) * (1.0 - gamma);  // c = (J_C - d)(1 - gamma)
  return c == 0.0 ? 1e-8 : c;  // SafePO: "if rescale_constraint_val == 0: rescale_constraint_val = 1e-8"
}

MacpoAgentStep macpo_agent_step(GaussianPolicy& policy, const AgentBatch& batch, const CorrectionFactor& factor,
                                double constraint_violation, const RunConfig& config, const MpiContext& mpi) {
  check_agent_batch(batch, policy, 0, batch.observations.rows());
  // L_R and L_C on M A and M A^C (M is a constant weight: no gradient through it).
  PolicySurrogate surrogate(batch.observations, batch.actions, batch.old_log_probs,
                            factor.corrected(batch.advantages), factor.corrected(batch.cost_advantages));
  // The CPO step reads neither J_C nor L: c is given.
  const PolicyUpdateInputs inputs{policy, surrogate, 0.0, 0.0, mpi};
  MacpoAgentStep step{single_constraint_cpo_update(inputs, constraint_violation, config), {}};
  step.diagnostics = single_constraint_cpo_diagnostics(inputs, step.update);
  return step;
}

std::vector<AgentRoundStatistics> macpo_round(std::span<GaussianPolicy* const> policies,
                                              std::span<const AgentBatch> batches, std::span<const int> order,
                                              std::span<const double> constraint_violations, const RunConfig& config,
                                              const MpiContext& mpi) {
  if (constraint_violations.size() != policies.size()) {
    throw std::invalid_argument("macpo_round: " + std::to_string(constraint_violations.size()) +
                                " constraint values for " + std::to_string(policies.size()) + " agents");
  }
  return sequential_round(policies, batches, order, [&](int agent, const CorrectionFactor& factor) {
    const auto k = static_cast<std::size_t>(agent);
    return macpo_agent_step(*policies[k], batches[k], factor, constraint_violations[k], config, mpi).diagnostics;
  });
}

}  // namespace bsg::algos
