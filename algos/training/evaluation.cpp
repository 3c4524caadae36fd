#include "algos/training/evaluation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/seeding.h"

namespace bsg::algos {

std::vector<EvaluationEpisode> run_evaluation_episodes(envs::Env& env, ActingPolicy& policy, int num_episodes,
                                                       std::uint64_t env_seed, int max_ep_len,
                                                       const StepCostSelector& costs, std::size_t term_count,
                                                       ActionMode mode, Rng& noise) {
  Eigen::VectorXd step_costs(costs.count());
  const int observation_size = policy.observation_size();
  std::vector<double> action(static_cast<std::size_t>(policy.action_size()));
  std::span<const double> observation;
  const auto check = [&](std::span<const double> given) {
    if (static_cast<int>(given.size()) != observation_size) {
      throw std::runtime_error("evaluation: the environment returned an observation of size " +
                               std::to_string(given.size()) + ", expected " + std::to_string(observation_size));
    }
    return given;
  };

  std::vector<EvaluationEpisode> episodes;
  episodes.reserve(static_cast<std::size_t>(std::max(0, num_episodes)));
  for (int episode = 0; episode < num_episodes; ++episode) {
    observation = check(episode == 0 ? env.reset(env_seed) : env.reset());
    EvaluationEpisode result;
    result.constraint_costs.assign(static_cast<std::size_t>(costs.count()), 0.0);
    result.term_costs.assign(term_count, 0.0);
    while (true) {
      policy.act(observation, mode, noise, action);
      const envs::StepResult step = env.step(action);
      result.episode_return += step.reward;
      result.episode_cost += step.cost;
      costs.select(step, step_costs);
      for (int i = 0; i < costs.count(); ++i) result.constraint_costs[static_cast<std::size_t>(i)] += step_costs[i];
      if (term_count > 0) {
        if (step.cost_terms.size() != term_count) {
          throw std::runtime_error("evaluation: the environment reported " + std::to_string(step.cost_terms.size()) +
                                   " cost terms, expected " + std::to_string(term_count));
        }
        for (std::size_t k = 0; k < term_count; ++k) result.term_costs[k] += step.cost_terms[k].value;
      }
      ++result.episode_length;
      if (step.terminated || step.truncated || result.episode_length >= max_ep_len) break;
      observation = check(step.observation);
    }
    episodes.push_back(result);
  }
  return episodes;
}

EvaluationSummary evaluate_policy(envs::Env& env, ActingPolicy& policy, int total_episodes, std::int64_t run_seed,
                                  int max_ep_len, const MpiContext& mpi, const StepCostSelector& costs,
                                  const std::vector<std::string>& term_names, ActionMode mode) {
  if (total_episodes < 0) {
    throw std::invalid_argument("evaluation: the number of episodes must be >= 0, got " +
                                std::to_string(total_episodes));
  }
  const int local_episodes = total_episodes / mpi.size();
  const std::uint64_t env_seed = derive_seed(static_cast<std::uint64_t>(run_seed), SeedStream::evaluation_environment,
                                             static_cast<std::uint64_t>(mpi.rank()));
  Rng action_noise(derive_seed(static_cast<std::uint64_t>(run_seed), SeedStream::evaluation_action_noise,
                               static_cast<std::uint64_t>(mpi.rank())));
  const std::vector<EvaluationEpisode> local = run_evaluation_episodes(
      env, policy, local_episodes, env_seed, max_ep_len, costs, term_names.size(), mode, action_noise);
  return gather_evaluation(local, mpi, static_cast<std::size_t>(costs.count()), term_names);
}

EvaluationSummary gather_evaluation(const std::vector<EvaluationEpisode>& local, const MpiContext& mpi, std::size_t m,
                                    const std::vector<std::string>& term_names, std::size_t agents) {
  // Per episode: J, H, length, then H_1..H_m, then the k term sums, then the agents' returns and costs.
  const std::size_t k = term_names.size();
  const std::size_t stride = 3 + m + k + 2 * agents;
  std::vector<double> flat;
  flat.reserve(local.size() * stride);
  for (const EvaluationEpisode& e : local) {
    flat.push_back(e.episode_return);
    flat.push_back(e.episode_cost);
    flat.push_back(static_cast<double>(e.episode_length));
    flat.insert(flat.end(), e.constraint_costs.begin(), e.constraint_costs.end());
    flat.insert(flat.end(), e.term_costs.begin(), e.term_costs.end());
    flat.insert(flat.end(), e.agent_returns.begin(), e.agent_returns.end());
    flat.insert(flat.end(), e.agent_costs.begin(), e.agent_costs.end());
  }
  const std::vector<double> gathered = mpi.gather_to_root(flat);
  EvaluationSummary summary;
  if (!mpi.is_root()) return summary;
  const auto slice = [&gathered](std::size_t begin, std::size_t count) {
    return std::vector<double>(gathered.begin() + static_cast<std::ptrdiff_t>(begin),
                               gathered.begin() + static_cast<std::ptrdiff_t>(begin + count));
  };
  for (std::size_t i = 0; i + stride - 1 < gathered.size(); i += stride) {
    summary.episodes.push_back({gathered[i], gathered[i + 1], static_cast<int>(gathered[i + 2]), slice(i + 3, m),
                                slice(i + 3 + m, k), slice(i + 3 + m + k, agents), slice(i + 3 + m + k + agents, agents)});
  }
  summary.term_names = term_names;
  summary.mean_term_costs.assign(k, summary.episodes.empty() ? std::nan("") : 0.0);
  for (const EvaluationEpisode& e : summary.episodes) {
    for (std::size_t j = 0; j < k; ++j) summary.mean_term_costs[j] += e.term_costs[j];
  }
  for (double& h : summary.mean_term_costs) {
    if (!summary.episodes.empty()) h /= static_cast<double>(summary.episodes.size());
  }
  // Each agent's mean return and cost (NaN without episodes).
  summary.mean_agent_returns.assign(agents, summary.episodes.empty() ? std::nan("") : 0.0);
  summary.mean_agent_costs.assign(agents, summary.episodes.empty() ? std::nan("") : 0.0);
  for (const EvaluationEpisode& e : summary.episodes) {
    for (std::size_t a = 0; a < agents; ++a) {
      summary.mean_agent_returns[a] += e.agent_returns[a];
      summary.mean_agent_costs[a] += e.agent_costs[a];
    }
  }
  for (std::size_t a = 0; a < agents && !summary.episodes.empty(); ++a) {
    summary.mean_agent_returns[a] /= static_cast<double>(summary.episodes.size());
    summary.mean_agent_costs[a] /= static_cast<double>(summary.episodes.size());
  }
  summary.mean_constraint_costs.assign(m, 0.0);
  if (summary.episodes.empty()) {
    summary.mean_return = summary.mean_cost = summary.mean_length = std::nan("");
    summary.mean_constraint_costs.assign(m, std::nan(""));
  } else {
    for (const EvaluationEpisode& e : summary.episodes) {
      summary.mean_return += e.episode_return;
      summary.mean_cost += e.episode_cost;
      summary.mean_length += e.episode_length;
      for (std::size_t j = 0; j < m; ++j) summary.mean_constraint_costs[j] += e.constraint_costs[j];
    }
    const double n = static_cast<double>(summary.episodes.size());
    summary.mean_return /= n;
    summary.mean_cost /= n;
    summary.mean_length /= n;
    for (double& h : summary.mean_constraint_costs) h /= n;
  }
  return summary;
}

}  // namespace bsg::algos
