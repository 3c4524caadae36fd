#include "algos/trust_region/trust_region_steps.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

ConjugateGradientOptions conjugate_gradient_options(const RunConfig& config) {
  ConjugateGradientOptions options;
  options.iterations = config.trust_region.cg_iters;
  return options;
}

FisherVectorProductOptions fisher_vector_product_options(const RunConfig& config) {
  FisherVectorProductOptions options;
  options.damping_coeff = config.trust_region.cg_damping;
  options.subsample_stride = config.trust_region.fvp_subsample;
  return options;
}

LineSearchOptions line_search_options(const RunConfig& config) {
  LineSearchOptions options;
  options.budget = config.trust_region.backtrack_budget;
  options.decay = config.trust_region.backtrack_decay;
  options.target_kl = config.trust_region.target_kl;
  options.kl_accept_factor = config.trust_region.kl_accept_factor;
  return options;
}

LinearOperator as_linear_operator(FisherVectorProduct& fisher) {
  return [&fisher](const Eigen::Ref<const Eigen::VectorXd>& direction, Eigen::Ref<Eigen::VectorXd> product) {
    fisher.apply(direction, product);
  };
}

PolicyGradients averaged_policy_gradients(const PolicyUpdateInputs& inputs) {
  const Eigen::Index num_parameters = inputs.policy.mean_net().num_parameters();
  Eigen::VectorXd both(2 * num_parameters);
  inputs.surrogate.gradient(inputs.policy, 1.0, 0.0, both.head(num_parameters));  // grad L_R
  inputs.surrogate.gradient(inputs.policy, 0.0, 1.0, both.tail(num_parameters));  // grad L_C
  inputs.mpi.average_in_place(both);                                               // one allreduce
  PolicyGradients gradients;
  gradients.reward = both.head(num_parameters);  // g = avg grad L_R
  gradients.cost = both.tail(num_parameters);    // b = avg grad L_C
  return gradients;
}

void apply_line_search_result(GaussianPolicy& policy, const Eigen::VectorXd& theta_old,
                              const LineSearchResult& result) {
  if (result.accepted()) {
    policy.mean_net().set_parameters(theta_old + result.step);  // theta = theta_old + final step
  } else {
    policy.mean_net().set_parameters(theta_old);  // bit-identical restore
  }
}

double per_step_constraint_violation(double mean_episode_cost, double mean_episode_length, double cost_limit) {
  if (!std::isfinite(mean_episode_cost)) {
    throw std::invalid_argument("per_step_constraint_violation: mean_episode_cost (J_C) is not finite: " +
                                std::to_string(mean_episode_cost) + " (no episode completed this epoch?)");
  }
  if (!std::isfinite(mean_episode_length) || mean_episode_length < 0.0) {
    throw std::invalid_argument("per_step_constraint_violation: mean_episode_length (L) must be finite and >= 0, got " +
                                std::to_string(mean_episode_length));
  }
  return (mean_episode_cost - cost_limit) / (mean_episode_length + 1e-8);  // c = (J_C - d) / (L + 1e-8)
}

ConstraintGradients averaged_constraint_gradients(const PolicyUpdateInputs& inputs) {
  const Eigen::Index num_parameters = inputs.policy.mean_net().num_parameters();
  const int m = inputs.surrogate.constraint_count();
  Eigen::VectorXd all((1 + m) * num_parameters);
  inputs.surrogate.gradient(inputs.policy, 1.0, 0.0, all.head(num_parameters));  // grad L_R
  std::vector<double> weights(static_cast<std::size_t>(m), 0.0);
  for (int j = 0; j < m; ++j) {
    weights[static_cast<std::size_t>(j)] = 1.0;  // grad L_Cj
    inputs.surrogate.gradient(inputs.policy, 0.0, weights, all.segment((1 + j) * num_parameters, num_parameters));
    weights[static_cast<std::size_t>(j)] = 0.0;
  }
  inputs.mpi.average_in_place(all);  // one allreduce
  ConstraintGradients gradients;
  gradients.reward = all.head(num_parameters);
  gradients.costs = Eigen::Map<const Eigen::MatrixXd>(all.data() + num_parameters, num_parameters, m);
  return gradients;
}

Eigen::VectorXd per_step_constraint_violations(std::span<const ConstraintEstimate> constraints,
                                               double mean_episode_length) {
  Eigen::VectorXd c(static_cast<Eigen::Index>(constraints.size()));
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    c[static_cast<Eigen::Index>(i)] = per_step_constraint_violation(constraints[i].mean_episode_cost,
                                                                    mean_episode_length, constraints[i].limit);
  }
  return c;
}

Eigen::VectorXd averaged_cost_surrogates(const SurrogateValues& values, int constraint_count, const MpiContext& mpi) {
  Eigen::VectorXd averaged =
      Eigen::Map<const Eigen::VectorXd>(values.cost_surrogates.data(), constraint_count);
  mpi.average_in_place(averaged);
  return averaged;
}

ConstrainedEvaluator all_constraints_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                                               Eigen::VectorXd averaged_cost_surrogates_old,
                                               Eigen::VectorXd allowances) {
  return [&inputs, &theta_old, old = std::move(averaged_cost_surrogates_old),
          allowance = std::move(allowances)](const Eigen::Ref<const Eigen::VectorXd>& step) {
    inputs.policy.mean_net().set_parameters(theta_old + step);
    const SurrogateValues values = inputs.surrogate.evaluate(inputs.policy);
    const Eigen::VectorXd cost = averaged_cost_surrogates(values, static_cast<int>(old.size()), inputs.mpi);
    const double margin = (cost - old - allowance).maxCoeff();  // <= 0: every D_j <= max(-c_j, 0)
    return ConstrainedTrial{-values.reward_surrogate, margin, values.kl};
  };
}

LineSearchResult constrained_line_search_all(const PolicyUpdateInputs& inputs, const PolicyUpdateStart& start,
                                             const Eigen::VectorXd& full_step, const Eigen::VectorXd& violations,
                                             bool require_reward_improvement, const RunConfig& config) {
  ConstrainedLineSearchInputs search_inputs;
  search_inputs.reward_loss_old = -start.before.reward_surrogate;
  search_inputs.cost_surrogate_old = 0.0;  // the evaluator returns the largest margin, accepted if <= 0
  search_inputs.constraint_violation = 0.0;
  search_inputs.require_reward_improvement = require_reward_improvement;
  const int m = static_cast<int>(violations.size());
  return constrained_line_search(
      full_step, search_inputs,
      all_constraints_evaluator(inputs, start.theta_old, averaged_cost_surrogates(start.before, m, inputs.mpi),
                                (-violations).cwiseMax(0.0)),
      inputs.mpi, line_search_options(config));
}

LossEvaluator surrogate_loss_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                                       double reward_weight, std::vector<double> cost_weights) {
  return [&inputs, &theta_old, reward_weight, weights = std::move(cost_weights)](
             const Eigen::Ref<const Eigen::VectorXd>& step) {
    inputs.policy.mean_net().set_parameters(theta_old + step);
    const SurrogateValues values = inputs.surrogate.evaluate(inputs.policy);
    return LossAndKl{weighted_surrogate_loss(values, reward_weight, weights), values.kl};
  };
}

LossEvaluator surrogate_loss_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old,
                                       double reward_weight, double cost_weight) {
  return surrogate_loss_evaluator(inputs, theta_old, reward_weight, std::vector<double>{cost_weight});
}

ConstrainedEvaluator constrained_evaluator(const PolicyUpdateInputs& inputs, const Eigen::VectorXd& theta_old) {
  return [&inputs, &theta_old](const Eigen::Ref<const Eigen::VectorXd>& step) {
    inputs.policy.mean_net().set_parameters(theta_old + step);
    const SurrogateValues values = inputs.surrogate.evaluate(inputs.policy);
    return ConstrainedTrial{-values.reward_surrogate, values.cost_surrogate, values.kl};  // l_R, L_C, KL
  };
}

}  // namespace bsg::algos
