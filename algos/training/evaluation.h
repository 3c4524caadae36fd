// Evaluation (docs/reproducing.md#evaluation) of any family's acting policy (algos/core/
// acting_policy.h): by default its mean action (the on-policy mu_theta(s_hat), the off-policy
// actor's tanh(mu(s)): the original's evaluation); with ActionMode::sampled the actions it explores
// with, drawn from a stream of their own (derive_seed(run seed, evaluation_action_noise, rank)).
// Each episode runs until the environment terminates or truncates (or max_ep_len steps). J and H
// are the undiscounted raw sums of reward and cost per episode, H_i each constraint's.
//
// With R ranks, each rank runs floor(episodes / R) episodes on its own environment, seeded with
// derive_seed(run seed, evaluation_environment, rank) once and then reset from its own stream;
// rank 0 gathers them in rank order. The training's final evaluation, `bsg eval` and
// `bsg collect`'s policies all act through this one loop.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "algos/core/acting_policy.h"
#include "algos/core/constraint_costs.h"
#include "algos/training/evaluation_actions.h"
#include "common/mpi_context.h"
#include "common/random.h"
#include "envs/env.h"

namespace bsg::algos {

struct EvaluationEpisode {
  double episode_return = 0.0;  // J
  double episode_cost = 0.0;    // H
  int episode_length = 0;
  std::vector<double> constraint_costs{};  // H_i per constraint (docs/algorithms.md#several-constraints)
  std::vector<double> term_costs{};        // each named cost term's episode sum (when asked for)
  std::vector<double> agent_returns{};     // a multi-agent episode: each agent's own return and cost
  std::vector<double> agent_costs{};       // (J and H above are the agents' mean)
};

// The same episodes acted with the policy that explores while collecting (an off-policy run's
// final evaluation: the policy whose training episodes its multipliers constrain).
struct ExploringEvaluation {
  long long episodes = 0;
  double mean_return = 0.0;  // J
  double mean_cost = 0.0;    // H
  double mean_length = 0.0;
};

struct EvaluationSummary {
  std::vector<EvaluationEpisode> episodes;  // every rank's, in rank order (rank 0 only)
  double mean_return = 0.0;                 // J (NaN without episodes)
  double mean_cost = 0.0;                   // H
  double mean_length = 0.0;
  std::vector<double> mean_constraint_costs{};  // H_i, one per constraint (NaN without episodes)
  std::vector<std::string> term_names{};        // the environment's cost terms, when asked for
  std::vector<double> mean_term_costs{};        // each term's mean episode sum
  double action_std = 0.0;                      // sigma of sampled Gaussian actions; 0 = mean actions
  std::optional<ExploringEvaluation> exploring{};  // off-policy final evaluations only
  std::vector<double> mean_agent_returns{};        // multi-agent runs: each agent's mean return and cost
  std::vector<double> mean_agent_costs{};
};

// The episodes of this rank.
// `costs` gives each episode's constraint costs (default: the one constraint on the environment's cost);
// with term_count > 0 every episode also sums each of the environment's term_count cost terms;
// sampled actions draw from `noise`.
std::vector<EvaluationEpisode> run_evaluation_episodes(envs::Env& env, ActingPolicy& policy, int num_episodes,
                                                       std::uint64_t env_seed, int max_ep_len,
                                                       const StepCostSelector& costs, std::size_t term_count,
                                                       ActionMode mode, Rng& noise);

// floor(total_episodes / R) episodes per rank, gathered to rank 0 (others get
// an empty summary). Collective. The summary's action_std is the caller's to set.
EvaluationSummary evaluate_policy(envs::Env& env, ActingPolicy& policy, int total_episodes, std::int64_t run_seed,
                                  int max_ep_len, const MpiContext& mpi,
                                  const StepCostSelector& costs = StepCostSelector(),
                                  const std::vector<std::string>& term_names = {},
                                  ActionMode mode = ActionMode::mean);

// Rank 0's summary of every rank's `local` episodes, each with m constraint costs,
// term_names.size() term sums and `agents` agents' returns and costs (evaluate_policy's second half;
// the multi-agent family's evaluation). Collective.
EvaluationSummary gather_evaluation(const std::vector<EvaluationEpisode>& local, const MpiContext& mpi, std::size_t m,
                                    const std::vector<std::string>& term_names, std::size_t agents = 0);

}  // namespace bsg::algos
