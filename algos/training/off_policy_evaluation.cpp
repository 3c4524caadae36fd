#include "algos/training/off_policy_evaluation.h"

#include <limits>
#include <vector>

#include "common/seeding.h"

namespace bsg::algos {

EvaluationSummary evaluate_off_policy(envs::Env& env, OffPolicyLearner& learner, int total_episodes,
                                      std::int64_t run_seed, int max_ep_len, const MpiContext& mpi,
                                      const StepCostSelector& costs) {
  const int local_episodes = total_episodes / mpi.size();
  const int observation_size = env.spec().observation_dim;
  const int constraint_count = costs.count();
  Eigen::VectorXd action(env.spec().action_dim);
  Eigen::VectorXd step_costs(constraint_count);
  Rng unused(0);  // act(deterministic) draws nothing
  std::vector<double> local;  // (return, cost, length, constraint costs...) per episode
  for (int e = 0; e < local_episodes; ++e) {
    const std::span<const double> first =
        e == 0 ? env.reset(derive_seed(static_cast<std::uint64_t>(run_seed), SeedStream::evaluation_environment,
                                       static_cast<std::uint64_t>(mpi.rank()), 0))
               : env.reset();
    Eigen::VectorXd current = Eigen::Map<const Eigen::VectorXd>(first.data(), observation_size);
    double episode_return = 0.0, episode_cost = 0.0;
    Eigen::VectorXd constraint_costs = Eigen::VectorXd::Zero(constraint_count);
    int length = 0;
    while (true) {
      learner.act(std::span<const double>(current.data(), static_cast<std::size_t>(current.size())), true, unused,
                  action);
      const envs::StepResult step = env.step(std::span<const double>(action.data(), static_cast<std::size_t>(action.size())));
      costs.select(step, step_costs);
      episode_return += step.reward;
      episode_cost += step.cost;
      constraint_costs += step_costs;
      ++length;
      if (step.terminated || step.truncated || length >= max_ep_len) break;
      current = Eigen::Map<const Eigen::VectorXd>(step.observation.data(), observation_size);
    }
    local.push_back(episode_return);
    local.push_back(episode_cost);
    local.push_back(length);
    for (int i = 0; i < constraint_count; ++i) local.push_back(constraint_costs(i));
  }
  const std::vector<double> gathered = mpi.gather_to_root(local);
  EvaluationSummary summary;
  if (!mpi.is_root()) return summary;
  const std::size_t width = 3 + static_cast<std::size_t>(constraint_count);
  for (std::size_t k = 0; k + width <= gathered.size(); k += width) {
    EvaluationEpisode episode;
    episode.episode_return = gathered[k];
    episode.episode_cost = gathered[k + 1];
    episode.episode_length = static_cast<int>(gathered[k + 2]);
    episode.constraint_costs.assign(gathered.begin() + static_cast<std::ptrdiff_t>(k + 3),
                                    gathered.begin() + static_cast<std::ptrdiff_t>(k + width));
    summary.episodes.push_back(std::move(episode));
  }
  const double count = static_cast<double>(summary.episodes.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  summary.mean_return = summary.mean_cost = summary.mean_length = count > 0 ? 0.0 : nan;
  summary.mean_constraint_costs.assign(static_cast<std::size_t>(constraint_count), count > 0 ? 0.0 : nan);
  for (const EvaluationEpisode& episode : summary.episodes) {
    summary.mean_return += episode.episode_return / count;
    summary.mean_cost += episode.episode_cost / count;
    summary.mean_length += episode.episode_length / count;
    for (int i = 0; i < constraint_count; ++i) {
      summary.mean_constraint_costs[static_cast<std::size_t>(i)] +=
          episode.constraint_costs[static_cast<std::size_t>(i)] / count;
    }
  }
  return summary;
}

}  // namespace bsg::algos
