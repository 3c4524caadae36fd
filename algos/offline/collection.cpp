#include "algos/offline/collection.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "common/seeding.h"

namespace bsg::algos {

std::vector<std::int64_t> split_by_shares(std::int64_t total, const std::vector<double>& shares) {
  if (total < 0) throw std::invalid_argument("collection: a negative count, " + std::to_string(total));
  if (shares.empty()) throw std::invalid_argument("collection: no policy to collect with");
  for (double share : shares) {
    if (!std::isfinite(share) || share <= 0.0) {
      throw std::invalid_argument("collection: a policy's share must be a positive number, got " +
                                  std::to_string(share));
    }
  }
  const double sum = std::accumulate(shares.begin(), shares.end(), 0.0);
  std::vector<std::int64_t> parts(shares.size());
  std::vector<double> remainders(shares.size());
  std::int64_t assigned = 0;
  for (std::size_t i = 0; i < shares.size(); ++i) {
    const double exact = static_cast<double>(total) * shares[i] / sum;
    parts[i] = static_cast<std::int64_t>(std::floor(exact));
    remainders[i] = exact - static_cast<double>(parts[i]);
    assigned += parts[i];
  }
  std::vector<std::size_t> order(shares.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return remainders[a] > remainders[b]; });
  for (std::size_t k = 0; assigned < total; k = (k + 1) % order.size(), ++assigned) ++parts[order[k]];
  return parts;
}

namespace {

void append(std::vector<float>& to, std::span<const double> values) {
  for (double v : values) to.push_back(static_cast<float>(v));
}

}  // namespace

OfflineDataset collect_dataset(envs::Env& env, const std::vector<SharedPolicy>& policies, const CollectionPlan& plan,
                               const StepCostSelector& costs, const std::vector<std::string>& constraint_names) {
  if (plan.count < 1) {
    throw std::invalid_argument("collection: the number of " +
                                std::string(plan.unit == CollectionUnit::episodes ? "episodes" : "transitions") +
                                " must be at least 1, got " + std::to_string(plan.count));
  }
  const int m = costs.count();
  if (m > 1 && static_cast<int>(constraint_names.size()) != m) {
    throw std::invalid_argument("collection: " + std::to_string(m) + " constraints but " +
                                std::to_string(constraint_names.size()) + " names");
  }
  std::vector<double> shares;
  for (const SharedPolicy& p : policies) shares.push_back(p.share);
  const std::vector<std::int64_t> quotas = split_by_shares(plan.count, shares);

  const envs::EnvSpec& spec = env.spec();
  OfflineDataset data;
  data.observation_dim = spec.observation_dim;
  data.action_dim = spec.action_dim;
  if (m > 1) data.constraint_names = constraint_names;
  std::vector<double> observation(static_cast<std::size_t>(spec.observation_dim));
  std::vector<double> action(static_cast<std::size_t>(spec.action_dim));
  Eigen::VectorXd step_costs(m);

  std::uint64_t episode = 0;
  std::vector<bool> episode_whole;  // false for an episode cut at a policy's quota of transitions
  std::string policy_lines;
  for (std::size_t p = 0; p < policies.size(); ++p) {
    CollectionPolicy& policy = *policies[p].policy;
    std::int64_t episodes_done = 0;
    std::int64_t transitions_done = 0;
    const auto quota_met = [&]() {
      return plan.unit == CollectionUnit::episodes ? episodes_done >= quotas[p] : transitions_done >= quotas[p];
    };
    while (!quota_met()) {
      const std::span<const double> first = env.reset(derive_seed(plan.seed, SeedStream::environment, 0, episode));
      std::copy(first.begin(), first.end(), observation.begin());
      policy.start_episode(derive_seed(plan.seed, SeedStream::action_noise, 0, episode));
      bool done = false;
      bool cut = false;
      while (!done) {
        policy.act(observation, action);
        for (double& a : action) a = std::clamp(a, spec.action_low, spec.action_high);
        const envs::StepResult step = env.step(action);
        append(data.observations, observation);
        append(data.next_observations, step.observation);
        append(data.actions, action);
        data.rewards.push_back(static_cast<float>(step.reward));
        costs.select(step, step_costs);
        data.costs.push_back(static_cast<float>(step_costs.sum()));
        if (m > 1) {
          for (int i = 0; i < m; ++i) data.constraint_costs.push_back(static_cast<float>(step_costs[i]));
        }
        ++transitions_done;
        const bool quota_reached = plan.unit == CollectionUnit::transitions && transitions_done >= quotas[p];
        data.terminals.push_back(step.terminated ? 1.0f : 0.0f);
        data.timeouts.push_back(!step.terminated && (step.truncated || quota_reached) ? 1.0f : 0.0f);
        done = step.terminated || step.truncated || quota_reached;
        cut = done && !step.terminated && !step.truncated;
        std::copy(step.observation.begin(), step.observation.end(), observation.begin());
      }
      episode_whole.push_back(!cut);
      ++episodes_done;
      ++episode;
    }
    policy_lines += (policy_lines.empty() ? "" : "\n") + policy.description() + ": share " +
                    std::to_string(policies[p].share) + ", " + std::to_string(episodes_done) + " episodes, " +
                    std::to_string(transitions_done) + " transitions";
  }
  data.text_attributes["policies"] = policy_lines;
  data.text_attributes["unit"] = plan.unit == CollectionUnit::episodes ? "episodes" : "transitions";
  data.text_attributes["seed"] = std::to_string(plan.seed);  // text: exact beyond a double's 2^53
  data.number_attributes["count"] = static_cast<double>(plan.count);
  data.number_attributes["episodes"] = static_cast<double>(episode);
  // The normalisation constants range over the whole episodes only: a cut
  // episode's returns are those of a fragment (one row of a random policy
  // would set max_episode_reward near 0). Without a whole episode the file
  // has no constants, and its readers say so.
  const std::vector<DatasetEpisode> episodes = dataset_episodes(data);
  std::vector<DatasetEpisode> whole;
  for (std::size_t e = 0; e < episodes.size(); ++e) {
    if (episode_whole[e]) whole.push_back(episodes[e]);
  }
  if (!whole.empty()) {
    const ReturnRanges ranges = return_ranges(whole);
    data.number_attributes["min_episode_reward"] = ranges.min_episode_reward;
    data.number_attributes["max_episode_reward"] = ranges.max_episode_reward;
    data.number_attributes["min_episode_cost"] = ranges.min_episode_cost;
    data.number_attributes["max_episode_cost"] = ranges.max_episode_cost;
  }
  return data;
}

}  // namespace bsg::algos
